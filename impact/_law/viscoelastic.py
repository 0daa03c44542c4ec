"""A viscoelastic half-space: the MDR law of a medium relaxing as a Prony series,
E*(t) = E∞* + Σ E_i·e^(−t/τ_i), with or without JKR adhesion (`Viscoelastic`: the rule of Heß
at the instantaneous modulus E₀* = E∞* + Σ E_i, `viscoelastic_springs`), or with Maugis–Dugdale
adhesion (`ViscoelasticDugdale`: a Dugdale zone of creeping springs, `viscoelastic_dugdale`).
E∞* is the scene's E* (`Physics.E_star`); the law holds the Prony terms and the works of
adhesion, and builds its spring array."""

import jax
import jax.numpy as jnp

from .. import theory
from .._core.types import Parameter
from ..profiles import Profile
from .base import AbstractAdhesiveLaw
from .jkr import hess_coefficients
from .prony import PronyElement
from .scales import Scales, adhesive_scales
from .viscoelastic_dugdale import DugdaleZoneArray, zone_array
from .viscoelastic_springs import ViscoelasticArray, spring_array

# Room for the Dugdale zone beyond the contact's bound: its JKR-limit width
# (π/4)·E∞*·Δγ/σ0² (`theory.dugdale_zone_width`) this many times.
_ZONE_WIDTHS = 4.0


class Viscoelastic(AbstractAdhesiveLaw):
    """The Prony terms (E_i, τ_i) of the medium and its works of adhesion (0: no adhesion), with
    JKR adhesion: the rule of Heß on each spring."""

    moduli: Parameter  # E_i (Pa) [M]
    times: Parameter  # τ_i (s) [M]
    work_of_adhesion: Parameter  # Δγ (J/m²); 0 without adhesion
    approach_work_of_adhesion: Parameter  # Δγa ≤ Δγ (J/m²)

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

    def zone_room(self, scales: Scales, E_star) -> jax.Array:
        """The array's length (scaled) beyond the contact's bound: none without a Dugdale zone."""
        return jnp.zeros(())

    def adhesion_range(self, scales: Scales) -> jax.Array:
        """How far (scaled) outside the contact the medium pulls: 0 (JKR's contact adhesion)."""
        return jnp.zeros(())

    def spring_array(
        self, element: PronyElement, g, length, count, slots: int, scales: Scales, E_star, adhesive: bool
    ) -> ViscoelasticArray | DugdaleZoneArray:
        """`count` springs of `element` over [0, `length`] in `slots` slots for the scaled profile
        `g` (`viscoelastic_springs.spring_array`), letting go and attaching by the rule of Heß
        (`adhesive`, static)."""
        detach, attach = self.hess_lengths(scales, E_star, adhesive)
        return spring_array(element, g, length, count, slots, detach, attach)


class ViscoelasticDugdale(Viscoelastic):
    """The Prony terms (E_i, τ_i) of the medium with Maugis–Dugdale adhesion: the Dugdale stress
    σ0 over the range h = Δγ/σ0 on a zone of creeping springs (`viscoelastic_dugdale`)."""

    adhesive_stress: Parameter  # σ0 (Pa)

    def zone_room(self, scales: Scales, E_star) -> jax.Array:
        """`_ZONE_WIDTHS` JKR-limit widths of the Dugdale zone (scaled)."""
        width = theory.dugdale_zone_width(E_star, self.work_of_adhesion, self.adhesive_stress)
        return jnp.asarray(_ZONE_WIDTHS * (width / scales.radial))

    def adhesion_range(self, scales: Scales) -> jax.Array:
        """The range ĥ = Δγ/σ0 (scaled): the zone is born where the tip comes within it."""
        return jnp.asarray(self.work_of_adhesion / self.adhesive_stress / scales.normal)

    def spring_array(
        self, element: PronyElement, g, length, count, slots: int, scales: Scales, E_star, adhesive: bool
    ) -> DugdaleZoneArray:
        """`count` springs of `element` over [0, `length`] in `slots` slots for the scaled profile
        `g`, with the Dugdale zone of σ̂ = σ0·ℓx/(E∞*·ℓz) and ĥ (`viscoelastic_dugdale.zone_array`)."""
        stress = self.adhesive_stress * scales.radial / (E_star * scales.normal)
        return zone_array(element, g, length, count, slots, stress, self.adhesion_range(scales))
