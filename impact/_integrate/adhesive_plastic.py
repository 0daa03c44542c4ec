"""Impacts of a paraboloid with Thornton & Ning's (1998) adhesive elastic–plastic contact
(`_law.adhesive_plastic`), on the reversible JKR law (jump-in at the touch).

An impact that never yields is the elastic adhesive impact: the `Continuum` integrator runs it
in the same units, with its phases ended from their energy (the elastic scene's default), and
its outcome is taken as it is (to the bit) unless its deepest indentation passes the yield
depth. Otherwise the impact is integrated again with the plastic law, riding
the contact radius â in a pseudo-time s as `continuum` does:

    â' = v·q,   v' = (g − F̂(â))·h'(â)·q,   t' = h'(â)·q,   q = 1/√(1 + h'²),

on the branch d̂ = h(â) of the phase: loading on the dent's elastic branch up to the onset of
flow (event `yield`), then on plastic loading to its turnaround (event `max_indentation`, where
the dent is fixed); unloading on the dent's branch down to its turning point (separation) or to
a turnaround (a capture: below the largest radius the branches conserve energy). The dent is
carried to the next contact, which starts with the jump-in at its depth.
"""

import jax
import jax.numpy as jnp

from .._core.pytree import replace, where
from .._law.adhesive_plastic import AdhesivePlasticLaw, DentState
from .._law.scales import Scales
from .._law.thornton import ThorntonNing
from .base import dense_states
from .carry import Carry, Outcome
from .codes import ADVANCE, EVENT_CODE
from .continuum import Continuum
from .flight import land
from .problem import AbstractClosedFormProblem, Motion, Options, Physics, Problem, build_problem
from .ride import AbstractPhaseArgs, AbstractRidingIntegrator, PhaseEnd, Ride, branch_rates, speed_scale
from .transitions import after_plastic_phase, next_phase
from .work import ContactSummary

# Plastic loading rides segment 1 of ADVANCE; the dent's elastic branch segment 0.
_ELASTIC, FLOWING = 0, 1


class AdhesivePlasticProblem(AbstractClosedFormProblem):
    """The elastic adhesive problem (`Continuum`) and the plastic law in its units."""

    elastic: Problem
    law: AdhesivePlasticLaw
    motion: Motion
    bounded: jax.Array

    @property
    def scales(self) -> Scales:
        return self.elastic.scales


