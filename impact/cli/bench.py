"""The `impact bench` commands (declared in `commands`): `impact bench` alone measures
work-precision, `impact bench speed` what a point of a sweep costs.

The benchmarks themselves live in `impact._bench`. Float64 is the entry point's business (the
`impact` command enables it); without it the commands refuse to run.
"""

from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

import jax
from rich.console import Console
from rich.table import Table

from .._bench.fragments import microseconds, speed_fragment, work_precision_fragment
from .._bench.plans import OUTPUTS
from .._bench.speed import run as run_speed
from .._bench.work_precision import provenance
from .._bench.work_precision import run as run_benchmark
from .._bench.workloads import SPEED_OUTPUTS, speed_plan, workloads
from .._core.defaults import SPEED_REPEATS
from .._io.files import write_text
from .console import out, refuse, refuse_value, say
from .folders import check_output, check_output_file, fresh_folder, removed_on_failure

Measured = TypeVar("Measured")


def run_bench(quick: bool, output: Path | None, overwrite: bool, markdown: Path | None = None) -> None:
    """`impact bench`: error against time per impact for every integrator (work-precision);
    `markdown`: also its tables as a Markdown fragment."""
    if markdown is not None:
        check_output_file(markdown, "--markdown")
    data = _into_folder(output, overwrite, lambda folder: run_benchmark(folder, quick=quick, log=say), OUTPUTS)
    if markdown is not None:
        write_text(markdown, work_precision_fragment(data, "impact bench" + (" --quick" if quick else "")))
        say(f"  {markdown}")


def run_bench_speed(
    quick: bool,
    points: list[int],
    only: list[str],
    repeats: int,
    chunk: int | None,
    output: Path | None,
    overwrite: bool,
    markdown: Path | None = None,
) -> None:
    """`impact bench speed`: µs per impact after compile, accuracy, compile time and the split
    build / integrate / post-process of every workload; writes speed.csv and speed.png, and with
    `markdown` the table as a Markdown fragment."""
    for value in points:
        if value < 1:
            refuse_value("--points", value, "be >= 1")
    if repeats < 1:
        refuse_value("--repeats", repeats, "be >= 1")
    if chunk is not None and chunk < 1:
        refuse_value("--chunk", chunk, "be >= 1")
    keys = [workload.key for workload in workloads(quick=False)]
    for key in only:
        if key not in keys:
            refuse_value("--only", repr(key), f"be one of {', '.join(keys)}")
    if markdown is not None:
        check_output_file(markdown, "--markdown")
    plan = speed_plan(quick=quick, points=tuple(points), only=tuple(only), repeats=repeats, chunk=chunk)
    rows = _into_folder(output, overwrite, lambda folder: run_speed(folder, plan, log=say), SPEED_OUTPUTS)
    if markdown is not None:
        command = speed_command(quick, points, only, repeats, chunk)
        write_text(markdown, speed_fragment(rows, provenance("quick" if quick else "full"), command))
        say(f"  {markdown}")
    # Thirteen columns: printed 180 wide whatever the terminal (rich cannot widen `out` per print,
    # and a narrower table truncates every number); the CSV holds the same rows.
    Console(width=max(out.width, 180), highlight=False).print(speed_table(rows))


def speed_command(quick: bool, points: list[int], only: list[str], repeats: int, chunk: int | None) -> str:
    """The `impact bench speed` command line that measures with these options (output options
    left out)."""
    words = ["impact bench speed", *(["--quick"] if quick else [])]
    words += [f"--only {key}" for key in only] + [f"--points {value}" for value in points]
    words += [f"--repeats {repeats}"] if repeats != SPEED_REPEATS else []
    return " ".join(words + ([f"--chunk {chunk}"] if chunk is not None else []))


def _into_folder(output: Path | None, overwrite: bool, measure: Callable[[Path], Measured], outputs) -> Measured:
    """Check the output folder, run `measure(folder)`, list its outputs; a folder this call made
    is removed again if the run fails or is interrupted."""
    if output is not None:
        check_output(output, overwrite, holds="benchmark")
    if not jax.config.read("jax_enable_x64"):
        refuse("float64", [("", "the benchmark needs float64: run it through the `impact` command (which enables it)")])
    folder = output or fresh_folder(Path("runs") / "bench")
    with removed_on_failure(folder, created=output is None):
        result = measure(folder)
    for name in outputs:
        say(f"  {folder / name}")
    return result


def speed_table(rows: list[dict]) -> Table:
    """The rows of `impact bench speed` as a rich table."""
    device = f" on {rows[0]['device']}" if rows else ""
    table = Table(title=f"What a point costs{device} (µs per impact after compile, median)")
    for heading in (
        "workload",
        "method",
        "points",
        "chunk",
        "µs/impact",
        "min–max",
        "max error",
        "vs",
        "compile s",
        "build",
        "integrate",
        "post",
        "steps",
    ):
        table.add_column(heading, justify="left" if heading in ("workload", "method", "vs") else "right")
    for row in rows:
        table.add_row(
            row["workload"],
            row["method"],
            str(row["points"]),
            str(row["chunk"]),
            microseconds(row["us_per_impact_median"]),
            f"{microseconds(row['us_min'])}–{microseconds(row['us_max'])}",
            f"{row['max_error']:.1e}",
            row["error_reference"],
            f"{row['compile_s']:.1f}",
            microseconds(row["build_us"]),
            microseconds(row["integrate_us"]),
            microseconds(row["post_us"]),
            f"{row['steps_mean']:.0f}",
        )
    return table
