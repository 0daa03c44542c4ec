"""`computed_once` stores values that XLA:CPU would otherwise compute again in each consumer, and
`only_where` computes a value only where some lane of a batch needs it, each lane's result
exact."""

import jax
import jax.numpy as jnp
import numpy as np

from impact._core.lanes import computed_once, only_where
from impact._core.quadrature import ordered_sum

MARKER = 0.123456789  # a constant that appears once in every fusion computing `polynomial`


def polynomial(x):
    """Elementwise work that XLA fuses into its consumers."""
    value = jnp.zeros_like(x)
    for _ in range(8):
        value = value * x + MARKER
    return value


def prefix_sums(values):
    """Running sums of a short vector, each a consumer of all the values before it."""
    sums = [values[0]]
    for value in values[1:]:
        sums.append(sums[-1] + value)
    return jnp.stack(sums)


def test_values_computed_once_are_the_values_and_compiled_once():
    points = jnp.linspace(0.1, 0.9, 3 * 10 * 12).reshape(3, 10, 12)

    def at_once(rows):
        return prefix_sums(ordered_sum(polynomial(rows)))

    def once(rows):
        return prefix_sums(ordered_sum(computed_once(polynomial, rows)))

    fused, stored = jax.jit(jax.vmap(at_once)), jax.jit(jax.vmap(once))
    assert np.array_equal(stored(points), fused(points))
    assert fused.lower(points).compile().as_text().count(f"constant({MARKER})") > 1
    assert stored.lower(points).compile().as_text().count(f"constant({MARKER})") == 1


def test_only_where_computes_where_a_lane_needs_it():
    calls = []

    def compute(x):
        jax.debug.callback(lambda: calls.append(1))
        return jnp.sqrt(x), x + 1.0

    def lane(needed, x):
        return only_where(needed, lambda: compute(x), (-x, jnp.zeros_like(x)))

    program = jax.jit(jax.vmap(lane))
    x = jnp.array([4.0, 9.0, 16.0])
    roots, next_ = program(jnp.array([True, False, True]), x)
    assert roots.tolist() == [2.0, -9.0, 4.0] and next_.tolist() == [5.0, 0.0, 17.0]
    assert len(calls) == 1  # one turn for the whole batch
    roots, _ = program(jnp.array([False, False, False]), x)
    assert roots.tolist() == [-4.0, -9.0, -16.0]
    assert len(calls) == 1  # no turn: nothing computed
