"""Where the command line writes: results to stdout, refusals and warnings to stderr.

Every refusal of bad input goes through `refuse`: it prints what is wrong (the field by its
dotted path or option name, then the message) and exits with code 2, without a traceback.
"""

from collections.abc import Iterable
from typing import Any, NoReturn

import typer
from rich.console import Console
from rich.text import Text
from typer.core import TyperCommand, TyperGroup

out = Console(highlight=False)
err = Console(stderr=True, highlight=False)

REFUSED = 2  # exit code of refused input


class _FlagsShowNoValue:
    """`--help` shows no `<bool>` beside a flag (`--overwrite`, `--help`): it takes no value."""

    def get_params(self, ctx: Any) -> Any:  # typer's own copy of click's types
        params = super().get_params(ctx)  # type: ignore[misc]
        for param in params:
            if getattr(param, "is_flag", False):
                param.metavar = ""
        return params


class FlagHelpCommand(_FlagsShowNoValue, TyperCommand):
    """A command of the app (flags without `<bool>` in `--help`)."""


class FlagHelpGroup(_FlagsShowNoValue, TyperGroup):
    """The app's group (flags without `<bool>` in `--help`)."""


def refuse(headline: str, problems: Iterable[tuple[str, str]]) -> NoReturn:
    """Print "error: <headline>" and one "<field>: <message>" line per problem to stderr, then
    exit with code 2."""
    err.print(Text(f"error: {headline}", "bold red"), soft_wrap=True)
    for field, message in problems:
        err.print(Text(f"  {field}: {message}" if field else f"  {message}"), soft_wrap=True)
    raise typer.Exit(REFUSED)


def refuse_value(option: str, value: object, allowed: str) -> NoReturn:
    """Refuse an option's value: `refuse_value("--chunk", 0, "be >= 1")` prints
    "--chunk: must be >= 1, got 0"."""
    refuse("options", [(option, f"must {allowed}, got {value}")])


def say(line: str) -> None:
    """Print one line to stdout as plain text (no markup, no wrapping of paths)."""
    out.print(Text(line), soft_wrap=True)


def warn(line: str) -> None:
    """Print one warning line to stderr, in yellow (not wrapped)."""
    err.print(Text(line, "yellow"), soft_wrap=True)


def show_warning(message, category, filename, lineno, file=None, line=None) -> None:  # noqa: ARG001
    """A Python warning as one line, "warning: <message>" (`warnings.showwarning` of the command
    line: no source file, line number or code)."""
    warn(f"warning: {message}")
