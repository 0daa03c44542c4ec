"""The figure of a sweep's named losses: each loss's share of the impact energy ½mv₀² against
the velocity (or the first axis), drawn only for a sweep whose scene names a loss."""

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .._integrate.codes import RESULT_CODE
from .._run.sweep.result import SweepResult
from .._run.sweep.theory_curves import VELOCITY, series_along_x
from .._scene.paths import with_values
from .figures import write_figures
from .sweep import format_x_axes, series_label

if TYPE_CHECKING:
    from matplotlib.figure import Figure

LINE_STYLES = ("-", "--", ":", "-.")


def losses_figure(result: SweepResult, max_series: int = len(LINE_STYLES)) -> "Figure":
    """Each named loss of the first contact over ½mv₀² (m the reduced mass) against the x axis,
    for the separated points: one colour per loss, one line style per series of the other
    axes (gid: the loss's name)."""
    from matplotlib.figure import Figure

    losses = result.named_losses()
    if not losses:
        raise ValueError(f"the sweep of {result.scene.name!r} names no loss (plasticity, damping, adhesion)")
    path, x, series = series_along_x(result)
    flat = {p: v.reshape(-1) for p, v in result.params.items()}
    mass = np.broadcast_to(with_values(result.scene, flat).reduced_mass, x.shape)
    energy = 0.5 * mass * result.touch_velocity.reshape(-1) ** 2
    separated = result.status.reshape(-1) == RESULT_CODE["separated"]
    figure = Figure(figsize=(7.5, 5.0), layout="constrained")
    axes = figure.subplots()
    for k, (fixed, members) in enumerate(series[:max_series]):
        shown = members[separated[members]]
        suffix = f": {series_label(fixed)}" if fixed else ""
        for colour, (name, column) in enumerate(losses.items()):
            share = column.reshape(-1)[shown] / energy[shown]
            axes.plot(
                x[shown],
                share,
                LINE_STYLES[k],
                marker=".",
                ms=3,
                lw=1.0,
                color=f"C{colour}",
                gid=name,
                label=f"{name.replace('_', ' ')}{suffix}",
            )
    if len(series) > max_series:
        axes.text(0.02, 0.02, f"{max_series} of {len(series)} series shown", transform=axes.transAxes, fontsize="small")
    format_x_axes([axes], x)
    axes.set_ylabel("share of the impact energy ½mv₀²\n(separated points)")
    unit = " (m/s)" if path == VELOCITY else ""
    axes.set_xlabel(f"{path}{unit}")
    axes.set_title(f"{result.scene.name}: the losses of the first contact")
    axes.legend(fontsize="x-small")
    return figure


def save_losses_figure(result: SweepResult, path: "str | Path") -> Path:
    """Write the losses figure to `path` at 150 dpi, atomically."""
    path = Path(path)
    return write_figures(path.parent, [(path.name, losses_figure(result))])[0]
