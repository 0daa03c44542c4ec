"""What an integrator returns, in scaled units, and the bookkeeping every integrator shares: the
carry of the phase loop, its event log and trajectory buffer, and how a stretch of contact is
booked."""

from typing import Any

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.pytree import replace, where
from .codes import DONE, EVENT_CODE, FLIGHT, Status, status_code
from .problem import Options
from .transitions import Next
from .work import ContactSummary

EVENTS_PER_PHASE = 2


class Outcome(eqx.Module):
    """Scaled results of one impact (mass 1, units of `Scales`)."""

    status: jax.Array  # result code (`codes.RESULT_CODES`, the index of a `codes.Status`)
    stuck: jax.Array
    touch_velocity: jax.Array  # speed at the first touch
    separation_velocity: jax.Array  # speed when the first contact let go (0 if captured)
    touch_time: jax.Array
    separation_time: jax.Array  # inf if the first contact never let go
    contacts: jax.Array  # number of contacts (bounces)
    max_indentation: jax.Array
    max_force: jax.Array
    min_force: jax.Array
    first_contact_work: jax.Array  # ∮F dd over the first contact (elastic and viscous)
    first_contact_viscous_work: jax.Array  # ∫F_visc ḋ dt over the first contact (damping)
    end_time: jax.Array
    end_indentation: jax.Array
    end_velocity: jax.Array
    steps: jax.Array  # solver steps (or spring events) in all
    accepted_steps: jax.Array
    rejected_steps: jax.Array
    event_times: jax.Array  # [E], nan where unused
    event_kinds: jax.Array  # [E], −1 where unused
    trajectory: jax.Array  # [T, 5]: t, d, v, F, a (nan where unused); T = 0 without samples
    # (an oblique impact's [T, 7] adds Q and c: `oblique`)
    tangential: Any = None  # an oblique impact's tangential results (`oblique.TangentialOutcome`)
    # The elastic energy a viscoelastic medium still holds when the first contact ends (0 for an
    # elastic one: `viscoelastic.ViscoelasticSprings`).
    first_contact_stored_energy: jax.Array | float = 0.0


class Carry(eqx.Module):
    """State of the phase loop (scaled units)."""

    t: jax.Array
    d: jax.Array
    v: jax.Array
    mode: jax.Array  # the phase under way (`codes`)
    segment: jax.Array  # the branch segment the radius rides
    radius: jax.Array  # contact radius at the start of the current phase
    phases: jax.Array
    contacts: jax.Array
    status: Status
    stuck: jax.Array
    touch_velocity: jax.Array
    separation_velocity: jax.Array
    touch_time: jax.Array
    separation_time: jax.Array
    max_indentation: jax.Array
    max_force: jax.Array
    min_force: jax.Array
    contact_work: jax.Array  # ∫F dd of the contact under way (elastic and viscous)
    contact_viscous_work: jax.Array  # ∫F_visc ḋ dt of the contact under way
    first_contact_work: jax.Array
    first_contact_viscous_work: jax.Array
    steps: jax.Array
    accepted: jax.Array
    rejected: jax.Array
    event_times: jax.Array
    event_kinds: jax.Array
    event_count: jax.Array
    trajectory: jax.Array
    memory: Any  # what the contact law remembers (a plastic state, a frozen Maugis–Dugdale zone); else a 0


