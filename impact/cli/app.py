"""The `impact` typer app and its console entry point `main`."""

from typing import Annotated

import typer

from .._core import runtime
from .._core.package import __version__
from . import bench, run, sweep
from .console import FlagHelpGroup, say

app = typer.Typer(
    help="Simulate adhesive impacts (MDR contact law on JAX + diffrax).",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_show_locals=False,
    cls=FlagHelpGroup,
)


def main() -> None:
    """Console entry point: float64 physics and whole-loop compilation (`runtime.configure`),
    then the command line."""
    runtime.configure()
    app()


def _print_version(value: bool) -> None:
    if value:
        say(f"impact {__version__}")
        raise typer.Exit()


@app.callback()
def _options(
    version: Annotated[
        bool,
        typer.Option("--version", callback=_print_version, is_eager=True, help="print the version and exit"),
    ] = False,
) -> None:
    """Simulate adhesive impacts (MDR contact law on JAX + diffrax)."""


run.register(app)
sweep.register(app)
bench.register(app)
