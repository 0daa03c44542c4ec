"""A root found by a search, differentiated by the implicit function theorem
(`impact._core.derivatives.implicit_root`): its value as found, its first and second derivatives
against the closed form, and its function traced once."""

import jax
import jax.numpy as jnp
import numpy as np

from impact._core.derivatives import implicit_root
from impact._core.runtime import float64
from impact._core.search import bisect


def cube_root(theta, calls=None):
    """x with x³ = θ (θ > 0), bisected on [0, 1 + θ]: 60 halvings, the bracket's midpoint."""

    def residual(x):
        if calls is not None:
            calls.append(1)
        return x**3 - theta

    lower, upper = bisect(lambda x: x**3 < theta, jnp.zeros_like(theta), 1.0 + theta, 60)
    return implicit_root(residual, 0.5 * (lower + upper))


@float64
def test_the_root_keeps_its_value_and_has_the_derivatives_of_the_closed_form():
    """The value is the bisected root bit for bit; d/dθ θ^(1/3) = θ^(−2/3)/3 and its derivative
    −(2/9)·θ^(−5/3) to 1e-14 relative (the tangent rule is differentiable again), also under vmap."""
    theta = jnp.asarray([0.3, 2.0, 27.0])
    lower, upper = bisect(lambda x: x**3 < theta, jnp.zeros_like(theta), 1.0 + theta, 60)
    np.testing.assert_array_equal(np.asarray(cube_root(theta)), np.asarray(0.5 * (lower + upper)))
    first = jax.vmap(jax.grad(cube_root))(theta)
    second = jax.vmap(jax.grad(jax.grad(cube_root)))(theta)
    np.testing.assert_allclose(np.asarray(first), np.asarray(theta ** (-2.0 / 3.0) / 3.0), rtol=1e-14)
    np.testing.assert_allclose(np.asarray(second), np.asarray(-2.0 / 9.0 * theta ** (-5.0 / 3.0)), rtol=1e-14)


@float64
def test_the_function_is_traced_once():
    """Its value alone, and its first and second derivatives, trace the function once (its
    derivatives are those of the traced program)."""
    for transform in (lambda f: f, jax.grad, lambda f: jax.grad(jax.grad(f))):
        calls: list[int] = []
        jax.make_jaxpr(transform(lambda theta, calls=calls: cube_root(theta, calls)))(2.0)
        assert len(calls) == 1
