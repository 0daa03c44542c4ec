"""The event root finder (`impact._integrate.rootfind.BracketIllinois`): a crossing located to
its tolerance in a handful of evaluations where bisection takes ~45, and a bracket without a
crossing closed onto its lower end, where bisection ends too."""

import jax
import jax.numpy as jnp
import numpy as np
import optimistix as optx
import pytest

from impact._core.runtime import float64
from impact._core.search import illinois_root
from impact._integrate.rootfind import BracketIllinois

RTOL, ATOL = 1e-14, 1e-15
# (condition, bracket, root): smooth, steep, kinked and nearly tangent crossings, upwards.
CROSSINGS = {
    "linear": (lambda t: t - 0.3, (0.0, 1.0), 0.3),
    "cubic": (lambda t: t**3 - 0.2, (0.0, 1.0), 0.2 ** (1 / 3)),
    "exponential": (lambda t: jnp.exp(t) - 2.0, (0.1, 3.0), np.log(2.0)),
    "square root": (lambda t: jnp.sqrt(t) - 0.5, (0.0, 1.0), 0.25),
    "steep": (lambda t: jnp.tanh(50.0 * (t - 0.37)), (0.0, 1.0), 0.37),
    "kinked": (lambda t: jnp.maximum(t - 0.7, t - 0.9), (0.0, 1.0), 0.7),
    "nearly tangent": (lambda t: 1e-3 - (1.0 - t) ** 2, (0.0, 1.0), 1.0 - np.sqrt(1e-3)),
    "late in a long solve": (lambda t: t - 3300.001, (3300.0, 3300.1), 3300.001),
}


@float64
def locate(condition, lower: float, upper: float):
    # diffrax starts the root find at the bracket's upper end
    return optx.root_find(
        lambda t, _: condition(t),
        BracketIllinois(rtol=RTOL, atol=ATOL),
        y0=jnp.asarray(upper),
        options=dict(lower=jnp.asarray(lower), upper=jnp.asarray(upper)),
        throw=False,
        max_steps=256,
    )


@pytest.mark.parametrize("name", CROSSINGS)
def test_a_crossing_is_located_to_the_tolerance_in_few_steps(name):
    condition, (lower, upper), root = CROSSINGS[name]
    solution = locate(condition, lower, upper)
    assert abs(float(solution.value) - root) <= 2 * (ATOL + RTOL * abs(root))
    assert int(solution.stats["num_steps"]) <= 25  # bisection: 45–50


def test_a_bracket_without_a_crossing_closes_onto_its_lower_end():
    # a lane whose ride found no event: diffrax asks for the root of t_end − t
    solution = locate(lambda t: 1.0 - t, 0.25, 1.0)
    assert float(solution.value) == 0.25
    assert int(solution.stats["num_steps"]) == 0


def test_lanes_of_a_batch_are_located_each_to_its_own_root():
    roots = jnp.linspace(0.05, 0.95, 9)
    located = jax.vmap(lambda r: locate(lambda t: jnp.sin(3.0 * (t - r)), 0.0, 1.0).value)(roots)
    np.testing.assert_allclose(located, roots, rtol=0, atol=2 * (ATOL + RTOL))


@pytest.mark.parametrize(
    ("function", "lower", "upper", "root"),
    [
        (lambda x: 2.0 - x**2, 1.0, 2.0, np.sqrt(2.0)),
        (lambda x: 1.0 - jnp.exp(8.0 * (x - 0.3)), 0.0, 1.0, 0.3),  # values 0.91 and −267: lopsided
    ],
)
def test_the_fixed_step_illinois_root_is_the_root_to_round_off(function, lower, upper, root):
    """`impact._core.search.illinois_root` (the quadrature's turnarounds): 16 steps reach the root
    to 4 ulps from a bracket of width 1, vmapped as well as alone (12 leave the lopsided one
    1.2e-4 off: measured)."""
    with jax.enable_x64(True):
        found = float(illinois_root(function, jnp.float64(lower), jnp.float64(upper), 16))
        batched = jax.vmap(lambda a: illinois_root(function, a, jnp.float64(upper), 16))(jnp.full(3, lower))
    assert abs(found - root) <= 4 * np.finfo(float).eps * root
    assert np.all(np.asarray(batched) == found)
