"""Figures of one indentation test (matplotlib's Agg canvas, imported only where a figure is drawn).

`force_indentation_figure`: the force–indentation curve in SI, the program's path (jumps as
straight segments) over the whole equilibrium curve d(a) = g(a) − Δl(a), F(a) = 2E*(a·d − G(a)),
with the pull-off marked. For a finite-range law (Maugis–Dugdale, Greenwood–Johnson) that curve is
its JKR limit, drawn with its DMT limit: the Hertz curve less the pull-off πσ0b², f(b) = h
(3.180, 3.195; Bradley's 2πRΔγ for the double Hertz).
`normalized_figure`: the chapter's normalized curves (Figs. 3.6–3.7, 3.10–3.11): F̂ and d̂
against â, and F̂ against d̂, in units of the pull-off |F_c|, |d_c| and a_c of the run itself
(for a paraboloid under force control these are (3.46) and the curves are (3.49)).
"""

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .._run.indentation import IndentationResult
from .figures import frame_force_indentation, si_prefix, write_figures
from .profile_curve import profile_along_radius

if TYPE_CHECKING:
    from matplotlib.figure import Figure

FIGURES = ("force_indentation.png", "normalized.png")
TIMED_FIGURES = ("force_indentation.png", "time.png")
_MARKERS = {"touch": "o", "snap_in": ">", "snap_out": "<", "pull_off": "s", "reversal": "^"}


def save_indentation_figures(result: IndentationResult, folder: str | Path) -> list[Path]:
    """Write the two figures into `folder` (atomically); return their paths. A viscoelastic
    test at a rate draws its curve against time (`time.png`) instead of the normalized one."""
    if result.time is not None:
        from .viscoelastic import rate_test_figure

        return write_figures(
            folder, zip(TIMED_FIGURES, (force_indentation_figure(result), rate_test_figure(result)), strict=True)
        )
    return write_figures(
        folder, zip(FIGURES, (force_indentation_figure(result), normalized_figure(result)), strict=True)
    )


def _title(result: IndentationResult) -> str:
    pull_off = result.pull_off
    control = f"{result.scene.control} control (ξ = {result.xi})"
    if not np.isfinite(pull_off.force):
        return f"{result.scene.name}: {control}, {result.status}"
    return f"{result.scene.name}: {control}, pull-off F = {pull_off.force:.4g} N at d = {pull_off.indentation:.4g} m"


def equilibrium(result: IndentationResult, points: int = 800):
    """(a, d, F) in SI along the detach edge up to the largest radius of the run:
    d = g(a) − √(2πaΔγ/E*), F = 2E*(a·d − G(a)) (3.27–3.28), every state stable or not."""
    scene = result.scene
    profile = scene.body.profile.build()
    modulus = scene.material.effective_modulus
    adhesion = scene.active_adhesion
    work = adhesion.work_of_adhesion if adhesion is not None else 0.0
    radius, g, G = profile_along_radius(profile, 1.02 * result.max_contact_radius, points)
    d = g - np.sqrt(2 * np.pi * radius * work / modulus)
    force = 2 * modulus * (radius * d - G)
    finite = np.isfinite(d) & np.isfinite(force)
    return radius[finite], d[finite], force[finite]


def dmt_limit(result: IndentationResult, points: int = 800):
    """(a, d, F) in SI of the DMT limit of a finite-range law up to the largest radius of the
    run: the Hertz curve d = g(a), F = 2E*(a·d − G(a)) less the DMT pull-off; None for JKR."""
    scene = result.scene
    adhesion = scene.active_adhesion
    profile = scene.body.profile.build()
    pull_off = None if adhesion is None else adhesion.dmt_pull_off(profile)
    if pull_off is None:
        return None
    modulus = scene.material.effective_modulus
    radius, d, G = profile_along_radius(profile, 1.02 * result.max_contact_radius, points)
    force = 2 * modulus * (radius * d - G) - pull_off
    shown = np.isfinite(d) & np.isfinite(force) & (d <= 1.02 * result.max_indentation)
    return radius[shown], d[shown], force[shown]


