"""Elastic–perfectly plastic impacts of a paraboloid: Thornton's limiting contact pressure model
(C. Thornton, "Coefficient of restitution for collinear collisions of elastic-perfectly plastic
spheres", J. Appl. Mech. 64, 383 (1997)).

The contact is Hertzian, F = (4/3)E*√R δ^(3/2), until the peak pressure p₀ = 2E*a/(πR) reaches
the limiting pressure p_y, at δ_y = (πp_y/(2E*))²R; then F = F_y + πp_yR(δ − δ_y). Unloading is
Hertzian with the enlarged radius R_p and the residual indentation δ_p fixed by the largest
state: the contact radius keeps a_max = √(Rδ_max) (Thornton's closure), so that
R_p = 4E*a_max³/(3F_max) and δ_max − δ_p = a_max²/R_p. The kinetic energy balance then gives
the restitution in closed form.
"""

import jax.numpy as jnp

from .._core.runtime import float64
from ..profiles import Scalars


@float64
def thornton_yield_indentation(R: Scalars, E_star: Scalars, yield_pressure: Scalars):
    """`δ_y = (πp_y/(2E*))²R` [m]: where the Hertzian peak pressure reaches p_y."""
    return (jnp.pi * yield_pressure / (2 * E_star)) ** 2 * R


@float64
def thornton_yield_force(R: Scalars, E_star: Scalars, yield_pressure: Scalars):
    """`F_y = (4/3)E*√R δ_y^(3/2)` [N]: the Hertzian force at the onset of yield."""
    return 4 / 3 * E_star * jnp.sqrt(R) * thornton_yield_indentation(R, E_star, yield_pressure) ** 1.5


@float64
def thornton_yield_velocity(mass: Scalars, R: Scalars, E_star: Scalars, yield_pressure: Scalars):
    """v_y [m/s] at which a Hertzian impact of a body of mass m just reaches p_y:
    ½mv_y² = (2/5)F_yδ_y. For a sphere of radius R and density ρ on a flat,
    `v_y = (π²/√40)(p_y⁵/(E*⁴ρ))^(1/2) = 1.5605…(p_y⁵/(E*⁴ρ))^(1/2)` (Thornton 1997: 1.56)."""
    depth = thornton_yield_indentation(R, E_star, yield_pressure)
    energy = 2 / 5 * thornton_yield_force(R, E_star, yield_pressure) * depth
    return jnp.sqrt(2 * energy / mass)


@float64
def thornton_restitution(velocity: Scalars, yield_velocity: Scalars):
    """Thornton's (1997) restitution of an elastic–perfectly plastic paraboloid at the impact
    speed v₀ [m/s], with r = v_y/v₀: 1 for v₀ ≤ v_y, else
    e = (6√3/5)^(1/2) [1 − r²/6]^(1/2) {r/[r + 2√(6/5 − r²/5)]}^(1/4);
    e → 1.185 r^(1/4) ∝ v₀^(−1/4) at high speed."""
    r = jnp.minimum(yield_velocity / velocity, 1.0)
    root = 2 * jnp.sqrt(6 / 5 - r**2 / 5)
    return jnp.sqrt(6 * jnp.sqrt(3.0) / 5) * jnp.sqrt(1 - r**2 / 6) * (r / (r + root)) ** 0.25


@float64
def thornton_loading_work(indentation: Scalars, R: Scalars, E_star: Scalars, yield_pressure: Scalars):
    """∫₀^δ F dδ [J] on first loading to δ [m]: `(2/5)(4/3)E*√R δ^(5/2)` up to δ_y, then
    `(2/5)F_yδ_y + F_y(δ − δ_y) + (π/2)p_yR(δ − δ_y)²`."""
    depth = thornton_yield_indentation(R, E_star, yield_pressure)
    force = thornton_yield_force(R, E_star, yield_pressure)
    elastic = 2 / 5 * 4 / 3 * E_star * jnp.sqrt(R) * jnp.minimum(indentation, depth) ** 2.5
    beyond = jnp.maximum(indentation - depth, 0.0)
    return elastic + force * beyond + jnp.pi / 2 * yield_pressure * R * beyond**2


@float64
def thornton_max_indentation(velocity: Scalars, mass: Scalars, R: Scalars, E_star: Scalars, yield_pressure: Scalars):
    """δ_max [m] of an impact at v₀ [m/s]: Hertz's δ_y(v₀/v_y)^(4/5) up to v_y, else δ_y(1 + u)
    with (15/8)u² + (5/2)u + 1 − (v₀/v_y)² = 0 (the loading work equals ½mv₀²)."""
    depth = thornton_yield_indentation(R, E_star, yield_pressure)
    ratio = velocity / thornton_yield_velocity(mass, R, E_star, yield_pressure)
    excess = jnp.maximum(ratio**2 - 1.0, 0.0)
    u = 2 * excess / (2.5 + jnp.sqrt(6.25 + 7.5 * excess))  # the root, free of cancellation
    return jnp.where(ratio > 1.0, depth * (1.0 + u), depth * ratio**0.8)
