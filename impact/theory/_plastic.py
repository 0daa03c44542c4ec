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
    """δ_y = (πp_y/(2E*))²R [m]: where the Hertzian peak pressure reaches p_y."""
    return (jnp.pi * yield_pressure / (2 * E_star)) ** 2 * R


@float64
def thornton_yield_force(R: Scalars, E_star: Scalars, yield_pressure: Scalars):
    """F_y = (4/3)E*√R δ_y^(3/2) [N]: the Hertzian force at the onset of yield."""
    return 4 / 3 * E_star * jnp.sqrt(R) * thornton_yield_indentation(R, E_star, yield_pressure) ** 1.5


@float64
def thornton_yield_velocity(mass: Scalars, R: Scalars, E_star: Scalars, yield_pressure: Scalars):
    """v_y [m/s] at which a Hertzian impact of a body of mass m just reaches p_y:
    ½mv_y² = (2/5)F_yδ_y. For a sphere of radius R and density ρ on a flat,
    v_y = (π²/√40)(p_y⁵/(E*⁴ρ))^(1/2) = 1.5605…(p_y⁵/(E*⁴ρ))^(1/2) (Thornton 1997: 1.56)."""
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
