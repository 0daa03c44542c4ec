"""`python -m impact.cli`: the `impact` command line."""

from .app import main

main()
