"""The `impact bench` command (declared in `commands`).

The benchmark itself lives in `impact._bench`. Float64 is the entry point's business (the
`impact` command enables it); without it the command refuses to run.
"""

import shutil
from datetime import datetime
from pathlib import Path

import jax

from .._bench.plans import OUTPUTS
from .._bench.work_precision import run as run_benchmark
from .console import refuse, say


def run_bench(quick: bool, output: Path | None, overwrite: bool) -> None:
    """`impact bench`: error against time per impact for every integrator (work-precision)."""
    folder = output or Path("runs") / "bench" / datetime.now().strftime("%Y%m%d-%H%M%S")
    if folder.exists() and not folder.is_dir():
        refuse("output folder", [("--output", f"{folder} exists and is not a folder")])
    if folder.exists() and not overwrite:
        refuse(
            "output folder",
            [("--output", f"folder {folder} exists; pass --overwrite to replace the benchmark in it")],
        )
    if not jax.config.read("jax_enable_x64"):
        refuse("float64", [("", "the benchmark needs float64: run it through the `impact` command (which enables it)")])

    created = not folder.exists()
    try:
        run_benchmark(folder, quick=quick, log=say)
    except BaseException:
        if created:
            shutil.rmtree(folder, ignore_errors=True)
        raise
    for name in OUTPUTS:
        say(f"  {folder / name}")
