"""The quasi-static march of the spring array, event by event, with the same rules."""

import functools

import equinox as eqx
import jax
import jax.numpy as jnp

from ..._core.pytree import replace_where
from ..._law.springs import TabulatedSpringArray
from ..codes import Status
from .events import AbstractMarchCarry, EventLog, MarchRecord, end_march, record_pull_off, run_march
from .loading import EVENT, QuasiStaticNumerics, QuasiStaticOutcome
from .program import Program, back_on_leg, next_leg
from .setup import Built


class SpringCarry(AbstractMarchCarry):
    leg: jax.Array
    direction: jax.Array
    target: jax.Array
    landing: jax.Array
    touching: jax.Array
    k: jax.Array  # springs attached
    d: jax.Array
    pre: jax.Array  # [2] k, d where the current instability began
    record: MarchRecord


def spring_array(built: Built, capacity: int, count, length) -> TabulatedSpringArray:
    """`count` ≤ `capacity` midpoint springs x_i = (i − ½)Δx on [0, L]; L is `length` (m) if
    given, else the radius the program can reach (or the body's wall). Slots beyond `count`
    never attach (threshold +inf), so one compiled march serves every count."""
    law = built.law
    scaled = jnp.where(jnp.isnan(length), built.top, length / law.scales.radial)
    spacing = scaled / count
    index = jnp.arange(capacity)
    real = index < count
    positions = jnp.where(real, (index + 0.5) * spacing, scaled)
    attach, detach = built.problem.attach, built.problem.detach
    return TabulatedSpringArray(
        spacing=spacing,
        attach_level=jnp.where(real, law.edge(positions, attach.coefficient), jnp.inf),
        detach_level=law.edge(positions, detach.coefficient),
        prefix=jnp.concatenate([jnp.zeros(1), jnp.cumsum(jnp.where(real, law.g(positions), 0.0))]),
        beyond_level=jnp.where(scaled >= law.extent(), jnp.inf, law.edge((count + 0.5) * spacing, attach.coefficient)),
    )


class SpringMarch(eqx.Module):
    """What every step reads: the program (`Built`), the spring array and how many of its slots
    are springs."""

    built: Built
    array: TabulatedSpringArray
    count: jax.Array  # springs of the array (N ≤ its capacity)

    @property
    def program(self) -> Program:
        return self.built.program

    def force(self, k, d):
        """F with k springs attached at the indentation d (scaled)."""
        return self.array.force(k, d)

    def emit(self, log: EventLog, k, d, keep, leg):
        """Points (radius of k springs, d, F) of program leg `leg`, kept where `keep`."""
        k, d = jnp.atleast_1d(k), jnp.atleast_1d(d)
        log.emit(k * self.array.spacing, d, self.force(k, d), keep, leg)

    def equilibrium(self, k, F):
        """d with k springs attached under the force F (k > 0)."""
        return (0.5 * F / self.array.spacing + self.array.prefix[k]) / jnp.maximum(k, 1)


class Threshold(eqx.Module):
    """In contact: the next threshold in the direction of motion, and where the hold ends."""

    reached: jax.Array  # the target comes before the threshold
    end: jax.Array  # d where the hold stops (inf: none up, from no spring past the wall)
    beyond: jax.Array  # every spring of the array is attached: the next is the one past it


def march_springs(built: Built, numerics: QuasiStaticNumerics, length, count) -> QuasiStaticOutcome:
    """March the program on the spring array (`numerics.springs` its capacity), event by event."""
    assert numerics.springs is not None, "a spring-array march needs the array's capacity"
    march = SpringMarch(built=built, array=spring_array(built, numerics.springs, count, length), count=count)
    steps = numerics.steps(built.program.targets.shape[0])
    return run_march(functools.partial(step, march), initial(built, steps), steps, built.top)


