"""A root of a scalar function found outward from a start: steps doubling in one direction to a
sign change, then Illinois's regula falsi (the Dugdale zone's radius of `viscoelastic_dugdale`)."""

import jax
import jax.numpy as jnp

# The zone radius's search: from c₀ outward in steps doubling from this fraction of Δx to a sign
# change of the range condition, then Illinois's regula falsi until the bracket is below this
# fraction of max(c, Δx), or this many steps.
_FIRST_STEP = 1.0 / 64.0
_EXPANSIONS = 48
_SETTLED = 1e-14
_REFINEMENTS = 100


def root_outward(function, start, value, direction, spacing, length):
    """(root, found): the first sign change of the scalar `function` from `start` (where it is
    `value`) in `direction`, within (0, `length`]: steps doubling from `_FIRST_STEP`·Δx to a
    bracket, then Illinois's regula falsi."""
    lowest = 1e-9 * spacing

    def expanding(search):
        _, _, _, _, bracketed, ended, steps = search
        return ~bracketed & ~ended & (steps < _EXPANSIONS)

    def expand(search):
        near, near_value, _, _, _, _, steps = search
        far = jnp.clip(start + direction * _FIRST_STEP * spacing * 2.0**steps, lowest, length)
        far_value = function(far)
        bracketed = jnp.sign(far_value) != jnp.sign(value)
        ended = (far <= lowest) | (far >= length)
        moved = ~bracketed
        near, near_value = jnp.where(moved, far, near), jnp.where(moved, far_value, near_value)
        return near, near_value, far, far_value, bracketed, ended, steps + 1

    first = (start, value, start, value, jnp.asarray(value == 0.0), jnp.asarray(False), jnp.zeros((), int))
    near, near_value, far, far_value, bracketed, _, _ = jax.lax.while_loop(expanding, expand, first)

    def refining(search):
        low, _, high, _, _, steps = search
        return (jnp.abs(high - low) > _SETTLED * jnp.maximum(jnp.abs(high), spacing)) & (steps < _REFINEMENTS)

    def refine(search):
        low, low_value, high, high_value, side, steps = search
        guess = (low * high_value - high * low_value) / (high_value - low_value)
        inside = jnp.isfinite(guess) & ((guess - low) * (guess - high) < 0.0)
        guess = jnp.where(inside, guess, 0.5 * (low + high))
        guess_value = function(guess)
        same_as_low = jnp.sign(guess_value) == jnp.sign(low_value)
        # Illinois: halve the value kept twice on the same side.
        high_value = jnp.where(same_as_low & (side == -1), 0.5 * high_value, high_value)
        low_value = jnp.where(~same_as_low & (side == 1), 0.5 * low_value, low_value)
        low, low_value = jnp.where(same_as_low, guess, low), jnp.where(same_as_low, guess_value, low_value)
        high, high_value = jnp.where(same_as_low, high, guess), jnp.where(same_as_low, high_value, guess_value)
        side = jnp.where(same_as_low, -1, 1)
        stop = guess_value == 0.0
        low, high = jnp.where(stop, guess, low), jnp.where(stop, guess, high)
        return low, low_value, high, high_value, side, steps + 1

    search = (near, near_value, far, far_value, jnp.zeros((), int), jnp.zeros((), int))
    search = jax.lax.cond(bracketed, lambda s: jax.lax.while_loop(refining, refine, s), lambda s: s, search)
    low, low_value, high, high_value, _, _ = search
    root = jnp.where(jnp.abs(low_value) <= jnp.abs(high_value), low, high)
    return jnp.where(bracketed, root, start), bracketed