def initial_carry(problem, options: Options, memory: Any = None) -> Carry:
    """The carry before the first flight (or already done: a branch overflow, an unbounded
    contact); `memory` is the contact law's initial memory (None: a law without one)."""
    events = EVENTS_PER_PHASE * options.max_phases
    rows = options.samples_per_phase * options.max_phases
    zero, inf = jnp.zeros(()), jnp.asarray(jnp.inf)
    return Carry(
        t=zero,
        d=jnp.asarray(problem.motion.start_indentation, jnp.float64),
        v=jnp.asarray(problem.motion.start_velocity, jnp.float64),
        mode=jnp.where(problem.overflow | ~problem.bounded, DONE, FLIGHT),
        segment=jnp.zeros((), int),
        radius=zero,
        phases=jnp.zeros((), int),
        contacts=jnp.zeros((), int),
        status=Status.where(
            problem.overflow,
            Status.branch_overflow,
            Status.where(problem.bounded, Status.separated, Status.unbounded_contact),
        ),
        stuck=jnp.asarray(False),
        touch_velocity=zero,
        separation_velocity=zero,
        touch_time=inf,
        separation_time=inf,
        max_indentation=-inf,
        max_force=-inf,
        min_force=inf,
        contact_work=zero,
        contact_viscous_work=zero,
        first_contact_work=zero,
        first_contact_viscous_work=zero,
        steps=jnp.zeros((), int),
        accepted=jnp.zeros((), int),
        rejected=jnp.zeros((), int),
        event_times=jnp.full(events, jnp.nan),
        event_kinds=jnp.full(events, -1, int),
        event_count=jnp.zeros((), int),
        trajectory=jnp.full((rows, 5), jnp.nan),
        memory=jnp.zeros(()) if memory is None else memory,
    )


def record_contact(c: Carry, end, summary: ContactSummary, separated, captured) -> Carry:
    """Fold a stretch of contact into the carry: the state `end` = (t, d, v) where it ended, what
    it did (`summary`); whether the body separated or was captured there (the first contact's
    speed and work are kept once it ends)."""
    t_end, d_end, v_end = end
    contact_work = c.contact_work + summary.work + summary.viscous_work
    viscous_work = c.contact_viscous_work + summary.viscous_work
    first = c.contacts == 1
    ended = first & (separated | captured)
    return replace(
        c,
        t=t_end,
        d=d_end,
        v=v_end,
        stuck=captured,
        separation_velocity=jnp.where(first & separated, jnp.abs(v_end), c.separation_velocity),
        separation_time=jnp.where(first & separated, t_end, c.separation_time),
        max_indentation=jnp.maximum(c.max_indentation, summary.deepest),
        max_force=jnp.maximum(c.max_force, summary.highest_force),
        min_force=jnp.minimum(c.min_force, summary.lowest_force),
        contact_work=contact_work,
        contact_viscous_work=viscous_work,
        first_contact_work=jnp.where(ended, contact_work, c.first_contact_work),
        first_contact_viscous_work=jnp.where(ended, viscous_work, c.first_contact_viscous_work),
    )


def close_phase(c: Carry, active, found, steps, end, nxt: Next, out_of_time, summary: ContactSummary) -> Carry:
    """Book a contact phase (kept only where `active`).

    `found`: whether the phase ended at its event (else the solver failed); `steps` the solver's
    (steps, accepted, rejected) in it (`base.ride_steps`); `end` is (t, d, v) at its end, `nxt`
    the phase after its event, `out_of_time` whether the time limit fired, `summary` what the
    phase did.
    """
    failed = active & ~found
    in_time = ~out_of_time
    separated = found & in_time & nxt.separated
    captured = found & in_time & nxt.captured
    out_of_time = found & out_of_time
    stopped = nxt.stops & ~out_of_time
    status = Status.where(
        failed,
        Status.solver_failure,
        Status.where(
            out_of_time,
            Status.time_limit,
            Status.where(stopped, nxt.stop, Status.where(captured, Status.captured, c.status)),
        ),
    )
    taken, accepted, rejected = steps
    updated = replace(
        record_contact(c, end, summary, separated, captured),
        mode=jnp.where(failed | stopped | out_of_time, DONE, nxt.mode),
        segment=nxt.segment,
        radius=nxt.radius,
        phases=c.phases + 1,
        status=status,
        steps=c.steps + taken,
        accepted=c.accepted + accepted,
        rejected=c.rejected + rejected,
    )
    updated = log_event(updated, end[0], jnp.where(in_time, nxt.event, EVENT_CODE["limit"]), found)
    return where(active, updated, c)


