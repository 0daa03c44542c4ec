"""What every quasi-static march records (its points, events, pull-off and status), how one
step's points and events reach the carry, and the loop that steps a march to its outcome."""

from collections.abc import Callable
from typing import Any

import jax
import jax.numpy as jnp

from ..._core.pytree import replace
from ..codes import Status, status_code
from .loading import QuasiStaticOutcome


def empty_record(rows: int, events: int) -> dict[str, Any]:
    """The record fields every march carry shares, before the first step: no instability begun
    (`pre`), no pull-off, separated, not done, no step, and empty buffers for `rows` points
    (a, d, F, leg) and `events` events (row, kind)."""
    nan = jnp.full((), jnp.nan)
    return {
        "pre": jnp.zeros(2),
        "pull_off": jnp.full(3, nan),
        "status": Status.separated,
        "done": jnp.asarray(False),
        "steps": jnp.zeros((), int),
        "rows": jnp.full((rows, 4), nan),
        "count": jnp.zeros((), int),
        "events": jnp.full((events, 2), -1),
        "event_count": jnp.zeros((), int),
    }


def run_march(step: Callable, start, steps: int, top) -> QuasiStaticOutcome:
    """Step the carry `start` until it is done or has taken `steps` steps (then its status is
    phase_limit); `top`: the radius the march's tables reach."""

    def running(c):
        return ~c.done & (c.steps < steps)

    end = jax.lax.while_loop(running, step, start)
    status = status_code(Status.where(end.done, end.status, Status.phase_limit))
    return QuasiStaticOutcome(
        status=status, pull_off=end.pull_off, rows=end.rows, events=end.events, steps=end.steps, top=top
    )


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
