"""The continuum contact law (N → ∞ springs) integrated with diffrax, phase by phase.

Every change of the contact law is a located event that ends a `diffeqsolve`; the rules in
`transitions` pick the next phase and a `while_loop` chains the phases. Free flight between
contacts is analytic.

While the contact radius rides a branch d = h(a), a(d) has a square-root singularity wherever
h' = 0 (the critical points where contacts snap or separate), which costs an adaptive method
its order. So those phases take the radius itself as state, with a pseudo-time s:

    a' = v·q,   v' = (g − F(a, h(a)))·h'(a)·q,   t' = h'(a)·q,   q = 1/√(1 + h'(a)²),

smooth through turnarounds (v = 0) and critical points (h' = 0) alike, and free of any root
solve: d = h(a) is explicit. Only a hold (a fixed, F linear in d) and loading that starts from
a = 0 on a steep tip (h' → ∞ as a → 0, power laws n < 1, no jump-in) are integrated in time
with d as state.
"""

import diffrax as dfx
import equinox as eqx
import jax
import jax.numpy as jnp

from . import transitions
from .carry import Carry, Outcome, active_branch, close_phase, log_event, phase_summary, run_phases, store_samples
from .rootfind import BracketBisection
from .codes import ADVANCE, DONE, EVENT_CODE, HOLD, RECEDE, RESULT_CODE
from .problem import Numerics, Problem

SOLVERS = {
    "tsit5": dfx.Tsit5,
    "dopri5": dfx.Dopri5,
    "dopri8": dfx.Dopri8,
    "bosh3": dfx.Bosh3,
    "heun": dfx.Heun,
    "kvaerno3": dfx.Kvaerno3,
    "kvaerno5": dfx.Kvaerno5,
}

# A contact phase lasts O(1) in scaled time; this horizon only stops a runaway solve.
_PHASE_HORIZON = 1.0e4
# Radii (scaled) at which the edge slope is compared to tell a steep tip.
_TIP_NEAR, _TIP_FAR = 1e-9, 1e-6
# Events are located by bisection inside the step that crossed, to a bracket of
# 1e-14 relative (+1e-15 absolute) in pseudo-time: a few ulps.
_ROOT_RTOL, _ROOT_ATOL = 1e-14, 1e-15


class PhaseArgs(eqx.Module):
    law: object
    branch: object
    riding: jax.Array  # state is (a, v, t) in pseudo-time; else (d, v, t) in time
    mode: jax.Array
    segment: jax.Array
    radius: jax.Array  # held radius (HOLD)
    gravity: jax.Array
    velocity_sign: jax.Array  # turnaround: sign·v crosses zero upwards
    level_sign: jax.Array  # branch end: sign·(distance to the end) crosses zero upwards
    level: jax.Array  # the end in the state's variable: a segment end (riding) or a depth d
    time_limit: jax.Array
    speed_scale: jax.Array  # 1 + the speeds of the phase start and of the touch


def timed_radius(d, args: PhaseArgs):
    """Contact radius of a time-parametrized phase: held, or the branch root at d."""
    riding = args.branch.radius(args.law, d, args.segment)
    return jnp.where(args.mode == HOLD, args.radius, riding)


def _make_vector_field(timed_loading: bool):
    def vector_field(s, y, args: PhaseArgs):
        x, v = y[0], y[1]
        law, branch = args.law, args.branch
        radius = jnp.maximum(x, 0.0)  # a stage may step a hair past a = 0
        slope = law.edge_slope(radius, branch.coefficient)
        pace = 1.0 / jnp.sqrt(1.0 + slope**2)
        force = law.force(radius, branch.level(law, radius))
        riding = jnp.stack([v * pace, (args.gravity - force) * slope * pace, slope * pace])
        held = law.force(args.radius, x)
        if timed_loading:
            held = law.force(timed_radius(x, args), x)
        timed = jnp.stack([v, args.gravity - held, jnp.ones_like(v)])
        return jnp.where(args.riding, riding, timed)

    return vector_field


