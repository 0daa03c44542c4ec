"""Impacts with a viscous force on the contact: the viscoelastic Hertz law of Brilliantov et al.
and the linear spring–dashpot, with the contact ending where the total force returns to zero.

Viscoelastic paraboloid (N. V. Brilliantov, F. Spahn, J.-M. Hertzsch, T. Pöschel, Phys. Rev. E
53, 5382 (1996)): F = ρ_H(δ^(3/2) + (3/2)A·δ^(1/2)·δ̇), ρ_H = (4/3)E*√R. For small
β = (3/2)A(ρ_H/m)^(2/5) (s^(1/5) m^(-1/5)) the restitution is
e = 1 − C₁β·v₀^(1/5) + O(β²v₀^(2/5)) with C₁ = Γ(3/5)√π/(2^(1/5)·5^(2/5)·Γ(21/10)) = 1.15345
(T. Schwager, T. Pöschel, Phys. Rev. E 57, 650 (1998); the series with the force-free end of
the contact: Schwager & Pöschel, Phys. Rev. E 78, 051304 (2008)).

Linear spring–dashpot, m·ẍ + c·ẋ + k·x = 0, damping ratio ζ = c/(2√(km)), released where
k·x + c·ẋ = 0 (ẍ = 0, the fastest return): e = exp(−2ζ·arccos ζ/√(1 − ζ²)) for ζ < 1,
exp(−2) at ζ = 1 and exp(−2ζ·arcosh ζ/√(ζ² − 1)) for ζ > 1; the contact lasts
2·arccos ζ/(ω₀√(1 − ζ²)), ω₀ = √(k/m) (continued likewise). A flat punch of radius a on the
MDR foundation is such a contact: k = 2E*a, and the viscoelastic model's c = 2E*a·A.
"""

import jax.numpy as jnp
from jax.scipy.special import gamma

from .._core.runtime import float64
from ..profiles import Scalars


@float64
def viscoelastic_beta(dissipative_constant: Scalars, mass: Scalars, R: Scalars, E_star: Scalars):
    """β = (3/2)A(ρ_H/m)^(2/5), ρ_H = (4/3)E*√R [s^(1/5) m^(-1/5)] (Schwager & Pöschel 2008)."""
    return 1.5 * dissipative_constant * (4 / 3 * E_star * jnp.sqrt(R) / mass) ** 0.4


@float64
def viscoelastic_restitution_first_order(velocity: Scalars, beta: Scalars):
    """e ≈ 1 − C₁β·v₀^(1/5), C₁ = Γ(3/5)√π/(2^(1/5)5^(2/5)Γ(21/10)) = 1.15345 (Schwager &
    Pöschel 1998): the first order in β·v₀^(1/5) of the viscoelastic paraboloid's restitution."""
    first = gamma(0.6) * jnp.sqrt(jnp.pi) / (2**0.2 * 5**0.4 * gamma(2.1))
    return 1.0 - first * beta * velocity**0.2


def _arc_over_root(damping_ratio):
    """arccos ζ/√(1 − ζ²), continued as arcosh ζ/√(ζ² − 1) beyond 1 (1 at ζ = 1)."""
    under = jnp.minimum(damping_ratio, 1.0 - 1e-12)
    over = jnp.maximum(damping_ratio, 1.0 + 1e-12)
    near = 1.0 - (damping_ratio - 1.0) / 3.0  # the series about ζ = 1
    return jnp.where(
        jnp.abs(damping_ratio - 1.0) < 1e-6,
        near,
        jnp.where(
            damping_ratio < 1.0,
            jnp.arccos(under) / jnp.sqrt(1.0 - under**2),
            jnp.arccosh(over) / jnp.sqrt(over**2 - 1.0),
        ),
    )


@float64
def dashpot_restitution(damping_ratio: Scalars):
    """e = exp(−2ζ·arccos ζ/√(1 − ζ²)) of a linear spring–dashpot released where its force
    vanishes (continued through ζ = 1 into the overdamped range)."""
    return jnp.exp(-2.0 * damping_ratio * _arc_over_root(damping_ratio))


@float64
def dashpot_contact_time(damping_ratio: Scalars, stiffness: Scalars, mass: Scalars):
    """2·arccos ζ/(ω₀√(1 − ζ²)) [s], ω₀ = √(k/m): from the touch to the force-free release."""
    return 2.0 * _arc_over_root(damping_ratio) / jnp.sqrt(stiffness / mass)
