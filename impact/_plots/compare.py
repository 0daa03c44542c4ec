"""The figure of `impact compare lammps`: restitution, contact time and largest force against the
velocity by impact and by LAMMPS (at dt and dt/2), and their relative difference beside LAMMPS's
own step error. It takes the comparison's table (`impact._compare.comparison.Comparison.columns`)."""

from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .figures import si_prefix, write_figures

if TYPE_CHECKING:
    from matplotlib.figure import Figure

FIGURE = "comparison.png"
_PANELS = (
    ("restitution", "coefficient of restitution e", ""),
    ("contact_time", "contact time", "s"),
    ("max_force", "largest compressive force", "N"),
)


def comparison_figure(columns: Mapping[str, np.ndarray], title: str, model: str) -> "Figure":
    """Three panels of a quantity against the velocity (impact: line and dots; LAMMPS at dt: open
    circles, at dt/2: crosses; captured points at e = 0 and off the other panels) and a fourth of
    |relative difference| (filled) and LAMMPS's relative step error (open), log scale."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(10.0, 7.5), layout="constrained")
    axes = figure.subplots(2, 2, sharex=True).reshape(-1)
    velocity = columns["velocity"]
    for panel, (name, label, unit) in zip(axes[:3], _PANELS, strict=True):
        ours, theirs, half = (columns[key] for key in (f"impact_{name}", f"lammps_{name}", f"lammps_{name}_half_step"))
        finite = np.concatenate([values[np.isfinite(values)] for values in (ours, theirs)])
        factor, prefix = si_prefix(float(np.max(np.abs(finite), initial=0.0)) if unit else 1.0)
        panel.plot(velocity, ours * factor, ".-", color="C0", lw=1.2, label="impact (exact MDR law)")
        panel.plot(velocity, theirs * factor, "o", mfc="none", color="C3", ms=6, label=f"LAMMPS {model}, dt")
        panel.plot(velocity, half * factor, "x", color="C1", ms=4, label=f"LAMMPS {model}, dt/2")
        panel.set_ylabel(f"{label} ({prefix}{unit})" if unit else label)
        panel.grid(alpha=0.3)
    axes[0].legend(fontsize="small", loc="lower right")
    _draw_differences(axes[3], columns)
    for panel in axes[2:]:
        panel.set_xlabel("velocity v₀ (m/s)")
    figure.suptitle(title, fontsize="medium")
    return figure


def _draw_differences(panel, columns: Mapping[str, np.ndarray]) -> None:
    """|relative difference| (filled, solid) and relative step error (open, dashed) per quantity."""
    velocity = columns["velocity"]
    for k, (name, label, _) in enumerate(_PANELS):
        difference = np.abs(columns[f"{name}_difference"])
        panel.plot(velocity, difference, "o-", color=f"C{k}", ms=4, lw=1, label=label.removeprefix("coefficient of "))
        panel.plot(velocity, columns[f"{name}_step_error"], "s--", mfc="none", color=f"C{k}", ms=4, lw=0.8)
    panel.set_yscale("log")
    panel.set_ylabel("relative to impact's value")
    panel.set_title("filled: |LAMMPS − impact|; open: LAMMPS's step error |X(dt) − X(dt/2)|", fontsize="small")
    panel.grid(alpha=0.3, which="both")
    panel.legend(fontsize="x-small", loc="best")


def save_comparison_figure(columns: Mapping[str, np.ndarray], title: str, model: str, path: "str | Path") -> Path:
    """Write the comparison figure to `path` at 150 dpi, atomically."""
    path = Path(path)
    return write_figures(path.parent, [(path.name, comparison_figure(columns, title, model))])[0]
