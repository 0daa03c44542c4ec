"""A root of a scalar function found outward from a start: steps doubling in one direction to a
sign change, then Illinois's regula falsi (the Dugdale zone's radius of `viscoelastic_dugdale`).
Every evaluation of the function, the start's included, is an iteration of one loop, so that the
function is compiled once."""

from typing import NamedTuple

import jax
import jax.numpy as jnp

# The zone radius's search: from c₀ outward in steps doubling from this fraction of Δx to a sign
# change of the range condition, then Illinois's regula falsi until the bracket is below this
# fraction of max(c, Δx), or this many steps.
_FIRST_STEP = 1.0 / 64.0
_EXPANSIONS = 48
_SETTLED = 1e-14
_REFINEMENTS = 100

# The search's phases: the start's value, the doubling steps, the regula falsi, done.
_START, _EXPAND, _REFINE, _DONE = 0, 1, 2, 3


class _Search(NamedTuple):
    phase: jax.Array
    start_value: jax.Array  # the function at the start
    low: jax.Array  # expanding: the last point short of a sign change; refining: one end
    low_value: jax.Array
    high: jax.Array  # expanding: the last point tried; refining: the other end
    high_value: jax.Array
    side: jax.Array  # Illinois's: the end the last guess replaced (−1 low, 1 high, 0 none yet)
    steps: jax.Array  # the doubling steps, then the regula falsi's
    bracketed: jax.Array


def root_outward(function, start, spacing, length, value=None, skip=False):
    """(root, found, value): the first sign change of the scalar `function` from `start` within
    (0, `length`], outward (c grows) where the function is negative at `start` (its `value`
    there, evaluated where None) and inward else: steps doubling from `_FIRST_STEP`·Δx to a
    bracket, then Illinois's regula falsi; `root` is `start` where none is found. Where `skip`
    (traced), nothing is evaluated and nothing found."""
    lowest = 1e-9 * spacing

    def settling(low, high, steps):
        return (jnp.abs(high - low) > _SETTLED * jnp.maximum(jnp.abs(high), spacing)) & (steps < _REFINEMENTS)

    def searching(search: _Search):
        return search.phase != _DONE

    def evaluate(search: _Search) -> _Search:
        phase, low, low_value, high, high_value, side, steps = (
            search.phase,
            search.low,
            search.low_value,
            search.high,
            search.high_value,
            search.side,
            search.steps,
        )
        direction = jnp.where(search.start_value < 0.0, 1.0, -1.0)
        far = jnp.clip(start + direction * _FIRST_STEP * spacing * 2.0**steps, lowest, length)
        guess = (low * high_value - high * low_value) / (high_value - low_value)
        inside = jnp.isfinite(guess) & ((guess - low) * (guess - high) < 0.0)
        guess = jnp.where(inside, guess, 0.5 * (low + high))
        point = jnp.where(phase == _START, start, jnp.where(phase == _EXPAND, far, guess))
        point_value = function(point)

        # The start: its value, and the direction of the search.
        at_start = _Search(
            phase=jnp.where(point_value == 0.0, _DONE, _EXPAND),
            start_value=point_value,
            low=start,
            low_value=point_value,
            high=start,
            high_value=point_value,
            side=side,
            steps=steps,
            bracketed=point_value == 0.0,
        )

        # A doubling step: on to a sign change, the end of the interval or the last step.
        bracketed = jnp.sign(point_value) != jnp.sign(search.start_value)
        ended = (far <= lowest) | (far >= length)
        moved = ~bracketed
        near, near_value = jnp.where(moved, far, low), jnp.where(moved, point_value, low_value)
        refines = bracketed & settling(near, far, jnp.zeros_like(steps))
        expands = ~bracketed & ~ended & (steps + 1 < _EXPANSIONS)
        expanded = _Search(
            phase=jnp.where(refines, _REFINE, jnp.where(expands, _EXPAND, _DONE)),
            start_value=search.start_value,
            low=near,
            low_value=near_value,
            high=far,
            high_value=point_value,
            side=jnp.zeros_like(side),
            steps=jnp.where(bracketed, 0, steps + 1),
            bracketed=bracketed,
        )

        # A step of the regula falsi.
        same_as_low = jnp.sign(point_value) == jnp.sign(low_value)
        # Illinois: halve the value kept twice on the same side.
        high_value = jnp.where(same_as_low & (side == -1), 0.5 * high_value, high_value)
        low_value = jnp.where(~same_as_low & (side == 1), 0.5 * low_value, low_value)
        low, low_value = jnp.where(same_as_low, point, low), jnp.where(same_as_low, point_value, low_value)
        high, high_value = jnp.where(same_as_low, high, point), jnp.where(same_as_low, high_value, point_value)
        stop = point_value == 0.0
        low, high = jnp.where(stop, point, low), jnp.where(stop, point, high)
        refined = _Search(
            phase=jnp.where(settling(low, high, steps + 1), _REFINE, _DONE),
            start_value=search.start_value,
            low=low,
            low_value=low_value,
            high=high,
            high_value=high_value,
            side=jnp.where(same_as_low, -1, 1),
            steps=steps + 1,
            bracketed=search.bracketed,
        )

        def by_phase(first, doubling, falsi):
            return jnp.where(phase == _START, first, jnp.where(phase == _EXPAND, doubling, falsi))

        return jax.tree.map(by_phase, at_start, expanded, refined)

    start = jnp.asarray(start)
    zero = jnp.zeros((), int)
    given = jnp.zeros_like(start) if value is None else jnp.asarray(value, start.dtype)
    first = _Search(
        phase=jnp.where(skip, _DONE, _START if value is None else jnp.where(given == 0.0, _DONE, _EXPAND)),
        start_value=given,
        low=start,
        low_value=given,
        high=start,
        high_value=given,
        side=zero,
        steps=zero,
        bracketed=~jnp.asarray(skip) & jnp.asarray(value is not None) & (given == 0.0),
    )
    search = jax.lax.while_loop(searching, evaluate, first)
    root = jnp.where(jnp.abs(search.low_value) <= jnp.abs(search.high_value), search.low, search.high)
    return jnp.where(search.bracketed, root, start), search.bracketed, search.start_value
