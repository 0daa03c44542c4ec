"""Thornton's elastic–perfectly plastic impacts without an ODE solve (`solver.method: quadrature`
with `effects.plasticity` and no adhesion).

Thornton's law is rate-independent: undamped, a body moves along a contact phase under a force
that depends on where it is only (the plastic state changes at a turnaround, between phases), so
its speed follows from the phase's energy balance v² = v₀² − 2∫F dd + 2g·(d − d₀) (unit mass,
scaled) with the work in closed form (`PlasticLaw.work`). The phases are the ODE leaf's
(`plastic.Plastic`): loading elastic up to the onset of flow, loading on the virgin curve to its
turnaround, unloading on the dent's elastic curve to separation at the dent or, under gravity,
to a turnaround (a capture). Each is a leg in x = √(d − d_p) (dd/dx = 2x: the force ∝ x³ of the
elastic curve is smooth from the dent), ended and timed as `quadrature.Leg` does: at its far end
where v² > 0 there, else at the first root of v²; t = ∫ 2x / |v(x)| dx by the graded rule. On the
virgin curve beyond the yield depth the force is linear in d, so the turnaround of plastic
loading is the root of a quadratic, in closed form.
"""

from typing import ClassVar

import jax.numpy as jnp

from .._core import derivatives
from .._core.pytree import replace, replace_where, where
from .._law.plastic import PlasticLaw, PlasticState
from .carry import Carry, close_phase, store_samples
from .codes import ADVANCE, DONE, Status
from .plastic import Plastic, PlasticProblem, plastic_phase_outcome
from .problem import Options
from .quadrature import Leg
from .ride import in_contact
from .transitions import Next
from .work import ContactSummary, squared_speed


class PlasticQuadrature(Plastic):
    """Thornton's impacts of a paraboloid, each contact phase ended by its energy balance and
    timed by Gauss–Legendre quadrature of dt = dd / v."""

    landed_contact: ClassVar[bool] = True

    def contact(self, problem: PlasticProblem, options: Options, c: Carry) -> Carry:
        """One contact phase: its end from the energy balance, its duration by quadrature; then the
        phase and plastic state that follow, as the ODE leaf books them."""
        law, state, gravity = problem.law, c.memory, problem.motion.gravity
        advancing = c.mode == ADVANCE
        onset = jnp.maximum(law.yield_depth, state.deepest)
        flowing = advancing & (c.d >= onset)  # loading resumed on the virgin curve at the onset
        start = (c.d, c.v)

        def depth(x):
            return state.residual + x**2

        def squared(x):  # v² at x from the phase's energy balance
            return squared_speed(start, law.work(depth(x), state) - law.work(c.d, state), gravity, depth(x))

        flow_turn = c.d + _flow_turnaround(law, c.d, c.v, gravity)
        far = jnp.where(advancing, jnp.where(flowing, flow_turn, onset), state.residual)
        direction = jnp.where(advancing, 1.0, -1.0)
        leg = Leg(_root(c.d - state.residual), _root(far - state.residual), squared, lambda x: 2.0 * x, direction)
        x_end, turned, settled = leg.end()
        # Plastic loading ends at its turnaround in closed form; elastic phases where the leg ends.
        x_end, turned, settled = jnp.where(flowing, leg.far, x_end), flowing | turned, flowing | settled
        duration, real = leg.time(x_end, turned)
        # Branch ends lie on the onset of flow, the turnaround of flow or the dent exactly.
        d_end = jnp.where(turned & ~flowing, depth(x_end), far)
        v_end = jnp.where(turned, 0.0, leg.direction * derivatives.sqrt(jnp.maximum(squared(x_end), 0.0)))
        t_end = c.t + duration

        rows = None
        if options.samples_per_phase:
            rows = _rows(law, state, leg, (x_end, turned, duration), options, c)
            end_row = jnp.stack([t_end, d_end, v_end, law.force(d_end, state), law.contact_radius(d_end, state)])
            rows = rows.at[-1].set(end_row)
        summary, nxt, memory = plastic_phase_outcome(law, state, advancing, turned, c.d, d_end)
        return book_leg(c, options, rows, (t_end, d_end, v_end), summary, nxt, memory, real & settled)


def book_leg(c: Carry, options: Options, rows, end, summary: ContactSummary, nxt: Next, memory, followed) -> Carry:
    """Book a contact phase timed by quadrature (kept only in contact): its trajectory `rows`
    ([samples, 5], None without samples), `end` = (t, d, v), what it did, the phase and the law's
    memory after it. A phase not `followed` (a speed not real at a node inside its leg, a
    turnaround whose search did not settle) ends the run with `solver_failure`."""
    active = in_contact(c)
    if rows is not None:
        c = where(active, store_samples(c, options, rows), c)
    steps = (jnp.zeros((), int),) * 3  # no solver: every end is found
    booked = close_phase(c, active, jnp.asarray(True), steps, end, nxt, jnp.asarray(False), summary)
    booked = replace(booked, memory=where(active, memory, c.memory))
    return replace_where(booked, active & ~followed, status=Status.solver_failure, mode=DONE)


def _root(excess):
    """x = √(d − d_p), 0 below the dent (no nan derivative there)."""
    return derivatives.sqrt(jnp.maximum(excess, 0.0))


def _flow_turnaround(law: PlasticLaw, d, v, gravity):
    """How far beyond d (past the yield depth) loading on the virgin curve goes at the speed v:
    the root Δ > 0 of v² − 2(F(d) − g)Δ − KΔ² (K = dF/dd = (3/2)k√d_y there), written without
    cancellation for either sign of F(d) − g."""
    slope = 1.5 * law.stiffness * jnp.sqrt(law.yield_depth)
    excess = law.virgin_force(d) - gravity
    root = jnp.sqrt(excess**2 + slope * v**2)
    return jnp.where(excess >= 0.0, v**2 / (excess + root), (root - excess) / slope)


def _rows(law: PlasticLaw, state: PlasticState, leg: Leg, end, options: Options, c: Carry):
    """Trajectory rows (t, d, v, F, a) of the leg to `end` = (x, turned, duration)."""
    x_end, turned, duration = end
    x, t, v = leg.samples(x_end, turned, jnp.linspace(0.0, 1.0, options.samples_per_phase), duration)
    d = state.residual + x**2
    return jnp.stack([c.t + t, d, v, law.force(d, state), law.contact_radius(d, state)], axis=1)
