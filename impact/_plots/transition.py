"""The JKR–DMT transition figure: pull-off force of the paraboloid against the Tabor parameter Λ
(3.172) for Maugis–Dugdale (§3.8, force control) and Greenwood–Johnson (§3.9, force and
displacement control, at the equivalent Λ(k) = (36k²/(π³(1 + k)))^(1/3)), with the JKR and DMT
limits. The documentation's image is made with

    python -c "from impact._plots.transition import pull_off_figure; \\
        pull_off_figure().savefig('docs/src/images/pull_off_transition.png', dpi=150)"

`comparison_figure`: the two laws side by side over Λ, pull-off under both controls with the
quasi-static simulation, restitution from sweeps of impacts, and the range of interaction.
"""

from typing import TYPE_CHECKING

import numpy as np

from .. import theory
from .._scene.adhesion import AbstractAdhesion, GreenwoodJohnsonAdhesion, MaugisDugdaleAdhesion

if TYPE_CHECKING:
    from matplotlib.figure import Figure

# Any R, E*, Δγ: the normalized pull-off depends on Λ (or k) alone.
_R, _E_STAR, _WORK = 1.0e-6, 1.0e9, 0.05


def pull_off_figure(tabors=None) -> "Figure":
    """|F_pull-off|/(πRΔγ) against Λ (default 1e-2 … 1e2): both models, both controls where
    known, both limits."""
    from matplotlib.figure import Figure

    tabors = np.geomspace(1e-2, 1e2, 81) if tabors is None else np.asarray(tabors)
    figure = Figure(figsize=(7.5, 4.8), layout="constrained")
    axes = figure.subplots()
    unit = np.pi * _R * _WORK
    axes.plot(tabors, 1.5 * theory.maugis_pull_off(tabors), label="Maugis–Dugdale, force control", gid="maugis")
    factors = np.asarray(theory.double_hertz_factor(tabors))
    for xi, control, style in ((3, "force control", "-"), (1, "displacement control", "--")):
        force = np.asarray(theory.double_hertz_pull_off(factors, _R, _E_STAR, _WORK, xi)[2])
        axes.plot(
            tabors,
            -force / unit,
            style,
            label=f"Greenwood–Johnson, {control}",
            gid=GreenwoodJohnsonAdhesion.model_name(),
        )
    limits = (
        (2.0, "DMT, Bradley: 2πRΔγ", "k:"),
        (1.5, "JKR: (3/2)πRΔγ", "k-."),
        (5 / 6, "JKR, displacement control: (5/6)πRΔγ", "C2:"),
    )
    for value, name, style in limits:
        axes.plot(tabors[[0, -1]], [value, value], style, linewidth=0.8, label=name, gid="limit")
    axes.set(
        xscale="log",
        xlabel="Tabor parameter Λ (Greenwood–Johnson: Λ(k) = (36k²/(π³(1 + k)))^(1/3))",
        ylabel="pull-off force |F| / (πRΔγ)",
        ylim=(0.6, 2.1),
    )
    axes.legend(fontsize="small")
    return figure


# The particle of configs/thornton_ning.yaml (sticking velocity v_s = 0.3032 m/s) and the impact
# speeds of the restitution panel, in multiples of v_s.
_MASS = 1.0472e-14
_SPEEDS = (1.5, 4.0, 16.0)
_SIMULATED_TABORS = (0.05, 0.3, 1.0, 3.0, 10.0)


