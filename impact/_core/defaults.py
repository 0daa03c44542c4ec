"""Defaults that the command line's help text shows, here so that `impact --help` need not import
the modules (and JAX) that use them."""

DEFAULT_CHUNK = 1000  # sweep points per compiled call
SPEED_REPEATS = 5  # timed runs per row of `impact bench speed`: the median is reported
