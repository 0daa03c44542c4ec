"""The zero-range laws of the continuum MDR: no adhesion, and JKR adhesion by the rule of Heß.

Rule of Heß (3.26): the edge spring at x lets go at the elongation Δl(x) = √(2πxΔγ/E*), and on
approach the next spring attaches once its gap closes to √(2πxΔγa/E*), 0 ≤ Δγa ≤ Δγ (Δγa = Δγ:
the reversible JKR law with its jump-in; Δγa = 0: attach on touch).
"""

import jax
import jax.numpy as jnp

from .._core import derivatives
from .._core.types import Parameter
from ..profiles import Profile
from .base import AbstractAdhesiveLaw, AbstractEdgeLaw
from .scales import Scales, adhesive_scales, energy_scales


class Elastic(AbstractEdgeLaw):
    """No adhesion: the springs attach on touch and let go unstretched (Hertz for a paraboloid)."""

    def scales(self, profile: Profile, E_star, mass, touch_velocity) -> Scales:
        """The impact energy's units (`scales.energy_scales`)."""
        return energy_scales(profile, E_star, mass, touch_velocity)

    def hess_coefficients(self, scales: Scales, E_star) -> tuple[jax.Array, jax.Array]:
        zero = jnp.zeros(())
        return zero, zero


class JKR(AbstractEdgeLaw, AbstractAdhesiveLaw):
    """JKR adhesion (zero range) by the rule of Heß, with hysteretic attachment Δγa ≤ Δγ."""

    work_of_adhesion: Parameter  # Δγ (J/m²): the Dupré work of separation
    approach_work_of_adhesion: Parameter  # Δγa ≤ Δγ (J/m²): attachment on approach

    def scales(self, profile: Profile, E_star, mass, touch_velocity) -> Scales:
        """The jump-in units of Δγa, or the impact energy's (`scales.adhesive_scales`)."""
        return adhesive_scales(profile, E_star, self.approach_work_of_adhesion, mass, touch_velocity)

    def hess_coefficients(self, scales: Scales, E_star) -> tuple[jax.Array, jax.Array]:
        return hess_coefficients(self.work_of_adhesion, self.approach_work_of_adhesion, scales, E_star)


def hess_coefficients(work_of_adhesion, approach_work_of_adhesion, scales: Scales, E_star):
    """(λ, λa) of the scaled Heß rule for Δγ and Δγa (J/m²): λ·√x̂ = √(2πℓx·x̂·Δγ/E*)/ℓz and
    λa = λ·√(Δγa/Δγ) (3.26 in the units of `scales`)."""
    detach = jnp.sqrt(2.0 * jnp.pi * scales.radial * work_of_adhesion / E_star) / scales.normal
    attach = detach * derivatives.sqrt(approach_work_of_adhesion / work_of_adhesion)
    return detach, attach
