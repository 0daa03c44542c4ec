"""The `impact` command line (typer + rich): run, validate and show scenes, sweep them, merge
the shards of a multi-process sweep, and benchmark the integrators.

`main` is the console entry point; `app` is the typer app (for typer's test runner).
"""

from .app import app as app
from .app import main as main

__all__ = ["app", "main"]
