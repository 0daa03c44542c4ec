"""The literal MDR spring array, integrated exactly from one spring event to the next.

N springs of stiffness E*·Δx sit at the midpoints x_i = (i − ½)·Δx of [0, L]. With the k inner
springs attached the force is F = 2Δx·(k·d − S_k), S_k = Σ_{i≤k} g(x_i). Nothing of size N is
stored: a spring's thresholds come from the law when asked (`ComputedSpringArray`), and S_k is
a running sum carried with k (`Attached`), updated with compensated summation as springs attach
and detach, so memory and the cost of an event are independent of N (and N may be traced: one
compilation serves every N). Between two events the motion is harmonic (or ballistic with no
spring attached) and is advanced in closed form; an event is the next spring reaching its
threshold: attach at d = h_attach(x_{k+1}) while moving in, detach at d = h_detach(x_k) while
moving out, each followed by the cascade of neighbours whose thresholds are already passed.
Time stepping adds no error: what differs from the continuum is the spatial discretisation
alone, which converges as N⁻².
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.pytree import replace, where
from .._law.reach import radius_bound
from .._law.scales import Scales
from .._law.springs import Attached, ComputedSpringArray
from .base import AbstractIntegrator
from .carry import Carry, Outcome, finish, initial_carry, log_event, record_contact
from .codes import ADVANCE, DONE, EVENT_CODE, FLIGHT, RECEDE, Status
from .flight import land
from .problem import Options, Physics, Problem, build_problem
from .transitions import next_phase
from .work import ContactSummary

# Default array length: the body's extent, or this margin over the bound on the contact radius.
_LENGTH_MARGIN = 1.25


class SpringArrayProblem(eqx.Module):
    """The scaled impact of the continuum law and the array of springs it is discretised into."""

    problem: Problem
    array: ComputedSpringArray

    @property
    def scales(self) -> Scales:
        return self.problem.scales


class AbstractSpringArrayIntegrator(AbstractIntegrator):
    """Integrators of the literal spring array: N = `Physics.spring_count` springs (traced, so
    one compilation serves every N) over `Physics.spring_length` (nan: the default)."""

    def build(self, physics: Physics, options: Options) -> SpringArrayProblem:
        problem = build_problem(physics, options)
        return SpringArrayProblem(
            problem, build_array(problem, physics.spring_count.astype(int), physics.spring_length)
        )


class SpringArray(AbstractSpringArrayIntegrator):
    """The spring array integrated exactly, in closed form from one spring event to the next."""

    def integrate(self, problem: SpringArrayProblem, options: Options) -> Outcome:
        return _run_events(problem.problem, options, problem.array)


def build_array(problem: Problem, count, length) -> ComputedSpringArray:
    """N = `count` midpoint springs on [0, L]; L is `length` (m) if given, else the default."""
    law = problem.law
    default = jnp.minimum(
        law.extent(), _LENGTH_MARGIN * radius_bound(law, problem.attach.coefficient, problem.motion.touch_speed)[0]
    )
    scaled = jnp.where(jnp.isnan(length), default, length / problem.scales.radial)
    spacing = scaled / count
    return ComputedSpringArray(
        law=law,
        attach_coefficient=problem.attach.coefficient,
        detach_coefficient=problem.detach.coefficient,
        spacing=spacing,
        count=jnp.asarray(count),
        beyond_level=jnp.where(
            scaled >= law.extent(), jnp.inf, law.edge((count + 0.5) * spacing, problem.attach.coefficient)
        ),
    )


class ArrayCarry(eqx.Module):
    """State of a spring array's loop: the phase loop's carry, the springs attached and the
    threshold of the spring that changes next in the direction of motion (`next_level`),
    carried from where it was computed so that the event loop computes each threshold once."""

    carry: Carry
    attached: Attached
    level: jax.Array


def touch_down(problem: Problem, options: Options, array: ComputedSpringArray, c: Carry) -> ArrayCarry:
    """Analytic flight to the next touch, whose jump-in attaches every spring with its threshold
    at or below d = 0; ends the run at a bound, or when the body flies off. Returns the carry and
    the springs attached (none unless it lands). The integrators store their own trajectory rows."""
    jump_in, level = array.cascade_from(Attached.none(), array.next_level(0, True), 0.0, True)
    touch = next_phase(ADVANCE, 0, 0.0, EVENT_CODE["touch"])
    c = land(problem, options, c, 0.0, touch, array.force(jump_in, 0.0), samples=False)
    return ArrayCarry(carry=c, attached=where(c.mode == ADVANCE, jump_in, Attached.none()), level=level)


def _arc(attached: Attached, spacing, gravity, d, v, level, inward):
    """Advance the closed-form motion to `level` or to the turnaround, whichever comes first.

    Returns (duration, d, v, turned). With k springs: harmonic about d_eq, ω² = 2Δx·k;
    with none: constant acceleration (only while moving in).
    """
    k = attached.count.astype(d.dtype)
    omega = jnp.sqrt(2.0 * spacing * jnp.maximum(k, 1.0))
    balance = (2.0 * spacing * attached.profile_sum() + gravity) / omega**2
    offset = d - balance
    amplitude = jnp.sqrt(offset**2 + (v / omega) ** 2)
    target = level - balance
    phase = jnp.arctan2(-v / omega, offset)  # offset = A·cos θ, v = −Aω·sin θ
    direction = jnp.where(inward, -1.0, 1.0)  # inward: θ ∈ (−π, 0]; outward: θ ∈ [0, π]
    reachable = jnp.where(inward, target < amplitude, target > -amplitude)
    ratio = jnp.clip(target / jnp.where(amplitude > 0, amplitude, 1.0), -1.0, 1.0)
    level_angle = direction * jnp.arccos(ratio)
    turn_angle = jnp.where(inward, 0.0, jnp.pi)
    angle = jnp.where(reachable, level_angle, turn_angle)
    duration_harmonic = jnp.maximum(
        (angle - jnp.where(inward, jnp.minimum(phase, 0.0), jnp.maximum(phase, 0.0))) / omega, 0.0
    )
    speed = omega * jnp.sqrt(jnp.maximum((amplitude - target) * (amplitude + target), 0.0))
    d_harmonic = jnp.where(reachable, level, balance - direction * amplitude)
    v_harmonic = jnp.where(reachable, -direction * speed, 0.0)

    # No spring attached (loading that starts at a = 0): ballistic until the first spring.
    rise = jnp.maximum(level - d, 0.0)
    arrival = jnp.sqrt(v**2 + 2.0 * gravity * rise)
    duration_free = 2.0 * rise / jnp.where(v + arrival > 0.0, v + arrival, 1.0)

    free = attached.count == 0
    # A threshold already passed in the direction of motion acts at once (cascades).
    passed = jnp.where(inward, level <= d, level >= d)
    return (
        jnp.where(passed, 0.0, jnp.where(free, duration_free, duration_harmonic)),
        jnp.where(passed, d, jnp.where(free, level, d_harmonic)),
        jnp.where(passed, v, jnp.where(free, arrival, v_harmonic)),
        ~passed & ~free & ~reachable,
    )


def _spring_event(problem: Problem, array: ComputedSpringArray, state: ArrayCarry) -> ArrayCarry:
    """Advance to the next spring event (or the turnaround) in closed form and apply it."""
    c, attached = state.carry, state.attached
    k = attached.count
    inward = c.mode == ADVANCE
    beyond = k >= array.count
    level = jnp.where(inward & beyond, array.beyond_level, state.level)
    duration, d, v, turned = _arc(attached, array.spacing, problem.motion.gravity, c.d, c.v, level, inward)
    t = c.t + duration
    out_of_time = t > problem.motion.time_limit
    # What the event does to the contact: unless it turned, d is `level` itself (or already
    # past it), so the event's own spring, tested against that same number, leads its cascade;
    # at a turn the frontier of the new direction gets its threshold.
    cascaded, following = array.cascade_from(attached, level, d, inward)
    now = where(turned, attached, cascaded)
    following = jnp.where(turned, array.next_level(attached.count, ~inward), following)
    overflow = inward & ~turned & beyond  # the contact outgrew the array
    separated = ~inward & ~turned & (now.count == 0)
    captured = ~inward & turned
    mode = jnp.where(
        out_of_time,
        DONE,
        jnp.where(
            inward,
            jnp.where(turned, RECEDE, jnp.where(overflow, DONE, ADVANCE)),
            jnp.where(captured, DONE, jnp.where(separated, FLIGHT, RECEDE)),
        ),
    )
    forces = jnp.stack([array.force(attached, d), array.force(now, d)])
    status = Status.where(
        out_of_time,
        Status.time_limit,
        Status.where(overflow, Status.radius_overflow, Status.where(captured, Status.captured, c.status)),
    )
    c = log_event(c, t, EVENT_CODE["max_indentation"], inward & turned)
    c = log_event(c, t, EVENT_CODE["separation"], separated)
    c = log_event(c, t, EVENT_CODE["capture"], captured)
    work = array.work(attached, c.d, d)
    summary = ContactSummary(work=work, lowest_force=jnp.min(forces), highest_force=jnp.max(forces), deepest=d)
    c = record_contact(c, (t, d, v), summary, separated, captured)
    return ArrayCarry(
        carry=replace(c, mode=mode, status=status, steps=c.steps + 1, accepted=c.accepted + 1),
        attached=now,
        level=following,
    )


def _run_events(problem: Problem, options: Options, array: ComputedSpringArray) -> Outcome:
    """Run one impact (possibly several bounces) on the array, event by event."""
    events_per_contact = 2 * array.count + 16
    max_events = options.max_bounces * events_per_contact + 16
    rows = options.samples_per_phase * options.max_phases
    stride = jnp.maximum(1, -(-events_per_contact // max(rows, 1)))

    def store(state: ArrayCarry, valid) -> ArrayCarry:
        if rows == 0:
            return state
        c, attached = state.carry, state.attached
        index = c.steps // stride
        keep = valid & (c.steps % stride == 0) & (index < rows)
        row = jnp.stack([c.t, c.d, c.v, array.force(attached, c.d), attached.count * array.spacing])
        target = jnp.minimum(index, rows - 1)
        trajectory = c.trajectory.at[target].set(jnp.where(keep, row, c.trajectory[target]))
        return replace(state, carry=replace(c, trajectory=trajectory))

    def running(state: ArrayCarry):
        return (state.carry.mode != DONE) & (state.carry.steps < max_events)

    def advance(state: ArrayCarry) -> ArrayCarry:
        flying = state.carry.mode == FLIGHT
        state = jax.lax.cond(
            flying,
            lambda s: touch_down(problem, options, array, s.carry),
            lambda s: _spring_event(problem, array, s),
            state,
        )
        # A flight stores the touch it lands with; every spring event is stored.
        return store(state, ~flying | (state.carry.mode == ADVANCE))

    # The first flight's touch computes the first threshold.
    start = ArrayCarry(carry=initial_carry(problem, options), attached=Attached.none(), level=jnp.asarray(jnp.nan))
    return finish(jax.lax.while_loop(running, advance, start).carry)
