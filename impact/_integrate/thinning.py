"""Trajectory rows of a stepping loop, evenly thinned to fit a fixed number of rows."""

import equinox as eqx
import jax
import jax.numpy as jnp


class KeptRows(eqx.Module):
    """The rows stored so far: `trajectory` (rows × columns, NaN where unwritten), how many are
    written (`stored`) and the steps between two of them (`stride`)."""

    trajectory: jax.Array
    stored: jax.Array
    stride: jax.Array


def keep_row(trajectory, stored, stride, step, row, valid=True) -> KeptRows:
    """Store `row` of step number `step` if the step is a multiple of `stride`; when the rows are
    full, first drop every other one and double the stride, so any number of steps fits, evenly
    thinned, in time order. `valid` false: nothing changes."""
    rows = trajectory.shape[0]
    full = valid & (stored >= rows)

    def thin(kept: tuple[jax.Array, jax.Array]) -> tuple[jax.Array, jax.Array]:
        trajectory, stride = kept
        half = trajectory[::2]
        return jnp.full_like(trajectory, jnp.nan).at[: half.shape[0]].set(half), 2 * stride

    trajectory, stride = jax.lax.cond(full, thin, lambda kept: kept, (trajectory, jnp.asarray(stride)))
    stored = jnp.where(full, (rows + 1) // 2, stored)
    keep = valid & (step % stride == 0)
    target = jnp.minimum(stored, rows - 1)
    trajectory = trajectory.at[target].set(jnp.where(keep, row, trajectory[target]))
    return KeptRows(trajectory=trajectory, stored=stored + jnp.asarray(keep, int), stride=stride)
