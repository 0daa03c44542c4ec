"""The quasi-static march of a finite-range law along its equilibrium curve s ↦ (d, F, a).

Maugis–Dugdale (§3.8) and Greenwood–Johnson (§3.9) give every equilibrium as one parameter s
(`_law.curve`), split into segments at the turning points of d(s). As for an impact
(`_integrate.curve`), the body sits on the rising segments (dd/ds > 0) and moves at fixed d from
the end of one to the next rising state at that level, or leaves the range of the stress.

Displacement control (ξ = 1) rides the rising segments in d and jumps at their ends: the contact
is lost at a minimum of d(s). Force control (ξ = 3) holds a state only where F rises too
(dd/ds > 0 and dF/ds > 0): the path is split further at the turning points of F(s), and beyond
one the state follows the applied force no longer. It then moves at that constant force (a
landing, as for the JKR law in `continuum`): in the direction the force pushes it, over the
rising segments of d and their jumps, until F meets the applied force again on a stable piece,
or off the surface; the pull-off is where that instability began, a minimum of F(s).

Each step moves over one piece (an interval between turning points of d or F, or a jump at fixed
d, or the approach) and solves one bisection: where the ride meets its target, or where the
jump lands. The curve (a, d, F) in program order and the pull-off come back scaled.

A curve that remembers (Maugis–Dugdale with approach hysteresis, `_law.dugdale_hysteresis`) is
one path of a family: each step marches on the path of the carry's memory (the frozen zone's
radius), a leg that ends in contact re-anchors it at the state (unloading from the approach
curve, or reloading from the detach curve, starts on a new frozen zone) and separation clears it.
"""

import functools

import equinox as eqx
import jax
import jax.numpy as jnp

from ..._core.pytree import replace, replace_where
from ..._core.search import bisect
from ..._law.branches import next_rising, previous_rising
from ..._law.curve import AbstractCurve, CurveLaw
from ..codes import Status
from .events import AbstractMarchCarry, EventLog, MarchRecord, end_march, record_pull_off, run_march
from .loading import BISECTION_STEPS, EVENT, SAME_RADIUS, QuasiStaticNumerics, QuasiStaticOutcome
from .program import Program, back_on_leg, next_leg


class CurveMarch(eqx.Module):
    """What every step reads: the law and its curve, the pieces of the path (the curve's nodes
    and the turning points of F, merged), and the program."""

    law: CurveLaw
    curve: AbstractCurve
    pieces: jax.Array  # [P+1] sorted: the curve's nodes and the turning points of F(s)
    force_rising: jax.Array  # [P] F rises with s on the piece
    program: Program  # its targets in the units of the law
    grid: jax.Array  # u ∈ [0, 1]: where a ride is sampled

    def at(self, memory) -> "CurveMarch":
        """The march on the path of the state's `memory`: itself, unless the curve remembers
        (`AbstractCurve.at`); then its pieces are those of that path."""
        if not self.curve.remembers:
            return self
        curve = self.curve.at(self.law, memory)
        pieces, force_rising, _ = path_pieces(self.law, curve, 0)  # its curves' turns of F, found once
        return replace(self, curve=curve, pieces=pieces, force_rising=force_rising)

    def state(self, s):
        """(a, d, F) at s."""
        depth, force, radius, _ = self.curve.state(self.law, s)
        return radius, depth, force

    def controlled(self, s, force):
        """d(s), or F(s) where `force`."""
        depth, force_value, _, _ = self.curve.state(self.law, s)
        return jnp.where(force, force_value, depth)


class CurveCarry(AbstractMarchCarry):
    leg: jax.Array
    direction: jax.Array  # +1 loading (d or F rising), −1 unloading
    target: jax.Array  # the leg's target, or the constant force of a landing
    landing: jax.Array  # force control: a move at constant force in progress
    attached: jax.Array  # within the range of the adhesive stress
    s: jax.Array
    segment: jax.Array  # the rising segment of the curve holding s
    memory: jax.Array  # what a curve that remembers keeps of the path (`AbstractCurve.at`); else 0
    d: jax.Array
    pre: jax.Array  # [2] s, d where the current instability began
    record: MarchRecord


def path_pieces(law: CurveLaw, curve: AbstractCurve, max_turns: int):
    """The curve's nodes and the turning points of F(s), sorted; whether F rises on each piece;
    whether F turns more often than `max_turns`."""
    turns, overflow = curve.force_turns(law, curve.nodes[-1], max_turns)
    pieces = jnp.sort(jnp.concatenate([curve.nodes, turns]))
    middles = 0.5 * (pieces[:-1] + pieces[1:])
    return pieces, curve.slopes(law, middles)[1] > 0.0, overflow


