"""The written comparison: the table as CSV and the summary in words (mapping, what LAMMPS leaves
out, the largest differences beside LAMMPS's step error, timing)."""

import csv
import io

import numpy as np

from .comparison import IMPACT_ACCURACY, QUANTITIES, STEP_ERROR_FACTOR, Comparison, finite_max

UNITS = {"velocity": "m/s", "contact_time": "s", "max_force": "N", "min_force": "N"}


def table_csv(comparison: Comparison) -> str:
    """The table as CSV: one row per speed; numbers to 17 significant digits, inf and nan as such."""
    columns = comparison.columns()
    text = io.StringIO()
    writer = csv.writer(text, lineterminator="\n")
    writer.writerow(columns)
    for row in zip(*columns.values(), strict=True):
        writer.writerow([_cell(value) for value in row])
    return text.getvalue()


def _cell(value) -> str:
    if isinstance(value, np.bool_ | bool):
        return "true" if value else "false"
    if isinstance(value, np.floating | float):
        return f"{float(value):.17g}"
    return str(value)


def summary_lines(comparison: Comparison) -> list[str]:
    """The summary of a comparison, line by line."""
    model, lammps, half = comparison.model, comparison.lammps, comparison.half_step
    speeds = comparison.velocities
    count = len(speeds)
    lines = [
        f"{comparison.scene.name}: LAMMPS {lammps.version} granular {model.model.keyword} against impact, "
        f"{count} speeds from {speeds.min():g} to {speeds.max():g} m/s",
        "mapping:",
        *(f"  {note}" for note in model.notes),
        f"what LAMMPS's {model.model.keyword} leaves out: {model.left_out}",
        f"time step: dt = {lammps.dt:.4g} s ({lammps.steps} steps), and dt/2 ({half.steps} steps); a particle still "
        "in contact when the run stops is captured",
        f"largest |relative difference| (LAMMPS − impact)/impact beside LAMMPS's step error |X(dt) − X(dt/2)|/impact "
        f"(agreement: within {STEP_ERROR_FACTOR:g}× the step error + {IMPACT_ACCURACY:g} at every speed both let go):",
    ]
    table, agreement = comparison.columns(), comparison.agreement()
    for name in QUANTITIES:
        unit = f" ({UNITS[name]})" if name in UNITS else ""
        difference, step = finite_max(table[f"{name}_difference"]), finite_max(table[f"{name}_step_error"])
        if np.isnan(difference):
            lines.append(f"  {name}{unit}: not compared (impact's is 0, or no speed let go in both)")
            continue
        verdict = "agree to the step error" if agreement[name] else "differ beyond the step error"
        lines.append(f"  {name}{unit}: {difference:.3g}, step error {step:.3g}: {verdict}")
    ratio = table["energy_loss_ratio"]
    shown = ratio[np.isfinite(ratio)]
    if shown.size:
        lines.append(
            f"energy lost, LAMMPS over impact: {shown.min():.4g} to {shown.max():.4g} (median {np.median(shown):.4g})"
        )
    captured_by_impact = int(np.sum(table["impact_status"] == "captured"))
    lines.append(f"captured: impact {captured_by_impact} of {count}, LAMMPS {int(np.sum(lammps.captured))} of {count}")
    stats = comparison.impact.stats
    lines.append(
        f"timing: LAMMPS {lammps.seconds:.3g} s at dt ({1e3 * lammps.seconds / count:.3g} ms per impact), "
        f"{half.seconds:.3g} s at dt/2; impact.sweep {comparison.impact_seconds:.3g} s "
        f"({stats['compile_time']:.3g} s compiling, {stats['solve_time']:.3g} s solving: "
        f"{1e3 * stats['solve_time'] / count:.3g} ms per impact)"
    )
    return lines


def lammps_input(comparison: Comparison) -> str:
    """The LAMMPS input of the run at dt, as run (its blocks of steps as one run)."""
    header = "# The LAMMPS input of `impact compare lammps` (the run at dt), in SI units: run it with `lmp -in`.\n"
    return header + "\n".join(comparison.lammps.commands) + "\n"
