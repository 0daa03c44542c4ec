"""The cascade of a continuum step: the radius jumps at constant d to the next edge crossing.

The segment that brackets the crossing is chosen before the step's one bisection
(`cascade_bracket`); the root then gives the new radius, a separation, the wall or a stop
(`cascade_outcome`), applied by `after_cascade`."""

import equinox as eqx
import jax
import jax.numpy as jnp

from ..._core.pytree import replace_where
from ..._law.branches import Branch
from ..codes import Status
from .continuum_state import Carry, ContinuumMarch, complete, instability
from .events import EventLog, end_march, record_pull_off
from .loading import EVENT, FREE, HOLD, RIDE, SAME_RADIUS
from .program import back_on_leg


class Bracket(eqx.Module):
    """The segment of the branch of the direction where the next edge crossing lies."""

    branch: Branch  # attach (outward) or detach (inward)
    segment: jax.Array
    none: jax.Array  # outward: blocked (wall or no end); inward: separated

    @property
    def lower(self) -> jax.Array:
        return self.branch.nodes[self.segment]

    @property
    def upper(self) -> jax.Array:
        return self.branch.nodes[self.segment + 1]


class Outcome(eqx.Module):
    """Where a cascade ends."""

    radius: jax.Array
    gone: jax.Array  # inward with no crossing: the contact is lost
    wall: jax.Array  # outward to the body's wall
    stop: jax.Array  # outward with no end: the march stops with `code`
    code: Status


def cascade_bracket(march: ContinuumMarch, c: Carry, up) -> Bracket:
    """At constant d from the current state: the first rising segment with a crossing of the
    level d, on the attach branch outward or the detach branch inward (`Branch.cascade_out`/`_in`)."""
    a, d = c.a, c.d
    branch = jax.tree.map(lambda x, y: jnp.where(up, x, y), march.attach, march.detach)
    outward = branch.increasing & (branch.nodes[1:] > a) & (branch.levels[1:] > d)
    inward = branch.increasing & (branch.nodes[:-1] < a) & (branch.levels[:-1] < d)
    candidate = jnp.where(up, outward, inward)
    count = candidate.shape[0]
    segment = jnp.where(up, jnp.argmax(outward), count - 1 - jnp.argmax(inward[::-1]))
    return Bracket(branch=branch, segment=segment, none=~jnp.any(candidate))


def cascade_outcome(march: ContinuumMarch, bracket: Bracket, root, a, up) -> Outcome:
    """The radius the cascade from a reaches (the root on the bracket), or the wall, a
    separation, or a stop: unbounded contact or a radius beyond the branch tables."""
    branch, none = bracket.branch, bracket.none
    radius = jnp.where(up, jnp.maximum(root, a), jnp.minimum(root, a))
    wall = up & none & (branch.nodes[-1] >= march.extent)
    stop = up & none & ~wall
    unbounded = (~branch.increasing[-1] & ~jnp.isfinite(march.extent)) | ~march.built.bounded
    code = Status.where(unbounded, Status.unbounded_contact, Status.radius_overflow)
    radius = jnp.where(wall, branch.nodes[-1], jnp.where(none, 0.0, radius))
    return Outcome(radius=radius, gone=~up & none, wall=wall, stop=stop, code=code)


def after_cascade(march: ContinuumMarch, c: Carry, log: EventLog, keep, a, d, outcome: Outcome, up) -> Carry:
    """The radius jumped (or not) at constant d from a: apply the outcome of the cascade."""
    moved = jnp.abs(outcome.radius - a) > SAME_RADIUS * jnp.maximum(a, SAME_RADIUS)  # scaled: O(1) radii
    # Force control: a jump that starts outside a landing is itself an instability.
    c = instability(march, c, keep & (moved | outcome.gone) & ~outcome.stop, a, d)
    c = separate(march, c, log, keep & outcome.gone, a, d)
    jumped = keep & ~outcome.gone & ~outcome.stop
    c = jump(march, c, log, jumped, moved, a, d, outcome, up)
    return end_march(c, keep & outcome.stop, outcome.code)


def separate(march: ContinuumMarch, c: Carry, log: EventLog, pulled, a, d) -> Carry:
    """Separation: the pull-off is where the instability began (force) or this point (a, d)."""
    before = jnp.where(c.landing, c.pre, jnp.stack([a, d]))
    F_before = march.force(before[0], before[1])
    c = record_pull_off(c, pulled, jnp.concatenate([before, F_before[None]]))
    # The curve ends at the pull-off; under displacement control the force then drops to 0 at
    # constant d (under force control the body leaves at constant force: no state follows).
    log.emit(before[0], before[1], F_before, pulled, c.leg)
    log.event(EVENT["pull_off"], pulled)
    log.emit(0.0, d, 0.0, pulled & ~march.program.force_control, c.leg)
    c = replace_where(c, pulled, mode=FREE, a=0.0, d=d, wall=False)
    c = back_on_leg(c, march.program, pulled)
    return complete(march, c, log, pulled & ~jnp.isfinite(march.program.targets[c.leg]))


def jump(march: ContinuumMarch, c: Carry, log: EventLog, jumped, moved, a, d, outcome: Outcome, up) -> Carry:
    """A jump to the new radius: logged (displacement control; a landing logs its own), the
    march goes on from there (a hold at the wall, else a ride); in a landing, a jump past the
    applied force turns the march back."""
    force = march.force
    radius = jnp.where(moved, outcome.radius, a)
    shown = jumped & moved & ~c.landing
    log.emit(jnp.stack([a, radius]), jnp.stack([d, d]), jnp.stack([force(a, d), force(radius, d)]), shown, c.leg)
    log.event(jnp.where(up, EVENT["snap_in"], EVENT["snap_out"]), shown)
    c = replace_where(c, jumped, a=radius, d=d, wall=outcome.wall, mode=jnp.where(outcome.wall, HOLD, RIDE))
    F = force(radius, d)
    overshoot = jumped & c.landing & jnp.where(up, F > c.target, F < c.target)
    return replace_where(c, overshoot, direction=-c.direction, mode=HOLD)
