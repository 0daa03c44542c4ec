"""Figures of a viscoelastic half-space (matplotlib's Agg canvas, imported only where drawn).

`rate_test_figure`: a test at a rate, indentation and force against time (what `impact run`
writes as `time.png` beside the force–indentation curve).
`deborah_figure`: the restitution of the micro-sphere of configs/viscoelastic_sphere.yaml
(without adhesion) against the Deborah number t_c/τ, and `pull_off_figure`: the largest tensile
force of a displacement-controlled retraction against the pulling rate, between its relaxed and
glassy limits. The documentation's images are made with

    python -c "from impact._plots.viscoelastic import deborah_figure, pull_off_figure; \\
        deborah_figure().savefig('docs/src/images/viscoelastic_deborah.png', dpi=130); \\
        pull_off_figure().savefig('docs/src/images/viscoelastic_pull_off.png', dpi=130)"
"""

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .. import theory
from .._run.indentation import IndentationResult
from .._run.sweep.execute import sweep
from .._scene.profiles import ParaboloidSpec
from .._scene.scene import load_scene
from .figures import si_prefix

if TYPE_CHECKING:
    from matplotlib.figure import Figure

CONFIGS = Path(__file__).parents[2] / "configs"
# The e(De) sweep: relaxation times around the contact time, three speeds, no adhesion.
_DEBORAH_TIMES = np.geomspace(5e-10, 5e-4, 49)
_SPEEDS = (1.0, 3.0, 10.0)
# The pull-off: a 10 µm probe 20 µm deep into a standard linear solid, E₀*/E∞* = 4, Δγ = 0.05 J/m².
_RATES = np.geomspace(1e-9, 1e3, 37)


def rate_test_figure(result: IndentationResult) -> "Figure":
    """Indentation (top) and force (bottom) of a test at a rate against time."""
    from matplotlib.figure import Figure

    assert result.time is not None, "a test at a rate has a time"
    figure = Figure(figsize=(7.5, 6), layout="constrained")
    top, bottom = figure.subplots(2, 1, sharex=True)
    length_factor, length_prefix = si_prefix(np.max(np.abs(result.indentation), initial=0.0))
    force_factor, force_prefix = si_prefix(np.max(np.abs(result.force), initial=0.0))
    top.plot(result.time, result.indentation * length_factor, color="C0", lw=1.5)
    bottom.plot(result.time, result.force * force_factor, color="C3", lw=1.5)
    top.set_ylabel(f"indentation d ({length_prefix}m)")
    bottom.set_ylabel(f"force F ({force_prefix}N)")
    bottom.set_xlabel("time (s)")
    for axes in (top, bottom):
        axes.axhline(0.0, color="0.6", lw=0.8, zorder=0)
        axes.grid(alpha=0.3)
    top.set_title(f"{result.scene.name}: {result.scene.control} control at a rate, {result.status}", fontsize="medium")
    return figure


def deborah_figure() -> "Figure":
    """e against De = t_c/τ (t_c: Hertz's contact time of the relaxed medium) at three speeds."""
    from matplotlib.figure import Figure

    scene = load_scene(CONFIGS / "viscoelastic_sphere.yaml")
    base = scene.model_copy(update={"effects": scene.effects.model_copy(update={"adhesion": None})})
    result = sweep(base, {"effects.viscoelasticity.prony.0.time": _DEBORAH_TIMES, "initial.velocity": list(_SPEEDS)})
    figure = Figure(figsize=(7.5, 4.8), layout="constrained")
    axes = figure.subplots()
    relaxed, profile = scene.material.effective_modulus, scene.contact_profile
    assert isinstance(profile, ParaboloidSpec), "the micro-sphere's tip is a paraboloid"
    for column, speed in enumerate(_SPEEDS):
        contact = float(theory.hertz_contact_time(speed, scene.reduced_mass, profile.R, relaxed))
        deborah = contact / _DEBORAH_TIMES
        restitution = result.restitution[:, column]
        axes.plot(deborah, restitution, "o-", ms=3, label=f"v₀ = {speed:g} m/s")
        lowest = int(np.nanargmin(restitution))
        axes.plot(deborah[lowest], restitution[lowest], "k*", ms=9)
    axes.set(xscale="log", xlabel="Deborah number De = t_c/τ (t_c: Hertz, E∞*)", ylabel="restitution e")
    axes.grid(alpha=0.3)
    axes.legend(fontsize="small", title="★ the minimum")
    axes.set_title("Viscoelastic micro-sphere (configs/viscoelastic_sphere.yaml, no adhesion)", fontsize="medium")
    return figure


def pull_off_figure() -> "Figure":
    """|min F|/((3/2)πRΔγ) of a displacement-controlled retraction against the rate, with the
    relaxed (E₀*/E∞*) and glassy (1) limits."""
    from matplotlib.figure import Figure

    from .._run.viscoelastic_indentation import simulate_rate_test

    radius, work, ratio = 1e-5, 0.05, 4.0
    forces = []
    for rate in _RATES:
        scene = load_scene(
            {
                "name": "pull_off",
                "kind": "indentation",
                "control": "displacement",
                "program": {"peak": 2e-5, "rate": float(rate)},
                "body": {"profile": {"shape": "paraboloid", "R": radius}},
                "material": {"E_star": 1e6},
                "contact": {"springs": 2000},
                "effects": {
                    "viscoelasticity": {"prony": [{"modulus": 3e6, "time": 0.5}]},
                    "adhesion": {"work_of_adhesion": work},
                },
            }
        )
        forces.append(-float(np.min(simulate_rate_test(scene).force)) / (1.5 * np.pi * radius * work))
    figure = Figure(figsize=(7.5, 4.8), layout="constrained")
    axes = figure.subplots()
    axes.plot(_RATES, forces, "o-", ms=3, label="springs (N = 2000)")
    for value, name, style in ((ratio, "relaxed: (3/2)πRΔγ·E₀*/E∞*", "k--"), (1.0, "glassy: (3/2)πRΔγ", "k:")):
        axes.plot(_RATES[[0, -1]], [value, value], style, lw=0.9, label=name)
    axes.set(xscale="log", xlabel="pulling rate (m/s)", ylabel="largest tensile force / ((3/2)πRΔγ)")
    axes.grid(alpha=0.3)
    axes.legend(fontsize="small")
    axes.set_title("Pull-off of a 10 µm probe from a standard linear solid (τ = 0.5 s)", fontsize="medium")
    return figure
