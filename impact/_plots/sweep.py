"""The figure of a sweep: the coefficient of restitution against the velocity (or the first
axis), simulated points beside the closed form, and their difference."""

import math
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .._integrate.codes import RESULT_CODE
from .._run.sweep.closed_forms import closed_form_name
from .._run.sweep.result import SweepResult
from .._run.sweep.theory_curves import VELOCITY, series_along_x, theory_dense
from .._scene.paths import with_values
from .figures import write_figures

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def restitution_figure(result: SweepResult, max_series: int = 12) -> "Figure":
    """e against the velocity (log axis) for each value of the other axes: simulated points
    (open markers, gid "simulated") and the closed-form curve beside them (lines, gid
    "theory"); below, |e − e_theory| of the separated points."""
    from matplotlib.figure import Figure

    path, x, series = series_along_x(result)
    has_theory = bool(np.isfinite(result.theory_restitution).any())
    figure = Figure(figsize=(7.5, 7.0 if has_theory else 5.0), layout="constrained")
    if has_theory:
        top, bottom = figure.subplots(2, 1, sharex=True, height_ratios=(3, 1.3))
    else:
        top, bottom = figure.subplots(), None
    for k, (fixed, members) in enumerate(series[:max_series]):
        _draw_series(top, bottom, result, path, x, fixed, members, k)
    if len(series) > max_series:
        top.text(0.02, 0.02, f"{max_series} of {len(series)} series shown", transform=top.transAxes, fontsize="small")
    format_x_axes([axes for axes in (top, bottom) if axes is not None], x)
    top.set_ylabel("coefficient of restitution e")
    top.axhline(0.0, color="0.6", lw=0.8, zorder=0)
    top.legend(loc="lower right", fontsize="x-small")
    top.set_title(f"{result.scene.name}: restitution against {path.split('.')[-1]} ({result.restitution.size} points)")
    unit = " (m/s)" if path == VELOCITY else ""
    (bottom or top).set_xlabel(f"{path}{unit}")
    if bottom is not None:
        bottom.set_yscale("log")
        bottom.set_ylabel("|e − e_theory|\n(separated points)")
    return figure


def _draw_series(top, bottom, result: SweepResult, path: str, x: np.ndarray, fixed: dict, members, k: int) -> None:
    """One series (the other axes at `fixed`, points `members` sorted by x) in colour Ck: the
    closed-form curve and the errors below (where it has a closed form), the simulated points,
    and red crosses at e = 0 for points without a physical outcome."""
    e = result.restitution.reshape(-1)
    theory_e = result.theory_restitution.reshape(-1)
    status = result.status.reshape(-1)
    color, label = f"C{k % 10}", series_label(fixed)
    suffix = f": {label}" if label else ""
    outcome = np.isin(status[members], (RESULT_CODE["separated"], RESULT_CODE["captured"]))
    ok, failed = members[outcome], members[~outcome]
    if np.isfinite(theory_e[members]).any():
        name = closed_form_name(with_values(result.scene, fixed))
        dense_x, dense_e = theory_dense(result.spec, fixed, path, float(x[members].min()), float(x[members].max()))
        top.plot(dense_x, dense_e, "-", color=color, lw=1.1, zorder=4, gid="theory", label=f"{name}{suffix}")
        separated = ok[(status[ok] == RESULT_CODE["separated"]) & np.isfinite(theory_e[ok])]
        error = np.abs(e[separated] - theory_e[separated])
        bottom.plot(x[separated], np.maximum(error, 1e-17), ".", ms=2 if len(separated) > 1000 else 3, color=color)
    # open markers under the closed-form line; at most ~300 drawn per series (all kept as data)
    every = max(1, len(ok) // 300)
    top.plot(
        x[ok],
        e[ok],
        "o",
        ms=3.5,
        mfc="none",
        mew=0.8,
        color=color,
        alpha=0.7,
        zorder=3,
        gid="simulated",
        markevery=every,
        label=f"simulated{suffix}",
    )
    if failed.size:
        top.plot(
            x[failed],
            np.zeros(failed.size),
            "x",
            color="red",
            ms=5,
            zorder=4,
            label="no physical outcome (see status)" if k == 0 else None,
        )


def format_x_axes(axes_list: list, x: np.ndarray) -> None:
    """A log x axis with plain-number ticks where x > 0 spans more than a decade; a grid."""
    from matplotlib.ticker import FormatStrFormatter, FuncFormatter, NullFormatter

    logarithmic = bool(np.all(x > 0)) and x.max() / x.min() > 10
    for axes in axes_list:
        if logarithmic:
            axes.set_xscale("log")
            axes.xaxis.set_major_formatter(FormatStrFormatter("%g"))
            few_decades = math.log10(x.max() / x.min()) < 2.5
            axes.xaxis.set_minor_formatter(FuncFormatter(_two_and_five) if few_decades else NullFormatter())
        axes.grid(alpha=0.3, which="both")


def save_restitution_figure(result: SweepResult, path: "str | Path") -> Path:
    """Write the restitution figure to `path` at 150 dpi, atomically."""
    path = Path(path)
    return write_figures(path.parent, [(path.name, restitution_figure(result))])[0]


def series_label(fixed: dict) -> str:
    """The other axes' values of a series, e.g. "work_of_adhesion = 0.05"."""
    return ", ".join(f"{p.split('.')[-1]} = {v:.4g}" for p, v in fixed.items())


def _two_and_five(value, _position) -> str:
    """Minor tick label of a log axis spanning few decades: 2 and 5 times a power of 10."""
    if value <= 0:
        return ""
    mantissa = round(value / 10 ** math.floor(math.log10(value)), 6)
    return f"{value:g}" if mantissa in (2.0, 5.0) else ""