def run_phases(
    problem, options: Options, flight, contact, memory: Any = None, *, landed_contact: bool = False
) -> Outcome:
    """Chain flights and contact phases (`flight(carry)`, `contact(carry)`, each returning the
    next carry) until the run is done or holds no more phases; `memory` as `initial_carry`.

    Each turn of the loop runs a flight or a contact phase; with `landed_contact`, a flight,
    then at once the contact phase it lands in, then the flight that contact ends in, so that a
    bounce takes one turn and an impact that separates two, not three. Under `jax.vmap` every
    turn computes all three for every lane: the quadrature's phases, of fixed cost, gain the
    turns saved; a diffrax ride's gain nothing measurable, so the ODE integrators keep one phase
    a turn. The flight closing a turn runs only where the phase bound leaves room for the contact
    it may land in as well (a turn that starts with the flight runs that contact unbounded), so
    that the phases run are those of a flight and its contact a turn.

    Without gravity (and with `landed_contact`) a body that leaves a contact moves away and
    never comes back: the run is the approach, a loop over the contact's phases alone and the
    flight away, the same phases as the loop of turns runs."""

    def running(c: Carry):
        return (c.mode != DONE) & (c.phases < options.max_phases)

    def unchanged(c: Carry):
        return c

    def contact_runs(c: Carry):  # the contact the approach lands in runs whatever the bound, as in a turn
        bounded = (c.phases < options.max_phases) | (c.phases == 1)
        return (c.mode != DONE) & (c.mode != FLIGHT) & bounded

    if landed_contact and not options.gravity:
        c = initial_carry(problem, options, memory)
        c = jax.lax.cond(c.mode == FLIGHT, flight, unchanged, c)
        c = jax.lax.while_loop(contact_runs, contact, c)
        return finish(jax.lax.cond(running(c) & (c.mode == FLIGHT), flight, unchanged, c))

    def advance(c: Carry):
        return jax.lax.cond(c.mode == FLIGHT, flight, contact, c)

    def land_and_advance(c: Carry):
        c = jax.lax.cond(c.mode == FLIGHT, flight, unchanged, c)
        c = jax.lax.cond((c.mode != FLIGHT) & (c.mode != DONE), contact, unchanged, c)
        return jax.lax.cond((c.mode == FLIGHT) & (c.phases + 1 < options.max_phases), flight, unchanged, c)

    body = land_and_advance if landed_contact else advance
    return finish(jax.lax.while_loop(running, body, initial_carry(problem, options, memory)))


def log_event(c: Carry, time, kind, valid=True) -> Carry:
    """Append an event (time, kind code) when `valid`."""
    index = jnp.minimum(c.event_count, c.event_times.shape[0] - 1)
    times = c.event_times.at[index].set(jnp.where(valid, time, c.event_times[index]))
    kinds = c.event_kinds.at[index].set(jnp.where(valid, kind, c.event_kinds[index]))
    return replace(c, event_times=times, event_kinds=kinds, event_count=c.event_count + jnp.asarray(valid, int))


def store_samples(c: Carry, options: Options, rows) -> Carry:
    """Write this phase's trajectory samples ([P, 5]) in its block of the buffer."""
    if options.samples_per_phase == 0:
        return c
    start = jnp.minimum(c.phases, options.max_phases - 1) * options.samples_per_phase
    return replace(c, trajectory=jax.lax.dynamic_update_slice(c.trajectory, rows, (start, jnp.zeros((), int))))


def finish(c: Carry) -> Outcome:
    """Close the books: a run cut off by the phase bound says so."""
    cut = c.mode != DONE
    return Outcome(
        status=status_code(Status.where(cut, Status.phase_limit, c.status)),
        stuck=c.stuck,
        touch_velocity=c.touch_velocity,
        separation_velocity=c.separation_velocity,
        touch_time=c.touch_time,
        separation_time=c.separation_time,
        contacts=c.contacts,
        max_indentation=c.max_indentation,
        max_force=c.max_force,
        min_force=c.min_force,
        first_contact_work=c.first_contact_work,
        first_contact_viscous_work=c.first_contact_viscous_work,
        end_time=c.t,
        end_indentation=c.d,
        end_velocity=c.v,
        steps=c.steps,
        accepted_steps=c.accepted,
        rejected_steps=c.rejected,
        event_times=c.event_times,
        event_kinds=c.event_kinds,
        trajectory=c.trajectory,
    )
