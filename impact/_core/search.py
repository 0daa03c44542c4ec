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


def illinois_root(function: Callable[[Array], Array], lower: ArrayLike, upper: ArrayLike, steps: int) -> Array:
    """A root of `function` between `lower` (function ≥ 0 there) and `upper` (≤ 0): regula falsi
    with the Illinois modification (Dowell & Jarratt, BIT 11, 168 (1971)), `steps` steps, each
    keeping the bracket (a secant point outside it is replaced by the middle). Returns the point
    tried of least |function|: once the method has settled, the bracket's ends carry halved
    values, and the last point tried may be a stale end's neighbour. (`_integrate.rootfind`'s
    `BracketIllinois` is the same method for diffrax's events, in optimistix's interface.)"""

    def step(state, _):
        a, fa, b, fb, best, least = state
        slope = fb - fa
        trial = jnp.where(slope != 0.0, b - fb * (b - a) / jnp.where(slope != 0.0, slope, 1.0), 0.5 * (a + b))
        lo, hi = jnp.minimum(a, b), jnp.maximum(a, b)
        trial = jnp.where((trial > lo) & (trial < hi), trial, 0.5 * (a + b))
        ft = function(trial)
        crosses = ft * fb < 0.0
        a, fa = jnp.where(crosses, b, a), jnp.where(crosses, fb, 0.5 * fa)
        better = jnp.abs(ft) < least
        return (a, fa, trial, ft, jnp.where(better, trial, best), jnp.where(better, jnp.abs(ft), least)), None

    lower, upper = jnp.asarray(lower), jnp.asarray(upper)
    f_lower, f_upper = function(lower), function(upper)
    best = jnp.where(jnp.abs(f_lower) < jnp.abs(f_upper), lower, upper)
    state = (lower, f_lower, upper, f_upper, best, jnp.minimum(jnp.abs(f_lower), jnp.abs(f_upper)))
    state, _ = jax.lax.scan(step, state, None, length=steps)
    return state[4]


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
