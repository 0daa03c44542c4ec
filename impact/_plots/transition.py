"""The JKR–DMT transition figure: pull-off force of the paraboloid against the Tabor parameter Λ
(3.172) for Maugis–Dugdale (§3.8, force control) and Greenwood–Johnson (§3.9, force and
displacement control, at the equivalent Λ(k) = (36k²/(π³(1 + k)))^(1/3)), with the JKR and DMT
limits. The documentation's image is made with

    python -c "from impact._plots.transition import pull_off_figure; \\
        pull_off_figure().savefig('docs/src/images/pull_off_transition.png', dpi=150)"
"""

from typing import TYPE_CHECKING

import numpy as np

from .. import theory

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
        axes.plot(tabors, -force / unit, style, label=f"Greenwood–Johnson, {control}", gid="greenwood_johnson")
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
