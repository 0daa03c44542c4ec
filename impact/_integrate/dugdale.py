"""Impacts with Maugis–Dugdale adhesion: the body rides the equilibrium curve of `dugdale`.

The body is free until its tip comes within the range h of the surface (d = −h, the `touch`
event); the adhesive zone then snaps to its first stable radius. While the state sits on a
rising segment of the curve d(s) the motion is integrated in the pseudo-time of the JKR
integrator (continuum.py), with the curve parameter s as state:

    s' = v·q,   v' = (g − F(s))·d'(s)·q,   t' = d'(s)·q,   q = 1/√(1 + d'(s)²).

At the end of a rising segment (a turning point of d, or the junction where the zone's centre
closes into a contact) the state moves at fixed d to the next rising segment at that level:
a snap-in or snap-out, or the release of the body when none is left. An outward turnaround on
the curve is a capture (the argument of `transitions.capture` holds: only the jumps dissipate).
"""

import diffrax as dfx
import equinox as eqx
import jax
import jax.numpy as jnp

from . import transitions
from .continuum import SOLVERS
from .._law.dugdale import DugdaleCurve, DugdaleLaw, build_curve
from .._law.law import ContactLaw
from .carry import Carry, Outcome, close_phase, extremes, gauss_legendre, log_event, run_phases, store_samples
from ..profiles import Cone, Paraboloid, PowerLaw, Profile
from .codes import ADVANCE, DONE, EVENT_CODE, FLIGHT, RECEDE, RESULT_CODE
from .rootfind import BracketBisection
from .._law.scales import Scales, adhesive_scales
from .problem import Numerics, Physics, touch_velocity

_PHASE_HORIZON = 1.0e4
_ROOT_RTOL, _ROOT_ATOL = 1e-14, 1e-15
# A landing further than this (relative) from the segment end is a jump, not a continuation.
_SAME_STATE = 1e-12


class DugdaleProblem(eqx.Module):
    """The scaled impact: law, its curve and the initial state (`Carry.radius` holds s)."""

    law: DugdaleLaw
    curve: DugdaleCurve
    gravity: jax.Array
    start_indentation: jax.Array  # −h − gap (scaled)
    start_velocity: jax.Array
    touch_speed: jax.Array  # speed when the tip comes within range
    bounded: jax.Array
    time_limit: jax.Array

    @property
    def scales(self) -> Scales:
        return self.law.law.scales

    @property
    def overflow(self):
        return self.curve.overflow


def build_dugdale_problem(physics: Physics, numerics: Numerics) -> DugdaleProblem:
    """Scale (JKR units, or the impact energy's where it reaches further) and tabulate."""
    profile = physics.profile
    speed = touch_velocity(physics, numerics)
    scales = adhesive_scales(profile, physics.E_star, physics.work_of_adhesion, physics.mass, speed)
    zero = jnp.zeros(())
    contact_law = ContactLaw(profile, scales, zero, zero, False)
    adhesion_range = physics.work_of_adhesion / physics.adhesive_stress
    law = DugdaleLaw(
        law=contact_law,
        degree=_degree(profile),
        stress=physics.adhesive_stress * scales.radial / (physics.E_star * scales.normal),
        range=adhesion_range / scales.normal,
    )
    touch_speed = speed / scales.velocity
    curve = build_curve(law, touch_speed, numerics.max_turns)
    gravity = physics.gravity * scales.time**2 / scales.normal if numerics.gravity else zero
    return DugdaleProblem(
        law=law,
        curve=curve,
        gravity=gravity,
        start_indentation=-(adhesion_range + physics.gap) / scales.normal,
        start_velocity=physics.velocity / scales.velocity,
        touch_speed=touch_speed,
        bounded=jnp.asarray(True),
        time_limit=physics.time_limit / scales.time,
    )


def _degree(profile: Profile):
    """n of a body f = c·rⁿ (the shapes `scene.DUGDALE_SHAPES` admits)."""
    if isinstance(profile, PowerLaw):
        return profile.n
    if isinstance(profile, Paraboloid):
        return jnp.asarray(2.0)
    if isinstance(profile, Cone):
        return jnp.asarray(1.0)
    raise ValueError(f"Maugis–Dugdale adhesion needs a power-law body, not {type(profile).__name__}")


class _Args(eqx.Module):
    law: DugdaleLaw
    curve: DugdaleCurve
    gravity: jax.Array
    velocity_sign: jax.Array  # turnaround: sign·v crosses zero upwards
    end: jax.Array  # the segment end in s the phase runs to
    end_sign: jax.Array
    time_limit: jax.Array
    speed_scale: jax.Array


