"""Quasi-static Maugis–Dugdale curves of the paraboloid in the chapter's normalized units
(Figs. 3.29–3.30): ã = a/a_c, d̃ = d/|d_c|, F̃ = F/F_A with the JKR a_c, d_c, F_A of (3.170).

The states come from the impact law (`dugdale.DugdaleLaw`) in those units, the zone without
contact included (ã = 0), so the figure shows what the impacts ride.

    from impact.dugdale_curves import equilibrium_figure
    equilibrium_figure([0.1, 0.3, 1, 3, 10]).savefig("maugis_curves.png", dpi=150)
"""

import equinox as eqx
import jax.numpy as jnp
import numpy as np
from matplotlib.figure import Figure

from .. import theory
from .._law.dugdale import DugdaleLaw
from .._law.law import ContactLaw
from ..profiles import Paraboloid
from .._law.scales import Scales

# Any paraboloid gives the same normalized curves; these values only fix the SI round trip.
_R, _E_STAR, _WORK = 1.0e-6, 1.0e9, 0.05


def normalized_curve(tabor: float, contact_points: int = 400, zone_points: int = 100):
    """(ã, d̃, F̃) along the whole equilibrium curve for Tabor parameter Λ: the zone without
    contact from b = 0 to the junction, then contacts with (b − a)/b from 1 to 1e-6."""
    a_c = (9.0 * np.pi * _R**2 * _WORK / (8.0 * _E_STAR)) ** (1.0 / 3.0)
    d_c = a_c**2 / (3.0 * _R)
    one = jnp.ones(())
    scales = Scales(radial=a_c * one, normal=d_c * one, force=_E_STAR * a_c * d_c * one, time=one)
    stress = float(theory.maugis_adhesive_stress(tabor, _R, _WORK, _E_STAR))
    law = DugdaleLaw(
        law=ContactLaw(Paraboloid(R=_R * one), scales, 0.0 * one, 0.0 * one, False),
        degree=2.0 * one,
        stress=stress * a_c / (_E_STAR * d_c) * one,
        range=_WORK / stress / d_c * one,
    )
    force_unit = 1.5 * np.pi * _R * _WORK / float(scales.force)
    (zone_depth, zone_force), (contact_depth, contact_force, radius, _) = _states(law, zone_points, contact_points)
    radii = np.concatenate([np.zeros(zone_points), np.asarray(radius)])
    depths = np.concatenate([np.asarray(zone_depth), np.asarray(contact_depth)])
    forces = np.concatenate([np.asarray(zone_force), np.asarray(contact_force)]) / force_unit
    return radii, depths, forces


@eqx.filter_jit
def _states(law: DugdaleLaw, zone_points: int, contact_points: int):
    """(d, F) of the zone from b = 0 to b_J; (d, F, a, b) of contacts with p from 1 to 1e-6."""
    zones = law.zone_radius(jnp.ones(())) * jnp.linspace(0.0, 1.0, zone_points)
    return law.zone(zones), law.contact(jnp.logspace(0.0, -6.0, contact_points))


def equilibrium_figure(tabors=(0.1, 0.3, 1.0, 3.0, 10.0), max_radius: float = 2.0) -> Figure:
    """F̃ against ã and against d̃ for each Λ, with the JKR and DMT limits as thin lines."""
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
    for (name, (depth, force)), style in zip(limits.items(), ("k-", "k--")):
        by_radius.plot(a, force, style, linewidth=0.8, label=name, gid="limit")
        by_depth.plot(depth, force, style, linewidth=0.8, label=name, gid="limit")
    by_radius.set(xlabel="contact radius ã = a/a_c", ylabel="force F̃ = F/F_A (JKR)", xlim=(0.0, max_radius), ylim=(-1.6, 3.0))
    by_depth.set(xlabel="indentation d̃ = d/|d_c|", ylabel="force F̃ = F/F_A (JKR)", xlim=(-4.0, 8.0), ylim=(-1.6, 3.0))
    for axes in (by_radius, by_depth):
        axes.axhline(0.0, color="0.7", linewidth=0.6)
        axes.grid(alpha=0.3)
    by_depth.legend(fontsize=8)
    figure.suptitle("Maugis–Dugdale paraboloid (3.171): normalized equilibrium curves")
    return figure
