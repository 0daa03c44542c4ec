"""What every quasi-static march records (its points, events, pull-off and status), how one
step's points and events reach the record, and the loop that steps a march to its outcome."""

from collections.abc import Callable
from typing import Any, TypeVar

import equinox as eqx
import jax
import jax.numpy as jnp

from ..._core.pytree import replace, replace_where
from ..codes import Status, status_code
from .loading import QuasiStaticOutcome


class MarchRecord(eqx.Module):
    """What a march records besides its state: the pull-off, how it ended, the steps it took,
    its points and its events, each buffer with the count written so far (scaled)."""

    pull_off: jax.Array  # [3] a, d, F of the last stable state before the contact is lost (nan: none)
    status: Status
    done: jax.Array
    steps: jax.Array
    rows: jax.Array  # [R, 4] a, d, F, leg (nan where unused)
    count: jax.Array  # rows written
    events: jax.Array  # [E, 2] row index, kind (−1 where unused)
    event_count: jax.Array  # events written

    @classmethod
    def empty(cls, rows: int, events: int) -> "MarchRecord":
        """Before the first step: no pull-off, separated, not done, no step, and empty buffers
        for `rows` points and `events` events."""
        nan = jnp.full((), jnp.nan)
        return cls(
            pull_off=jnp.full(3, nan),
            status=Status.separated,
            done=jnp.asarray(False),
            steps=jnp.zeros((), int),
            rows=jnp.full((rows, 4), nan),
            count=jnp.zeros((), int),
            events=jnp.full((events, 2), -1),
            event_count=jnp.zeros((), int),
        )


class AbstractMarchCarry(eqx.Module):
    """The state of a march: where it is in the program (`program.Program`), the state of its
    law (each march's own fields) and its `record`."""

    leg: eqx.AbstractVar[jax.Array]  # the program's leg being run
    direction: eqx.AbstractVar[jax.Array]  # +1 up (d or F rising), −1 down
    target: eqx.AbstractVar[jax.Array]  # the leg's target, or the constant force of a landing
    landing: eqx.AbstractVar[jax.Array]  # force control: a move at constant force in progress
    record: eqx.AbstractVar[MarchRecord]


Carried = TypeVar("Carried", bound=AbstractMarchCarry)


def end_march(c: Carried, condition: Any, status: Status) -> Carried:
    """The carry with its march done where `condition` holds, ended with `status`."""
    return replace(c, record=replace_where(c.record, condition, status=status, done=True))


def record_pull_off(c: Carried, condition: Any, state: jax.Array) -> Carried:
    """The carry with the pull-off (a, d, F) `state` recorded where `condition` holds."""
    return replace(c, record=replace_where(c.record, condition, pull_off=state))


def run_march(step: Callable, start: Carried, steps: int, top) -> QuasiStaticOutcome:
    """Step the carry `start` until it is done or has taken `steps` steps (then its status is
    phase_limit); `top`: the radius the march's tables reach."""

    def running(c: Carried):
        return ~c.record.done & (c.record.steps < steps)

    def counted_step(c: Carried) -> Carried:
        return step(replace(c, record=replace(c.record, steps=c.record.steps + 1)))

    end = jax.lax.while_loop(running, counted_step, start).record
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

    def write(self, c: Carried) -> Carried:
        """The carry `c` with the kept points appended to its record's rows and the logged events
        to its events (past the buffers' ends they are dropped)."""
        record = c.record
        a, d, F, keep, leg = (jnp.concatenate(parts) for parts in zip(*self.points, strict=True))
        position = record.count + jnp.cumsum(keep) - 1
        size = record.rows.shape[0]
        index = jnp.where(keep & (position < size), position, size)
        row = jnp.stack([a, d, F, leg], axis=-1)
        rows = record.rows.at[index].set(row, mode="drop")
        at = jnp.stack([position[i] if i >= 0 else record.count - 1 for i, _, _ in self.events])
        kinds = jnp.stack([jnp.asarray(kind) for _, kind, _ in self.events])
        logged = jnp.stack([jnp.asarray(k) for _, _, k in self.events])
        slot = record.event_count + jnp.cumsum(logged) - 1
        slots = record.events.shape[0]
        slot = jnp.where(logged & (slot < slots), slot, slots)
        events = record.events.at[slot].set(jnp.stack([at, kinds], axis=-1), mode="drop")
        written = replace(
            record,
            rows=rows,
            count=record.count + jnp.sum(keep),
            events=events,
            event_count=record.event_count + jnp.sum(logged),
        )
        return replace(c, record=written)
