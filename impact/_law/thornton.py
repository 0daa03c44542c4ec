"""Plasticity of a paraboloid by Thornton's limiting contact pressure p_y (C. Thornton, J. Appl.
Mech. 64, 383 (1997)): the Hertzian peak pressure p₀ = 2E*a/(πR) cannot exceed p_y; beyond, the
contact yields (`plastic`). With adhesion, Thornton & Ning's (1998) adhesive elastic–plastic law
on the reversible JKR law (`adhesive_plastic`)."""

import jax
import jax.numpy as jnp

from .. import theory
from .._core.types import Parameter
from ..profiles import Profile
from .adhesive_plastic import AdhesivePlasticLaw
from .base import AbstractAdhesiveLaw, AbstractEdgeLaw, AbstractPlasticLaw
from .jkr import hess_coefficients
from .plastic import PlasticLaw
from .scales import Scales, adhesive_scales


class Thornton(AbstractPlasticLaw):
    """Thornton's elastic–perfectly plastic contact of a paraboloid (no adhesion)."""

    yield_pressure: Parameter  # p_y (Pa)

    def scales(self, profile: Profile, E_star, mass, touch_velocity) -> Scales:
        return plastic_scales(self, profile.radius_scale(), E_star, mass, touch_velocity)


class ThorntonNing(AbstractPlasticLaw, AbstractEdgeLaw, AbstractAdhesiveLaw):
    """Thornton & Ning's adhesive elastic–plastic contact of a paraboloid: the reversible JKR law
    (Δγa = Δγ) until the pressure at the centre reaches p_y. Without adhesion (Δγ = 0) an impact
    runs on Thornton's law with the same p_y."""

    work_of_adhesion: Parameter  # Δγ (J/m²)
    approach_work_of_adhesion: Parameter  # Δγa = Δγ (J/m²): the reversible JKR law
    yield_pressure: Parameter  # p_y (Pa)

    def scales(self, profile: Profile, E_star, mass, touch_velocity) -> Scales:
        """The JKR law's units (`scales.adhesive_scales`): an impact that never yields is its
        elastic adhesive impact."""
        return adhesive_scales(profile, E_star, self.approach_work_of_adhesion, mass, touch_velocity)

    def hess_coefficients(self, scales: Scales, E_star) -> tuple[jax.Array, jax.Array]:
        return hess_coefficients(self.work_of_adhesion, self.approach_work_of_adhesion, scales, E_star)

    def adhesive_law(self, radius, E_star, scales: Scales) -> AdhesivePlasticLaw:
        """Thornton & Ning's law of a paraboloid of radius R (m) in the units of `scales`:
        ĝ = (ℓx²/(Rℓz))x̂², Δl̂ = √(2πℓxΔγ/E*)/ℓz·√x̂, yield where the JKR pressure at the centre
        reaches p_y."""
        yield_radius = theory.adhesive_plastic_yield_radius(radius, E_star, self.work_of_adhesion, self.yield_pressure)
        return AdhesivePlasticLaw(
            curvature=scales.radial**2 / (radius * scales.normal),
            hess=jnp.sqrt(2.0 * jnp.pi * scales.radial * self.work_of_adhesion / E_star) / scales.normal,
            yield_radius=yield_radius / scales.radial,
            flow_pressure=jnp.pi * self.yield_pressure * scales.radial / (E_star * scales.normal),
        )


def plastic_scales(law: AbstractPlasticLaw, radius, E_star, mass, touch_velocity) -> Scales:
    """Units in which an impact on Thornton's law is O(1) however far it yields: the deepest
    indentation δ_max (Thornton's closed form), the contact radius √(Rδ_max), the time δ_max/v₀
    and the force m·v₀²/δ_max (scaled mass 1, touch speed 1); R the paraboloid's radius (m)."""
    depth = theory.thornton_max_indentation(touch_velocity, mass, radius, E_star, law.yield_pressure)
    time = depth / touch_velocity
    return Scales(radial=jnp.sqrt(radius * depth), normal=depth, force=mass * depth / time**2, time=time)


def plastic_law(law: AbstractPlasticLaw, radius, E_star, scales: Scales) -> PlasticLaw:
    """Thornton's law of a paraboloid of radius R (m) in the units of `scales`: the yield depth
    δ_y = (πp_y/(2E*))²R."""
    yield_depth = (jnp.pi * law.yield_pressure / (2.0 * E_star)) ** 2 * radius
    return PlasticLaw(
        scales=scales,
        stiffness=4.0 / 3.0 * E_star * jnp.sqrt(radius) * scales.normal**1.5 / scales.force,
        radius_unit=jnp.sqrt(radius * scales.normal) / scales.radial,
        yield_depth=yield_depth / scales.normal,
    )