def _limits(result: IndentationResult):
    """(label, line style, (a, d, F)) of the curves drawn under the program's path."""
    dmt = dmt_limit(result)
    if result.scene.effects.viscoelasticity is not None:
        return [("equilibrium curve of the relaxed medium (E∞*)", "--", equilibrium(result))]
    if dmt is None:
        return [("equilibrium curve", "--", equilibrium(result))]
    return [("JKR limit", "--", equilibrium(result)), ("DMT limit", ":", dmt)]


def force_indentation_figure(result: IndentationResult) -> "Figure":
    """F against d in SI: the equilibrium curve (dashed) and the program's path."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(7, 5.5), layout="constrained")
    axes = figure.subplots()
    length_factor, length_prefix = si_prefix(np.max(np.abs(result.indentation), initial=0.0))
    force_factor, force_prefix = si_prefix(np.max(np.abs(result.force), initial=0.0))
    for label, style, (_, d, F) in _limits(result):
        axes.plot(d * length_factor, F * force_factor, style, color="0.45", lw=1.0, label=label)
    axes.plot(result.indentation * length_factor, result.force * force_factor, color="C0", lw=1.6, label="program")
    for kind, marker in _MARKERS.items():
        points = [index for index, event in result.events if event == kind]
        if points:
            axes.plot(
                result.indentation[points] * length_factor,
                result.force[points] * force_factor,
                marker,
                color="k",
                mfc="none",
                ms=6,
                label=kind.replace("_", " "),
            )
    frame_force_indentation(axes, length_prefix, force_prefix, legend="best")
    axes.set_title(_title(result), fontsize="medium")
    return figure


def normalized_figure(result: IndentationResult) -> "Figure":
    """â = a/a_c, d̂ = d/|d_c|, F̂ = F/|F_c| with the run's pull-off: F̂(â), d̂(â) and F̂(d̂)."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(11, 4.8), layout="constrained")
    left, right = figure.subplots(1, 2)
    pull_off = result.pull_off
    a_c, d_c, F_c = abs(pull_off.contact_radius), abs(pull_off.indentation), abs(pull_off.force)
    usable = all(np.isfinite(v) and v > 0 for v in (a_c, d_c, F_c))
    if not usable:  # no pull-off (or one at a = 0): the largest values of the run instead
        a_c = result.max_contact_radius or 1.0
        d_c = np.max(np.abs(result.indentation), initial=0.0) or 1.0
        F_c = np.max(np.abs(result.force), initial=0.0) or 1.0
    limits = _limits(result)
    for _, style, (a_eq, d_eq, F_eq) in limits:
        left.plot(a_eq / a_c, F_eq / F_c, style, color="C3", lw=1.0)
        left.plot(a_eq / a_c, d_eq / d_c, style, color="C0", lw=1.0)
    left.plot(result.contact_radius / a_c, result.force / F_c, color="C3", lw=1.6, label="F̂ = F/|F_c|")
    left.plot(result.contact_radius / a_c, result.indentation / d_c, color="C0", lw=1.6, label="d̂ = d/|d_c|")
    left.set_xlabel("â = a/a_c")
    left.legend(loc="best", fontsize="small")
    for label, style, (_, d_eq, F_eq) in limits:
        right.plot(d_eq / d_c, F_eq / F_c, style, color="0.45", lw=1.0, label=label)
    right.plot(result.indentation / d_c, result.force / F_c, color="C0", lw=1.6, label="program")
    right.set_xlabel("d̂ = d/|d_c|")
    right.set_ylabel("F̂ = F/|F_c|")
    right.legend(loc="best", fontsize="small")
    for axes in (left, right):
        axes.axhline(0.0, color="0.6", lw=0.8, zorder=0)
        axes.grid(alpha=0.3)
    basis = "the pull-off of this run" if usable else "the largest values of this run"
    figure.suptitle(f"{_title(result)}\nnormalized by {basis}", fontsize="medium")
    return figure
