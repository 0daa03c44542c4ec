"""Internal units of a scene: lengths, force and time chosen so the contact problem is O(1).

With adhesion the radial unit is the jump-in radius a0 (g(a0) = Δl(a0)) and the normal unit
Δl(a0), so the Heß criterion reads Δl̂(x̂) = √x̂ — unless the impact energy reaches further, or
there is no jump-in: then the energy units below. Without adhesion the units follow from the
impact energy: E*·ℓx·ℓz² = ½·m·v². In both cases the force unit is E*·ℓx·ℓz and the time unit
√(m/(E*·ℓx)), which makes the scaled mass 1.
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.search import log_sign_change
from ..profiles import Profile

_BISECTION_STEPS = 100
# The bracket around the profile's radius scale, within the float64 range (power laws near
# n = 1/2 put the jump-in radius dozens of decades away from it).
_BRACKET_DECADES = 100.0
_SMALLEST, _LARGEST = 1e-300, 1e300


class Scales(eqx.Module):
    """SI values of the internal units."""

    radial: jax.Array  # ℓx (m)
    normal: jax.Array  # ℓz (m)
    force: jax.Array  # E*·ℓx·ℓz (N)
    time: jax.Array  # √(m/(E*·ℓx)) (s)

    @property
    def velocity(self):
        """Velocity unit ℓz/t (m/s)."""
        return self.normal / self.time

    @property
    def energy(self):
        """Energy unit F·ℓz (J)."""
        return self.force * self.normal


def _bracket(profile: Profile):
    reference = profile.radius_scale()
    lower = jnp.maximum(reference * 10.0 ** (-_BRACKET_DECADES), _SMALLEST)
    upper = jnp.minimum(profile.extent(), jnp.minimum(reference * 10.0**_BRACKET_DECADES, _LARGEST))
    return lower, upper


def adhesive_scales(profile: Profile, E_star, approach_work_of_adhesion, mass, touch_velocity) -> Scales:
    """Units of an adhesive impact: the jump-in radius on approach, g(ℓx) = √(2π·ℓx·Δγa/E*),
    with ℓz that elongation (so the Heß rule reads √x̂), unless the impact energy reaches a
    larger radius: then the energy units. Without a jump-in (Δγa = 0, attach on touch) or a
    jump-in radius (g ∝ √x, power law n = 1/2), the energy units; a flat punch uses its radius.
    """

    def elongation(x):
        return jnp.sqrt(2.0 * jnp.pi * x * approach_work_of_adhesion / E_star)

    lower, upper = _bracket(profile)
    # g(x) = A·xⁿ meets √(2π·x·Δγa/E*) where x^(2n−1) = 2πΔγa/(E*·A²).
    radial, crosses = _radius_where(
        profile, lambda x: profile.g(x) - elongation(x), 2.0 * jnp.pi * approach_work_of_adhesion / E_star, -1.0
    )
    # A jump-in needs h = g − Δl below zero at the bracket's lower end (for n < 1/2 the crossing
    # is the far zero of h instead; for a tiny Δγa the jump-in lies below the bracket); it
    # reaches the crossing, or the wall of a body that h stays below (the flat punch).
    below_at_tip = profile.g(lower) < elongation(lower)
    walled = jnp.isfinite(profile.extent())
    jump_in = _complete(radial, elongation(radial), E_star, mass)
    energetic = energy_scales(profile, E_star, mass, touch_velocity)
    use_jump_in = below_at_tip & (crosses | walled) & (approach_work_of_adhesion > 0.0) & (radial >= energetic.radial)
    return jax.tree.map(lambda a, e: jnp.where(use_jump_in, a, e), jump_in, energetic)


def energy_scales(profile: Profile, E_star, mass, touch_velocity) -> Scales:
    """Units from the impact energy: E*·ℓx·g(ℓx)² = ½·m·v²."""
    energy = 0.5 * mass * touch_velocity**2
    # g(x) = A·xⁿ: x^(2n+1) = energy/(E*·A²).
    radial, _ = _radius_where(profile, lambda x: E_star * x * profile.g(x) ** 2 - energy, energy / E_star, 1.0)
    normal = jnp.sqrt(energy / (E_star * radial))
    return _complete(radial, normal, E_star, mass)


def _radius_where(profile: Profile, excess, power_constant, power_offset: float):
    """Where `excess` changes sign in the bracket of the profile: (radius, found), the upper end
    where it does not. For a profile g = A·xⁿ (`Profile.power_form`) the excess vanishes where
    A²·x^(2n + offset) = constant, and the radius is stated, ln x = (ln constant − 2 ln A)/(2n +
    offset) (to ~1e-15·|ln x| relative); else bisected in log x."""
    lower, upper = _bracket(profile)
    form = profile.power_form()
    if form is None:
        return log_sign_change(excess, lower, upper, _BISECTION_STEPS)
    scale, exponent = form
    power = 2.0 * exponent + power_offset
    solvable = power != 0.0
    log_radius = (jnp.log(power_constant) - 2.0 * jnp.log(scale)) / jnp.where(solvable, power, 1.0)
    found = solvable & (log_radius > jnp.log(lower)) & (log_radius < jnp.log(upper))
    return jnp.where(found, jnp.exp(log_radius), upper), found


def _complete(radial, normal, E_star, mass) -> Scales:
    return Scales(
        radial=radial,
        normal=normal,
        force=E_star * radial * normal,
        time=jnp.sqrt(mass / (E_star * radial)),
    )
