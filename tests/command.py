"""The `impact` command run in this process (typer's runner), as the tests call it."""

from typer.testing import CliRunner

from impact.cli import app


def invoke(*args):
    """`impact ARGS…` (each argument as text); typer's `Result`: exit_code, output."""
    return CliRunner().invoke(app, [str(arg) for arg in args])
