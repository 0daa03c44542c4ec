"""The figure of the quasi-static Maugis–Dugdale curves of the paraboloid in the chapter's
normalized units (Popov, Heß & Willert, Handbook of Contact Mechanics (Springer 2019), ch. 3,
Figs. 3.29–3.30):

    equilibrium_figure([0.1, 0.3, 1, 3, 10]).savefig("maugis_curves.png", dpi=150)
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
