"""Friction: the tangential springs of an oblique impact and the body's sliding and spin, as
traced SI parameters (a sweep varies them without recompiling)."""

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np

from .._core.types import Parameter
from .._law.scales import Scales


class Friction(eqx.Module):
    """SI parameters of the tangential contact and motion (unused unless the integrator is an
    oblique one)."""

    coefficient: Parameter  # μ
    shear_modulus: Parameter  # G* (Pa): 1/G* = (2 − ν)/(4G) + (2 − ν_b)/(4G_b)
    tangential_velocity: Parameter  # v_t of the centre at the start (m/s), along +x
    spin: Parameter  # ω at the start (rad/s), > 0 rolling along +x
    inertia: Parameter  # I about the centre (kg·m²)
    lever_arm: Parameter  # R from the centre to the contact point (m)
    adhesive_load: Parameter  # 2F_c (N) of Thornton's whole-contact limit μ|F_n + 2F_c|; 0 else
    time_step: Parameter  # largest step of the tangential springs (s); nan: the default

    @staticmethod
    def none() -> "Friction":
        """No friction (the effect switched off): every value 0, the step the default."""
        zero = jax.device_put(np.zeros(()))  # copied from NumPy: jnp.zeros would compile a program
        return Friction(zero, zero, zero, zero, zero, zero, zero, jax.device_put(np.nan))

    def stiffness_ratio(self, E_star):
        """G*/E*: a tangential spring's stiffness over its normal spring's."""
        return self.shear_modulus / E_star

    def rotation(self, mass):
        """ρ = mR²/I: how much of the tangential impulse spins the body up (5/2 for a solid sphere)."""
        return mass * self.lever_arm**2 / self.inertia

    def scaled_start(self, scales: Scales):
        """(v_t, Ω = Rω) at the start in the units of `scales`."""
        return self.tangential_velocity / scales.velocity, self.lever_arm * self.spin / scales.velocity

    def scaled_step(self, scales: Scales, default):
        """The largest step in the units of `scales` (`default` where none is given)."""
        return jnp.where(jnp.isnan(self.time_step), default, self.time_step / scales.time)
