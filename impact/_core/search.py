"""Root and extremum searches with a fixed number of steps (jit- and vmap-friendly).

Every search here runs a `jax.lax.fori_loop` of a given length: the cost is known in advance,
batched lanes stay in lock step, and no runtime check can fail. The callers state how many
steps their bracket needs (bisection gains one bit per step, golden sections 0.69).
"""

import math
from collections.abc import Callable

import jax
import jax.numpy as jnp
from jaxtyping import Array, ArrayLike

from .derivatives import implicit_root

# (√5 − 1)/2: the golden-section ratio.
GOLDEN_RATIO = 0.5 * (math.sqrt(5.0) - 1.0)


def _arithmetic_mean(lower: Array, upper: Array) -> Array:
    return 0.5 * (lower + upper)


def bisect(
    stays_lower: Callable[[Array], Array],
    lower: ArrayLike,
    upper: ArrayLike,
    steps: int,
    midpoint: Callable[[Array, Array], Array] = _arithmetic_mean,
) -> tuple[Array, Array]:
    """Halve the bracket [lower, upper] `steps` times: the midpoint replaces the lower end where
    `stays_lower(midpoint)` holds, the upper end elsewhere. Returns the final (lower, upper).

    `midpoint` is the arithmetic mean, or e.g. the geometric mean for a search in log x.
    """

    def step(_, bracket):
        low, high = bracket
        middle = midpoint(low, high)
        moves = stays_lower(middle)
        return jnp.where(moves, middle, low), jnp.where(moves, high, middle)

    return jax.lax.fori_loop(0, steps, step, (jnp.asarray(lower), jnp.asarray(upper)))


def sign_change(function: Callable[[Array], Array], lower: ArrayLike, upper: ArrayLike, steps: int) -> Array:
    """Where `function` changes sign on [lower, upper], by bisection: the midpoint of the final
    bracket (meaningful only where the signs at the two ends differ)."""
    sign = jnp.sign(function(jnp.asarray(lower)))
    low, high = bisect(lambda x: jnp.sign(function(x)) == sign, lower, upper, steps)
    return 0.5 * (low + high)


def log_sign_change(
    excess: Callable[[Array], Array], lower: ArrayLike, upper: ArrayLike, steps: int
) -> tuple[Array, Array]:
    """Where `excess` changes sign between two positive points, bisected in log x (and
    differentiated implicitly): (point, found). Where the signs at the ends agree, `found` is False and the point is the
    upper end."""
    lower, upper = jnp.asarray(lower), jnp.asarray(upper)
    sign = jnp.sign(excess(lower))
    found = sign != jnp.sign(excess(upper))
    low, high = bisect(lambda log_x: jnp.sign(excess(jnp.exp(log_x))) == sign, jnp.log(lower), jnp.log(upper), steps)
    return jnp.where(found, implicit_root(excess, jnp.exp(0.5 * (low + high))), upper), found


def golden_section(
    function: Callable[[Array], Array], lower: ArrayLike, upper: ArrayLike, steps: int
) -> tuple[Array, Array]:
    """Shrink [lower, upper] around the minimum of a unimodal `function` by golden sections;
    returns the final bracket. Each step keeps one inner point and its value: one evaluation a
    step."""
    lower, upper = jnp.asarray(lower), jnp.asarray(upper)
    left = upper - GOLDEN_RATIO * (upper - lower)
    right = lower + GOLDEN_RATIO * (upper - lower)

    def step(_, state):
        low, high, left, right, left_value, right_value = state
        keep_left = left_value < right_value
        low, high = jnp.where(keep_left, low, left), jnp.where(keep_left, right, high)
        new = jnp.where(keep_left, high - GOLDEN_RATIO * (high - low), low + GOLDEN_RATIO * (high - low))
        value = function(new)
        return (
            low,
            high,
            jnp.where(keep_left, new, right),
            jnp.where(keep_left, left, new),
            jnp.where(keep_left, value, right_value),
            jnp.where(keep_left, left_value, value),
        )

    state = (lower, upper, left, right, function(left), function(right))
    low, high, *_ = jax.lax.fori_loop(0, steps, step, state)
    return low, high
