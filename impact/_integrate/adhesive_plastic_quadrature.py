"""Thornton & Ning's adhesive elastic–plastic impacts without an ODE solve (`solver.method:
quadrature` with `effects.plasticity` and adhesion).

As the ODE leaf (`adhesive_plastic.AdhesivePlastic`) does, an impact that never yields is the
elastic adhesive impact, here by the continuum law's quadrature (`quadrature.Quadrature`), taken
as it is unless its deepest indentation passes the yield depth; otherwise the impact runs on the
plastic law. Each of its phases rides a branch d̂ = h(â) of the contact radius under a force that
depends on â only (`_law.adhesive_plastic`), so its speed follows from the energy balance
v² = v₀² − 2∫F dd + 2g·(d − d₀) with the work in closed form (`AdhesivePlasticLaw.work`), and it
is a `quadrature.Leg` in â (dd/dâ = h'(â)): loading on the dent's branch to the onset of flow,
plastic loading to its turnaround, unloading to the snap-off (separation) or to a turnaround (a
capture). Plastic loading has no end of its own: its turnaround is bracketed on a geometric
ladder of radii from its start before the leg is ended and timed.
"""

from typing import ClassVar

import jax
import jax.numpy as jnp

from .._core import derivatives
from .._law.adhesive_plastic import DentState
from .adhesive_plastic import FLOWING, AdhesivePlastic, AdhesivePlasticProblem, dent_phase_outcome
from .carry import Carry, Outcome
from .codes import ADVANCE
from .plastic_quadrature import book_leg
from .problem import Options
from .quadrature import Leg, Quadrature
from .work import squared_speed

# Radii tried for the turnaround of plastic loading: its start times _LADDER_STEP^k, k = 1 …
# _LADDER_RUNGS (up to 2^24 times the start); the first where v² ≤ 0 ends its leg.
_LADDER_STEP = 2.0**0.5
_LADDER_RUNGS = 48


class AdhesivePlasticQuadrature(AdhesivePlastic):
    """Thornton & Ning's impacts of an adhesive paraboloid, each contact phase ended by its energy
    balance and timed by Gauss–Legendre quadrature of dt = dd / v."""

    landed_contact: ClassVar[bool] = True

    def integrate(self, problem: AdhesivePlasticProblem, options: Options) -> Outcome:
        elastic = Quadrature().integrate(problem.elastic, options)
        law = problem.law
        virgin = DentState.virgin(law.yield_radius)
        yielded = elastic.max_indentation > law.depth(law.yield_radius, virgin, False)
        return jax.lax.cond(yielded, lambda: super(AdhesivePlastic, self).integrate(problem, options), lambda: elastic)

    def contact(self, problem: AdhesivePlasticProblem, options: Options, c: Carry) -> Carry:
        """One contact phase: its end from the energy balance, its duration by quadrature; then the
        phase and dent that follow, as the ODE leaf books them."""
        law, state, gravity = problem.law, c.memory, problem.motion.gravity
        advancing = c.mode == ADVANCE
        flowing = advancing & (c.segment == FLOWING)
        start = (c.d, c.v)

        def squared(a):  # v² at the radius a from the phase's energy balance
            work = law.work(c.radius, a, state, flowing)
            return squared_speed(start, work, gravity, law.depth(a, state, flowing))

        rungs = c.radius * _LADDER_STEP ** jnp.arange(1, _LADDER_RUNGS + 1)
        past = squared(rungs) <= 0.0
        turnaround_bound = jnp.where(jnp.any(past), rungs[jnp.argmax(past)], rungs[-1])
        far = jnp.where(advancing, jnp.where(flowing, turnaround_bound, state.onset), law.snap_off(state))
        direction = jnp.where(advancing, 1.0, -1.0)
        leg = Leg(c.radius, far, squared, lambda a: jnp.abs(law.slope(a, state, flowing)), direction)
        a_end, turned, settled = leg.end()
        # Plastic loading that no rung turns goes on past every rung: not followed.
        settled = settled & ~(flowing & ~turned)
        duration, real = leg.time(a_end, turned)
        d_end = law.depth(a_end, state, flowing)
        v_end = jnp.where(turned, 0.0, direction * derivatives.sqrt(jnp.maximum(squared(a_end), 0.0)))
        t_end = c.t + duration

        rows = None
        if options.samples_per_phase:
            theta = jnp.linspace(0.0, 1.0, options.samples_per_phase)
            a, t, v = leg.samples(a_end, turned, theta, duration)
            rows = jnp.stack([c.t + t, law.depth(a, state, flowing), v, law.force(a, state, flowing), a], axis=1)
            end_row = jnp.stack([t_end, d_end, v_end, law.force(a_end, state, flowing), a_end])
            rows = rows.at[-1].set(end_row)
        radii, depths = (c.radius, a_end), (c.d, d_end)
        summary, nxt, memory = dent_phase_outcome(law, state, flowing, advancing, turned, radii, depths)
        return book_leg(c, options, rows, (t_end, d_end, v_end), summary, nxt, memory, real & settled)