class AdhesivePlastic(AbstractRidingIntegrator[AdhesivePlasticProblem, "_Args"]):
    """Impacts of an adhesive paraboloid with Thornton & Ning's limiting contact pressure."""

    def build(self, physics: Physics, options: Options) -> AdhesivePlasticProblem:
        """The elastic adhesive problem, and the plastic law in its units."""
        assert isinstance(physics.law, ThorntonNing), f"Thornton & Ning's law, not {type(physics.law).__name__}"
        elastic = build_problem(physics, options)
        law = physics.law.adhesive_law(physics.profile.radius_scale(), physics.E_star, elastic.scales)
        return AdhesivePlasticProblem(
            elastic=elastic,
            law=law,
            motion=elastic.motion,
            bounded=jnp.asarray(True),
        )

    def integrate(self, problem: AdhesivePlasticProblem, options: Options) -> Outcome:
        continuum = Continuum(
            method=self.method,
            rtol=self.rtol,
            atol=self.atol,
            max_steps=self.max_steps,
            adjoint=self.adjoint,
            phase_ends="energy",
        )
        elastic = continuum.integrate(problem.elastic, options)
        law = problem.law
        virgin = DentState.virgin(law.yield_radius)
        yielded = elastic.max_indentation > law.depth(law.yield_radius, virgin, False)
        return jax.lax.cond(yielded, lambda: super(AdhesivePlastic, self).integrate(problem, options), lambda: elastic)

    def memory(self, problem: AdhesivePlasticProblem) -> DentState:
        return DentState.virgin(problem.law.yield_radius)

    def flight(self, problem: AdhesivePlasticProblem, options: Options):
        law = problem.law

        def flight(c: Carry) -> Carry:
            state = c.memory
            radius = law.jump_in(state)
            touch = next_phase(ADVANCE, _ELASTIC, radius, EVENT_CODE["touch"])
            return land(problem, options, c, state.residual, touch, law.force(radius, state, False), samples=True)

        return flight

    def phase(self, problem: AdhesivePlasticProblem, options: Options, c: Carry) -> "_Args":
        law, state = problem.law, c.memory
        advancing = c.mode == ADVANCE
        flowing = advancing & (c.segment == FLOWING)
        return _Args(
            law=law,
            state=state,
            flowing=flowing,
            advancing=advancing,
            end=jnp.where(advancing, jnp.where(flowing, jnp.nan, state.onset), law.snap_off(state)),
            motion=problem.motion,
            speed_scale=speed_scale(problem, c),
        )

    def vector_field(self, options: Options):
        return _vector_field

    def conditions(self, y, args: "_Args"):
        """Turnaround and the end of the branch (the onset of flow outward, the snap-off inward):
        each negative until its event."""
        radius, v = y[0], y[1]
        sign = jnp.where(args.advancing, 1.0, -1.0)
        end = jnp.where(jnp.isnan(args.end), -1.0, sign * (radius - args.end) / (1.0 + args.end))
        return [-sign * v / args.speed_scale, end]

    def end(self, problem: AdhesivePlasticProblem, options: Options, c: Carry, args: "_Args", ride: Ride) -> PhaseEnd:
        law, state, flowing, advancing = problem.law, args.state, args.flowing, args.advancing
        a_end, v_end, t_end = ride.y_end[0], ride.y_end[1], ride.y_end[2]
        # A branch end lies on its radius to round-off: the next phase starts there.
        a_end = jnp.where(~ride.turned & ~ride.out_of_time & ~jnp.isnan(args.end), args.end, a_end)
        d_start, d_end = law.depth(jnp.stack([c.radius, a_end]), state, flowing)
        rows = None
        if options.samples_per_phase:
            a, v, t = dense_states(ride.solution, options.samples_per_phase).T
            a = jnp.maximum(a, 0.0)
            rows = jnp.stack([t, law.depth(a, state, flowing), v, law.force(a, state, flowing), a], axis=1)
        radii, depths = (c.radius, a_end), (d_start, d_end)
        summary, nxt, memory = dent_phase_outcome(law, state, flowing, advancing, ride.turned, radii, depths)
        return PhaseEnd(t=t_end, d=d_end, v=v_end, rows=rows, summary=summary, nxt=nxt, memory=memory)


class _Args(AbstractPhaseArgs):
    law: AdhesivePlasticLaw
    state: DentState
    flowing: jax.Array
    advancing: jax.Array
    end: jax.Array  # the radius ending the branch: the onset of flow, the snap-off; nan: none
    motion: Motion
    speed_scale: jax.Array


def _vector_field(s, y, args: _Args):
    radius, v = jnp.maximum(y[0], 1e-300), y[1]
    slope = args.law.slope(radius, args.state, args.flowing)
    force = args.law.force(radius, args.state, args.flowing)
    return branch_rates(v, force, slope, args.motion.gravity)


def dent_phase_outcome(law: AdhesivePlasticLaw, state: DentState, flowing, advancing, turned, radii, depths):
    """(what a contact phase of Thornton & Ning's law over the contact `radii` (start, end), at the
    `depths` (start, end), did, the phase after it, the dent after it): the ODE leaf's and the
    quadrature's booking of a phase."""
    (a_start, a_end), (d_start, d_end) = radii, depths
    lowest, highest = _force_range(law, state, flowing, a_start, a_end)
    summary = ContactSummary(
        work=law.work(a_start, a_end, state, flowing),
        lowest_force=lowest,
        highest_force=highest,
        deepest=jnp.maximum(d_start, d_end),
    )
    nxt = replace(after_plastic_phase(advancing, turned, flowing=FLOWING), radius=a_end)
    memory = where(advancing & turned, law.after_turn(a_end, state), state)
    return summary, nxt, memory


def _force_range(law: AdhesivePlasticLaw, state: DentState, flowing, start, end):
    """(least, largest) force while the radius moves between `start` and `end` (F̂ has one minimum)."""
    low, high = jnp.minimum(start, end), jnp.maximum(start, end)
    weakest = jnp.clip(law.weakest(state, flowing), low, high)
    forces = law.force(jnp.stack([start, end, weakest]), state, flowing)
    return jnp.min(forces), jnp.max(forces[:2])
