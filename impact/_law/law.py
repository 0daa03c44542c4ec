"""The MDR contact law in scaled units: profile, Heß elongation and force.

Lengths are in the units of `Scales` (x̂ = x/ℓx, d̂ = d/ℓz), forces in E*·ℓx·ℓz. An attached
spring at x carries the displacement d − g(x); with the contact radius a the force is
F = 2·(a·d − G(a)) (3.28). The edge spring detaches when g(a) − d reaches Δl(a) = λ·√a (3.26)
and the next spring attaches when g(x) − d ≤ λa·√x, so the edge functions
h(x) = g(x) − λ·√x decide every change of the contact radius.
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core import derivatives
from ..profiles import PowerLaw, Profile
from .scales import Scales


class ContactLaw(eqx.Module):
    """A profile pressed into the scaled spring foundation, with or without adhesion."""

    profile: Profile
    scales: Scales
    detach_coefficient: jax.Array  # λ: Δl̂(x̂) = λ·√x̂ (0 without adhesion)
    attach_coefficient: jax.Array  # λa = λ·√(Δγa/Δγ)
    # (Â, n) of a power-law body, ĝ = Â·x̂ⁿ, computed once: its g and G are then one log and
    # one exp of the scaled radius, not a power with a traced exponent and κ(n)'s two
    # log-gammas in every evaluation (many times a paraboloid's cost); None else.
    power_law: tuple[jax.Array, jax.Array] | None
    adhesive: bool = eqx.field(static=True)

    def __init__(self, profile: Profile, scales: Scales, detach_coefficient, attach_coefficient, adhesive: bool):
        self.profile = profile
        self.scales = scales
        self.detach_coefficient = detach_coefficient
        self.attach_coefficient = attach_coefficient
        self.adhesive = adhesive
        self.power_law = _scaled_power_form(profile, scales) if isinstance(profile, PowerLaw) else None

    def g(self, x):
        """Scaled 1-D profile ĝ(x̂)."""
        if self.power_law is not None:
            coefficient, exponent = self.power_law
            return coefficient * power(x, exponent)
        return self.profile.g(x * self.scales.radial) / self.scales.normal

    def G(self, x):
        """Scaled ∫₀^x̂ ĝ."""
        if self.power_law is not None:
            coefficient, exponent = self.power_law
            return coefficient * x * power(x, exponent) / (exponent + 1.0)
        return self.profile.G(x * self.scales.radial) / (self.scales.radial * self.scales.normal)

    def extent(self):
        """Largest scaled contact radius the body allows (inf for unbounded shapes; kept out of
        the division, whose derivative would be nan)."""
        extent = self.profile.extent()
        return jnp.where(jnp.isfinite(extent), extent / self.scales.radial, jnp.inf)

    def power_form(self):
        """(Â, n) where ĝ(x̂) = Â·x̂ⁿ, or None where the profile has no such form."""
        if self.power_law is not None:
            return self.power_law
        return _scaled_power_form(self.profile, self.scales)

    def edge(self, x, coefficient):
        """Edge function h(x̂) = ĝ(x̂) − coefficient·√x̂ (ĝ alone without adhesion)."""
        if not self.adhesive:
            return self.g(x)
        return self.g(x) - coefficient * derivatives.sqrt(x)

    def g_slope(self, x):
        """dĝ/dx̂."""
        return jax.jvp(self.g, (x,), (jnp.ones_like(x),))[1]

    def edge_slope(self, x, coefficient):
        """dh/dx̂ (the Heß term's slope written out: 0 when its coefficient is 0, even at x̂ = 0)."""
        if not self.adhesive:
            return self.g_slope(x)
        hess = jnp.where(coefficient > 0.0, 0.5 * coefficient / jnp.sqrt(jnp.where(coefficient > 0.0, x, 1.0)), 0.0)
        return self.g_slope(x) - hess

    def force(self, radius, indentation):
        """Scaled force 2·(a·d − Ĝ(a)) (3.28); compressive positive."""
        return 2.0 * (radius * indentation - self.G(radius))


def _scaled_power_form(profile: Profile, scales: Scales):
    """(Â, n) of ĝ = Â·x̂ⁿ in the units of `scales`, or None where g has no power form."""
    form = profile.power_form()
    if form is None:
        return None
    coefficient, exponent = form
    return coefficient * scales.radial**exponent / scales.normal, exponent


def half_power_root(ratio, exponent, usable):
    """The radius a where a^(n−½) = `ratio` for ĝ = Â·aⁿ: where the edge h = Â·aⁿ − λ·√a and
    what is built on it (force, stored work) turn, with `ratio` a multiple of λ/(nÂ); 1 where
    not `usable` (no adhesion, n = ½)."""
    return jnp.where(usable, ratio, 1.0) ** (1.0 / jnp.where(usable, exponent - 0.5, 1.0))


def power(x, exponent):
    """x̂ⁿ for x̂ ≥ 0 as exp(n·ln x̂) (0 at x̂ = 0, with slope 0 there: as `PowerLaw.f`). In the
    scaled units ln x̂ = O(1), so it is within a few ulps of the power, at a fraction of the
    cost of a power with a traced exponent."""
    positive = x > 0.0
    return jnp.where(positive, jnp.exp(exponent * jnp.log(jnp.where(positive, x, 1.0))), 0.0)
