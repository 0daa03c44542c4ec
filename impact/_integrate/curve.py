"""Impacts on the equilibrium curve of a finite-range adhesive law (`_law.curve`): the body
rides the curve's rising segments and jumps between them, phase by phase.

The body is free until it reaches the depth where the interaction starts (the law's `onset`, the
`touch` event); the state then snaps to the first stable (rising) state at that depth. While the
state sits on a rising segment of the curve d(s) the motion is integrated in the pseudo-time of
the JKR integrator (`continuum`), with the curve parameter s as state:

    s' = v·q,   v' = (g − F(s))·d'(s)·q,   t' = d'(s)·q,   q = 1/√(1 + d'(s)²).

At the end of a rising segment (a turning point of d, or the junction where a zone's centre
closes into a contact) the state moves at fixed d to the next rising segment at that level:
a snap-in or snap-out, or the release of the body when none is left. An outward turnaround on
the curve is a capture (the argument of `transitions.capture` holds: only the jumps dissipate).
Every curve law (`_law.base.AbstractCurveLaw`: Maugis–Dugdale, Greenwood–Johnson) is built
and ridden here; `CurveIntegrator` rides the continuum law's curve, `dugdale.DugdaleSpringIntegrator`
the curve of a Maugis–Dugdale spring array.

A curve that remembers (Maugis–Dugdale with approach hysteresis, `_law.dugdale_hysteresis`) is
one path of a family, chosen by the carry's memory (the frozen zone's radius; 0 apart, where the
path is the approach curve): loading turns back onto the frozen zone of its path anchored there,
which unloads onto the detach curve (`detach_start`); separation clears the memory.
"""

import abc
import functools
from typing import ClassVar

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.quadrature import gauss_legendre, ordered_sum
from .._core.types import Parameter
from .._law.base import AbstractCurveLaw
from .._law.curve import AbstractCurve, CurveLaw, Reach, top_of_reach
from .._law.scales import Scales
from .base import dense_states
from .carry import Carry
from .codes import ADVANCE, DONE, EVENT_CODE, FLIGHT, RECEDE, Status
from .flight import land
from .problem import AbstractProblem, Motion, Options, Physics, motion_of, touch_velocity
from .ride import AbstractPhaseArgs, AbstractRidingIntegrator, PhaseEnd, Ride, branch_rates, speed_scale
from .transitions import Next, next_phase
from .work import ContactSummary, extremes

_QUADRATURE_NODES = 48
# A landing further than this (relative) from the segment end is a jump, not a continuation.
_SAME_STATE = 1e-12


class CurveProblem(AbstractProblem):
    """The scaled impact: law, its curve and the initial state (`Carry.radius` holds s)."""

    law: CurveLaw
    curve: AbstractCurve
    motion: Motion  # it starts at the onset less the gap; its touch speed is where the interaction starts
    bounded: Parameter

    @property
    def scales(self) -> Scales:
        return self.law.scales

    @property
    def overflow(self):
        return self.curve.overflow


