"""Greenwood–Johnson double-Hertz adhesion (§3.9, Greenwood and Johnson 1998) of a paraboloid
f = r²/(2R), in the scaled units of `Scales`, as an equilibrium curve parametrised by the
contact radius s = â.

With Ĉ = ℓx²/(R·ℓz) (the scaled ĝ(1)) and the ring width û = ĉ − â, the root of
û²(û + 3â) = K̂ = 3πR²Δγ/(2E*k(k+1)ℓx³) (3.201):

    d̂ = Ĉ·(â² − k·û(2â + û)),   F̂ = (4/3)·Ĉ·(â³ − k·û(3â² + 3âû + û²)),

explicit along the whole curve (no range condition to solve). It starts at â = 0, where the
interaction switches on (d̂₀ = −k·Ĉ·K̂^(2/3)); d rises from there for k ≤ 1 and first falls
to its minimum at â/ĉ = (k − 1)/(k + 1) for k > 1 (`impact.theory.double_hertz_pull_off`), its
only turning point: the nodes are 0, that minimum (0 when k ≤ 1) and the top.
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from ..profiles import Paraboloid, Profile, Sphere
from ..theory._double_hertz import ring_width
from .curve import AbstractCurve
from .scales import Scales

# Contact radii searched for the reach of an impact: 0 and logarithmic from 1e-3 to 1e3 units.
_REACH_POINTS = 256
_TOP_MARGIN = 4.0


def tip_radius(profile: Profile) -> jax.Array:
    """R of the paraboloid f = r²/(2R), or of a sphere's tip (its paraboloid, a ≪ R)."""
    if isinstance(profile, Paraboloid | Sphere):
        return jnp.asarray(profile.R)
    raise ValueError(f"Greenwood–Johnson adhesion needs a paraboloid (§3.9), not {type(profile).__name__}")


class DoubleHertzLaw(eqx.Module):
    """The double-Hertz law of a paraboloid in scaled units."""

    scales: Scales
    curvature: jax.Array  # Ĉ = ℓx²/(R·ℓz)
    factor: jax.Array  # k
    ring: jax.Array  # K̂ of (3.201)

    @staticmethod
    def scaled(profile: Profile, scales: Scales, E_star, work_of_adhesion, factor) -> "DoubleHertzLaw":
        """The law with Δγ (J/m²) and k, in the units of `scales`."""
        R = tip_radius(profile)
        ring = 3.0 * jnp.pi * R**2 * work_of_adhesion / (2.0 * E_star * factor * (factor + 1.0))
        return DoubleHertzLaw(
            scales=scales,
            curvature=scales.radial**2 / (R * scales.normal),
            factor=jnp.asarray(factor),
            ring=ring / scales.radial**3,
        )

    @property
    def onset(self):
        """d̂₀ = −k·Ĉ·ĉ₀² where the interaction starts (â = 0)."""
        return -self.factor * self.curvature * jnp.cbrt(self.ring) ** 2

    def turning_radius(self):
        """â of the minimum of d(â) for k > 1, (k − 1)/(k + 1) of ĉ; 0 for k ≤ 1."""
        k = self.factor
        gap = jnp.where(k > 1.0, 2.0 / (k + 1.0), 1.0)
        ratio = 1.0 - gap
        return ratio * jnp.cbrt(self.ring / (gap**2 * (1.0 + 2.0 * ratio)))


class DoubleHertzCurve(AbstractCurve):
    """The double-Hertz states along s = â ≥ 0: nodes 0, the turning radius, the top."""

    junction: jax.Array  # 0: every state is a contact
    nodes: jax.Array
    levels: jax.Array
    increasing: jax.Array
    overflow: jax.Array

    def state(self, law: DoubleHertzLaw, s):
        """(d̂, F̂, â, ĉ) at â = s."""
        a = jnp.maximum(s, 0.0)
        u = ring_width(a, law.ring)
        k, curvature = law.factor, law.curvature
        depth = curvature * (a**2 - k * u * (2.0 * a + u))
        force = 4.0 / 3.0 * curvature * (a**3 - k * u * (3.0 * a**2 + 3.0 * a * u + u**2))
        return depth, force, a, a + u

    def riding(self, law: DoubleHertzLaw, s):
        """(d̂, F̂, dd̂/dâ) with dĉ/dâ = 2â/(â + ĉ): dd̂/dâ = 2Ĉ·â·(1 − k·û/(2â + û))."""
        depth, force, a, outer = self.state(law, s)
        u = outer - a
        return depth, force, 2.0 * law.curvature * a * (1.0 - law.factor * u / (2.0 * a + u))


def build_double_hertz_curve(law: DoubleHertzLaw, speed) -> DoubleHertzCurve:
    """The curve up to `_TOP_MARGIN` times the contact radius where the work ∫F dd from the onset
    (trapezoids) first exceeds ½v² + 1 plus twice the largest work the adhesive pull gave back
    before (an impact at scaled speed v cannot reach further)."""
    turn = law.turning_radius()
    partial = DoubleHertzCurve(
        junction=jnp.zeros(()),
        nodes=jnp.zeros(1),
        levels=jnp.zeros(1),
        increasing=jnp.zeros(0, bool),
        overflow=jnp.asarray(False),
    )
    grid = jnp.concatenate([jnp.zeros(1), jnp.logspace(-3.0, 3.0, _REACH_POINTS)])
    depths, forces, _, _ = partial.state(law, grid)
    steps = 0.5 * (forces[1:] + forces[:-1]) * (depths[1:] - depths[:-1])
    work = jnp.concatenate([jnp.zeros(1), jnp.cumsum(steps)])
    given_back = jnp.maximum(-jax.lax.cummin(work), 0.0)
    enough = work >= 0.5 * speed**2 + 1.0 + 2.0 * given_back
    reach = grid[jnp.where(jnp.any(enough), jnp.argmax(enough), grid.shape[0] - 1)]
    top = _TOP_MARGIN * jnp.maximum(jnp.maximum(reach, turn), 1.0)
    nodes = jnp.stack([jnp.zeros(()), turn, top])
    return DoubleHertzCurve(
        junction=jnp.zeros(()),
        nodes=nodes,
        levels=partial.depth(law, nodes),
        increasing=jnp.stack([jnp.asarray(False), jnp.asarray(True)]) & (nodes[1:] > nodes[:-1]),
        overflow=jnp.asarray(False),
    )