def _vector_field(pseudo_time, y, args: _Args):
    s, v = y[0], y[1]
    _, force, slope = args.curve.riding(args.law, s)
    pace = 1.0 / jnp.sqrt(1.0 + slope**2)
    return jnp.stack([v * pace, (args.gravity - force) * slope * pace, slope * pace])


def _conditions(y, args: _Args):
    """Turnaround, segment end, time limit: each negative until its event, of relative size."""
    return jnp.stack(
        [
            args.velocity_sign * y[1] / args.speed_scale,
            args.end_sign * (y[0] - args.end) / (1.0 + jnp.abs(args.end)),
            (y[2] - args.time_limit) / (1.0 + jnp.abs(y[2])),
        ]
    )


def _first_event(t, y, args: _Args, **kwargs):
    return jnp.max(_conditions(y, args))


def flight(problem: DugdaleProblem, numerics: Numerics, c: Carry) -> Carry:
    """Free flight (analytic) until the tip comes within range, or out of reach for good."""
    reach = -problem.law.range
    duration, speed, reaches = transitions.flight_to_touch(problem, c.d - reach, c.v)
    touch_time = c.t + duration
    over_bounces = c.contacts >= numerics.max_bounces
    lands = reaches & ~over_bounces & (touch_time <= problem.time_limit)
    if numerics.samples_per_phase:
        tau = jnp.linspace(0.0, jnp.where(lands, duration, 0.0), numerics.samples_per_phase)
        kept = lands | (jnp.arange(numerics.samples_per_phase) == 0)
        zeros = jnp.zeros_like(tau)
        rows = jnp.stack(
            [c.t + tau, c.d + c.v * tau + 0.5 * problem.gravity * tau**2, c.v + problem.gravity * tau, zeros, zeros],
            axis=1,
        )
        c = store_samples(c, numerics, jnp.where(kept[:, None], rows, jnp.nan))
    # The zone snaps to the first rising state at d = −h.
    landing, segment, blocked = problem.curve.cascade_out(problem.law, jnp.zeros(()), reach)
    status = jnp.where(
        ~reaches,
        RESULT_CODE["separated"],
        jnp.where(over_bounces, RESULT_CODE["bounce_limit"], RESULT_CODE["time_limit"]),
    )
    status = jnp.where(lands, jnp.where(blocked, RESULT_CODE["radius_overflow"], c.status), status)
    c = log_event(c, touch_time, EVENT_CODE["touch"], lands)
    c = log_event(c, c.t, EVENT_CODE["limit"], reaches & ~lands)
    first = c.contacts == 0
    start_force = problem.curve.force(problem.law, landing)
    return eqx.tree_at(
        lambda s: (
            s.t, s.d, s.v, s.mode, s.segment, s.radius, s.phases, s.contacts, s.status,
            s.touch_velocity, s.touch_time, s.contact_work, s.max_force, s.min_force,
        ),
        c,
        (
            jnp.where(lands, touch_time, c.t),
            jnp.where(lands, reach, c.d),
            jnp.where(lands, speed, c.v),
            jnp.where(lands & ~blocked, ADVANCE, DONE),
            segment,
            landing,
            c.phases + 1,
            c.contacts + jnp.asarray(lands, int),
            status,
            jnp.where(lands & first, speed, c.touch_velocity),
            jnp.where(lands & first, touch_time, c.touch_time),
            jnp.zeros(()),
            jnp.where(lands, jnp.maximum(c.max_force, start_force), c.max_force),
            jnp.where(lands, jnp.minimum(c.min_force, start_force), c.min_force),
        ),
    )


def _work(law: DugdaleLaw, curve: DugdaleCurve, start, end):
    """∫F dd along the curve from s = start to end (Gauss–Legendre; smooth on a segment)."""
    nodes, weights = gauss_legendre()
    points = start + (end - start) * nodes
    _, force, slope = curve.riding(law, points)
    return (end - start) * jnp.sum(weights * force * slope)


