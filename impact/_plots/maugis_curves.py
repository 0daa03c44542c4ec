"""The figure of the quasi-static Maugis–Dugdale curves of the paraboloid in the chapter's
normalized units (Popov, Heß & Willert, Handbook of Contact Mechanics (Springer 2019), ch. 3,
Figs. 3.29–3.30):

    equilibrium_figure([0.1, 0.3, 1, 3, 10]).savefig("maugis_curves.png", dpi=150)

and of its approach hysteresis (`hysteresis_figure`: cycles and restitution against Δγa).
"""

from typing import TYPE_CHECKING

import numpy as np

from .._law.maugis_curves import normalized_curve

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def equilibrium_figure(tabors=(0.1, 0.3, 1.0, 3.0, 10.0), max_radius: float = 2.0) -> "Figure":
    """F̃ against ã and against d̃ for each Λ, with the JKR and DMT limits as thin lines."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(11, 4.8), layout="constrained")
    by_radius, by_depth = figure.subplots(1, 2)
    for tabor in tabors:
        radii, depths, forces = normalized_curve(tabor)
        by_radius.plot(radii, forces, label=f"Λ = {tabor:g}", gid="maugis")
        by_depth.plot(depths, forces, label=f"Λ = {tabor:g}", gid="maugis")
    a = np.linspace(0.0, max_radius, 400)
    limits = {
        "JKR (Λ → ∞)": (3 * a**2 - 4 * np.sqrt(a), a**3 - 2 * a**1.5),
        "DMT (Λ → 0)": (3 * a**2, a**3 - 4.0 / 3.0),
    }
    for (name, (depth, force)), style in zip(limits.items(), ("k-", "k--"), strict=True):
        by_radius.plot(a, force, style, linewidth=0.8, label=name, gid="limit")
        by_depth.plot(depth, force, style, linewidth=0.8, label=name, gid="limit")
    by_radius.set(
        xlabel="contact radius ã = a/a_c", ylabel="force F̃ = F/F_A (JKR)", xlim=(0.0, max_radius), ylim=(-1.6, 3.0)
    )
    by_depth.set(xlabel="indentation d̃ = d/|d_c|", ylabel="force F̃ = F/F_A (JKR)", xlim=(-4.0, 8.0), ylim=(-1.6, 3.0))
    for axes in (by_radius, by_depth):
        axes.axhline(0.0, color="0.7", linewidth=0.6)
        axes.grid(alpha=0.3)
    by_depth.legend(fontsize=8)
    figure.suptitle("Maugis–Dugdale paraboloid (3.171): normalized equilibrium curves")
    return figure


# The particle of configs/maugis_dugdale_hysteresis.yaml.
_R, _MASS, _E_STAR, _WORK, _SPEED = 1.0e-6, 1.0472e-14, 1.0e9, 0.05, 0.6


def hysteresis_figure(shares=(1.0, 0.5, 0.1), tabors=(1.0, 10.0, 100.0)) -> "Figure":
    """Maugis–Dugdale approach hysteresis (`_law.dugdale_hysteresis`): left, two
    displacement-controlled cycles at Λ = 1 for each Δγa/Δγ in `shares` (the second reloads from
    d = 0 along a frozen zone); right, the restitution at v0 = 0.6 m/s against Δγa/Δγ for each Λ in
    `tabors` and for the JKR law with the same Δγa. The documentation's image:

        python -c "from impact._plots.maugis_curves import hysteresis_figure; \\
            hysteresis_figure().savefig('docs/src/images/maugis_hysteresis.png', dpi=130)"
    """
    from matplotlib.figure import Figure

    from .. import theory
    from .._run.impacts import simulate_impact
    from .._run.indentation import simulate_indentation
    from .._scene.adhesion import MaugisDugdaleAdhesion
    from .._scene.scene import load_scene

    a_c = (9.0 * np.pi * _R**2 * _WORK / (8.0 * _E_STAR)) ** (1.0 / 3.0)  # (3.170)
    d_c, f_c = a_c**2 / (3.0 * _R), 1.5 * np.pi * _R * _WORK

    def adhesion(tabor, share):
        law = {"work_of_adhesion": _WORK, "approach_work_of_adhesion": share * _WORK}
        if tabor is None:
            return law
        return MaugisDugdaleAdhesion.section(
            **law, stress=float(theory.maugis_adhesive_stress(tabor, _R, _WORK, _E_STAR))
        )

    body = {"profile": {"shape": "paraboloid", "R": _R}}
    figure = Figure(figsize=(11, 4.6), layout="constrained")
    loops, restitutions = figure.subplots(1, 2)
    for share in shares:
        test = simulate_indentation(
            load_scene(
                {
                    "kind": "indentation",
                    "control": "displacement",
                    "program": {"peak": 4.0 * d_c, "cycles": 2, "unload_to": 0.0},
                    "body": body,
                    "material": {"E_star": _E_STAR},
                    "effects": {"adhesion": adhesion(1.0, share)},
                }
            )
        )
        loops.plot(test.indentation / d_c, test.force / f_c, label=f"Δγa/Δγ = {share:g}", gid="maugis")
    loops.set(
        xlabel="indentation d/|d_c|", ylabel="force F/F_A (JKR)", title="Λ = 1, two cycles (the second from d = 0)"
    )
    grid = np.geomspace(1e-4, 1.0, 13)
    for tabor in (*tabors, None):
        values = [
            simulate_impact(
                load_scene(
                    {
                        "body": {**body, "mass": _MASS},
                        "material": {"E_star": _E_STAR},
                        "initial": {"velocity": _SPEED},
                        "effects": {"adhesion": adhesion(tabor, share)},
                    }
                ),
                trajectory=False,
            ).restitution
            for share in grid
        ]
        name, style = ("JKR, attach edge Δγa", "k--") if tabor is None else (f"Λ = {tabor:g}", "o-")
        restitutions.plot(grid, values, style, markersize=3, label=name, gid="limit" if tabor is None else "maugis")
    restitutions.set(
        xscale="log",
        xlabel="approach work of adhesion Δγa/Δγ",
        ylabel="restitution e",
        title="v0 = 0.6 m/s (R = 1 µm, E* = 1 GPa, Δγ = 0.05 J/m²)",
    )
    for axes in (loops, restitutions):
        axes.grid(alpha=0.3)
        axes.legend(fontsize=8)
    figure.suptitle("Maugis–Dugdale with approach hysteresis: the frozen zone between the ranges Δγa/σ0 and Δγ/σ0")
    return figure
