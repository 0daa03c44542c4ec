"""The `impact bench` command: `register(app)` adds it to a typer app (`impact.cli` calls it).

The benchmark itself lives in `impact._bench`. Float64 is the entry point's business (the
`impact` command enables it); without it the command refuses to run.
"""

import shutil
from datetime import datetime
from pathlib import Path
from typing import Annotated

import jax
import typer

from .._bench.plans import OUTPUTS
from .._bench.work_precision import run as run_benchmark
from .console import FlagHelpCommand, refuse, say


def register(app: typer.Typer) -> None:
    """Add the `bench` command to `app`."""

    @app.command("bench", cls=FlagHelpCommand)
    def bench(
        quick: Annotated[
            bool,
            typer.Option("--quick", help="a reduced plan that finishes in about a minute (one solver, fewer points)"),
        ] = False,
        output: Annotated[
            Path | None,
            typer.Option(
                "-o", "--output", help="output folder (default: runs/bench/<YYYYmmdd-HHMMSS>)", show_default=False
            ),
        ] = None,
        overwrite: Annotated[bool, typer.Option("--overwrite", help="write into an existing output folder")] = False,
    ) -> None:
        """Measure what accuracy costs: error against time per impact for every integrator (work-precision)."""
        folder = output or Path("runs") / "bench" / datetime.now().strftime("%Y%m%d-%H%M%S")
        if folder.exists() and not folder.is_dir():
            refuse("output folder", [("--output", f"{folder} exists and is not a folder")])
        if folder.exists() and not overwrite:
            refuse(
                "output folder",
                [("--output", f"folder {folder} exists; pass --overwrite to replace the benchmark in it")],
            )
        if not jax.config.read("jax_enable_x64"):
            refuse(
                "float64", [("", "the benchmark needs float64: run it through the `impact` command (which enables it)")]
            )

        created = not folder.exists()
        try:
            run_benchmark(folder, quick=quick, log=say)
        except BaseException:
            if created:
                shutil.rmtree(folder, ignore_errors=True)
            raise
        for name in OUTPUTS:
            say(f"  {folder / name}")
