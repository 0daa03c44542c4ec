"""The MDR spring array stepped with a fixed-step velocity Verlet (the classical alternative).

The same array as `springs.SpringArray` (`ComputedSpringArray`; the attached
springs and their running sum S_k in `Attached`), but integrated in time with a fixed step Δt
instead of from one spring event to the next:

    v½ = v + ½Δt·(g − F(k, d)),   d' = d + Δt·v½,   k' = cascade(k, d'),   v' = v½ + ½Δt·(g − F(k', d')).

The contact edge is an index k with the running sum S_k, so a step costs O(1) and memory is
independent of N. After each position update the springs attach (while moving in) or detach
(while moving out) with the same thresholds and cascades as the exact stepper; turnaround,
separation and capture are read from the sign of v and from k. Each attach or detach lands on
the step grid instead of at its exact time, so the method is first order in Δt (and noisy:
each spring event adds an error of either sign). Its error against the exact discrete model
(`springs`) is the pure time-stepping error; that model's error against the continuum is the
spatial one.

The loop work ∮F dd is summed with the mean of the two forces that each step's kicks apply,
so velocity Verlet's discrete energy identity holds to round-off over a contact: kinetic energy
lost = ∮F dd + ⅛Δt²(a_first² − a_last²), a the acceleration (it tends to the exact model's
dissipation at first order in Δt).

Free flight between contacts is analytic, as in the other integrators: a contact starts at
d = 0 at the exact touch time. Lengths and times are scaled (units of `Scales`); the step `Verlet.dt` is in seconds
(scene: `solver: {method: verlet, dt: …}` with `contact.springs: N`).
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.pytree import replace
from .._law.springs import Attached, ComputedSpringArray
from .carry import Carry, Outcome, finish, initial_carry, log_event, record_contact
from .codes import ADVANCE, DONE, EVENT_CODE, FLIGHT, RECEDE, Status
from .problem import Motion, Options, Problem
from .springs import AbstractSpringArrayIntegrator, SpringArrayProblem, touch_down
from .thinning import keep_row
from .work import ContactSummary

# Steps allowed in all: a guard against a runaway, far above any scene's steps.
_MAX_STEPS = 1_000_000_000


class Verlet(AbstractSpringArrayIntegrator):
    """The spring array stepped with a fixed-step velocity Verlet."""

    dt: float | jax.Array  # time step (s); traced when given as an array

    def integrate(self, problem: SpringArrayProblem, options: Options) -> Outcome:
        step = jnp.asarray(self.dt / problem.scales.time, jnp.float64)
        return _run_steps(problem.problem, options, problem.array, step)


class _Ending(eqx.Module):
    """What ends a stretch of steps (each a flag of the step that reached it)."""

    turned: jax.Array  # loading turned around
    separated: jax.Array  # unloading let the last spring go
    captured: jax.Array  # unloading turned around in contact
    overflow: jax.Array  # loading outgrew the array
    out_of_time: jax.Array  # the time limit passed

    @classmethod
    def none(cls) -> "_Ending":
        false = jnp.asarray(False)
        return cls(turned=false, separated=false, captured=false, overflow=false, out_of_time=false)

    def any(self) -> jax.Array:
        return self.turned | self.separated | self.captured | self.overflow | self.out_of_time


class _Stretch(eqx.Module):
    """State of the stepping loop inside one contact phase (scalars, plus trajectory rows)."""

    t: jax.Array
    d: jax.Array
    v: jax.Array
    attached: Attached  # the springs in contact
    steps: jax.Array  # steps in all (the run's count)
    work: jax.Array  # ∫F dd of this phase
    deepest: jax.Array
    high: jax.Array  # largest force
    low: jax.Array  # smallest force
    ending: _Ending  # what ended the stretch, once one did
    trajectory: jax.Array  # [T, 5] rows (T = 0 without samples)
    stored: jax.Array  # rows written
    stride: jax.Array  # steps between stored rows (doubles whenever the rows fill up)


def _store(s: _Stretch, array: ComputedSpringArray, rows: int, valid=True) -> _Stretch:
    """The stretch with its state (t, d, v, F, a) kept among its trajectory rows (`keep_row`)."""
    if rows == 0:
        return s
    row = jnp.stack([s.t, s.d, s.v, array.force(s.attached, s.d), s.attached.count * array.spacing])
    kept = keep_row(s.trajectory, s.stored, s.stride, s.steps, row, valid)
    return replace(s, trajectory=kept.trajectory, stored=kept.stored, stride=kept.stride)


class VerletCarry(eqx.Module):
    """State of the stepping loop between phases: the phase loop's carry, the springs attached,
    and the trajectory rows stored so far with their stride (`_store`)."""

    carry: Carry
    attached: Attached
    stored: jax.Array
    stride: jax.Array


def _verlet_step(array: ComputedSpringArray, motion: Motion, dt, inward, rows: int, s: _Stretch) -> _Stretch:
    """One kick–drift–kick step; the springs attach (moving in) or detach (moving out) after the drift."""
    gravity = motion.gravity
    old_force = array.force(s.attached, s.d)
    half = s.v + 0.5 * dt * (gravity - old_force)
    d = s.d + dt * half
    attached = array.cascade(s.attached, d, inward)
    k = attached.count
    force = array.force(attached, d)
    v = half + 0.5 * dt * (gravity - force)
    t = s.t + dt
    s = replace(
        s,
        t=t,
        d=d,
        v=v,
        attached=attached,
        steps=s.steps + 1,
        work=s.work + 0.5 * (old_force + force) * (d - s.d),  # the kicks' mean force
        deepest=jnp.maximum(s.deepest, d),
        high=jnp.maximum(s.high, force),
        low=jnp.minimum(s.low, force),
        ending=_Ending(
            turned=inward & (v < 0.0),
            separated=~inward & (k == 0),
            captured=~inward & (k > 0) & (v > 0.0),
            overflow=inward & (k >= array.count) & (d >= array.beyond_level),
            out_of_time=t > motion.time_limit,
        ),
    )
    return _store(s, array, rows)


def _stretch(problem: Problem, array: ComputedSpringArray, dt, rows: int, state: VerletCarry) -> _Stretch:
    """Step until the phase ends: turnaround (loading), separation or capture (unloading), the
    contact outgrowing the array, or the time limit."""
    c, attached = state.carry, state.attached
    inward = c.mode == ADVANCE
    start_force = array.force(attached, c.d)
    start = _Stretch(
        t=c.t,
        d=c.d,
        v=c.v,
        attached=attached,
        steps=c.steps,
        work=jnp.zeros(()),
        deepest=c.d,
        high=start_force,
        low=start_force,
        ending=_Ending.none(),
        trajectory=c.trajectory,
        stored=state.stored,
        stride=state.stride,
    )

    def running(s: _Stretch):
        return ~s.ending.any() & (s.steps < _MAX_STEPS)

    def step(s: _Stretch) -> _Stretch:
        return _verlet_step(array, problem.motion, dt, inward, rows, s)

    return jax.lax.while_loop(running, step, _store(start, array, rows))


def _book(c: Carry, s: _Stretch) -> Carry:
    """Fold a finished stretch into the carry: its events, the next phase and the result code."""
    inward = c.mode == ADVANCE
    ending = s.ending
    capped = ~ending.any()
    turned, separated, captured, overflow = (
        flag & ~ending.out_of_time for flag in (ending.turned, ending.separated, ending.captured, ending.overflow)
    )
    mode = jnp.where(ending.out_of_time | capped | overflow | captured, DONE, jnp.where(inward, RECEDE, FLIGHT))
    status = Status.where(
        ending.out_of_time,
        Status.time_limit,
        Status.where(
            capped,
            Status.solver_failure,
            Status.where(overflow, Status.radius_overflow, Status.where(captured, Status.captured, c.status)),
        ),
    )
    c = log_event(c, s.t, EVENT_CODE["max_indentation"], turned)
    c = log_event(c, s.t, EVENT_CODE["separation"], separated)
    c = log_event(c, s.t, EVENT_CODE["capture"], captured)
    c = log_event(c, s.t, EVENT_CODE["limit"], ending.out_of_time | capped)
    summary = ContactSummary(work=s.work, lowest_force=s.low, highest_force=s.high, deepest=s.deepest)
    c = record_contact(c, (s.t, s.d, s.v), summary, separated, captured)
    return replace(
        c,
        mode=mode,
        status=status,
        steps=s.steps,
        accepted=c.accepted + (s.steps - c.steps),
        phases=c.phases + 1,
        trajectory=s.trajectory,
    )


def _run_steps(problem: Problem, options: Options, array: ComputedSpringArray, dt) -> Outcome:
    """Run one impact (possibly several bounces) on the array with velocity Verlet."""
    rows = options.samples_per_phase * options.max_phases

    def contact(state: VerletCarry) -> VerletCarry:
        s = _stretch(problem, array, dt, rows, state)
        return VerletCarry(carry=_book(state.carry, s), attached=s.attached, stored=s.stored, stride=s.stride)

    def flight(state: VerletCarry) -> VerletCarry:
        landed = touch_down(problem, options, array, state.carry)
        return replace(state, carry=landed.carry, attached=landed.attached)

    def running(state: VerletCarry):
        return state.carry.mode != DONE

    def advance(state: VerletCarry) -> VerletCarry:
        return jax.lax.cond(state.carry.mode == FLIGHT, flight, contact, state)

    one = jnp.ones((), int)
    start = VerletCarry(carry=initial_carry(problem, options), attached=Attached.none(), stored=0 * one, stride=one)
    return finish(jax.lax.while_loop(running, advance, start).carry)
