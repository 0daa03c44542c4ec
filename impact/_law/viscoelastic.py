"""A viscoelastic half-space: the MDR law of a medium relaxing as a Prony series,
E*(t) = E∞* + Σ E_i·e^(−t/τ_i), with or without JKR adhesion (the rule of Heß at the
instantaneous modulus E₀* = E∞* + Σ E_i: `viscoelastic_springs`), or Maugis–Dugdale adhesion
(a Dugdale zone of creeping springs: `viscoelastic_dugdale`). E∞* is the scene's E*
(`Physics.E_star`); the law holds the Prony terms and the works of adhesion."""

import jax
import jax.numpy as jnp

from .._core.types import Parameter
from ..profiles import Profile
from .base import AbstractAdhesiveLaw
from .jkr import hess_coefficients
from .prony import PronyElement
from .scales import Scales, adhesive_scales


class Viscoelastic(AbstractAdhesiveLaw):
    """The Prony terms (E_i, τ_i) of the medium, its works of adhesion (0: no adhesion) and the
    Dugdale stress (0: JKR)."""

    moduli: Parameter  # E_i (Pa) [M]
    times: Parameter  # τ_i (s) [M]
    work_of_adhesion: Parameter  # Δγ (J/m²); 0 without adhesion
    approach_work_of_adhesion: Parameter  # Δγa ≤ Δγ (J/m²)
    adhesive_stress: Parameter  # σ0 (Pa) of Maugis–Dugdale adhesion (`viscoelastic_dugdale`); 0: JKR

    def scales(self, profile: Profile, E_star, mass, touch_velocity) -> Scales:
        """The units of the relaxed medium (E∞* = `E_star`): the jump-in's of Δγa, or the
        impact energy's (`scales.adhesive_scales`)."""
        return adhesive_scales(profile, E_star, self.approach_work_of_adhesion, mass, touch_velocity)

    def instantaneous_modulus(self, E_star) -> jax.Array:
        """E₀* = E∞* + Σ E_i (Pa), for the relaxed modulus `E_star` (Pa)."""
        return E_star + jnp.sum(self.moduli, axis=-1)

    def element(self, scales: Scales, E_star) -> PronyElement:
        """Each spring's element in the units of `scales`: moduli relative to E∞* = `E_star`."""
        return PronyElement(self.moduli / E_star, self.times / scales.time)

    def hess_lengths(self, scales: Scales, E_star, adhesive: bool) -> tuple[jax.Array, jax.Array]:
        """(λ₀, λa₀) of the scaled rule of Heß at the instantaneous modulus: a spring at x̂ lets
        go at the tension e₀·λ₀·√x̂ per width (e₀ = E₀*/E∞*) and attaches across the gap
        λa₀·√x̂; both 0 without adhesion (`adhesive`, static)."""
        if not adhesive:
            zero = jnp.zeros(())
            return zero, zero
        return hess_coefficients(
            self.work_of_adhesion, self.approach_work_of_adhesion, scales, self.instantaneous_modulus(E_star)
        )
