"""Oblique impacts on the spring array: the exact event stepper of the normal springs with the
tangential springs, the body's sliding and its spin stepped along each of its arcs.

The normal motion is the one of `springs.SpringArray`, event by event in closed form and
bitwise the same: friction does not act on it (Goodman's approximation, which the MDR makes;
exact for elastically similar bodies). Each arc between two spring events, on which the
indentation d(t) is harmonic (or ballistic) in closed form, is cut into n = ⌈τ/h⌉ equal steps
(h the largest step); the tangential springs (`tangential.TangentialMotion`) take them with the
indentation and the springs attached of the arc, so that every spring attaches and detaches at
a step's end. A spring attaches with no tangential displacement and detaches without it (with
per-spring friction its limit has fallen to 0 by then; under the whole-contact limit the energy
it held is lost and booked as friction work). The tangential error is that of the trapezoidal
rule, second order in h; the energy balance of the whole impact (normal and tangential kinetic
energy in = out + ∮F dd + friction work) holds to round-off at any h.

The trajectory holds seven columns: t, d, v, F, a (as every integrator's) and the tangential
force Q and the inner radius c of the slip zone, sampled at the end of every step (thinned
evenly where the steps outnumber the rows).
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.pytree import replace
from .._law.scales import Scales
from .._law.springs import Attached
from .._law.tangential import AbstractFrictionLimit, PerSpring, WholeContact
from .carry import Carry, Outcome, finish, initial_carry
from .codes import ADVANCE, DONE, FLIGHT
from .problem import Options, Physics
from .springs import AbstractSpringArrayIntegrator, ArrayCarry, SpringArrayProblem, _arc, _spring_event, touch_down
from .tangential import TangentialMotion, TangentialState
from .thinning import keep_row

# The friction limits: Coulomb spring by spring, or over the whole contact (Thornton's).
FRICTION_LIMITS = ("per_spring", "whole_contact")
# The largest tangential step where the scene gives none, in the impact's time unit √(m/(E*ℓx)).
DEFAULT_STEP = 1.0 / 1024.0
COLUMNS = 7  # t, d, v, F, a, Q, c


class TangentialOutcome(eqx.Module):
    """Scaled tangential results of the first contact (taken where it ended: separation or
    capture; nan where it never did)."""

    velocity: jax.Array  # v_t of the centre
    surface_speed: jax.Array  # Ω = Rω
    friction_work: jax.Array  # friction work of the first contact


class ObliqueProblem(eqx.Module):
    """The normal spring array and the tangential springs and motion (scaled)."""

    springs: SpringArrayProblem
    motion: TangentialMotion
    start: tuple[jax.Array, jax.Array]  # (v_t, Ω) at the start
    step: jax.Array  # the largest step h

    @property
    def scales(self) -> Scales:
        return self.springs.scales


class ObliqueSpringArray(AbstractSpringArrayIntegrator):
    """The spring array with tangential springs: `capacity` slots (static) hold N ≤ capacity
    springs' tangential displacements; `limit` is one of `FRICTION_LIMITS`."""

    capacity: int = eqx.field(default=64, static=True)
    limit: str = eqx.field(default="per_spring", static=True)

    def __check_init__(self):
        if self.limit not in FRICTION_LIMITS:
            raise ValueError(f"unknown friction limit {self.limit!r}; known: {', '.join(FRICTION_LIMITS)}")

    def build(self, physics: Physics, options: Options) -> ObliqueProblem:  # type: ignore[override]
        springs = super().build(physics, options)
        scales, friction, array = springs.scales, physics.friction, springs.array
        stiffness = 2.0 * friction.stiffness_ratio(physics.E_star) * array.spacing
        limit: AbstractFrictionLimit
        if self.limit == "per_spring":
            ratio = friction.coefficient / friction.stiffness_ratio(physics.E_star)
            limit = PerSpring(stiffness=stiffness, ratio=ratio)
        else:
            limit = WholeContact(
                stiffness=stiffness,
                coefficient=jnp.asarray(friction.coefficient),
                adhesive_load=jnp.asarray(friction.adhesive_load / scales.force),
            )
        index = jnp.arange(self.capacity)
        heights = jnp.where(index < array.count, array.law.g(array.position(index)), jnp.inf)
        motion = TangentialMotion(
            limit=limit, heights=heights, rotation=friction.rotation(physics.mass), spacing=array.spacing
        )
        step = friction.scaled_step(scales, DEFAULT_STEP)
        return ObliqueProblem(springs, motion, friction.scaled_start(scales), step)

    def integrate(self, problem: ObliqueProblem, options: Options) -> Outcome:
        return _run(problem, options)


class _State(eqx.Module):
    """State of the event loop: the normal springs' carry (with the threshold of the spring
    that changes next, as `springs.ArrayCarry`), the tangential state, the first contact's
    tangential results and the trajectory rows."""

    carry: Carry
    attached: Attached
    level: jax.Array
    tangential: TangentialState
    first: TangentialOutcome
    trajectory: jax.Array  # [T, COLUMNS]
    stored: jax.Array  # rows written
    stride: jax.Array  # steps between stored rows (doubles whenever the rows fill up)
    steps: jax.Array  # tangential steps taken


def arc_state(attached: Attached, spacing, gravity, d, v, tau):
    """(d, v) a time τ along the arc that starts at (d, v) with the springs `attached`:
    harmonic about d_eq with ω² = 2Δx·k, or with none attached a fall under `gravity`."""
    k = attached.count.astype(d.dtype)
    omega = jnp.sqrt(2.0 * spacing * jnp.maximum(k, 1.0))
    balance = (2.0 * spacing * attached.profile_sum() + gravity) / omega**2
    offset = d - balance
    cos, sin = jnp.cos(omega * tau), jnp.sin(omega * tau)
    harmonic = (balance + offset * cos + v / omega * sin, -offset * omega * sin + v * cos)
    free = (d + v * tau + 0.5 * gravity * tau**2, v + gravity * tau)
    none = attached.count == 0
    return jnp.where(none, free[0], harmonic[0]), jnp.where(none, free[1], harmonic[1])