def march_curve(
    law: CurveLaw, curve: AbstractCurve, program: Program, numerics: QuasiStaticNumerics
) -> QuasiStaticOutcome:
    """March the program along the curve."""
    pieces, force_rising, overflow = path_pieces(law, curve, numerics.tabulation.max_turns)
    march = CurveMarch(
        law=law,
        curve=curve,
        pieces=pieces,
        force_rising=force_rising,
        program=program,
        grid=jnp.linspace(0.0, 1.0, numerics.samples),
    )
    steps = numerics.steps(program.targets.shape[0])
    start = initial(march, numerics, steps)
    start = end_march(start, overflow | curve.overflow, Status.branch_overflow)
    start = end_march(start, ~curve.resolves(law), Status.unresolved_zone)
    return run_march(functools.partial(step, march), start, steps, march.state(curve.nodes[-1])[0])


def initial(march: CurveMarch, numerics: QuasiStaticNumerics, steps: int) -> CurveCarry:
    """Apart, at the depth where the interaction starts, on the first leg; empty buffers."""
    return CurveCarry(
        **march.program.start(),
        attached=jnp.asarray(False),
        s=jnp.zeros(()),
        segment=jnp.zeros((), int),
        memory=jnp.zeros(()),
        d=jnp.asarray(march.law.onset, float),
        pre=jnp.zeros(2),
        record=MarchRecord.empty(rows=steps * (numerics.samples + 8), events=4 * steps),
    )


class JumpPlan(eqx.Module):
    """A jump at fixed d: from s = `start` at the depth `level` onto the next rising segment in
    the direction of motion."""

    start: jax.Array  # s where the jump starts
    level: jax.Array  # d of the jump
    segment: jax.Array  # the rising segment the jump lands on
    lost: jax.Array  # no such segment: blocked (up, the top of the curve) or released (down)


class RidePlan(eqx.Module):
    """A ride along one piece of the path (between turning points of d or F)."""

    far: jax.Array  # the end of the piece in the direction of motion
    unstable: jax.Array  # force control: the ride cannot follow the applied force here
    crossed: jax.Array  # the ride meets its target inside the piece


class Piece(eqx.Module):
    """What a step moves over: the approach (apart), a jump at fixed d (the touch, or the end of
    a rising segment), or a ride over one piece of the path; and its one bisection."""

    away: jax.Array  # apart, not reaching the onset: d moves to the target (or the leg ends)
    jumping: jax.Array  # a jump at fixed d
    touching: jax.Array  # the jump is the touch at the onset
    riding: jax.Array
    jump: JumpPlan
    ride: RidePlan
    lower: jax.Array  # the bracket of the step's bisection
    upper: jax.Array
    goal: jax.Array  # the level the bisection looks for
    force: jax.Array  # it bisects F (else d)


def plan(march: CurveMarch, c: CurveCarry) -> Piece:
    """The piece a step moves over, and the bracket of its bisection."""
    curve, law = march.curve, march.law
    up = c.direction > 0
    touching = ~c.attached & up & (march.program.force_control | (c.target >= law.onset))
    at_end = c.attached & jnp.where(up, c.s >= curve.nodes[c.segment + 1], c.s <= curve.nodes[c.segment])
    jumping = touching | at_end
    riding = c.attached & ~at_end
    jump = plan_jump(march, c, up, touching)
    ride = plan_ride(march, c, up, riding)
    return Piece(
        away=~c.attached & ~touching,
        jumping=jumping,
        touching=touching,
        riding=riding,
        jump=jump,
        ride=ride,
        lower=jnp.where(jumping, curve.nodes[jump.segment], jnp.minimum(c.s, ride.far)),
        upper=jnp.where(jumping, curve.nodes[jump.segment + 1], jnp.maximum(c.s, ride.far)),
        goal=jnp.where(jumping, jump.level, c.target),
        force=riding & march.program.force_control,
    )


def plan_jump(march: CurveMarch, c: CurveCarry, up, touching) -> JumpPlan:
    """The jump from the state (or, `touching`, from the onset at s = 0) to the next rising
    segment at its level."""
    curve = march.curve
    start = jnp.where(touching, 0.0, c.s)
    level = jnp.where(touching, march.law.onset, c.d)
    out, blocked = next_rising(curve.nodes, curve.levels, curve.increasing, start, level)
    back, released = previous_rising(curve.nodes, curve.levels, curve.increasing, start, level)
    return JumpPlan(start=start, level=level, segment=jnp.where(up, out, back), lost=jnp.where(up, blocked, released))


