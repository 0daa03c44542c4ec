"""Greenwood–Johnson double-Hertz adhesion (§3.9, Greenwood and Johnson 1998) of a paraboloid
f = r²/(2R), in the scaled units of `Scales`, as an explicit equilibrium curve.

With Ĉ = ℓx²/(R·ℓz) (the scaled ĝ(1)) and the ring width û = ĉ − â, the root of
û²(û + 3â) = K̂ = 3πR²Δγ/(2E*k(k+1)ℓx³) (3.201):

    d̂ = Ĉ·(â² − k·û(2â + û)),   F̂ = (4/3)·Ĉ·(â³ − k·û(3â² + 3âû + û²)).

Parametrised by the ring width, s = ln(û₀/û) with û₀ = K̂^(1/3), the cubic (3.201) is solved
for â instead: â = (K̂/û² − û)/3, so the whole curve is explicit (no root inside a step) and
dâ/ds = 2â + û. s = 0 is â = 0, where the interaction switches on (d̂₀ = −k·Ĉ·û₀²); d rises
from there for k ≤ 1, and first falls to its minimum at 2â = (k − 1)û, â/ĉ = (k − 1)/(k + 1),
for k > 1 (`impact.theory.double_hertz_pull_off`), its only turning point: the nodes are 0, that
minimum (0 when k ≤ 1) and the top.
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from ..profiles import Paraboloid, Profile, Sphere
from .curve import AbstractCurve, Reach
from .scales import Scales

# States searched for the reach of a curve: s from 0 to 40 (â up to ~e^80·û₀/3).
_REACH_SPAN = 40.0
_REACH_POINTS = 513


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

    def radius(self, s):
        """(â, û) at s = ln(û₀/û), û₀ = K̂^(1/3): â = (K̂/û² − û)/3 from (3.201), explicit."""
        u = jnp.cbrt(self.ring) * jnp.exp(-jnp.maximum(s, 0.0))
        return jnp.maximum((self.ring / u**2 - u) / 3.0, 0.0), u

    def turning_point(self):
        """s of the minimum of d for k > 1, where 2â = (k − 1)·û, i.e. û³ = 2K̂/(3k − 1)
        (â/ĉ = (k − 1)/(k + 1)); 0 for k ≤ 1."""
        k = self.factor
        return jnp.where(k > 1.0, jnp.log((3.0 * k - 1.0) / 2.0) / 3.0, 0.0)


class DoubleHertzCurve(AbstractCurve):
    """The double-Hertz states along s = ln(û₀/û) ≥ 0 (`DoubleHertzLaw.radius`): nodes 0, the
    turning point, the top."""

    junction: jax.Array  # 0: every state is a contact
    nodes: jax.Array
    levels: jax.Array
    increasing: jax.Array
    overflow: jax.Array

    def state(self, law: DoubleHertzLaw, s):
        """(d̂, F̂, â, ĉ) at s."""
        a, u = law.radius(s)
        k, curvature = law.factor, law.curvature
        depth = curvature * (a**2 - k * u * (2.0 * a + u))
        force = 4.0 / 3.0 * curvature * (a**3 - k * u * (3.0 * a**2 + 3.0 * a * u + u**2))
        return depth, force, a, a + u

    def grid(self, law: DoubleHertzLaw):
        """s from 0 to 40 (â up to ~e^80·û₀/3), evenly."""
        return jnp.linspace(0.0, _REACH_SPAN, _REACH_POINTS)

    def riding(self, law: DoubleHertzLaw, s, segment=None):
        """(d̂, F̂, dd̂/ds) (the curve is smooth across its segments' ends: `segment` is not needed)."""
        depth, force, _, _ = self.state(law, s)
        return depth, force, self.slopes(law, s)[0]

    def slopes(self, law: DoubleHertzLaw, s):
        """(dd̂/ds, dF̂/ds) with dâ/ds = 2â + û, dĉ/ds = 2â: dd̂/ds = 2Ĉ·â·(2â − (k − 1)·û) and
        dF̂/ds = 4Ĉ·â·((1 + k)·â·(2â + û) − 2k·ĉ²), both 0 at â = 0."""
        a, u = law.radius(s)
        k, curvature = law.factor, law.curvature
        depth_slope = 2.0 * curvature * a * (2.0 * a - (k - 1.0) * u)
        force_slope = 4.0 * curvature * a * ((1.0 + k) * a * (2.0 * a + u) - 2.0 * k * (a + u) ** 2)
        return depth_slope, force_slope


def build_double_hertz_curve(law: DoubleHertzLaw, reach: Reach) -> DoubleHertzCurve:
    """The curve up to `reach` (`top_of_reach` for an impact, `top_of_peak` for a quasi-static
    program), and at least twice beyond the turning point."""
    turn = law.turning_point()
    partial = DoubleHertzCurve(
        junction=jnp.zeros(()),
        nodes=jnp.zeros(1),
        levels=jnp.zeros(1),
        increasing=jnp.zeros(0, bool),
        overflow=jnp.asarray(False),
    )
    grid = partial.grid(law)
    depths, forces, radii, _ = partial.state(law, grid)
    top = jnp.maximum(reach(grid, depths, forces, radii), 2.0 * turn)
    nodes = jnp.stack([jnp.zeros(()), turn, top])
    return DoubleHertzCurve(
        junction=jnp.zeros(()),
        nodes=nodes,
        levels=partial.depth(law, nodes),
        increasing=jnp.stack([jnp.asarray(False), jnp.asarray(True)]) & (nodes[1:] > nodes[:-1]),
        overflow=jnp.asarray(False),
    )
