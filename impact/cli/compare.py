"""`impact compare lammps`: a scene's velocity sweep by LAMMPS's granular contact model beside
impact's exact law (declared in `commands`).

    impact compare lammps SCENE.yaml [--model jkr|dmt|hertz/material|mdr] [--damping MODEL:VALUE]
                          [--velocities A:B:N] [--dt DT] [-o DIR] [--set PATH=VALUE ...] [--overwrite]

It writes DIR/comparison.csv (the table), DIR/comparison.png (the figure), DIR/summary.txt (the
mapping of the parameters, what LAMMPS leaves out, the differences beside LAMMPS's step error,
the timing), DIR/in.lammps (LAMMPS's input as run) and DIR/config.yaml (the resolved scene).
Bad input, a scene LAMMPS cannot represent or LAMMPS missing exit with code 2, without a
traceback and before anything is written.
"""

import math
from pathlib import Path

import numpy as np
from rich.table import Table
from rich.text import Text

from .._compare.comparison import compare_lammps
from .._compare.granular import NormalModel
from .._compare.lammps_batch import LammpsFailed
from .._compare.lammps_library import LammpsMissing
from .._compare.report import lammps_input, summary_lines, table_csv
from .._io.files import write_text
from .._plots.compare import FIGURE, save_comparison_figure
from .._plots.figures import import_ahead
from .._scene.errors import SceneError
from .._scene.scene import scene_yaml
from .console import out, refuse, say
from .folders import check_output, fresh_folder, make_folder, removed_on_failure
from .run import scene_of

MOST_SPEEDS = 100_000
VELOCITIES = "A:B:N"


def velocities_of(text: str) -> np.ndarray:
    """--velocities A:B:N: N speeds (m/s) evenly from A to B, or a refusal."""
    parts = text.split(":")
    try:
        low, high, count = float(parts[0]), float(parts[1]), int(parts[2])
    except (ValueError, IndexError):
        low, high, count = math.nan, math.nan, 0
    valid = len(parts) == 3 and 0 < low <= high < math.inf and 1 <= count <= MOST_SPEEDS
    if not valid or (count > 1 and low == high):
        refuse(
            "options",
            [
                (
                    "--velocities",
                    f"must be {VELOCITIES}: N speeds (m/s) from A to B, 0 < A < B (A = B for N = 1), "
                    f"1 <= N <= {MOST_SPEEDS}, got {text!r}",
                )
            ],
        )
    return np.linspace(low, high, count)


def run_compare_lammps(
    scene_file: Path,
    model: str | None,
    damping: str | None,
    velocities: str | None,
    dt: float | None,
    output: Path | None,
    assignments: list[str] | None,
    overwrite: bool,
) -> None:
    """`impact compare lammps`: run the comparison, write its files, print its summary."""
    scene = scene_of(scene_file, assignments)
    speeds = None if velocities is None else velocities_of(velocities)
    label = (model or "default").replace("/", "-")
    if output is not None:
        check_output(output, overwrite, holds="comparison")
    import_ahead()
    try:
        normal = None if model is None else NormalModel.named(model)
        comparison = compare_lammps(scene, normal, damping, speeds, dt)
    except LammpsMissing as error:
        refuse("LAMMPS is not installed", [("", str(error))])
    except LammpsFailed as error:
        refuse("LAMMPS stopped with an error", [("", str(error))])
    except SceneError as error:  # CompareError (LAMMPS cannot represent it or the option) or SweepError
        refuse(f"cannot compare {scene_file} with LAMMPS", error.problems)
    folder = output or fresh_folder(Path("runs") / "compare" / f"{scene.name}-lammps-{label}")
    _write(comparison, folder, overwrite, created=output is None)
    out.print(_speeds_table(comparison.columns()))
    for line in summary_lines(comparison):
        say(line)
    say(f"comparison written to {folder}")


def _write(comparison, folder: Path, overwrite: bool, created: bool) -> None:
    """comparison.csv, comparison.png, summary.txt, in.lammps and config.yaml, each atomically; a
    folder created for them (`created`: made already, by `fresh_folder`) is removed again if a
    write fails."""
    with removed_on_failure(folder, created):
        if not created:
            make_folder(folder, exist_ok=overwrite, holds="comparison")
        write_text(folder / "config.yaml", scene_yaml(comparison.scene))
        write_text(folder / "comparison.csv", table_csv(comparison))
        write_text(folder / "summary.txt", "\n".join(summary_lines(comparison)) + "\n")
        write_text(folder / "in.lammps", lammps_input(comparison))
        keyword = comparison.model.model.keyword
        title = f"{comparison.scene.name}: impact against LAMMPS {keyword}"
        save_comparison_figure(comparison.columns(), title, keyword, folder / FIGURE)


def _speeds_table(columns: dict[str, np.ndarray]) -> Table:
    """Per speed: restitution by both codes, their relative difference and LAMMPS's step error."""
    table = Table(title=Text("restitution: impact against LAMMPS"))
    for name in ("v₀ m/s", "e impact", "e LAMMPS", "Δe/e", "dt error", "impact", "LAMMPS"):
        table.add_column(Text(name), justify="right")
    for row in zip(
        columns["velocity"],
        columns["impact_restitution"],
        columns["lammps_restitution"],
        columns["restitution_difference"],
        columns["restitution_step_error"],
        columns["impact_status"],
        columns["lammps_captured"],
        strict=True,
    ):
        v, ours, theirs, difference, step, status, captured = row
        cells = (f"{v:.4g}", f"{ours:.6f}", f"{theirs:.6f}", f"{difference:.2e}", f"{step:.1e}", str(status))
        table.add_row(*(Text(cell) for cell in cells), Text("captured" if captured else "separated"))
    table.caption = Text("Δe/e = (e_LAMMPS − e_impact)/e_impact; dt error = |e(dt) − e(dt/2)|/e_impact")
    return table
