"""Effects a scene switches on: each holds its traced SI parameters and what it does to the law
and the motion. An effect that a scene does not name is not compiled at all (the static switches
of `impact._integrate.Options`)."""