def initial(built: Built, steps: int) -> SpringCarry:
    """The state before the first step: apart, no spring attached, on the first leg, with empty
    buffers for the curve and its events."""
    return SpringCarry(
        **built.program.start(),
        touching=jnp.asarray(False),
        k=jnp.zeros((), int),
        d=jnp.zeros(()),
        pre=jnp.zeros(2),
        record=MarchRecord.empty(rows=2 * steps + 64 * built.program.targets.shape[0], events=steps // 2 + 64),
    )


def step(march: SpringMarch, c: SpringCarry) -> SpringCarry:
    """One event: apart, the approach (and the touch); in contact, the hold to the next
    threshold or the target, and past the threshold the attach or detach cascade."""
    log = EventLog()
    up = c.direction > 0
    k, d = c.k, c.d
    approaching = ~c.touching
    contact = ~approaching
    c = approach(march, c, log, up, approaching)
    at = threshold(march, c, up, contact, k, d)
    c = hold(march, c, log, contact, k, at)
    c = cross(march, c, log, up, contact & ~at.reached, k, at.beyond)
    return log.write(c)


def complete_leg(march: SpringMarch, c: SpringCarry, log: EventLog, keep) -> SpringCarry:
    """The current target is met: a landing ends, or the leg ends (a reversal in contact)."""
    landed = keep & c.landing
    c = back_on_leg(c, march.program, landed)
    return next_leg(c, march.program, log, keep & ~landed, c.touching)


def approach(march: SpringMarch, c: SpringCarry, log: EventLog, up, approaching) -> SpringCarry:
    """Not touching: the approach to d = 0 and the touch, or away to the leg's target."""
    touches = approaching & up & (c.target >= 0.0)
    end = jnp.where(up, 0.0, jnp.where(jnp.isfinite(c.target), jnp.minimum(c.target, c.d), c.d))
    shown = approaching & ~march.program.force_control & (touches | ~up)
    march.emit(log, jnp.zeros(2, int), jnp.stack([c.d, end]), shown, c.leg)
    c = touch(march, c, log, touches)
    c = complete_leg(march, c, log, approaching & ~touches)
    return replace_where(c, approaching & ~touches, d=end)


def touch(march: SpringMarch, c: SpringCarry, log: EventLog, touches) -> SpringCarry:
    """The touch at d = 0 with its jump-in; under force control a nonzero force there starts a
    landing back at F = 0."""
    jump_in = march.array.attach_cascade(jnp.zeros((), int), 0.0)
    march.emit(log, jnp.zeros((), int), 0.0, touches, c.leg)
    log.event(EVENT["touch"], touches)
    march.emit(log, jump_in, 0.0, touches, c.leg)
    log.event(EVENT["snap_in"], touches & (jump_in > 0))
    F_touch = march.force(jump_in, 0.0)
    lands = touches & march.program.force_control & (F_touch != 0.0) & (jump_in > 0)
    c = replace_where(c, touches, touching=True, k=jump_in, d=0.0)
    return replace_where(
        c,
        lands,
        landing=True,
        target=0.0,
        pre=jnp.stack([jump_in, 0]).astype(float),
        direction=jnp.where(F_touch > 0.0, -1, 1),
    )


def threshold(march: SpringMarch, c: SpringCarry, up, contact, k, d) -> Threshold:
    """With k springs at d: the next attach threshold up (past the array: the spring beyond it),
    the edge spring's detach threshold down (no spring: gone at once), or the target first."""
    array, force_control = march.array, march.program.force_control
    capacity = array.count
    beyond = k >= march.count
    attach_next = jnp.where(beyond, array.beyond_level, array.attach_level[jnp.minimum(k, capacity - 1)])
    detach_edge = jnp.where(k > 0, array.detach_level[jnp.maximum(k - 1, 0)], d)
    level = jnp.where(up, attach_next, detach_edge)
    F_level = jnp.where(
        jnp.isfinite(level),
        march.force(k, jnp.where(jnp.isfinite(level), level, 0.0)),
        jnp.where(up, jnp.inf, -jnp.inf),
    )
    F_level = jnp.where(k > 0, F_level, jnp.where(up, 0.0, jnp.inf))  # no spring: F = 0
    value = jnp.where(force_control, F_level, level)
    reached = contact & jnp.where(up, c.target <= value, c.target >= value)
    aimed = jnp.where(force_control, jnp.where(k > 0, march.equilibrium(k, c.target), d), c.target)
    aimed = jnp.where(up, jnp.maximum(aimed, d), jnp.minimum(aimed, d))
    return Threshold(reached=reached, end=jnp.where(reached, aimed, level), beyond=beyond)


def hold(march: SpringMarch, c: SpringCarry, log: EventLog, contact, k, at: Threshold) -> SpringCarry:
    """In contact: to the threshold or the target at k fixed (each piece starts where the last
    one, or the last jump, ended: only its end is new); a landing that meets its force ends."""
    march.emit(log, k, at.end, contact & ~c.landing & jnp.isfinite(at.end), c.leg)
    c = replace_where(c, contact & jnp.isfinite(at.end), d=at.end)
    landed = at.reached & c.landing
    march.emit(log, k, c.d, landed, c.leg)
    log.event(jnp.where(k >= c.pre[0], EVENT["snap_in"], EVENT["snap_out"]), landed & (jnp.abs(k - c.pre[0]) > 1))
    return complete_leg(march, c, log, at.reached)


def cross(march: SpringMarch, c: SpringCarry, log: EventLog, up, passes, k, beyond) -> SpringCarry:
    """The threshold is passed: attach or detach, with the cascade at constant d; past the
    array's last spring (not at a wall) the march stops."""
    array, d_now = march.array, c.d
    overflow = passes & up & beyond & jnp.isfinite(array.beyond_level)
    moves = passes & ~overflow
    k_new = jnp.where(
        up,
        array.attach_cascade(jnp.minimum(k + 1, march.count), d_now),
        array.detach_cascade(jnp.maximum(k - 1, 0), d_now),
    )
    start = moves & march.program.force_control & ~c.landing
    c = replace_where(c, start, landing=True, target=march.force(k, d_now), pre=jnp.stack([k.astype(float), d_now]))
    gone = moves & ~up & (k_new == 0)
    c = separate(march, c, log, gone, k, d_now)
    c = snap(march, c, log, moves & ~gone, up, k, k_new, d_now)
    code = Status.where(march.built.bounded, Status.radius_overflow, Status.unbounded_contact)
    return end_march(c, overflow, code)


def separate(march: SpringMarch, c: SpringCarry, log: EventLog, gone, k, d_now) -> SpringCarry:
    """The last spring let go: the pull-off is where the instability began (force) or here."""
    before_k = jnp.where(c.landing, c.pre[0], k).astype(int)
    before_d = jnp.where(c.landing, c.pre[1], d_now)
    c = record_pull_off(c, gone, jnp.stack([before_k * march.array.spacing, before_d, march.force(before_k, before_d)]))
    march.emit(log, before_k, before_d, gone, c.leg)
    log.event(EVENT["pull_off"], gone)
    march.emit(log, jnp.zeros((), int), d_now, gone & ~march.program.force_control, c.leg)
    c = replace_where(c, gone, touching=False, k=0)
    c = back_on_leg(c, march.program, gone)
    return complete_leg(march, c, log, gone & ~jnp.isfinite(march.program.targets[c.leg]))


def snap(march: SpringMarch, c: SpringCarry, log: EventLog, jumped, up, k, k_new, d_now) -> SpringCarry:
    """k → k_new springs at constant d (logged outside a landing); in a landing, a jump past the
    applied force turns the march back."""
    march.emit(log, k_new, d_now, jumped & ~c.landing, c.leg)
    log.event(jnp.where(up, EVENT["snap_in"], EVENT["snap_out"]), jumped & ~c.landing & (jnp.abs(k_new - k) > 1))
    c = replace_where(c, jumped, k=k_new)
    F = march.force(k_new, d_now)
    overshoot = jumped & c.landing & jnp.where(up, F > c.target, F < c.target)
    return replace_where(c, overshoot, direction=-c.direction)