class AbstractCurveIntegrator(AbstractRidingIntegrator[CurveProblem, "_Args"]):
    """Impacts that ride the equilibrium curve of a curve law, phase by phase with an adaptive
    diffrax solver; a subclass states which curve (`scaled_curve`)."""

    # XLA:CPU compiles a while loop into one kernel while the bytes it touches stay under a
    # threshold (`impact._core.runtime.SMALL_LOOP_OPTION`), and op by op above it; the two round
    # differently. A curve ride's step crosses it between 32 and 60 lanes, so its batches stay
    # below it on CPU devices (16 lanes cost the same per impact as 512: `impact bench speed`).
    most_lanes: ClassVar[int | None] = 16

    @abc.abstractmethod
    def scaled_curve(
        self, law: AbstractCurveLaw, physics: Physics, options: Options, scales: Scales, reach: Reach
    ) -> tuple[CurveLaw, AbstractCurve]:
        """The law in the units of `scales` and the curve it rides, up to `reach`."""

    def build(self, physics: Physics, options: Options) -> CurveProblem:
        """Scale (JKR units, or the impact energy's where it reaches further) and tabulate."""
        law = physics.law
        assert isinstance(law, AbstractCurveLaw), f"a curve is ridden on a curve law, not {type(law).__name__}"
        speed = touch_velocity(physics, options)
        scales = law.scales(physics.profile, physics.E_star, physics.mass, speed)
        touch_speed = speed / scales.velocity
        scaled, curve = self.scaled_curve(
            law, physics, options, scales, functools.partial(top_of_reach, speed=touch_speed)
        )
        return CurveProblem(
            law=scaled,
            curve=curve,
            motion=motion_of(physics, options, scales, law.start_indentation(scaled, physics.gap, scales), touch_speed),
            bounded=jnp.asarray(True),
        )

    def flight(self, problem: CurveProblem, options: Options):
        # The interaction starts at the onset; the state snaps to the first rising one there
        # (the same for every bounce: found once, outside the loop over phases). A curve too
        # coarse for the law ends the run there.
        reach = problem.law.onset
        landing, segment, blocked = problem.curve.cascade(problem.law, True, jnp.zeros(()), reach)
        stops = blocked | ~problem.curve.resolves(problem.law)
        stop = Status.where(blocked, Status.radius_overflow, Status.unresolved_zone)
        touch = next_phase(ADVANCE, segment, landing, EVENT_CODE["touch"], stops=stops, stop=stop)
        landing_force = problem.curve.force(problem.law, landing)
        return lambda c: land(problem, options, c, reach, touch, landing_force, samples=True)

    def phase(self, problem: CurveProblem, options: Options, c: Carry) -> "_Args":
        law = problem.law
        curve = problem.curve.at(law, c.memory)
        advancing = c.mode == ADVANCE
        return _Args(
            law=law,
            curve=curve,
            motion=problem.motion,
            velocity_sign=jnp.where(advancing, -1.0, 1.0),
            end=jnp.where(advancing, curve.nodes[c.segment + 1], curve.nodes[c.segment]),
            segment=c.segment,
            end_sign=jnp.where(advancing, 1.0, -1.0),
            speed_scale=speed_scale(problem, c),
        )

    def vector_field(self, options: Options):
        return _vector_field

    def conditions(self, y, args: "_Args"):
        """Turnaround and segment end, each negative until its event, of relative size."""
        return [
            args.velocity_sign * y[1] / args.speed_scale,
            args.end_sign * (y[0] - args.end) / (1.0 + jnp.abs(args.end)),
        ]

    def end(self, problem: CurveProblem, options: Options, c: Carry, args: "_Args", ride: Ride) -> PhaseEnd:
        law, curve = problem.law, args.curve
        s_end, v_end, t_end = ride.y_end[0], ride.y_end[1], ride.y_end[2]
        s_end = jnp.clip(s_end, curve.nodes[c.segment], curve.nodes[c.segment + 1])
        d_end = curve.depth(law, s_end)
        rows = None
        if options.samples_per_phase:
            states = dense_states(ride.solution, options.samples_per_phase)
            s = jnp.clip(states[:, 0], curve.nodes[c.segment], curve.nodes[c.segment + 1])
            depth, force, radius, _ = curve.state(law, s)
            rows = jnp.stack([states[:, 2], depth, states[:, 1], force, radius], axis=1)
        work = _work(law, curve, c.radius, s_end)
        low, high = extremes(lambda s: curve.force(law, s), c.radius, s_end)
        advancing = c.mode == ADVANCE
        nxt, memory = after_ride(problem, curve, advancing, ride.turned, c.segment, s_end, d_end, c.memory)
        summary = ContactSummary(work=work, lowest_force=low, highest_force=high, deepest=jnp.maximum(c.d, d_end))
        return PhaseEnd(t=t_end, d=d_end, v=v_end, rows=rows, summary=summary, nxt=nxt, memory=memory)


class CurveIntegrator(AbstractCurveIntegrator):
    """The continuum law's equilibrium curve (Maugis–Dugdale, Greenwood–Johnson); with
    `hysteresis` (static) the path of a law with approach hysteresis (Δγa < Δγ)."""

    hysteresis: bool = eqx.field(default=False, static=True)

    def scaled_curve(
        self, law: AbstractCurveLaw, physics: Physics, options: Options, scales: Scales, reach: Reach
    ) -> tuple[CurveLaw, AbstractCurve]:
        scaled = law.scaled(physics.profile, physics.E_star, scales, self.hysteresis)
        return scaled, law.curve(scaled, reach, options.tabulation.max_turns)