def comparison_figure(tabors=None, speeds=_SPEEDS) -> "Figure":
    """Maugis–Dugdale against Greenwood–Johnson over the Tabor parameter Λ (Greenwood–Johnson at
    k(Λ) of `theory.double_hertz_factor`): the pull-off force under force and displacement
    control (closed forms; markers: the quasi-static simulation), the restitution of the
    Thornton–Ning particle at a few impact speeds (simulated sweeps), and the depth at which the
    interaction starts (the range), with the JKR and DMT limits. The documentation's image:

        python -c "import impact; impact.configure(); from impact._plots.transition import \\
            comparison_figure; comparison_figure().savefig('docs/src/images/finite_range_comparison.png', dpi=130)"

    It runs two sweeps of 3 × 13 impacts and 20 quasi-static tests (a few minutes, mostly
    compiling)."""
    from matplotlib.figure import Figure

    tabors = np.geomspace(0.03, 100.0, 13) if tabors is None else np.asarray(tabors)  # k ≤ 1e6
    figure = Figure(figsize=(15, 4.8), layout="constrained")
    pull_off, restitution, reach = figure.subplots(1, 3)
    _pull_off_panel(pull_off)
    _restitution_panel(restitution, tabors, speeds)
    _range_panel(reach)
    for axes in (pull_off, restitution, reach):
        axes.set_xscale("log")
        axes.set_xlabel("Tabor parameter Λ (Greenwood–Johnson: Λ(k) = (36k²/(π³(1 + k)))^(1/3))", fontsize="small")
        axes.grid(alpha=0.3)
    figure.suptitle("Finite-range adhesion of a paraboloid: Maugis–Dugdale (§3.8) and Greenwood–Johnson (§3.9)")
    return figure


def _pull_off_panel(axes) -> None:
    """|F_pull-off|/(πRΔγ): closed forms (lines) and quasi-static simulations (markers)."""
    lines = np.geomspace(1e-2, 1e3, 61)
    unit = np.pi * _R * _WORK
    factors = np.asarray(theory.double_hertz_factor(lines))
    for xi, control, style in ((3, "force", "-"), (1, "displacement", "--")):
        maugis = [-theory.maugis_critical_state(tabor, xi)[2] * 1.5 for tabor in lines]
        axes.plot(lines, maugis, style, color="C0", label=f"Maugis–Dugdale, {control} control")
        double_hertz = -np.asarray(theory.double_hertz_pull_off(factors, _R, _E_STAR, _WORK, xi)[2]) / unit
        axes.plot(lines, double_hertz, style, color="C1", label=f"Greenwood–Johnson, {control} control")
        for model, color in ((MaugisDugdaleAdhesion, "C0"), (GreenwoodJohnsonAdhesion, "C1")):
            forces = [_simulated_pull_off(model, tabor, control) / unit for tabor in _SIMULATED_TABORS]
            axes.plot(_SIMULATED_TABORS, np.abs(forces), "o" if xi == 3 else "s", color=color, mfc="none", ms=6)
    for value, name, style in (
        (2.0, "DMT limit (force control): 2πRΔγ", "k:"),
        (1.5, "JKR limit, force control: (3/2)πRΔγ", "k-."),
        (5 / 6, "JKR limit, displacement control: (5/6)πRΔγ", "C2:"),
    ):
        axes.plot(lines[[0, -1]], [value, value], style, lw=0.8, label=name)
    axes.set(ylabel="pull-off force |F| / (πRΔγ)", ylim=(0.0, 2.9))
    axes.set_title("pull-off (markers: quasi-static simulation)", fontsize="medium")
    axes.legend(fontsize="x-small", loc="upper right", ncol=2)


def _simulated_pull_off(model: type[AbstractAdhesion], tabor: float, control: str) -> float:
    """Pull-off force (N) of a quasi-static test of the paraboloid at Λ (k(Λ) for the double Hertz)."""
    from .._run.simulate import simulate

    if model is MaugisDugdaleAdhesion:
        values = {"stress": float(theory.maugis_adhesive_stress(tabor, _R, _WORK, _E_STAR))}
    else:
        values = {"k": float(theory.double_hertz_factor(tabor))}
    peak = 2.0 * np.pi * _R * _WORK if control == "force" else 1e-8
    scene = {
        "name": "pull_off",
        "kind": "indentation",
        "control": control,
        "program": {"peak": peak},
        "body": {"profile": {"shape": "paraboloid", "R": _R}},
        "material": {"E_star": _E_STAR},
        "effects": {"adhesion": model.section(work_of_adhesion=_WORK, **values)},
    }
    return simulate(scene).pull_off.force  # type: ignore[union-attr]


