"""The parts of a step of the viscoelastic Maugis–Dugdale array
(`viscoelastic_dugdale.DugdaleZoneArray.advance`): a segment at loads linear in time, the zone's
walk in sub-steps, and a snap of the zone (its birth or collapse). Scaled units of `Scales`."""

import equinox as eqx
import jax
import jax.numpy as jnp

from .viscoelastic_springs import SpringStates


class Segment(eqx.Module):
    """The springs after a segment of a step at zone loads linear in time, and its totals."""

    springs: SpringStates
    impulse: jax.Array
    dissipation: jax.Array
    released: jax.Array  # the edge's snaps letting go: (f_load − f)²/(2e₀) each
    gained: jax.Array  # the edge's snaps attaching: ½e₀·Δu² each
    last_release: jax.Array


# Halvings of the sub-step that locate the fold (the step / 2⁴⁰: below round-off of the time).
FOLD_HALVINGS = 40


class FoldBracket(eqx.Module):
    """The bisection that locates the fold within a sub-step: the range condition keeps a root
    up to `low` and none at `high` (times into the sub-step); `FOLD_HALVINGS` halvings: none
    under way."""

    low: jax.Array
    high: jax.Array
    halvings: jax.Array

    @staticmethod
    def idle(duration) -> "FoldBracket":
        """No bisection under way."""
        return FoldBracket(jnp.zeros_like(duration), duration, jnp.asarray(FOLD_HALVINGS))


class Walked(eqx.Module):
    """The zone's part of a step (`viscoelastic_dugdale.DugdaleZoneArray._zone_walk`)."""

    springs: SpringStates
    zone: jax.Array  # c where the walk stopped
    elapsed: jax.Array  # time walked (the fold's time where it folds)
    impulse: jax.Array
    dissipation: jax.Array
    released: jax.Array
    gained: jax.Array
    last_release: jax.Array
    folds: jax.Array
    overflow: jax.Array
    length: jax.Array  # the next sub-step's length
    finished: jax.Array  # the last sub-step reached the step's end
    until: jax.Array  # where the walk ends: the step's end, or the fold once located
    pending: jax.Array  # the fold is located (or being located): the walk goes on to it
    fold: FoldBracket  # the fold's bisection, iterations of the walk's loop


class Snap(eqx.Module):
    """The springs and the zone after the zone's birth or collapse, and what it dissipated."""

    springs: SpringStates
    zone: jax.Array
    dissipation: jax.Array  # −(Δ stored + ΔU)