def _store(s: _State, row, rows: int) -> _State:
    """The state with `row` kept among its trajectory rows (`keep_row`)."""
    if rows == 0:
        return s
    kept = keep_row(s.trajectory, s.stored, s.stride, s.steps, row)
    return replace(s, trajectory=kept.trajectory, stored=kept.stored, stride=kept.stride)


def _row(c_t, d, v, force, radius, tangential: TangentialState):
    return jnp.stack([c_t, d, v, force, radius, tangential.force, tangential.stick_radius])


def _arc_steps(problem: ObliqueProblem, s: _State, duration, end_d, rows: int) -> _State:
    """The tangential steps along the arc from the carry's state, `duration` long, ending at
    the indentation `end_d` (the event's own, so the last step ends exactly there)."""
    springs = problem.springs
    array, gravity = springs.array, springs.problem.motion.gravity
    c, attached = s.carry, s.attached
    mask = jnp.arange(problem.motion.heights.shape[0]) < attached.count
    count = jnp.where(duration > 0.0, jnp.ceil(duration / problem.step), 0.0).astype(int)
    h = duration / jnp.maximum(count, 1)
    radius = attached.count * array.spacing

    def running(state):
        return state[0] < count

    def one(state):
        j, s = state
        tau = (j + 1) * h
        d, v = arc_state(attached, array.spacing, gravity, c.d, c.v, tau)
        d = jnp.where(j + 1 == count, end_d, d)
        force = array.force(attached, d)
        tangential = problem.motion.step(s.tangential, h, d, mask, force)
        s = replace(s, tangential=tangential, steps=s.steps + 1)
        return j + 1, _store(s, _row(c.t + tau, d, v, force, radius, tangential), rows)

    return jax.lax.while_loop(running, one, (jnp.zeros((), int), s))[1]


def _event(problem: ObliqueProblem, s: _State, rows: int) -> _State:
    """The tangential steps along the arc to the next spring event, then the event itself
    (`springs._spring_event`, the normal motion exactly as the spring array's)."""
    springs = problem.springs
    array = springs.array
    c, attached = s.carry, s.attached
    inward = c.mode == ADVANCE
    beyond = attached.count >= array.count
    level = jnp.where(inward & beyond, array.beyond_level, s.level)
    duration, end_d, _, _ = _arc(attached, array.spacing, springs.problem.motion.gravity, c.d, c.v, level, inward)
    s = _arc_steps(problem, s, duration, end_d, rows)
    after = _spring_event(springs.problem, array, ArrayCarry(carry=c, attached=attached, level=s.level))
    mask = jnp.arange(problem.motion.heights.shape[0]) < after.attached.count
    tangential = problem.motion.detach(s.tangential, mask)
    new = after.carry
    ended = (new.contacts == 1) & ((new.mode == FLIGHT) | new.stuck)
    first = jax.tree.map(
        lambda now, kept: jnp.where(ended, now, kept),
        TangentialOutcome(tangential.velocity, tangential.surface_speed, tangential.work),
        s.first,
    )
    return replace(s, carry=new, attached=after.attached, level=after.level, tangential=tangential, first=first)


def _land(problem: ObliqueProblem, options: Options, s: _State, rows: int) -> _State:
    """Analytic flight to the next touch (`springs.touch_down`); a new contact starts with no
    friction work and nothing slipping."""
    landed = touch_down(problem.springs.problem, options, problem.springs.array, s.carry)
    c = landed.carry
    radius = landed.attached.count * problem.springs.array.spacing
    # No spring has slipped yet: the stick zone is the whole contact (of the jump-in).
    tangential = replace(s.tangential, work=jnp.where(c.mode == DONE, s.tangential.work, 0.0), stick_radius=radius)
    s = replace(s, carry=c, attached=landed.attached, level=landed.level, tangential=tangential)
    force = problem.springs.array.force(landed.attached, c.d)
    return _store(s, _row(c.t, c.d, c.v, force, radius, tangential), rows)


def _run(problem: ObliqueProblem, options: Options) -> Outcome:
    """Run one oblique impact (possibly several bounces) on the spring array."""
    array = problem.springs.array
    rows = options.samples_per_phase * options.max_phases
    max_events = options.max_bounces * (2 * array.count + 16) + 16

    def running(s: _State):
        return (s.carry.mode != DONE) & (s.carry.steps < max_events)

    def advance(s: _State) -> _State:
        return jax.lax.cond(
            s.carry.mode == FLIGHT, lambda s: _land(problem, options, s, rows), lambda s: _event(problem, s, rows), s
        )

    nan = jnp.asarray(jnp.nan)
    one = jnp.ones((), int)
    start = _State(
        carry=replace(initial_carry(problem.springs.problem, options), trajectory=jnp.zeros((0, 5))),
        attached=Attached.none(),
        level=nan,  # the first flight's touch computes the first threshold
        tangential=problem.motion.start(*problem.start),
        first=TangentialOutcome(nan, nan, nan),
        trajectory=jnp.full((rows, COLUMNS), jnp.nan),
        stored=0 * one,
        stride=one,
        steps=0 * one,
    )
    end = jax.lax.while_loop(running, advance, start)
    return replace(finish(end.carry), trajectory=end.trajectory, tangential=end.first)
