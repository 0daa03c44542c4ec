"""What an integrator returns, in scaled units, and the bookkeeping both integrators share."""

import diffrax as dfx
import equinox as eqx
import jax
import jax.numpy as jnp

from .._law.branches import Branch
from .._law.law import ContactLaw
from .codes import ADVANCE, DONE, EVENT_CODE, FLIGHT, RESULT_CODE
from .problem import Numerics, Problem
from .transitions import Next

EVENTS_PER_PHASE = 2

_QUADRATURE_NODES = 48
# The largest ln(a_high/a_low) one Gauss–Legendre panel in ln a takes at full accuracy; the rest
# of a longer ride, ≲ e^(−10·(p+1)) of the work for F·h' ∝ a^p, gets a panel of its own.
_LOG_PANEL = 10.0
_SCAN_POINTS = 33
_GOLDEN_STEPS = 60


class Outcome(eqx.Module):
    """Scaled results of one impact (mass 1, units of `Scales`)."""

    status: jax.Array  # result code (phases.RESULT_CODES)
    stuck: jax.Array
    touch_velocity: jax.Array  # speed at the first touch
    separation_velocity: jax.Array  # speed when the first contact let go (0 if captured)
    touch_time: jax.Array
    separation_time: jax.Array  # inf if the first contact never let go
    contacts: jax.Array  # number of contacts (bounces)
    max_indentation: jax.Array
    max_force: jax.Array
    min_force: jax.Array
    first_contact_work: jax.Array  # ∮F dd over the first contact
    end_time: jax.Array
    end_indentation: jax.Array
    end_velocity: jax.Array
    steps: jax.Array  # solver steps (or spring events) in all
    accepted_steps: jax.Array
    rejected_steps: jax.Array
    event_times: jax.Array  # [E], nan where unused
    event_kinds: jax.Array  # [E], −1 where unused
    trajectory: jax.Array  # [T, 5]: t, d, v, F, a (nan where unused); T = 0 without samples


def gauss_legendre(nodes: int = _QUADRATURE_NODES):
    """Nodes and weights on [0, 1]."""
    import numpy as np

    x, w = np.polynomial.legendre.leggauss(nodes)
    return jnp.asarray(0.5 * (x + 1.0)), jnp.asarray(0.5 * w)


def branch_force(law: ContactLaw, branch: Branch, radius):
    """Force while the contact radius rides the branch: d = h(a)."""
    return law.force(radius, branch.level(law, radius))


def branch_work(law: ContactLaw, branch: Branch, start_radius, end_radius):
    """∫F dd while a moves along the branch from start to end: ∫F(a)·h'(a) da.

    Gauss–Legendre in u = ln a over the top e^10 of the radii, where power-law behaviour a^p
    becomes exponential (an interval [a0, 40·a0] is no harder than [a0, 2·a0]); below that
    (from a = 0, or from a jump-in radius decades further down), in s with
    a = a_low + (a_split − a_low)·s².
    """
    nodes, weights = gauss_legendre()

    def integrand(radii):
        return branch_force(law, branch, radii) * law.edge_slope(radii, branch.coefficient)

    low = jnp.minimum(start_radius, end_radius)
    high = jnp.maximum(start_radius, end_radius)
    sign = jnp.where(end_radius >= start_radius, 1.0, -1.0)
    positive = low > 0.0
    log_high = jnp.log(jnp.where(positive, high, 1.0))
    log_split = jnp.maximum(jnp.log(jnp.where(positive, low, 1.0)), log_high - _LOG_PANEL)
    log_span = log_high - log_split
    logarithmic = jnp.exp(log_split + log_span * nodes)
    top = jnp.where(positive, jnp.sum(weights * log_span * logarithmic * integrand(logarithmic)), 0.0)
    split = jnp.where(positive, jnp.exp(log_split), high)
    squared = low + (split - low) * nodes**2
    bottom = jnp.sum(weights * 2.0 * (split - low) * nodes * integrand(squared))
    return sign * (top + bottom)


def hold_work(law: ContactLaw, radius, start, end):
    """∫F dd at a fixed contact radius: F = 2(a·d − G(a)) is linear in d."""
    return radius * (end**2 - start**2) - 2.0 * law.G(radius) * (end - start)