def plan_ride(march: CurveMarch, c: CurveCarry, up, riding) -> RidePlan:
    """The piece of the path the state rides next, and whether it can follow the control there
    and meets its target inside."""
    pieces, force_control = march.pieces, march.program.force_control
    index = jnp.where(
        up,
        jnp.searchsorted(pieces, c.s, side="right", method="compare_all") - 1,
        jnp.searchsorted(pieces, c.s, side="left", method="compare_all") - 1,
    )
    index = jnp.clip(index, 0, pieces.shape[0] - 2)
    far = jnp.where(up, pieces[index + 1], pieces[index])
    follows = ~force_control | march.force_rising[index]
    far_value = march.controlled(far, force_control)
    crossed = riding & follows & jnp.where(up, c.target <= far_value, c.target >= far_value)
    return RidePlan(far=far, unstable=riding & ~follows & ~c.landing, crossed=crossed)


class Evaluated(eqx.Module):
    """(a, d, F) of the states a step reads, from one batched evaluation of the curve."""

    start: tuple  # the jump's start
    landing: tuple  # where the jump lands
    here: tuple  # the state before the step
    before: tuple  # where the current instability began
    ride: tuple  # along the ride, its end last


def evaluate(march: CurveMarch, c: CurveCarry, p: Piece, root) -> tuple[jax.Array, jax.Array, Evaluated]:
    """Where the jump lands and the ride stops, and the states the step reads there."""
    up = c.direction > 0
    landing = jnp.where(up, jnp.maximum(root, p.jump.start), jnp.minimum(root, p.jump.start))
    # A rising segment that goes on from the current one's end (the junction) is no jump: the
    # state stays at the node, whatever an ulp of d finds on the flat start of the next one.
    nodes = march.curve.nodes
    onto = p.jump.segment
    adjacent = jnp.where(up, nodes[onto] == nodes[c.segment + 1], nodes[onto + 1] == nodes[c.segment])
    landing = jnp.where(p.jumping & ~p.touching & adjacent, p.jump.start, landing)
    stop = jnp.where(p.ride.crossed, root, p.ride.far)
    ride = c.s + (stop - c.s) * march.grid
    radius, depth, force = march.state(jnp.concatenate([jnp.stack([p.jump.start, landing, c.s, c.pre[0]]), ride]))

    def at(i):
        return radius[i], depth[i], force[i]

    tail = slice(4, None)
    return landing, stop, Evaluated(start=at(0), landing=at(1), here=at(2), before=at(3), ride=at(tail))


def step(march: CurveMarch, c: CurveCarry) -> CurveCarry:
    """One piece: planned from the state, its one bisection, the states it reads (one batched
    evaluation of the curve), then applied."""
    march = march.at(c.memory)
    log = EventLog()
    p = plan(march, c)
    lo, hi = bisect(lambda s: march.controlled(s, p.force) < p.goal, p.lower, p.upper, BISECTION_STEPS)
    landing, stop, states = evaluate(march, c, p, 0.5 * (lo + hi))
    c = approach(march, c, log, p)
    c = jump(march, c, log, p, landing, states)
    c = ride(march, c, log, p, stop, states)
    return log.write(c)


def approach(march: CurveMarch, c: CurveCarry, log: EventLog, p: Piece) -> CurveCarry:
    """Apart: d moves to the target out of range (displacement control; shown), or the leg ends."""
    up = c.direction > 0
    end = jnp.where(up, c.target, jnp.where(jnp.isfinite(c.target), jnp.minimum(c.target, c.d), c.d))
    shown = p.away & ~march.program.force_control
    zeros = jnp.zeros_like(march.grid)
    log.emit(zeros, c.d + (end - c.d) * march.grid, zeros, shown, c.leg)
    c = replace_where(c, shown, d=end)
    return complete(march, c, log, p.away)


