"""Adhesion of the interface: the work of adhesion, its approach value and, for Maugis–Dugdale,
the adhesive stress; for Greenwood–Johnson, the double-Hertz factor k.

Zero range (JKR) by the rule of Heß (3.26): the edge spring at x lets go at the elongation
Δl(x) = √(2πxΔγ/E*), and on approach the next spring attaches once its gap closes to
√(2πxΔγa/E*), 0 ≤ Δγa ≤ Δγ (Δγa = Δγ: the reversible JKR law with its jump-in; Δγa = 0:
attach on touch). Finite range (Maugis–Dugdale, §3.8): the stress σ0 acts up to the range
h = Δγ/σ0 (3.4); or Greenwood and Johnson's double Hertz (§3.9), the factor k of the second
Hertz distribution (k → ∞: JKR, k → 0: DMT).
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core import derivatives
from .._core.types import Parameter
from .._law.scales import Scales


class Adhesion(eqx.Module):
    """Adhesion parameters (SI, traced: new values do not recompile)."""

    work_of_adhesion: Parameter  # Δγ (J/m²): the Dupré work of separation
    approach_work_of_adhesion: Parameter  # Δγa ≤ Δγ (J/m²): attachment on approach (JKR, Maugis–Dugdale)
    adhesive_stress: Parameter  # σ0 (Pa) of Maugis–Dugdale adhesion; nan for the other laws
    double_hertz_factor: Parameter  # k of Greenwood–Johnson adhesion; nan for the other laws

    @staticmethod
    def none() -> "Adhesion":
        """No adhesion (the effect switched off)."""
        zero = jnp.zeros(())
        return Adhesion(zero, zero, jnp.full((), jnp.nan), jnp.full((), jnp.nan))

    @property
    def adhesion_range(self) -> Parameter:
        """h = Δγ/σ0 (m) of the Maugis–Dugdale stress (3.4)."""
        return self.work_of_adhesion / self.adhesive_stress

    @property
    def approach_range(self) -> Parameter:
        """ha = Δγa/σ0 (m): the range over which Maugis–Dugdale's stress attaches on approach
        (`_law.dugdale_hysteresis`)."""
        return self.approach_work_of_adhesion / self.adhesive_stress

    def hess_coefficients(self, scales: Scales, E_star) -> tuple[jax.Array, jax.Array]:
        """(λ, λa) of the scaled Heß rule: the edge spring at x̂ detaches at the elongation λ·√x̂
        and the next one attaches at λa·√x̂, λa = λ·√(Δγa/Δγ) (3.26 in the units of `scales`)."""
        detach = jnp.sqrt(2.0 * jnp.pi * scales.radial * self.work_of_adhesion / E_star) / scales.normal
        attach = detach * derivatives.sqrt(self.approach_work_of_adhesion / self.work_of_adhesion)
        return detach, attach