def _after(problem: DugdaleProblem, advancing, turned, segment, s_end, d_end):
    """The phase after a ride ended (`Next.radius` holds s)."""
    law, curve = problem.law, problem.curve
    junction = curve.junction
    # Loading reaches its segment's top: on to the next rising state at this level.
    out_s, out_segment, blocked = curve.cascade_out(law, curve.nodes[segment + 1], d_end)
    jumped_out = out_s > curve.nodes[segment + 1] + _SAME_STATE * (1.0 + out_s)
    out_event = jnp.where(jumped_out, EVENT_CODE["snap_in"], EVENT_CODE["contact_start"])
    # Unloading reaches its segment's foot: back to the last rising state at this level.
    in_s, in_segment, released = curve.cascade_in(law, curve.nodes[segment], d_end)
    jumped_in = in_s < curve.nodes[segment] - _SAME_STATE * (1.0 + in_s)
    in_event = jnp.where(
        released,
        EVENT_CODE["separation"],
        jnp.where(jumped_in | (curve.nodes[segment] != junction), EVENT_CODE["snap_out"], EVENT_CODE["contact_end"]),
    )
    mode = jnp.where(
        advancing,
        jnp.where(turned, RECEDE, jnp.where(blocked, DONE, ADVANCE)),
        jnp.where(turned, DONE, jnp.where(released, FLIGHT, RECEDE)),
    )
    new_segment = jnp.where(advancing, jnp.where(turned, segment, out_segment), jnp.where(turned, segment, in_segment))
    new_s = jnp.where(turned, s_end, jnp.where(advancing, out_s, in_s))
    event = jnp.where(
        advancing,
        jnp.where(turned, EVENT_CODE["max_indentation"], out_event),
        jnp.where(turned, EVENT_CODE["capture"], in_event),
    )
    return transitions.Next(
        mode=mode,
        segment=new_segment,
        radius=new_s,
        event=event,
        separated=~advancing & ~turned & released,
        captured=~advancing & turned,
        stop=jnp.where(advancing & ~turned & blocked, RESULT_CODE["radius_overflow"], -1),
    )


def contact(problem: DugdaleProblem, numerics: Numerics, c: Carry) -> Carry:
    """One ride along a rising segment with diffrax, ended by its located event."""
    law, curve = problem.law, problem.curve
    riding = (c.mode == ADVANCE) | (c.mode == RECEDE)
    advancing = c.mode == ADVANCE
    end = jnp.where(advancing, curve.nodes[c.segment + 1], curve.nodes[c.segment])
    args = _Args(
        law=law,
        curve=curve,
        gravity=problem.gravity,
        velocity_sign=jnp.where(advancing, -1.0, 1.0),
        end=end,
        end_sign=jnp.where(advancing, 1.0, -1.0),
        time_limit=problem.time_limit,
        speed_scale=1.0 + jnp.abs(c.v) + problem.touch_speed,
    )
    s_start = c.radius
    solution = dfx.diffeqsolve(
        dfx.ODETerm(_vector_field),
        SOLVERS[numerics.method](),
        t0=0.0,
        t1=jnp.where(riding, _PHASE_HORIZON, 1e-9),
        dt0=None,
        y0=jnp.stack([s_start, c.v, c.t]),
        args=args,
        saveat=dfx.SaveAt(t1=True, dense=numerics.samples_per_phase > 0),
        stepsize_controller=dfx.PIDController(rtol=numerics.rtol, atol=numerics.atol),
        event=dfx.Event(_first_event, root_finder=BracketBisection(rtol=_ROOT_RTOL, atol=_ROOT_ATOL), direction=True),
        max_steps=numerics.max_steps,
        throw=False,
    )
    s_end = jnp.clip(solution.ys[-1, 0], curve.nodes[c.segment], curve.nodes[c.segment + 1])
    v_end, t_end = solution.ys[-1, 1], solution.ys[-1, 2]
    d_end = curve.depth(law, s_end)
    event_found = solution.result == dfx.RESULTS.event_occurred
    fired = jnp.argmax(_conditions(solution.ys[-1], args))
    turned, out_of_time = fired == 0, fired == 2
    v_end = jnp.where(event_found & turned, 0.0, v_end)

    if numerics.samples_per_phase:
        pseudo = jnp.linspace(0.0, solution.ts[-1], numerics.samples_per_phase)
        states = jax.vmap(solution.evaluate)(pseudo)
        s = jnp.clip(states[:, 0], curve.nodes[c.segment], curve.nodes[c.segment + 1])
        depth, force, radius, _ = curve.state(law, s)
        rows = jnp.stack([states[:, 2], depth, states[:, 1], force, radius], axis=1)
        c = jax.tree.map(lambda new, old: jnp.where(riding, new, old), store_samples(c, numerics, rows), c)

    work = _work(law, curve, s_start, s_end)
    low, high = extremes(lambda s: curve.force(law, s), s_start, s_end)
    nxt = _after(problem, advancing, turned, c.segment, s_end, d_end)
    summary = (work, low, high, jnp.maximum(c.d, d_end))
    return close_phase(c, riding, solution, (t_end, d_end, v_end), nxt, out_of_time, summary)


def integrate(problem: DugdaleProblem, numerics: Numerics) -> Outcome:
    """Run one impact (possibly several bounces) on the Maugis–Dugdale curve."""
    return run_phases(problem, numerics, flight, contact)
