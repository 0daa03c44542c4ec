"""Radii that a power-law body ĝ = Â·aⁿ states instead of searching for them, each against the
search that serves every other profile: the units' radii (`adhesive_scales`, `energy_scales`)
against a bisection in log x of their defining equation, and the bound on the contact radius
(`power_law_bound`) against the table of the stored work (`tabulated_bound`), found or not, over
exponents on both sides of n = 1/2, with and without adhesion."""

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from impact._core.search import log_sign_change
from impact._law.law import ContactLaw
from impact._law.reach import power_law_bound, radius_bound, tabulated_bound
from impact._law.scales import Scales, _bracket, adhesive_scales, energy_scales
from impact.profiles import Cone, Paraboloid, PowerLaw

ONE = jnp.ones(())
UNITS = Scales(radial=ONE, normal=ONE, force=ONE, time=ONE)  # SI = scaled: ĝ = κ(n)·c·aⁿ
PROFILES = {
    "paraboloid 10 µm": Paraboloid(R=1e-5),
    "paraboloid 1 cm": Paraboloid(R=1e-2),
    "cone 0.3 rad": Cone(theta=0.3),
    "cone 1.4 rad": Cone(theta=1.4),
    "power law n = 0.6": PowerLaw(n=0.6, c=0.1),
    "power law n = 1.5": PowerLaw(n=1.5, c=3e3),
    "power law n = 4": PowerLaw(n=4.0, c=1e12),
}
# The stated radius and the bisected one (100 halvings of 200 decades: to the last bit) differ
# by the rounding of ln x, ≤ 1e-15·|ln x| relative.
RADIUS_RTOL = 1e-13


@pytest.mark.parametrize("name", PROFILES)
def test_the_units_radii_of_a_power_law_body_are_the_roots_of_their_equations(name):
    profile = PROFILES[name]
    rng = np.random.default_rng(7)
    E_star, mass, speed, approach = (
        10 ** rng.uniform(low, high, 10) for low, high in ((6, 11), (-20, 3), (-3, 2), (-4, 3))
    )

    @jax.jit
    @jax.vmap
    def radii(E_star, mass, speed, approach):
        energy = 0.5 * mass * speed**2
        lower, upper = _bracket(profile)
        energetic, _ = log_sign_change(lambda x: E_star * x * profile.g(x) ** 2 - energy, lower, upper, 100)
        elongation = lambda x: jnp.sqrt(2.0 * jnp.pi * x * approach / E_star)  # noqa: E731
        jump_in, crosses = log_sign_change(lambda x: profile.g(x) - elongation(x), lower, upper, 100)
        stated = (
            energy_scales(profile, E_star, mass, speed).radial,
            adhesive_scales(profile, E_star, approach, mass, speed).radial,
        )
        # The jump-in radius is the unit where the impact reaches no further; else the energy's is.
        return stated, (energetic, jnp.where(crosses & (jump_in >= energetic), jump_in, energetic))

    stated, searched = radii(E_star, mass, speed, approach)
    np.testing.assert_allclose(stated, searched, rtol=RADIUS_RTOL)


def test_a_power_laws_radius_bound_is_the_tabulated_one():
    """The first radius above 1 where the stored work reaches ½v² + 1: stated and tabulated
    agree to 1e-12 (their sums of W round differently) and on whether it exists, for exponents
    on both sides of n = 1/2 (25 random edges and speeds each, a fifth without adhesion)."""
    rng = np.random.default_rng(11)
    exponent = np.repeat([0.3, 0.5, 0.55, 0.75, 1.0, 1.5, 2.0, 3.0, 6.0], 25)
    count = exponent.size
    coefficient = np.where(rng.random(count) < 0.2, 0.0, 10 ** rng.uniform(-3, 1.5, count))
    c, speed = 10 ** rng.uniform(-2, 2, count), 10 ** rng.uniform(-2, 3, count)

    @jax.jit
    @jax.vmap
    def bounds(exponent, c, coefficient, speed):
        law = ContactLaw(PowerLaw(n=exponent, c=c), UNITS, coefficient, coefficient, True)
        return (
            power_law_bound(law, coefficient, speed),
            tabulated_bound(law, coefficient, speed),
            radius_bound(law, coefficient, speed),
        )

    (stated, stated_found), (table, table_found), (capped, _) = bounds(exponent, c, coefficient, speed)
    np.testing.assert_array_equal(stated_found, table_found)
    assert stated_found[exponent > 0.5].all() and not stated_found.all()
    np.testing.assert_allclose(stated, table, rtol=1e-12)
    np.testing.assert_array_equal(capped, stated)  # an unwalled body: no cap
