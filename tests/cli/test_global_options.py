"""The global options of `impact` (--cache-dir, --no-cache) and the help that answers without
loading JAX."""

import os
import subprocess
import sys
from pathlib import Path

import jax
import pytest
from typer.testing import CliRunner

import impact
from impact.cli import app
from tests.scenes import ROOT, THORNTON_NING

# A fresh interpreter that asks for the help and says whether JAX (or numpy) got imported.
HELP = """
import sys
from typer.testing import CliRunner
from impact.cli import app
result = CliRunner().invoke(app, sys.argv[1:])
print(result.exit_code, "Usage" in result.output, "jax" in sys.modules, "numpy" in sys.modules)
"""


@pytest.mark.parametrize("arguments", [["--help"], ["run", "--help"], ["sweep", "--help"], ["run", "--bad"]])
def test_help_does_not_import_jax(arguments):
    process = subprocess.run([sys.executable, "-c", HELP, *arguments], capture_output=True, text=True, cwd=ROOT)
    assert process.returncode == 0, process.stderr
    exit_code = "2" if "--bad" in arguments else "0"
    assert process.stdout.split() == [exit_code, "True", "False", "False"]


@pytest.mark.parametrize(("arguments", "status", "printed"), [(["--version"], 0, "impact "), (["--bad"], 2, "--bad")])
def test_console_entry_point_ends_with_the_commands_status_and_its_output(arguments, status, printed):
    """`main` ends the process itself (no interpreter teardown): the status and the text survive."""
    command = [sys.executable, "-c", "from impact.cli import main; main()", *arguments]
    process = subprocess.run(command, capture_output=True, text=True, cwd=ROOT)
    assert process.returncode == status
    assert printed in process.stdout + process.stderr


def test_help_says_where_the_cache_lives():
    result = CliRunner().invoke(app, ["--help"])
    assert result.exit_code == 0
    text = " ".join(result.output.replace("│", " ").split())
    for phrase in ("--cache-dir", "--no-cache", "$IMPACT_CACHE_DIR", "IMPACT_CACHE_DIR=off", "~/.cache/impact/jax"):
        assert phrase in text


@pytest.fixture
def restore_cache():
    """Put the suite's cache back (conftest's IMPACT_CACHE_DIR) after a command that moved it."""
    yield
    assert impact.configure() == Path(os.environ["IMPACT_CACHE_DIR"])


def test_cache_dir_option_moves_the_cache(tmp_path, restore_cache):
    folder = tmp_path / "elsewhere"
    result = CliRunner().invoke(app, ["--cache-dir", str(folder), "validate", str(THORNTON_NING)])
    assert result.exit_code == 0, result.output
    assert folder.is_dir() and jax.config.jax_compilation_cache_dir == str(folder)
    assert jax.config.jax_enable_compilation_cache is True


def test_no_cache_option_switches_it_off(restore_cache):
    result = CliRunner().invoke(app, ["--no-cache", "validate", str(THORNTON_NING)])
    assert result.exit_code == 0, result.output
    assert jax.config.jax_enable_compilation_cache is False


def test_run_with_an_unusable_cache_directory_warns_once_and_runs(tmp_path, restore_cache):
    blocker = tmp_path / "a file"
    blocker.write_text("not a folder")
    result = CliRunner().invoke(
        app, ["--cache-dir", str(blocker / "jax"), "run", str(THORNTON_NING), "-o", str(tmp_path / "run")]
    )
    assert result.exit_code == 0, result.output
    warning = f"warning: compilation cache {blocker / 'jax'} is not usable (Not a directory); compiling without a cache"
    lines = [line.strip() for line in result.output.splitlines()]
    assert lines.count(warning) == 1
    assert (tmp_path / "run" / "run.h5").is_file()