def _distance_to_end(y, args: PhaseArgs):
    """How far the state is from the phase's end, of relative size and sign-normalised.

    Timed phases end at a depth d. Riding phases end at a segment end p, where a − p
    crosses linearly at a turning point of h and |h − h(p)| grows linearly at a steep tip
    (where a ∝ (s_end − s)² only touches): their sum, both with the sign of a − p, changes
    sign exactly at p in both cases, whatever the curvature there.
    """
    x = y[0]
    offset = x - args.level
    edge = args.branch.level(args.law, jnp.maximum(x, 0.0)) - args.branch.level(args.law, args.level)
    riding = offset + jnp.sign(offset) * jnp.abs(edge)
    distance = jnp.where(args.riding, riding, x - args.level)
    return args.level_sign * distance / (1.0 + jnp.abs(args.level))


def _conditions(y, args: PhaseArgs):
    """The phase's event conditions, each negative until its event and of relative size:
    turnaround (sign·v), phase end and time limit (t − t_max)."""
    return jnp.stack(
        [
            args.velocity_sign * y[1] / args.speed_scale,
            _distance_to_end(y, args),
            (y[2] - args.time_limit) / (1.0 + jnp.abs(y[2])),
        ]
    )


def _first_event(t, y, args: PhaseArgs, **kwargs):
    """Crosses zero upwards when the first of the conditions does (one scalar to bisect)."""
    return jnp.max(_conditions(y, args))


def flight(problem: Problem, numerics: Numerics, c: Carry) -> Carry:
    """Free flight (analytic) to the next touch, or out of reach for good."""
    duration, speed, reaches = transitions.flight_to_touch(problem, c.d, c.v)
    touch_time = c.t + duration
    over_bounces = c.contacts >= numerics.max_bounces
    over_time = touch_time > problem.time_limit
    lands = reaches & ~over_bounces & ~over_time

    if numerics.samples_per_phase:
        tau = jnp.linspace(0.0, jnp.where(lands, duration, 0.0), numerics.samples_per_phase)
        kept = lands | (jnp.arange(numerics.samples_per_phase) == 0)
        rows = jnp.stack(
            [
                c.t + tau,
                c.d + c.v * tau + 0.5 * problem.gravity * tau**2,
                c.v + problem.gravity * tau,
                jnp.zeros_like(tau),
                jnp.zeros_like(tau),
            ],
            axis=1,
        )
        c = store_samples(c, numerics, jnp.where(kept[:, None], rows, jnp.nan))

    nxt = transitions.touch(problem)
    first = c.contacts == 0
    status = jnp.where(
        ~reaches,
        RESULT_CODE["separated"],
        jnp.where(over_bounces, RESULT_CODE["bounce_limit"], RESULT_CODE["time_limit"]),
    )
    ended_by_limit = reaches & ~lands
    c = log_event(c, touch_time, EVENT_CODE["touch"], lands)
    c = log_event(c, c.t, EVENT_CODE["limit"], ended_by_limit)
    stopped = nxt.stop >= 0
    c = log_event(c, touch_time, EVENT_CODE["limit"], lands & stopped)
    start_force = problem.law.force(nxt.radius, 0.0)
    return eqx.tree_at(
        lambda s: (
            s.t, s.d, s.v, s.mode, s.segment, s.radius, s.phases, s.contacts, s.status,
            s.touch_velocity, s.touch_time, s.contact_work, s.max_force, s.min_force,
        ),
        c,
        (
            jnp.where(lands, touch_time, c.t),
            jnp.where(lands, 0.0, c.d),
            jnp.where(lands, speed, c.v),
            jnp.where(lands, jnp.where(stopped, DONE, nxt.mode), DONE),
            nxt.segment,
            nxt.radius,
            c.phases + 1,
            c.contacts + jnp.asarray(lands, int),
            jnp.where(lands, jnp.where(stopped, nxt.stop, c.status), status),
            jnp.where(lands & first, speed, c.touch_velocity),
            jnp.where(lands & first, touch_time, c.touch_time),
            jnp.zeros(()),
            jnp.where(lands, jnp.maximum(c.max_force, start_force), c.max_force),
            jnp.where(lands, jnp.minimum(c.min_force, start_force), c.min_force),
        ),
    )


