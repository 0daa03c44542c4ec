"""Figures of one impact run (matplotlib's Agg canvas, imported only where a figure is drawn).

`time_figure`: indentation and force against time, with the events marked.
`force_indentation_figure`: the simulated force–indentation loop beside the closed-form
equilibrium curves of the profile, d(a) = g(a) − √(2πaΔγ/E*), F(a) = 2E*(a·d − G(a))
(JKR for adhesion, Hertz or the non-adhesive MDR curve for Δγ = 0).
"""

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .._run.impacts import Result
from .._scene.scene import Scene
from .figures import frame_force_indentation, si_prefix, write_figures
from .profile_curve import profile_along_radius

if TYPE_CHECKING:
    from matplotlib.figure import Figure

FIGURES = ("time.png", "force_indentation.png")
# Axes placed by hand (fractions of the figure; room for two-line labels and titles and tick
# labels of up to five characters, which `si_prefix` keeps them to): matplotlib's constrained
# layout would measure every text first, drawing each figure twice (a third of a run's time).
_TIME_LAYOUT = {"left": 0.13, "right": 0.985, "bottom": 0.08, "top": 0.905, "hspace": 0.06}
_LOOP_LAYOUT = {"left": 0.11, "right": 0.98, "bottom": 0.085, "top": 0.9}
_EVENT_MARKERS = {
    "touch": "o",
    "max_indentation": "^",
    "detach_start": "D",
    "snap_in": ">",
    "snap_out": "<",
    "separation": "s",
    "capture": "X",
    "limit": "*",
}


def save_figures(result: Result, folder: str | Path) -> list[Path]:
    """Write `time.png` and `force_indentation.png` into `folder` (atomically); return their paths."""
    return write_figures(folder, zip(FIGURES, (time_figure(result), force_indentation_figure(result)), strict=True))


def time_figure(result: Result) -> "Figure":
    """Indentation (top) and force (bottom) against time; events marked on the indentation."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(7.5, 6))
    top, bottom = figure.subplots(2, 1, sharex=True, gridspec_kw=_TIME_LAYOUT)
    time_factor, time_prefix = si_prefix(np.max(np.abs(result.t), initial=0.0))
    length_factor, length_prefix = _scale(result.indentation)
    force_factor, force_prefix = _scale(result.force)
    t = result.t * time_factor
    top.plot(t, result.indentation * length_factor, color="C0", lw=1.5, label="indentation d")
    for kind, marker in _EVENT_MARKERS.items():
        times = np.array([time for time, event in result.events if event == kind])
        if times.size:
            depth = np.interp(times, result.t, result.indentation) * length_factor
            top.plot(times * time_factor, depth, marker, color="k", ms=6, mfc="none", label=kind.replace("_", " "))
    bottom.plot(t, result.force * force_factor, color="C3", lw=1.5)
    for axes in (top, bottom):
        axes.axhline(0.0, color="0.6", lw=0.8, zorder=0)
        axes.grid(alpha=0.3)
    top.set_ylabel(f"indentation d ({length_prefix}m)\n> 0 pressed in")
    bottom.set_ylabel(f"force F ({force_prefix}N)\n> 0 compressive, < 0 adhesive")
    bottom.set_xlabel(f"time t ({time_prefix}s)")
    top.legend(loc="best", fontsize="small")
    figure.suptitle(f"{result.scene.name}: indentation and force against time\n{_outcome(result)}")
    return figure


def force_indentation_figure(result: Result) -> "Figure":
    """The simulated force–indentation loop (contacts only) and the closed-form curves."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(7, 5.5))
    axes = figure.subplots(gridspec_kw=_LOOP_LAYOUT)
    contact = _in_contact(result.contact_radius)
    indentation = np.where(contact, result.indentation, np.nan)
    force = np.where(contact, result.force, np.nan)
    length_factor, length_prefix = _scale(indentation)
    force_factor, force_prefix = _scale(force)
    largest_radius = np.max(result.contact_radius, initial=0.0)
    for label, (d, F), style in _closed_form_curves(result.scene, 1.05 * largest_radius):
        axes.plot(d * length_factor, F * force_factor, style, color="0.35", lw=1.2, label=label)
    axes.plot(indentation * length_factor, force * force_factor, color="C0", lw=1.8, alpha=0.85, label="simulation")
    frame_force_indentation(axes, length_prefix, force_prefix, legend="upper left")
    axes.set_title(f"{result.scene.name}: force against indentation\n{_outcome(result)}")
    return figure


def equilibrium_curve(scene: Scene, work_of_adhesion: float, largest_radius: float, points: int = 400):
    """(d, F) in SI along contact radii 0 ≤ a ≤ largest_radius (m) of the scene's profile:
    d = g(a) − √(2πaΔγ/E*), F = 2E*(a·d − G(a)); Δγ = 0 is the non-adhesive curve."""
    modulus = scene.material.effective_modulus
    radius, g, G = profile_along_radius(scene.contact_profile.build(), largest_radius, points)
    d = g - np.sqrt(2 * np.pi * radius * work_of_adhesion / modulus)
    force = 2 * modulus * (radius * d - G)
    finite = np.isfinite(d) & np.isfinite(force)
    return d[finite], force[finite]


def _closed_form_curves(scene: Scene, largest_radius: float):
    """(label, (d, F), line style) of the unloading curve and, if it differs, the loading one."""
    adhesion = scene.active_adhesion
    unloading = adhesion.work_of_adhesion if adhesion is not None else 0.0
    loading = adhesion.approach if adhesion is not None else 0.0
    curves = [(_curve_name(scene, unloading), equilibrium_curve(scene, unloading, largest_radius), "--")]
    if loading != unloading:
        name = f"loading: {_curve_name(scene, loading)} (Δγa)"
        curves.append((name, equilibrium_curve(scene, loading, largest_radius), ":"))
    return curves


def _curve_name(scene: Scene, work_of_adhesion: float) -> str:
    if work_of_adhesion > 0:
        return f"JKR, Δγ = {work_of_adhesion:.3g} J/m²"
    return "Hertz" if scene.contact_profile.shape == "paraboloid" else "non-adhesive MDR"


def _in_contact(contact_radius: np.ndarray) -> np.ndarray:
    """Samples in contact and their neighbours (so that jump-in and pull-off show as jumps)."""
    touching = contact_radius > 0
    around = touching.copy()
    around[1:] |= touching[:-1]
    around[:-1] |= touching[1:]
    return around


def _scale(values: np.ndarray) -> tuple[float, str]:
    finite = np.abs(values[np.isfinite(values)])
    return si_prefix(np.max(finite, initial=0.0))


def _outcome(result: Result) -> str:
    return f"{result.status}, e = {result.restitution:.6f}, {result.bounces} contact(s)"
