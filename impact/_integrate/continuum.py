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

With damping (`impact._effects.damping`) the viscous force F_v = (η_a·a + η_0)·v of the springs
in contact adds to F, and a fourth state integrates its work, w' = F_v·v·t'. Without adhesion the
contact then ends where the total force returns to zero while unloading (the body leaves faster
than the surface recovers; Schwager & Pöschel, Phys. Rev. E 78, 051304 (2008)); with adhesion
the rule of Heß still decides detachment from the elastic state.

With `phase_ends="energy"` (undamped only) the end of a phase along a branch (ridden in a, or
timed in d from a steep tip) or held comes from the energy balance of the phase,
½v² = ½v₀² − ∫F dd + g·(d − d₀) (the work in closed form or by quadrature: `work.branch_work`,
`work.hold_work`), instead of from the solver's dense output at the located event: at a segment
end or the end of a hold the speed, at a turnaround the radius (Newton on v² = 0). The
restitution and the deepest indentation are then exact to round-off at any tolerance; the times
still come from the solver. With the located ends (`phase_ends="integrated"`) an undamped phase's
speed is checked against that balance: where they disagree by more than the phase's kinetic
energies (`work.drifts`) the run ends with the status `energy_drift`, not a number. A ride that
starts off its edge function (d ≠ h(a): a jump of the radius that landed where the law does not
hold) ends the run with the status `off_branch`.
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.pytree import replace, replace_where, where
from . import transitions
from .base import PHASE_ENDS, dense_states
from .carry import Carry
from .codes import DONE, EVENT_CODE, FLIGHT, HOLD, Status
from .continuum_args import PhaseArgs, phase_args, timed_radius, total_force, viscous_force
from .energy_end import energy_end
from .flight import land_on_touch
from .problem import Options, Physics, Problem, build_problem
from .ride import AbstractRidingIntegrator, PhaseEnd, Ride, branch_rates, in_contact
from .transitions import Next
from .work import ContactSummary, drifts, extremes, phase_summary

# A damped phase that ends without an event (max_steps, or the horizon) at a speed below this
# fraction of the phase's speed scale creeps towards rest (overdamped): a named outcome, not a
# solver failure. Such a creep is stiff: tsit5 uses up max_steps near 1e-4 of the touch speed,
# an implicit method (kvaerno5) gets to rest.
_CREEP = 1e-3


class Continuum(AbstractRidingIntegrator[Problem, "PhaseArgs"]):
    """The continuum MDR law (N → ∞ springs), phase by phase with an adaptive diffrax solver."""

    phase_ends: str = eqx.field(default="integrated", static=True)  # a key of PHASE_ENDS

    def __check_init__(self):
        if self.phase_ends not in PHASE_ENDS:
            raise ValueError(f"unknown phase_ends {self.phase_ends!r}; known: {', '.join(PHASE_ENDS)}")

    def build(self, physics: Physics, options: Options) -> Problem:
        return build_problem(physics, options)

    def flight(self, problem: Problem, options: Options):
        return lambda c: land_on_touch(problem, options, c)

    def phase(self, problem: Problem, options: Options, c: Carry) -> "PhaseArgs":
        return phase_args(problem, options, c)

    def start(self, options: Options, args: "PhaseArgs", c: Carry) -> jax.Array:
        damped = [jnp.zeros(())] if options.damped else []
        return jnp.stack([jnp.where(args.riding, c.radius, c.d), c.v, c.t, *damped])

    def vector_field(self, options: Options):
        return _make_vector_field(options.damped)

    def conditions(self, y, args: "PhaseArgs"):
        return _conditions(y, args)

    def dense(self, options: Options) -> bool:
        return options.samples_per_phase > 0 or options.damped

    def end(self, problem: Problem, options: Options, c: Carry, args: "PhaseArgs", ride: Ride) -> PhaseEnd:
        return _end(self, problem, options, c, args, ride)

    def amend(
        self, problem: Problem, options: Options, c: Carry, args: "PhaseArgs", ride: Ride, end: PhaseEnd, booked: Carry
    ) -> Carry:
        return _amend(self, problem, options, c, args, ride, end, booked)


def _make_vector_field(damped: bool):
    def vector_field(s, y, args: PhaseArgs):
        x, v = y[0], y[1]
        law, branch = args.law, args.branch
        radius = jnp.maximum(x, 0.0)  # a stage may step a hair past a = 0
        slope = law.edge_slope(radius, branch.coefficient)
        force = law.force(radius, branch.level(law, radius))
        held_radius = timed_radius(x, args)
        held = law.force(held_radius, x)
        if not damped:
            riding = branch_rates(v, force, slope, args.motion.gravity)
            timed = jnp.stack([v, args.motion.gravity - held, jnp.ones_like(v)])
            return jnp.where(args.riding, riding, timed)
        pace = 1.0 / jnp.sqrt(1.0 + slope**2)
        viscous = viscous_force(radius, v, args)
        held_viscous = viscous_force(held_radius, v, args)
        riding = jnp.stack(
            [v * pace, (args.motion.gravity - force - viscous) * slope * pace, slope * pace, viscous * v * slope * pace]
        )
        timed = jnp.stack([v, args.motion.gravity - held - held_viscous, jnp.ones_like(v), held_viscous * v])
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


