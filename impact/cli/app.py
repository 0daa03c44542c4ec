"""The `impact` typer app and its console entry point `main`."""

import atexit
import gc
import os
import sys
import warnings
from pathlib import Path
from typing import Annotated

import typer

from .._core.package import __version__
from . import commands
from .console import FlagHelpGroup, say, show_warning, warn
from .long_runs import INTERRUPTED, Interrupted, catch_ctrl_c
from .settings import CacheChoice

HELP = (
    "Simulate adhesive impacts (MDR contact law on JAX + diffrax).\n\n"
    "Compiled programs are kept in a cache on disk, so that only the first run of a scene compiles: "
    "in --cache-dir DIR, else in $IMPACT_CACHE_DIR, else in the per-user cache directory "
    "(~/.cache/impact/jax on Linux). --no-cache or IMPACT_CACHE_DIR=off compiles without it; "
    "delete the directory to clear it."
)

app = typer.Typer(
    help=HELP, no_args_is_help=True, add_completion=False, pretty_exceptions_show_locals=False, cls=FlagHelpGroup
)


# At its default thresholds (700, 10, 10) Python's cyclic garbage collector runs every 700
# allocations while a command's imports create hundreds of thousands of long-lived objects (JAX,
# equinox classes, matplotlib), traversing them again and again: a share of a short command's CPU
# time worth saving. Run once 10⁶ more objects have been made than freed, it leaves a run's imports
# and the traces of its programs (a few hundred thousand objects) alone. It stays on, less often
# (a sweep's or a fit's memory is in arrays).
_COLLECTION_THRESHOLDS = (1_000_000, 50, 100)


def main() -> None:
    """Console entry point: the command line (each command configures float64, whole-loop
    compilation and the compilation cache itself, as the global options ask); a Python warning
    is printed as one line; Ctrl-C ends it with exit code 130 (`long_runs`). The process ends as
    soon as the command has: see `_end`."""
    gc.set_threshold(*_COLLECTION_THRESHOLDS)
    warnings.showwarning = show_warning
    catch_ctrl_c()
    try:
        app()
    except SystemExit as stop:
        _end(stop.code)
    except Interrupted:
        warn("interrupted")
        _end(INTERRUPTED)
    _end(0)


def _end(code: object) -> None:
    """End the process with the exit status `code` (None: 0; text: printed, then 1), after the
    atexit handlers and with both output streams flushed, but without tearing the interpreter
    down: freeing every module, object and JAX's compiled programs one by one would take a large
    share of a short run's time."""
    if code is not None and not isinstance(code, int):
        print(code, file=sys.stderr)
        code = 1
    atexit._run_exitfuncs()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code or 0)


def _print_version(value: bool) -> None:
    if value:
        say(f"impact {__version__}")
        raise typer.Exit()


@app.callback(help=HELP)
def _options(
    ctx: typer.Context,
    version: Annotated[
        bool,
        typer.Option("--version", callback=_print_version, is_eager=True, help="print the version and exit"),
    ] = False,
    cache_dir: Annotated[
        Path | None,
        typer.Option(
            "--cache-dir",
            metavar="DIR",
            help="keep compiled programs in DIR (default: $IMPACT_CACHE_DIR, else the per-user cache directory)",
            show_default=False,
        ),
    ] = None,
    no_cache: Annotated[
        bool,
        typer.Option("--no-cache", help="compile in this process without the cache", show_default=False),
    ] = False,
) -> None:
    ctx.obj = CacheChoice(directory=cache_dir, enabled=not no_cache)


commands.register(app)