class _Args(AbstractPhaseArgs):
    law: CurveLaw
    curve: AbstractCurve
    motion: Motion
    velocity_sign: Parameter  # turnaround: sign·v crosses zero upwards
    end: Parameter  # the segment end in s the phase runs to
    segment: Parameter  # the segment ridden
    end_sign: Parameter
    speed_scale: jax.Array


def _vector_field(pseudo_time, y, args: _Args):
    s, v = y[0], y[1]
    _, force, slope = args.curve.riding(args.law, s, args.segment)
    return branch_rates(v, force, slope, args.motion.gravity)


def _work(law: CurveLaw, curve: AbstractCurve, start, end):
    """∫F dd along the curve from s = start to end (Gauss–Legendre; smooth on a segment)."""
    nodes, weights = gauss_legendre(_QUADRATURE_NODES)
    points = start + (end - start) * nodes
    _, force, slope = curve.riding(law, points)
    return (end - start) * ordered_sum(weights * force * slope)


def after_ride(problem: CurveProblem, curve: AbstractCurve, advancing, turned, segment, s_end, d_end, memory):
    """The phase after a ride along `curve` ended (`Next.radius` holds s), and the memory of a
    curve that `remembers`: re-anchored where loading turns back, cleared where the body leaves."""
    law = problem.law
    # The cascade from the end of the segment the ride went to: loading its top, unloading its
    # foot (each value below is read only on its own side of `advancing`).
    top, foot = curve.nodes[segment + 1], curve.nodes[segment]
    cascade_s, cascade_segment, none_left = curve.cascade(law, advancing, jnp.where(advancing, top, foot), d_end)
    # Loading reaches its segment's top: on to the next rising state at this level.
    # A rising segment that goes on from this one's end (the junction) is no jump: the state
    # stays at the node, whatever an ulp of d finds on the flat start of the next one.
    out_segment, blocked = cascade_segment, none_left
    out_s = jnp.where(curve.nodes[out_segment] == top, top, cascade_s)
    jumped_out = out_s > top + _SAME_STATE * (1.0 + out_s)
    out_event = jnp.where(jumped_out, EVENT_CODE["snap_in"], EVENT_CODE["contact_start"])
    # Unloading reaches its segment's foot: back to the last rising state at this level (riding
    # on across a hysteretic path's switch: from the frozen zone onto the detach curve).
    in_segment, released = cascade_segment, none_left
    in_s = jnp.where(curve.nodes[in_segment + 1] == foot, foot, cascade_s)
    jumped_in = in_s < foot - _SAME_STATE * (1.0 + in_s)
    goes_on = jnp.where(
        curve.switches(foot),
        EVENT_CODE["detach_start"],
        jnp.where(curve.closes(foot), EVENT_CODE["contact_end"], EVENT_CODE["snap_out"]),
    )
    in_event = jnp.where(released, EVENT_CODE["separation"], jnp.where(jumped_in, EVENT_CODE["snap_out"], goes_on))
    mode = jnp.where(
        advancing,
        jnp.where(turned, RECEDE, jnp.where(blocked, DONE, ADVANCE)),
        jnp.where(turned, DONE, jnp.where(released, FLIGHT, RECEDE)),
    )
    turn_segment, turn_s = segment, s_end
    if curve.remembers:  # unloading starts on the frozen zone of the path anchored at the turn
        turned_curve, turned_memory, turn_s = curve.anchored(law, s_end, memory)
        turn_segment = turned_curve.holding(turn_s, False)
        memory = jnp.where(advancing & turned, turned_memory, jnp.where(~advancing & released, 0.0, memory))
    new_segment = jnp.where(
        advancing, jnp.where(turned, turn_segment, out_segment), jnp.where(turned, segment, in_segment)
    )
    new_s = jnp.where(turned, jnp.where(advancing, turn_s, s_end), jnp.where(advancing, out_s, in_s))
    event = jnp.where(
        advancing,
        jnp.where(turned, EVENT_CODE["max_indentation"], out_event),
        jnp.where(turned, EVENT_CODE["capture"], in_event),
    )
    nxt = Next(
        mode=mode,
        segment=new_segment,
        radius=new_s,
        event=event,
        separated=~advancing & ~turned & released,
        captured=~advancing & turned,
        stops=advancing & ~turned & blocked,
        stop=Status.radius_overflow,
    )
    return nxt, memory