def _conditions(y, args: PhaseArgs) -> list[jax.Array]:
    """The law's event conditions of a phase, each negative until its event and of relative
    size: turnaround (sign·v), phase end and, damped, the release (−F)."""
    conditions = [args.velocity_sign * y[1] / args.speed_scale, _distance_to_end(y, args)]
    if y.shape[0] > 3:
        conditions.append(jnp.where(args.releases, -total_force(y, args), -1.0))
    return conditions


def _end(integrator: Continuum, problem: Problem, options: Options, c: Carry, args: PhaseArgs, ride: Ride) -> PhaseEnd:
    """Where the ride ended on the law: from the located event or, with the energy's ends, from
    the phase's energy balance; its samples, summary and the phase after it."""
    law = problem.law
    riding, branch = args.riding, args.branch
    x_end, v_end, t_end = ride.y_end[0], ride.y_end[1], ride.y_end[2]
    turned = ride.turned
    # A located event may overshoot the segment end by round-off: the radius stays on it.
    x_end = jnp.where(riding, jnp.clip(x_end, branch.nodes[c.segment], branch.nodes[c.segment + 1]), x_end)
    if integrator.phase_ends == "energy":
        x_end, v_end, turned = energy_end(problem, args, c, (x_end, v_end), ride.found & ~ride.out_of_time, turned)
    d_end = jnp.where(riding, branch.level(law, x_end), x_end)
    a_end = jnp.where(riding, x_end, timed_radius(x_end, args))

    rows = None
    if options.samples_per_phase:
        states = dense_states(ride.solution, options.samples_per_phase)
        x, v, t = states[:, 0], states[:, 1], states[:, 2]
        radii = jnp.where(riding, x, jax.vmap(lambda d: timed_radius(d, args))(x))
        d = jnp.where(riding, branch.level(law, x), x)
        rows = jnp.stack([t, d, v, law.force(radii, d) + viscous_force(radii, v, args), radii], axis=1)
        # The last sample is the phase's end as the next phase starts from it (with the energy's
        # ends its depth and speed come from the balance, not from the dense output).
        end_force = law.force(a_end, d_end) + viscous_force(a_end, v_end, args)
        rows = rows.at[-1].set(jnp.stack([t_end, d_end, v_end, end_force, a_end]))

    summary = phase_summary(
        law, branch, c.mode != HOLD, (c.radius, a_end), problem.motion.gravity, (c.d, c.v), (d_end, v_end)
    )
    nxt = transitions.after_phase(problem, c.mode, c.segment, a_end, d_end, turned)
    if options.damped:
        released = jnp.argmax(integrator.all_conditions(ride.y_end, args)) == 3
        summary, nxt = _damped(problem, ride.solution, args, summary, nxt, ride.y_end, d_end, released)
    return PhaseEnd(t=t_end, d=d_end, v=v_end, rows=rows, summary=summary, nxt=nxt, memory=c.memory)


def _amend(
    integrator: Continuum,
    problem: Problem,
    options: Options,
    c: Carry,
    args: PhaseArgs,
    ride: Ride,
    end: PhaseEnd,
    booked: Carry,
) -> Carry:
    """The statuses the law detects in a booked phase: a speed off its energy balance (located
    ends), an overdamped creep, a ride that started off its edge function."""
    active = in_contact(c)
    if not options.damped:
        if integrator.phase_ends == "integrated":
            off_balance = drifts(
                (c.d, c.v), (end.d, end.v), end.summary.work, problem.motion.gravity, problem.motion.touch_speed
            )
            drifted = active & ride.found & ~ride.out_of_time & off_balance
            booked = replace_where(booked, drifted, status=Status.energy_drift, mode=DONE)
    else:
        # A phase that found no event while the body all but stopped: overdamped creep towards rest.
        creeping = active & ~ride.found & (jnp.abs(end.v) <= _CREEP * args.speed_scale)
        booked = replace_where(booked, creeping, status=Status.overdamped)
    off_branch = active & args.riding & args.branch.misses(problem.law, c.radius, c.d)
    return replace_where(booked, off_branch, status=Status.off_branch, mode=DONE)


def _damped(problem: Problem, solution, args: PhaseArgs, summary: ContactSummary, nxt: Next, y_end, d_end, released):
    """What damping changes at a phase's end: its viscous work, the range of the total force
    (scanned along the dense solution) and, where the total force returned to zero (`released`:
    the release event fired), the release.

    Under gravity a body released at depth d with v² < 2g·d turns before it clears the
    undeformed surface: it cannot leave, and is counted as captured.
    """
    lowest, highest = extremes(
        jnp.vectorize(lambda s: total_force(solution.evaluate(s), args)), jnp.zeros(()), solution.ts[-1]
    )
    summary = replace(
        summary,
        viscous_work=y_end[3],
        lowest_force=jnp.minimum(lowest, summary.lowest_force),
        highest_force=jnp.maximum(highest, summary.highest_force),
    )
    leaves = y_end[1] ** 2 >= 2.0 * problem.motion.gravity * d_end
    release = where(
        leaves, transitions.next_phase(FLIGHT, 0, 0.0, EVENT_CODE["separation"], separated=True), transitions.capture()
    )
    return summary, where(released, release, nxt)
