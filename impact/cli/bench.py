"""The `impact bench` command: `register(app)` adds it to a typer app (cli.py calls it).

The benchmark itself lives in `impact.bench` and is imported only when the command runs.
Float64 is the entry point's business (`impact.cli.main` enables it); without it the
command refuses to run.
"""

import shutil
from datetime import datetime
from pathlib import Path
from typing import Annotated, Optional

import typer
from rich.console import Console
from rich.text import Text

_out = Console(highlight=False)
_err = Console(stderr=True, highlight=False)


def register(app: typer.Typer) -> None:
    """Add the `bench` command to `app`."""

    @app.command("bench")
    def bench(
        quick: Annotated[
            bool, typer.Option("--quick", help="a reduced plan that finishes in about a minute (one solver, fewer points)")
        ] = False,
        output: Annotated[
            Optional[Path],
            typer.Option("-o", "--output", help="output folder (default: runs/bench/<YYYYmmdd-HHMMSS>)", show_default=False),
        ] = None,
        overwrite: Annotated[bool, typer.Option("--overwrite", help="write into an existing output folder")] = False,
    ) -> None:
        """Measure what accuracy costs: error against time per impact for every integrator (work-precision)."""
        import jax

        folder = output or Path("runs") / "bench" / datetime.now().strftime("%Y%m%d-%H%M%S")
        if folder.exists() and not folder.is_dir():
            _refuse(f"--output: {folder} exists and is not a folder")
        if folder.exists() and not overwrite:
            _refuse(f"--output: folder {folder} exists; pass --overwrite to replace the benchmark in it")
        if not jax.config.jax_enable_x64:
            _refuse("the benchmark needs float64: run it through the `impact` command (which enables it)")

        from .._bench import work_precision as benchmark

        created = not folder.exists()
        try:
            benchmark.run(folder, quick=quick, log=lambda line: _out.print(Text(line), soft_wrap=True))
        except BaseException:
            if created:
                shutil.rmtree(folder, ignore_errors=True)
            raise
        for name in benchmark.OUTPUTS:
            _out.print(Text(f"  {folder / name}"), soft_wrap=True)


def _refuse(message: str) -> None:
    _err.print(Text(f"error: {message}", "bold red"), soft_wrap=True)
    raise typer.Exit(2)