def contact(problem: Problem, numerics: Numerics, c: Carry) -> Carry:
    """One contact phase with diffrax, ended by its located event."""
    law = problem.law
    in_contact = (c.mode == ADVANCE) | (c.mode == HOLD) | (c.mode == RECEDE)
    branch = active_branch(c.mode, problem.attach, problem.detach)
    # A segment rising from (or within 1e-6 of) a steep tip (h' → ∞ at a = 0, power laws
    # n < 1) is integrated in time: in a, the pace q would never let a get there.
    steep = (branch.nodes[c.segment] < _TIP_FAR) & (
        law.edge_slope(_TIP_NEAR, branch.coefficient) > law.edge_slope(_TIP_FAR, branch.coefficient)
    )
    riding = ((c.mode == RECEDE) | (c.mode == ADVANCE)) & ~steep
    # Ends of the phase: the branch's segment end (in a when riding, in d when timed), or the
    # detach edge of the held radius.
    segment_end = jnp.where(c.mode == ADVANCE, branch.nodes[c.segment + 1], branch.nodes[c.segment])
    level = jnp.where(
        riding,
        segment_end,
        jnp.where(c.mode == HOLD, problem.detach.level(law, c.radius), branch.level(law, segment_end)),
    )
    args = PhaseArgs(
        law=law,
        branch=branch,
        riding=riding,
        mode=c.mode,
        segment=c.segment,
        radius=c.radius,
        gravity=problem.gravity,
        velocity_sign=jnp.where(c.mode == ADVANCE, -1.0, 1.0),
        level_sign=jnp.where(c.mode == ADVANCE, 1.0, -1.0),
        level=level,
        time_limit=problem.time_limit,
        speed_scale=1.0 + jnp.abs(c.v) + problem.touch_speed,
    )
    horizon = jnp.where(in_contact, _PHASE_HORIZON, 1e-9)
    save_dense = numerics.samples_per_phase > 0
    solution = dfx.diffeqsolve(
        dfx.ODETerm(_make_vector_field(numerics.timed_loading)),
        SOLVERS[numerics.method](),
        t0=0.0,
        t1=horizon,
        dt0=None,
        y0=jnp.stack([jnp.where(riding, c.radius, c.d), c.v, c.t]),
        args=args,
        saveat=dfx.SaveAt(t1=True, dense=save_dense),
        stepsize_controller=dfx.PIDController(rtol=numerics.rtol, atol=numerics.atol),
        event=dfx.Event(
            _first_event,
            root_finder=BracketBisection(rtol=_ROOT_RTOL, atol=_ROOT_ATOL),
            direction=True,
        ),
        max_steps=numerics.max_steps,
        throw=False,
    )
    x_end, v_end, t_end = solution.ys[-1, 0], solution.ys[-1, 1], solution.ys[-1, 2]
    # A located event may overshoot the segment end by round-off: the radius stays on it.
    x_end = jnp.where(riding, jnp.clip(x_end, branch.nodes[c.segment], branch.nodes[c.segment + 1]), x_end)
    d_end = jnp.where(riding, branch.level(law, x_end), x_end)
    a_end = jnp.where(
        riding, x_end, jnp.where(c.mode == HOLD, c.radius, branch.radius(law, x_end, c.segment))
    )
    event_found = solution.result == dfx.RESULTS.event_occurred
    fired = jnp.argmax(_conditions(solution.ys[-1], args))
    turned, out_of_time = fired == 0, fired == 2
    # A located turnaround is v = 0: round-off of either sign would make the next phase's
    # combined condition start positive and mask its other events.
    v_end = jnp.where(event_found & turned, 0.0, v_end)

    if save_dense:
        pseudo = jnp.linspace(0.0, solution.ts[-1], numerics.samples_per_phase)
        states = jax.vmap(solution.evaluate)(pseudo)
        x, v, t = states[:, 0], states[:, 1], states[:, 2]
        radii = jnp.where(riding, x, jax.vmap(lambda d: timed_radius(d, args))(x))
        d = jnp.where(riding, branch.level(law, x), x)
        rows = jnp.stack([t, d, v, law.force(radii, d), radii], axis=1)
        c = jax.tree.map(lambda new, old: jnp.where(in_contact, new, old), store_samples(c, numerics, rows), c)

    work, low, high, deepest = phase_summary(
        law, branch, c.mode != HOLD, (c.radius, a_end), problem.gravity, (c.d, c.v), (d_end, v_end)
    )
    nxt = transitions.after_phase(problem, c.mode, c.segment, a_end, d_end, turned)
    return close_phase(c, in_contact, solution, (t_end, d_end, v_end), nxt, out_of_time, (work, low, high, deepest))


def integrate(problem: Problem, numerics: Numerics) -> Outcome:
    """Run one impact (possibly several bounces) with the continuum law."""
    return run_phases(problem, numerics, flight, contact)