def _restitution_panel(axes, tabors, speeds) -> None:
    """e(Λ) at v0 = speeds·v_s from two sweeps; Thornton–Ning (JKR) and e = 1 (DMT) marked."""
    from .._run.sweep import sweep

    sticking = float(theory.thornton_ning_sticking_velocity(_MASS, _R, _E_STAR, _WORK))
    velocities = [speed * sticking for speed in speeds]
    base = {
        "body": {"profile": {"shape": "paraboloid", "R": _R}, "mass": _MASS},
        "material": {"E_star": _E_STAR},
        "initial": {"velocity": velocities[0]},
    }
    stresses = theory.maugis_adhesive_stress(tabors, _R, _WORK, _E_STAR)
    maugis = sweep(
        {**base, "effects": {"adhesion": MaugisDugdaleAdhesion.section(work_of_adhesion=_WORK, stress=1e7)}},
        {"initial.velocity": velocities, "effects.adhesion.stress": np.asarray(stresses)},
    )
    double_hertz = sweep(
        {**base, "effects": {"adhesion": GreenwoodJohnsonAdhesion.section(work_of_adhesion=_WORK, k=1.0)}},
        {"initial.velocity": velocities, "effects.adhesion.k": np.asarray(theory.double_hertz_factor(tabors))},
    )
    for row, (speed, velocity) in enumerate(zip(speeds, velocities, strict=True)):
        color = f"C{row + 2}"
        axes.plot(tabors, maugis.restitution[row], "-o", color=color, ms=4, label=f"MD, v0 = {speed:g} v_s")
        axes.plot(
            tabors, double_hertz.restitution[row], "--s", color=color, ms=4, mfc="none", label=f"GJ, v0 = {speed:g} v_s"
        )
        jkr = float(theory.thornton_ning_restitution(velocity, _MASS, _R, _E_STAR, _WORK))
        axes.axhline(jkr, color=color, lw=0.8, linestyle="-.")
    axes.axhline(1.0, color="k", lw=0.8, linestyle=":")
    axes.plot([], [], "k-.", lw=0.8, label="JKR limit: Thornton–Ning (3.50)")
    axes.plot([], [], "k:", lw=0.8, label="DMT limit: e = 1 (no jumps)")
    axes.set(ylabel="coefficient of restitution e")
    axes.set_title(f"restitution (R = 1 µm, E* = 1 GPa, Δγ = 0.05 J/m², v_s = {sticking:.3g} m/s)", fontsize="medium")
    axes.legend(fontsize="x-small", ncol=2, loc="center right")


def _range_panel(axes) -> None:
    """Where the interaction starts, over the JKR |d_c| (3.170): Maugis–Dugdale's range h; the
    double Hertz's onset k·c0²/R (its equivalent Dugdale range h = Δγ/σ_max is Maugis's h at the
    same Λ by construction)."""
    tabors = np.geomspace(1e-2, 1e3, 61)
    depth = (3 * np.pi**2 * _R * _WORK**2 / (64 * _E_STAR**2)) ** (1 / 3)
    maugis = np.asarray(theory.maugis_range(tabors, _R, _WORK, _E_STAR)) / depth
    onset = -np.asarray(theory.double_hertz_onset(theory.double_hertz_factor(tabors), _R, _E_STAR, _WORK)[1]) / depth
    axes.plot(tabors, maugis, color="C0", label="Maugis–Dugdale: range h = Δγ/σ0 (= 4/(πΛ))")
    axes.plot(tabors, onset, "--", color="C1", label="Greenwood–Johnson: onset k·c0²/R")
    axes.plot(tabors, 4 / (np.pi * tabors), ":", color="0.4", lw=0.8)
    axes.set(yscale="log", ylabel="depth where the stress starts / |d_c(JKR)|")
    axes.set_title("range of interaction (JKR: → 0; DMT: ≫ elastic displacements)", fontsize="medium")
    axes.legend(fontsize="x-small")
