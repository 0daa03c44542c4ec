"""Impacts of a paraboloid with Thornton's elastic–perfectly plastic contact (`_law.plastic`).

Each contact phase is integrated with an adaptive diffrax solver. The force grows as
(d − d_p)^(3/2) from the dent, which costs a solver in time its order at touch and separation;
so the state is x = √(d − d_p) (∝ the contact radius), with a pseudo-time s:

    x' = v·q,   v' = (g − F(x² + d_p))·2x·q,   t' = 2x·q,   q = 1/√(1 + 4x²),

smooth through x = 0 (as `continuum` rides the contact radius). Loading (elastic up to the
deepest indentation so far, then on the virgin curve) ends at its turnaround, where the plastic
state (d_max, R_p, d_p) is updated; unloading (elastic with R_p about the dent d_p) ends at
separation, x = 0, or — under gravity — at a turnaround, where the body can never leave again
(the elastic oscillation below d_max conserves energy): a capture. The state is carried to the
next contact, which starts at the dent d_p.
"""

import jax
import jax.numpy as jnp

from .._core.pytree import where
from .._core.types import Parameter
from .._law.base import AbstractPlasticLaw
from .._law.plastic import PlasticLaw, PlasticState
from .._law.scales import Scales
from .._law.thornton import plastic_law, plastic_scales
from .base import dense_states
from .carry import Carry
from .codes import ADVANCE, EVENT_CODE
from .flight import land
from .problem import AbstractClosedFormProblem, Motion, Options, Physics, motion_of, touch_velocity
from .ride import AbstractPhaseArgs, AbstractRidingIntegrator, PhaseEnd, Ride, speed_scale
from .transitions import after_plastic_phase, next_phase
from .work import ContactSummary


class PlasticProblem(AbstractClosedFormProblem):
    """The scaled impact: Thornton's law and the initial state."""

    law: PlasticLaw
    motion: Motion
    bounded: Parameter

    @property
    def scales(self) -> Scales:
        return self.law.scales


class Plastic(AbstractRidingIntegrator[PlasticProblem, "_Args"]):
    """Impacts of a paraboloid with Thornton's limiting contact pressure (no adhesion)."""

    def build(self, physics: Physics, options: Options) -> PlasticProblem:
        """Scale with the deepest indentation and the touch speed, and state Thornton's law."""
        law = physics.law
        assert isinstance(law, AbstractPlasticLaw), f"Thornton's law needs a yield pressure, not {type(law).__name__}"
        speed = touch_velocity(physics, options)
        radius = physics.profile.radius_scale()  # R: the scene takes paraboloids only
        scales = plastic_scales(law, radius, physics.E_star, physics.mass, speed)
        return PlasticProblem(
            law=plastic_law(law, radius, physics.E_star, scales),
            motion=motion_of(physics, options, scales, -physics.gap / scales.normal, speed / scales.velocity),
            bounded=jnp.asarray(True),
        )

    def memory(self, problem: PlasticProblem) -> PlasticState:
        return PlasticState.virgin()

    def flight(self, problem: PlasticProblem, options: Options):
        def flight(c: Carry) -> Carry:
            touch = next_phase(ADVANCE, 0, 0.0, EVENT_CODE["touch"])
            return land(problem, options, c, c.memory.residual, touch, jnp.zeros(()), samples=True)

        return flight

    def phase(self, problem: PlasticProblem, options: Options, c: Carry) -> "_Args":
        law, state = problem.law, c.memory
        onset = jnp.maximum(law.yield_depth, state.deepest)
        x_onset = jnp.sqrt(jnp.maximum(onset - state.residual, 0.0))
        return _Args(
            law=law,
            state=state,
            motion=problem.motion,
            advancing=c.mode == ADVANCE,
            onset=onset,
            flows=jnp.where(c.d < onset, x_onset, jnp.nan),
            speed_scale=speed_scale(problem, c),
        )

    def start(self, options: Options, args: "_Args", c: Carry) -> jax.Array:
        return jnp.stack([jnp.sqrt(jnp.maximum(c.d - args.state.residual, 0.0)), c.v, c.t])

    def vector_field(self, options: Options):
        return _vector_field

    def conditions(self, y, args: "_Args"):
        """Turnaround and the end of the branch (loading: the onset of flow, where the force's
        second derivative jumps; unloading: separation at x = 0): each negative until its event."""
        x, v = y[0], y[1]
        onset = jnp.where(jnp.isnan(args.flows), -1.0, (x - args.flows) / (1.0 + args.flows))
        return [jnp.where(args.advancing, -v, v) / args.speed_scale, jnp.where(args.advancing, onset, -x)]

    def end(self, problem: PlasticProblem, options: Options, c: Carry, args: "_Args", ride: Ride) -> PhaseEnd:
        law, state, advancing = problem.law, args.state, args.advancing
        x_end, v_end, t_end = ride.y_end[0], ride.y_end[1], ride.y_end[2]
        # Branch ends lie on the onset of flow or on the dent to round-off: the next phase starts there.
        on_branch_end = ~ride.turned & ~ride.out_of_time
        d_end = jnp.where(on_branch_end, jnp.where(advancing, args.onset, state.residual), _depth(x_end, state))
        rows = None
        if options.samples_per_phase:
            x, v, t = dense_states(ride.solution, options.samples_per_phase).T
            d = _depth(jnp.maximum(x, 0.0), state)
            rows = jnp.stack([t, d, v, law.force(d, state), law.contact_radius(d, state)], axis=1)
        summary, nxt, memory = plastic_phase_outcome(law, state, advancing, ride.turned, c.d, d_end)
        return PhaseEnd(t=t_end, d=d_end, v=v_end, rows=rows, summary=summary, nxt=nxt, memory=memory)


def plastic_phase_outcome(law: PlasticLaw, state: PlasticState, advancing, turned, d_start, d_end):
    """(what a contact phase of Thornton's law from `d_start` to `d_end` did, the phase after it,
    the plastic state after it): the ODE leaf's and the quadrature's booking of a phase."""
    forces = jnp.stack([law.force(d_start, state), law.force(d_end, state)])
    summary = ContactSummary(
        work=law.work(d_end, state) - law.work(d_start, state),
        lowest_force=jnp.min(forces),
        highest_force=jnp.max(forces),
        deepest=jnp.maximum(d_start, d_end),
    )
    memory = where(advancing, law.after_turn(d_end, state), state)
    return summary, after_plastic_phase(advancing, turned, flowing=0), memory


class _Args(AbstractPhaseArgs):
    law: PlasticLaw
    state: PlasticState
    motion: Motion
    advancing: Parameter
    onset: Parameter  # the depth where loading starts (or resumes) plastic flow
    flows: Parameter  # x where loading starts (or resumes) plastic flow; nan where it flows already
    speed_scale: jax.Array


def _depth(x, state: PlasticState):
    """d = d_p + x²."""
    return state.residual + x**2


def _vector_field(s, y, args: _Args):
    x, v = y[0], y[1]
    pace = 1.0 / jnp.sqrt(1.0 + 4.0 * x**2)
    slope = 2.0 * x * pace  # dt/ds
    force = args.law.force(_depth(x, args.state), args.state)
    return jnp.stack([v * pace, (args.motion.gravity - force) * slope, slope])