def extremes(function, lower, upper):
    """(min, max) of a scalar function between two points: a scan, then golden sections."""
    lower, upper = jnp.minimum(lower, upper), jnp.maximum(lower, upper)
    grid = jnp.linspace(0.0, 1.0, _SCAN_POINTS)
    points = lower + (upper - lower) * grid
    values = function(points)
    step = (upper - lower) / (_SCAN_POINTS - 1)

    def refine(sign):
        best = jnp.argmin(sign * values)
        lo = jnp.maximum(points[best] - step, lower)
        hi = jnp.minimum(points[best] + step, upper)
        ratio = 0.5 * (jnp.sqrt(5.0) - 1.0)

        def golden(_, bracket):
            a, b = bracket
            c = b - ratio * (b - a)
            e = a + ratio * (b - a)
            keep_left = sign * function(c) < sign * function(e)
            return jnp.where(keep_left, a, c), jnp.where(keep_left, e, b)

        a, b = jax.lax.fori_loop(0, _GOLDEN_STEPS, golden, (lo, hi))
        return sign * jnp.minimum(sign * function(0.5 * (a + b)), sign * values[best])

    low, high = jax.vmap(refine)(jnp.array([1.0, -1.0]))
    return low, high


def phase_summary(law: ContactLaw, branch: Branch, riding, radii, gravity, start, end):
    """Work ∫F dd, the force range and the deepest indentation of one contact phase.

    `riding`: the radius follows the branch (else it is held fixed at radii[0]);
    `radii` are the contact radii and `start`, `end` the (d, v) at the two ends of the phase.
    """
    a_start, a_end = radii
    d_start, v_start = start
    d_end, _ = end

    work_riding = branch_work(law, branch, a_start, a_end)
    low_riding, high_riding = extremes(lambda a: branch_force(law, branch, a), a_start, a_end)

    # Hold: a harmonic arc about d_eq; if it starts inward it turns at d_eq + amplitude.
    stiffness = 2.0 * jnp.maximum(a_start, 1e-300)
    balance = (2.0 * law.G(a_start) + gravity) / stiffness
    turn = balance + jnp.sqrt((d_start - balance) ** 2 + v_start**2 / stiffness)
    deepest_hold = jnp.where(v_start > 0.0, jnp.maximum(turn, d_start), jnp.maximum(d_start, d_end))
    forces_hold = law.force(a_start, jnp.stack([jnp.minimum(d_start, d_end), deepest_hold]))
    work_hold = hold_work(law, a_start, d_start, d_end)

    work = jnp.where(riding, work_riding, work_hold)
    low = jnp.where(riding, low_riding, forces_hold[0])
    high = jnp.where(riding, high_riding, forces_hold[1])
    deepest = jnp.where(riding, jnp.maximum(d_start, d_end), deepest_hold)
    return work, low, high, deepest


def active_branch(mode, attach: Branch, detach: Branch) -> Branch:
    """Loading rides the attach branch; hold and unloading answer to the detach branch."""
    return jax.tree.map(lambda a, d: jnp.where(mode == ADVANCE, a, d), attach, detach)


class Carry(eqx.Module):
    t: jax.Array
    d: jax.Array
    v: jax.Array
    mode: jax.Array
    segment: jax.Array
    radius: jax.Array  # contact radius at the start of the current phase
    phases: jax.Array
    contacts: jax.Array
    status: jax.Array
    stuck: jax.Array
    touch_velocity: jax.Array
    separation_velocity: jax.Array
    touch_time: jax.Array
    separation_time: jax.Array
    max_indentation: jax.Array
    max_force: jax.Array
    min_force: jax.Array
    contact_work: jax.Array
    first_contact_work: jax.Array
    steps: jax.Array
    accepted: jax.Array
    rejected: jax.Array
    event_times: jax.Array
    event_kinds: jax.Array
    event_count: jax.Array
    trajectory: jax.Array


