"""The state of the continuum march, what its steps read, and how a leg or a landing ends."""

import equinox as eqx
import jax
import jax.numpy as jnp

from ..._core.pytree import replace_where
from ..._law.branches import Branch
from ..._law.law import ContactLaw
from .events import AbstractMarchCarry, EventLog, MarchRecord
from .loading import EVENT, FREE, HOLD
from .program import Program, back_on_leg, next_leg
from .setup import Built, EdgePath


class Carry(AbstractMarchCarry):
    leg: jax.Array
    direction: jax.Array  # +1 up (d or F increasing), −1 down
    target: jax.Array  # the leg's target, or the force of a landing
    landing: jax.Array  # a jump at constant force in progress (force control)
    mode: jax.Array
    wall: jax.Array  # held at the body's wall
    a: jax.Array
    d: jax.Array
    pre: jax.Array  # [2] a, d where the current instability began
    record: MarchRecord


class ContinuumMarch(eqx.Module):
    """What every step reads: the law, its branches and the program (`Built`), the turning points
    of the path out and in (`edge_path`), the grid u ∈ [0, 1] a piece is sampled on, and the
    body's largest radius."""

    built: Built
    up: EdgePath  # out, along the attach edge
    down: EdgePath  # in, along the detach edge
    grid: jax.Array
    extent: jax.Array

    @property
    def law(self) -> ContactLaw:
        return self.built.law

    @property
    def attach(self) -> Branch:
        return self.built.problem.attach

    @property
    def detach(self) -> Branch:
        return self.built.problem.detach

    @property
    def program(self) -> Program:
        return self.built.program

    def force(self, a, d):
        """F(a, d) of the law (scaled)."""
        return self.built.law.force(a, d)


def complete(march: ContinuumMarch, c: Carry, log: EventLog, keep) -> Carry:
    """The current target is met: a landing ends (its jump logged), or the leg ends."""
    program = march.program
    landed = keep & c.landing
    log.emit(c.a, c.d, march.force(c.a, c.d), landed, c.leg)
    kind = jnp.where(c.a >= c.pre[0], EVENT["snap_in"], EVENT["snap_out"])
    log.event(kind, landed & (c.a != c.pre[0]))
    # Landing against the leg's direction, the march holds before it goes on.
    c = replace_where(c, landed, mode=jnp.where(c.direction != program.directions[c.leg], HOLD, c.mode))
    c = back_on_leg(c, program, landed)
    finished = keep & ~landed
    c = next_leg(c, program, log, finished, c.mode != FREE)
    return replace_where(c, finished, mode=jnp.where(c.mode == FREE, FREE, HOLD))


def instability(march: ContinuumMarch, c: Carry, keep, a, d) -> Carry:
    """Force control: the applied force can no longer be met here; jump at constant force."""
    start = keep & march.program.force_control & ~c.landing
    return replace_where(c, start, landing=True, target=march.force(a, d), pre=jnp.stack([a, d]))
