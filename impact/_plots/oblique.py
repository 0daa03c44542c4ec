"""The figures of oblique impacts: of a sweep over the angle of incidence, tangential
restitution, rebound angle and spin against the angle, beside the rigid-body sliding limit (Maw,
Barber & Fawcett 1976) where the impact slides throughout; of one run, the tangential force and
the slip zone against time.

`impact sweep` writes it as `tangential.png` for a sweep whose scene names friction; the docs'
figures are the sweeps of `configs/sweeps/oblique_*.yaml`, drawn one over another:
    python -c "import impact; from impact._plots.oblique import tangential_figure as f; \
        f([impact.open_sweep('runs/a'), impact.open_sweep('runs/b')], ['a', 'b']).savefig('x.png', dpi=110)"
"""

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .. import theory
from .._run.impacts import Result
from .._run.sweep.result import SweepResult
from .._run.sweep.theory_curves import series_along_x
from .._scene.friction import lever_arm
from .._scene.paths import with_values
from .figures import si_prefix, write_figures

if TYPE_CHECKING:
    from matplotlib.figure import Figure

FIGURE = "tangential.png"
ANGLE = "initial.angle"


def save_tangential_figure(result: SweepResult, folder: "str | Path") -> Path:
    """Write `tangential.png` into `folder` (atomically); return its path."""
    return write_figures(folder, [(FIGURE, tangential_figure([result]))])[0]


def tangential_figure(results: Sequence[SweepResult], labels: Sequence[str] | None = None) -> "Figure":
    """Tangential restitution |v_t′|/v_t, rebound angle and spin ω′ against the sweep's first
    axis (the angle of incidence in degrees where it is swept), one line per series of each
    result; the rigid-body sliding limit dashed where it holds (per-spring friction, no adhesion)."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(7.5, 8.0), layout="constrained")
    panels = figure.subplots(3, 1, sharex=True)
    path = ""
    for index, result in enumerate(results):
        path, x, series = series_along_x(result)
        prefix = f"{labels[index]}" if labels else ""
        for k, (fixed, members) in enumerate(series):
            color = f"C{(index * len(series) + k) % 10}"
            words = ", ".join(f"{p.split('.')[-1]} = {v:.4g}" for p, v in fixed.items())
            label = ": ".join(part for part in (prefix, words) if part) or "simulated"
            shown = _shown(path, x[members])
            columns = (result.tangential_restitution, result.rebound_angle, result.spin_after)
            for axes, column, scale in zip(panels, columns, (1.0, 180.0 / np.pi, 1.0), strict=True):
                assert column is not None, "a sweep with friction holds the tangential columns"
                axes.plot(shown, column.reshape(-1)[members] * scale, "o-", ms=3, color=color, label=label)
            _sliding_limit(panels, result, path, x[members], members)
    panels[0].set_ylabel("tangential restitution |v_t′|/v_t")
    panels[1].set_ylabel("rebound angle (°)")
    panels[2].set_ylabel("spin after ω′ (rad/s)")
    panels[2].set_xlabel("angle of incidence (°)" if path == ANGLE else path)
    panels[0].legend(fontsize="x-small")
    for axes in panels:
        axes.grid(alpha=0.3)
    scene = results[0].scene if results else None
    if scene is not None:
        panels[0].set_title(f"{scene.name}: oblique impacts ({sum(r.restitution.size for r in results)} points)")
    return figure


def _shown(path: str, x: np.ndarray) -> np.ndarray:
    """The axis values as drawn: degrees for the angle of incidence."""
    return np.degrees(x) if path == ANGLE else x


def modulus_ratio(scene) -> float:
    """E*/G* of a scene (numbers, or arrays of a sweep's points)."""
    return scene.material.effective_modulus / scene.material.tangential_modulus


def _sliding_limit(panels, result: SweepResult, path: str, x: np.ndarray, members: np.ndarray) -> None:
    """The rigid-body sliding limit (`theory.sliding_impact`) of each point with per-spring
    friction and no adhesion, dashed where tan θ passes `theory.gross_sliding_tangent`."""
    scene = result.scene
    friction = scene.effects.friction
    if friction is None or friction.limit != "per_spring" or scene.adhesive:
        return
    batch = with_values(scene, {p: v.reshape(-1)[members] for p, v in result.params.items()})
    start, body = batch.start, batch.body
    mass, radius = body.resolved_mass, lever_arm(body.profile)
    inertia = 0.4 * mass * radius**2 if body.inertia is None else body.inertia
    normal, tangential = start.normal_velocity, start.tangential_velocity
    e = result.restitution.reshape(-1)[members]
    mu = batch.effects.friction.coefficient if batch.effects.friction is not None else friction.coefficient
    velocity, spin = (
        np.asarray(v) for v in theory.sliding_impact(normal, tangential, start.spin, e, mu, mass, radius, inertia)
    )
    slides = np.tan(np.broadcast_to(start.angle, e.shape)) >= np.asarray(
        theory.gross_sliding_tangent(e, mu, mass, radius, inertia, modulus_ratio(batch))
    )
    values = (np.abs(velocity) / tangential, np.degrees(np.arctan2(velocity, e * normal)), spin)
    for axes, value in zip(panels, values, strict=True):
        label = "rigid sliding (Maw et al. 1976)" if axes is panels[0] else None
        shown = np.broadcast_to(value, e.shape)[slides]
        axes.plot(_shown(path, x)[slides], shown, "k--", lw=1.2, label=label, zorder=3)


def save_run_tangential_figure(result: Result, folder: "str | Path") -> Path:
    """Write `tangential.png` of one run into `folder` (atomically); return its path."""
    return write_figures(folder, [(FIGURE, run_tangential_figure(result))])[0]


def run_tangential_figure(result: Result) -> "Figure":
    """The tangential force Q with μ·F_n beside it (top), the contact radius a and the inner
    radius c of the slip zone (bottom), against time, samples in contact only."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(7.5, 6), layout="constrained")
    top, bottom = figure.subplots(2, 1, sharex=True)
    contact = result.contact_radius > 0
    time = np.where(contact, result.t, np.nan)
    time_factor, time_prefix = si_prefix(np.max(np.abs(result.t), initial=0.0))
    force_factor, force_prefix = si_prefix(np.max(np.abs(result.force), initial=0.0))
    length_factor, length_prefix = si_prefix(np.max(result.contact_radius, initial=0.0))
    friction = result.scene.effects.friction
    mu = 0.0 if friction is None else friction.coefficient
    top.plot(time * time_factor, result.tangential_force * force_factor, "C0", label="tangential force Q")
    top.plot(time * time_factor, mu * result.force * force_factor, "k:", label="μ·F_n")
    bottom.plot(time * time_factor, result.contact_radius * length_factor, "C1", label="contact radius a")
    bottom.plot(time * time_factor, result.stick_radius * length_factor, "C2", label="stick radius c")
    top.set_ylabel(f"force ({force_prefix}N)")
    bottom.set_ylabel(f"radius ({length_prefix}m)")
    bottom.set_xlabel(f"time t ({time_prefix}s)")
    for axes in (top, bottom):
        axes.grid(alpha=0.3)
        axes.legend(fontsize="small")
    top.set_title(
        f"{result.scene.name}: tangential restitution {result.tangential_restitution:.4g}, "
        f"spin after {result.spin_after:.4g} rad/s"
    )
    return figure
