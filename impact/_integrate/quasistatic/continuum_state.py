"""The state of the continuum march, what its steps read, and how a leg or a landing ends."""

import equinox as eqx
import jax
import jax.numpy as jnp

from ..._core.pytree import replace_where
from ..._law.branches import Branch
from ..._law.law import ContactLaw
from ..codes import Status
from .events import EventLog
from .loading import EVENT, FREE, HOLD
from .setup import Built


class Carry(eqx.Module):
    leg: jax.Array
    direction: jax.Array  # +1 up (d or F increasing), −1 down
    target: jax.Array  # the leg's target, or the force of a landing
    landing: jax.Array  # a jump at constant force in progress (force control)
    mode: jax.Array
    wall: jax.Array  # held at the body's wall
    a: jax.Array
    d: jax.Array
    pre: jax.Array  # [2] a, d where the current instability began
    pull_off: jax.Array  # [3]
    status: Status
    done: jax.Array
    steps: jax.Array
    rows: jax.Array
    count: jax.Array
    events: jax.Array
    event_count: jax.Array


class ContinuumMarch(eqx.Module):
    """What every step reads: the law, its branches and the program (`Built`), the turning points
    of the path out and in (`edge_path`), the grid u ∈ [0, 1] a piece is sampled on, and the
    body's largest radius."""

    built: Built
    up_nodes: jax.Array
    up_tags: jax.Array  # 0: a turning point of h, 1: of the force (ξ = 3)
    down_nodes: jax.Array
    down_tags: jax.Array
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
    def force_control(self) -> jax.Array:
        return self.built.force_control

    def force(self, a, d):
        """F(a, d) of the law (scaled)."""
        return self.built.law.force(a, d)


def complete(march: ContinuumMarch, c: Carry, log: EventLog, keep) -> Carry:
    """The current target is met: a landing ends (its jump logged), or the leg ends."""
    built = march.built
    landed = keep & c.landing
    log.emit(c.a, c.d, march.force(c.a, c.d), landed, c.leg)
    kind = jnp.where(c.a >= c.pre[0], EVENT["snap_in"], EVENT["snap_out"])
    log.event(kind, landed & (c.a != c.pre[0]))
    leg_direction = built.directions[c.leg]
    c = replace_where(
        c,
        landed,
        landing=False,
        target=built.targets[c.leg],
        direction=leg_direction,
        mode=jnp.where(c.direction != leg_direction, HOLD, c.mode),
    )
    finished = keep & ~landed
    more = c.leg + 1 < built.legs
    following = jnp.minimum(c.leg + 1, built.legs - 1)
    log.event(EVENT["reversal"], finished & more & (c.mode != FREE))
    return replace_where(
        c,
        finished,
        leg=following,
        done=~more,
        direction=built.directions[following],
        target=built.targets[following],
        mode=jnp.where(c.mode == FREE, FREE, HOLD),
    )


def instability(march: ContinuumMarch, c: Carry, keep, a, d) -> Carry:
    """Force control: the applied force can no longer be met here; jump at constant force."""
    start = keep & march.force_control & ~c.landing
    return replace_where(c, start, landing=True, target=march.force(a, d), pre=jnp.stack([a, d]))