def initial_carry(problem: Problem, numerics: Numerics) -> Carry:
    events = EVENTS_PER_PHASE * numerics.max_phases
    rows = numerics.samples_per_phase * numerics.max_phases
    zero, inf = jnp.zeros(()), jnp.asarray(jnp.inf)
    return Carry(
        t=zero,
        d=jnp.asarray(problem.start_indentation, jnp.float64),
        v=jnp.asarray(problem.start_velocity, jnp.float64),
        mode=jnp.where(problem.overflow | ~problem.bounded, DONE, FLIGHT),
        segment=jnp.zeros((), int),
        radius=zero,
        phases=jnp.zeros((), int),
        contacts=jnp.zeros((), int),
        status=jnp.where(
            problem.overflow,
            RESULT_CODE["branch_overflow"],
            jnp.where(problem.bounded, RESULT_CODE["separated"], RESULT_CODE["unbounded_contact"]),
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
        first_contact_work=zero,
        steps=jnp.zeros((), int),
        accepted=jnp.zeros((), int),
        rejected=jnp.zeros((), int),
        event_times=jnp.full(events, jnp.nan),
        event_kinds=jnp.full(events, -1, int),
        event_count=jnp.zeros((), int),
        trajectory=jnp.full((rows, 5), jnp.nan),
    )


def close_phase(c: Carry, active, solution, end, nxt: Next, out_of_time, summary) -> Carry:
    """Book a contact phase that diffrax ended (kept only where `active`).

    `end` is (t, d, v) at its end, `nxt` the phase after its event, `out_of_time` whether the
    time limit fired, `summary` its (work ∫F dd, lowest force, highest force, deepest d).
    """
    t_end, d_end, v_end = end
    work, low, high, deepest = summary
    event_found = solution.result == dfx.RESULTS.event_occurred
    failed = active & ~event_found
    in_time = ~out_of_time
    separated = event_found & in_time & nxt.separated
    captured = event_found & in_time & nxt.captured
    out_of_time = event_found & out_of_time
    stopped = (nxt.stop >= 0) & ~out_of_time
    status = jnp.where(
        failed,
        RESULT_CODE["solver_failure"],
        jnp.where(
            out_of_time,
            RESULT_CODE["time_limit"],
            jnp.where(stopped, nxt.stop, jnp.where(captured, RESULT_CODE["captured"], c.status)),
        ),
    )
    contact_work = c.contact_work + work
    first = c.contacts == 1
    updated = eqx.tree_at(
        lambda s: (
            s.t, s.d, s.v, s.mode, s.segment, s.radius, s.phases, s.status, s.stuck,
            s.separation_velocity, s.separation_time, s.max_indentation, s.max_force, s.min_force,
            s.contact_work, s.first_contact_work, s.steps, s.accepted, s.rejected,
        ),
        c,
        (
            t_end, d_end, v_end, jnp.where(failed | stopped | out_of_time, DONE, nxt.mode), nxt.segment, nxt.radius,
            c.phases + 1, status, captured,
            jnp.where(first & separated, jnp.abs(v_end), c.separation_velocity),
            jnp.where(first & separated, t_end, c.separation_time),
            jnp.maximum(c.max_indentation, deepest),
            jnp.maximum(c.max_force, high),
            jnp.minimum(c.min_force, low),
            contact_work,
            jnp.where(first & (separated | captured), contact_work, c.first_contact_work),
            c.steps + solution.stats["num_steps"],
            c.accepted + solution.stats["num_accepted_steps"],
            c.rejected + solution.stats["num_rejected_steps"],
        ),
    )
    updated = log_event(updated, t_end, jnp.where(in_time, nxt.event, EVENT_CODE["limit"]), event_found)
    return jax.tree.map(lambda new, old: jnp.where(active, new, old), updated, c)


def run_phases(problem, numerics: Numerics, flight, contact) -> Outcome:
    """Chain flights and contact phases (`flight(problem, numerics, carry)`, `contact(...)`)
    until the run is done or holds no more phases."""

    def running(c: Carry):
        return (c.mode != DONE) & (c.phases < numerics.max_phases)

    def advance(c: Carry):
        return jax.lax.cond(
            c.mode == FLIGHT,
            lambda s: flight(problem, numerics, s),
            lambda s: contact(problem, numerics, s),
            c,
        )

    return finish(jax.lax.while_loop(running, advance, initial_carry(problem, numerics)))


def log_event(c: Carry, time, kind, valid=True) -> Carry:
    """Append an event (time, kind code) when `valid`."""
    index = jnp.minimum(c.event_count, c.event_times.shape[0] - 1)
    times = c.event_times.at[index].set(jnp.where(valid, time, c.event_times[index]))
    kinds = c.event_kinds.at[index].set(jnp.where(valid, kind, c.event_kinds[index]))
    count = c.event_count + jnp.asarray(valid, int)
    return eqx.tree_at(lambda s: (s.event_times, s.event_kinds, s.event_count), c, (times, kinds, count))


def store_samples(c: Carry, numerics: Numerics, rows) -> Carry:
    """Write this phase's trajectory samples ([P, 5]) in its block of the buffer."""
    if numerics.samples_per_phase == 0:
        return c
    start = jnp.minimum(c.phases, numerics.max_phases - 1) * numerics.samples_per_phase
    trajectory = jax.lax.dynamic_update_slice(c.trajectory, rows, (start, jnp.zeros((), int)))
    return eqx.tree_at(lambda s: s.trajectory, c, trajectory)


def finish(c: Carry) -> Outcome:
    """Close the books: a run cut off by the phase bound says so."""
    cut = c.mode != DONE
    return Outcome(
        status=jnp.where(cut, RESULT_CODE["phase_limit"], c.status),
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
