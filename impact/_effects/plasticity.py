"""Plasticity of the contact: Thornton's limiting contact pressure p_y for paraboloids (C.
Thornton, J. Appl. Mech. 64, 383 (1997)): the Hertzian peak pressure p₀ = 2E*a/(πR) cannot
exceed p_y; beyond, the contact yields (`impact._law.plastic`)."""

import equinox as eqx
import jax.numpy as jnp

from .. import theory
from .._core.types import Parameter
from .._law.adhesive_plastic import AdhesivePlasticLaw
from .._law.plastic import PlasticLaw
from .._law.scales import Scales


class Plasticity(eqx.Module):
    """The limiting contact pressure (SI, traced: new values do not recompile)."""

    yield_pressure: Parameter  # p_y (Pa); nan when the effect is off

    @staticmethod
    def none() -> "Plasticity":
        """No plasticity (the effect switched off)."""
        return Plasticity(jnp.full((), jnp.nan))

    def law(self, radius, E_star, scales: Scales) -> PlasticLaw:
        """Thornton's law of a paraboloid of radius R (m) in the units of `scales`: the yield
        depth δ_y = (πp_y/(2E*))²R."""
        yield_depth = (jnp.pi * self.yield_pressure / (2.0 * E_star)) ** 2 * radius
        return PlasticLaw(
            scales=scales,
            stiffness=4.0 / 3.0 * E_star * jnp.sqrt(radius) * scales.normal**1.5 / scales.force,
            radius_unit=jnp.sqrt(radius * scales.normal) / scales.radial,
            yield_depth=yield_depth / scales.normal,
        )

    def scales(self, radius, E_star, mass, touch_velocity) -> Scales:
        """Units in which the impact is O(1) however far it yields: the deepest indentation
        δ_max (Thornton's closed form), the contact radius √(Rδ_max), the time δ_max/v₀ and the
        force m·v₀²/δ_max (scaled mass 1, touch speed 1)."""
        depth = theory.thornton_max_indentation(touch_velocity, mass, radius, E_star, self.yield_pressure)
        time = depth / touch_velocity
        return Scales(radial=jnp.sqrt(radius * depth), normal=depth, force=mass * depth / time**2, time=time)

    def adhesive_law(self, radius, E_star, work_of_adhesion, scales: Scales) -> AdhesivePlasticLaw:
        """Thornton & Ning's (1998) adhesive law of a paraboloid of radius R (m) in the units of
        `scales`: ĝ = (ℓx²/(Rℓz))x̂², Δl̂ = √(2πℓxΔγ/E*)/ℓz·√x̂, yield where the JKR pressure at
        the centre reaches p_y."""
        yield_radius = theory.adhesive_plastic_yield_radius(radius, E_star, work_of_adhesion, self.yield_pressure)
        return AdhesivePlasticLaw(
            curvature=scales.radial**2 / (radius * scales.normal),
            hess=jnp.sqrt(2.0 * jnp.pi * scales.radial * work_of_adhesion / E_star) / scales.normal,
            yield_radius=yield_radius / scales.radial,
            flow_pressure=jnp.pi * self.yield_pressure * scales.radial / (E_star * scales.normal),
        )