def jump(march: CurveMarch, c: CurveCarry, log: EventLog, p: Piece, landing, states: Evaluated) -> CurveCarry:
    """A jump at fixed d: the touch, a snap to the next rising segment, a release (the body
    leaves the range: separation) or the top of the curve (the march stops). Under force control
    a jump is an instability: the landing at constant force starts (or goes on) here."""
    up = c.direction > 0
    log.emit(0.0, march.law.onset, 0.0, p.touching, c.leg)
    log.event(EVENT["touch"], p.touching)
    # Force control: the touch starts a landing at F = 0 (the applied force out of range); a
    # segment's end, one at the force there.
    begins = p.jumping & march.program.force_control & ~c.landing
    start_force = jnp.where(p.touching, 0.0, states.start[2])
    before = tuple(jnp.where(c.landing, b, s) for b, s in zip(states.before, states.start, strict=True))
    c = replace_where(c, begins, landing=True, target=start_force, pre=jnp.stack([p.jump.start, p.jump.level]))

    blocked = p.jumping & up & p.jump.lost
    c = end_march(c, blocked, Status.radius_overflow)
    c = separate(march, c, log, p.jumping & ~up & p.jump.lost, before, p.jump.level)

    moves = p.jumping & ~p.jump.lost
    start, after, level = states.start, states.landing, p.jump.level
    # A jump moves the radius or the force (scaled: O(1)); a landing within round-off does not.
    moved = (jnp.abs(after[0] - start[0]) > SAME_RADIUS * jnp.maximum(jnp.abs(start[0]), 1.0)) | (
        jnp.abs(after[2] - start[2]) > SAME_RADIUS * jnp.maximum(jnp.abs(start[2]), 1.0)
    )
    # Displacement control shows the jump (the touch: the force switching on, even in place).
    shown = moves & ~c.landing & (moved | p.touching)
    keep = jnp.stack([shown & ~p.touching, shown])
    log.emit(jnp.stack([start[0], after[0]]), jnp.stack([level, level]), jnp.stack([start[2], after[2]]), keep, c.leg)
    log.event(jnp.where(up, EVENT["snap_in"], EVENT["snap_out"]), shown & moved)
    c = replace_where(c, moves, attached=True, s=landing, segment=p.jump.segment, d=p.jump.level)
    # In a landing, a jump past the applied force turns the motion back (riding on across a node
    # is no jump: on a frozen Maugis–Dugdale zone F equals the applied force to round-off there).
    overshoot = moves & moved & c.landing & jnp.where(c.direction > 0, after[2] > c.target, after[2] < c.target)
    return replace_where(c, overshoot, direction=-c.direction)


def ride(march: CurveMarch, c: CurveCarry, log: EventLog, p: Piece, stop, states: Evaluated) -> CurveCarry:
    """Along one piece of a rising segment: to the target (the root), else to the piece's end.
    Force control, where F falls along the way: not followed; a landing starts (none moves)."""
    c = replace_where(c, p.ride.unstable, landing=True, target=states.here[2], pre=jnp.stack([c.s, c.d]))
    moving = p.riding & ~p.ride.unstable
    radius, depth, force = states.ride
    log.emit(radius, depth, force, moving & ~c.landing, c.leg)
    c = replace_where(c, moving, s=stop, d=depth[-1])
    end = (radius[-1], depth[-1], force[-1])
    return complete(march, c, log, moving & p.ride.crossed, end)


def complete(march: CurveMarch, c: CurveCarry, log: EventLog, keep, here=(0.0, 0.0, 0.0)) -> CurveCarry:
    """The target is met: a landing ends at (a, d, F) `here` (its jump logged), or the leg ends."""
    landed = keep & c.landing
    log.emit(here[0], here[1], here[2], landed, c.leg)
    log.event(jnp.where(c.s >= c.pre[0], EVENT["snap_in"], EVENT["snap_out"]), landed & (c.s != c.pre[0]))
    c = back_on_leg(c, march.program, landed)
    finished = keep & ~landed
    c = next_leg(c, march.program, log, finished, c.attached)
    return anchor(march, c, finished & c.attached) if march.curve.remembers else c


def anchor(march: CurveMarch, c: CurveCarry, turning) -> CurveCarry:
    """A leg ends in contact: the memory of a curve that remembers is re-anchored at the state
    (`AbstractCurve.anchored`), and the state placed on that path, on the segment it moves
    along next. (A landing is one jump: its path is not re-anchored on the way.)"""
    curve, memory, place = march.curve.anchored(march.law, c.s, c.memory)
    return replace_where(c, turning, memory=memory, s=place, segment=curve.holding(place, c.direction > 0))


def separate(march: CurveMarch, c: CurveCarry, log: EventLog, released, before, d) -> CurveCarry:
    """The body leaves the range of the stress at the depth d: the pull-off is `before`, the
    (a, d, F) where the instability began (force control) or the last state. Under displacement
    control the force then drops to 0 at this d; under force control the body leaves at constant
    force (no state follows)."""
    c = record_pull_off(c, released, jnp.stack(before))
    log.emit(before[0], before[1], before[2], released, c.leg)
    log.event(EVENT["pull_off"], released)
    log.emit(0.0, d, 0.0, released & ~march.program.force_control, c.leg)
    c = replace_where(
        c,
        released,
        attached=False,
        s=0.0,
        segment=0,
        memory=0.0,
        d=d,
    )
    c = back_on_leg(c, march.program, released)
    return complete(march, c, log, released & ~jnp.isfinite(march.program.targets[c.leg]))
