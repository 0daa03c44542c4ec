"""Damping of the contact: a viscous force on the springs in contact, added to the elastic force
of the law and dissipating ∫F_visc ḋ dt.

Viscoelastic (Brilliantov, Spahn, Hertzsch & Pöschel, Phys. Rev. E 53, 5382 (1996)): for a
paraboloid F = ρ_H(δ^(3/2) + (3/2)A·δ^(1/2)·δ̇), ρ_H = (4/3)E*√R, with the dissipative constant A
(s). Its viscous part is A·(dF_el/dδ)·δ̇ = A·k_c·δ̇, k_c = 2E*a the contact stiffness: each spring
of the MDR foundation in contact (stiffness E*Δx) is damped by E*·A·Δx, so

    F_visc = 2E*·a·A·δ̇

for any profile, with a the current contact radius (with adhesion too). Linear (DEM-style):
F_visc = c·δ̇ while in contact, a force that jumps from 0 to c·v₀ at the touch.
"""

import equinox as eqx
import jax.numpy as jnp

from .._core.types import Parameter
from .._law.scales import Scales


class Damping(eqx.Module):
    """Damping parameters (SI, traced: new values do not recompile); 0 where unused."""

    dissipative_constant: Parameter  # A (s) of the viscoelastic model
    coefficient: Parameter  # c (N·s/m) of the linear model

    @staticmethod
    def none() -> "Damping":
        """No damping (the effect switched off)."""
        return Damping(jnp.zeros(()), jnp.zeros(()))

    def scaled(self, scales: Scales) -> tuple[Parameter, Parameter]:
        """(η_a, η_0) of the scaled viscous force F̂ = (η_a·â + η_0)·v̂ in the units of `scales`
        (force E*ℓxℓz, time √(m/(E*ℓx))): η_a = 2A/t* and η_0 = c/(E*ℓx·t*)."""
        per_radius = 2.0 * self.dissipative_constant / scales.time
        constant = self.coefficient * scales.normal / (scales.force * scales.time)
        return per_radius, constant
