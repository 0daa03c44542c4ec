"""Quasi-static Maugis–Dugdale curves of the paraboloid in the chapter's normalized units
(Figs. 3.29–3.30): ã = a/a_c, d̃ = d/|d_c|, F̃ = F/F_A with the JKR a_c, d_c, F_A of (3.170).

The states come from the impact law (`DugdaleLaw`) in those units, the zone without contact
included (ã = 0), so the figure of them (`impact._plots.maugis_curves`) shows what the impacts
ride. Popov, Heß & Willert, Handbook of Contact Mechanics (Springer 2019), ch. 3, §3.8.
"""

import equinox as eqx
import jax.numpy as jnp
import numpy as np

from .. import theory
from ..profiles import Paraboloid
from .dugdale import DugdaleLaw
from .law import ContactLaw
from .scales import Scales

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
