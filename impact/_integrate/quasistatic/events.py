"""The points and events of one step of a quasi-static march, and how they reach the carry."""

import jax.numpy as jnp

from ..._core.pytree import replace


class EventLog:
    """Points and events of one step, written to the carry's buffers in one scatter each (every
    scatter is a separate kernel for XLA to compile)."""

    def __init__(self):
        self.points, self.events, self.size = [], [], 0

    def emit(self, a, d, F, keep, leg):
        """Points (a, d, F) of program leg `leg`, kept where `keep`."""
        a, d, F = (jnp.atleast_1d(v) for v in (a, d, F))
        leg = jnp.broadcast_to(jnp.asarray(leg, a.dtype), a.shape)
        self.points.append((a, d, F, jnp.broadcast_to(keep, a.shape), leg))
        self.size += a.shape[0]

    def event(self, kind, keep):
        """An event at the last point emitted so far."""
        self.events.append((self.size - 1, kind, keep))

    def write(self, c):
        """The carry `c` with the kept points appended to its rows and the logged events to its
        events (past the buffers' ends they are dropped)."""
        a, d, F, keep, leg = (jnp.concatenate(parts) for parts in zip(*self.points, strict=True))
        position = c.count + jnp.cumsum(keep) - 1
        size = c.rows.shape[0]
        index = jnp.where(keep & (position < size), position, size)
        row = jnp.stack([a, d, F, leg], axis=-1)
        rows = c.rows.at[index].set(row, mode="drop")
        at = jnp.stack([position[i] if i >= 0 else c.count - 1 for i, _, _ in self.events])
        kinds = jnp.stack([jnp.asarray(kind) for _, kind, _ in self.events])
        logged = jnp.stack([jnp.asarray(k) for _, _, k in self.events])
        slot = c.event_count + jnp.cumsum(logged) - 1
        slots = c.events.shape[0]
        slot = jnp.where(logged & (slot < slots), slot, slots)
        events = c.events.at[slot].set(jnp.stack([at, kinds], axis=-1), mode="drop")
        return replace(
            c, rows=rows, count=c.count + jnp.sum(keep), events=events, event_count=c.event_count + jnp.sum(logged)
        )
