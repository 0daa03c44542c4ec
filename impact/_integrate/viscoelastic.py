"""Impacts on a viscoelastic half-space: the spring array of `_law.viscoelastic_springs` stepped
at a fixed step (scene: `contact.springs: N`, `solver: {method: midpoint, dt: <s>}`).

Over a step of length h the body moves at the constant speed v½ (its indentation is linear in
time), so the springs are advanced exactly: each one's state, the times it attaches or lets go,
and the step's impulse I = ∫F dt, the work W = v½·I, the dashpots' dissipation and the energy of
the snaps come in closed form. The body follows the implicit midpoint rule

    v½ = (v + v')/2,   v' = v − I(v½)/m,   d' = d + h·v½,

solved by `ITERATIONS` fixed-point evaluations from v½ = v − h·F/(2m) (each contracts the error
by ≈ (ωh)²/4). Its kinetic energy changes by −v½·I: the work on the springs, exactly. So the
first contact's energy balance, ½m(v₀² − v²) = W = dissipation + stored energy + energy of the
snaps, holds to the iteration's residual, and the scheme is second order in h (jumps of the
force at snaps included: their impulse is integrated exactly along the step).

Free flight is analytic and starts the contact at d = 0 on a medium at rest: without gravity
(refused with viscoelasticity: between bounces the surface still creeps back, which an analytic
flight does not see) the body leaves for good after its first contact. A body that turns back
towards the surface while still attached is captured (the creep that follows is not simulated)
where it turns: a step that ends moving inward again is rejected and retaken with the length that
linear interpolation of v gives for v' = 0, so that, as in the elastic integrators, the first
contact's work closes at rest (up to ½m·v'², v' of that step second order in h) and the medium's
state is the turnaround's.
"""

from typing import Any, ClassVar

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.pytree import replace, where
from .._core.types import Parameter
from .._law.jkr import hess_coefficients
from .._law.law import ContactLaw
from .._law.reach import radius_bound
from .._law.scales import Scales, energy_scales
from .._law.viscoelastic import Viscoelastic
from .._law.viscoelastic_dugdale import DugdaleZoneArray
from .._law.viscoelastic_springs import SpringStates, StepTotals, ViscoelasticArray
from .base import AbstractIntegrator
from .carry import Carry, Outcome, finish, initial_carry, log_event, record_contact
from .codes import ADVANCE, DONE, EVENT_CODE, FLIGHT, RECEDE, Status
from .flight import land
from .problem import AbstractProblem, Motion, Options, Physics, motion_of, touch_velocity
from .thinning import keep_row
from .transitions import next_phase
from .work import ContactSummary

# Default array length: the body's extent, or this margin over the bound on the contact radius of
# the relaxed medium (E∞*: the softest, so the widest contact).
_LENGTH_MARGIN = 1.25


class ViscoelasticProblem(AbstractProblem):
    """The scaled impact on the spring array of a viscoelastic medium."""

    motion: Motion
    bounded: Parameter
    units: Scales
    array: ViscoelasticArray | DugdaleZoneArray
    step: Parameter  # h, scaled

    @property
    def scales(self) -> Scales:
        return self.units

    @property
    def overflow(self) -> jax.Array:
        return jnp.asarray(False)


class Relaxed(eqx.Module):
    """The medium when the run ends (scaled), and the first contact's snaps."""

    springs: SpringStates  # [capacity]: the first `count` are the array's
    spacing: jax.Array  # Δx
    count: jax.Array  # N
    released: jax.Array  # elastic energy released by the springs that let go in the first contact
    gained: jax.Array  # elastic energy gained by the springs that jumped onto the indenter in it


class ViscoelasticSprings(AbstractIntegrator[ViscoelasticProblem]):
    """N springs (`Physics.spring_count`, traced), each the medium's generalized Maxwell element,
    in `capacity` compiled slots, stepped at dt (s)."""

    capacity: int = eqx.field(static=True)  # slots of the compiled array (≥ N)
    dt: float  # step (s)
    max_steps: int = eqx.field(static=True, default=4096)  # steps a contact may take

    ITERATIONS: ClassVar[int] = 3  # evaluations of the springs per step (the implicit midpoint)

    def build(self, physics: Physics, options: Options) -> ViscoelasticProblem:
        assert not options.gravity, "validated: a viscoelastic impact has no gravity"
        law, profile, E_star = physics.law, physics.profile, physics.E_star
        assert isinstance(law, Viscoelastic), f"a viscoelastic array rides a Viscoelastic law, not {type(law).__name__}"
        speed = touch_velocity(physics, options)
        if options.adhesive:
            scales = law.scales(profile, E_star, physics.mass, speed)
            relaxed, relaxed_attach = hess_coefficients(
                law.work_of_adhesion, law.approach_work_of_adhesion, scales, E_star
            )
        else:
            scales = energy_scales(profile, E_star, physics.mass, speed)
            relaxed = relaxed_attach = jnp.zeros(())
        elastic = ContactLaw(profile, scales, relaxed, relaxed_attach, options.adhesive)
        touch_speed = speed / scales.velocity
        reach, bounded = radius_bound(elastic, relaxed_attach, touch_speed)
        # Beyond the bound on the contact, the room the law's adhesion needs outside it (a Dugdale zone).
        default = jnp.minimum(elastic.extent(), _LENGTH_MARGIN * reach) + law.zone_room(scales, E_star)
        length = jnp.where(jnp.isnan(physics.spring_length), default, physics.spring_length / scales.radial)
        count = physics.spring_count.astype(int)
        element = law.element(scales, E_star)
        array = law.spring_array(element, elastic.g, length, count, self.capacity, scales, E_star, options.adhesive)
        start = -physics.gap / scales.normal - law.adhesion_range(scales)  # where the tip comes within range
        return ViscoelasticProblem(
            motion=motion_of(physics, options, scales, start, touch_speed),
            bounded=bounded | jnp.isfinite(elastic.extent()),
            units=scales,
            array=array,
            step=jnp.asarray(self.dt, jnp.float64) / scales.time,
        )

    def integrate(self, problem: ViscoelasticProblem, options: Options) -> Outcome:
        return self.integrate_with_springs(problem, options)[0]

    def integrate_with_springs(self, problem: ViscoelasticProblem, options: Options) -> tuple[Outcome, Relaxed]:
        """The outcome and the medium when the run ends."""
        rows = options.samples_per_phase * options.max_phases
        terms = problem.array.element.moduli.shape[-1]
        zero = jnp.zeros(())
        start = _Walk(
            carry=initial_carry(problem, options),
            springs=problem.array.virgin(terms),
            force=zero,
            contact_steps=jnp.zeros((), int),
            released=zero,
            gained=zero,
            first=_FirstContact(stored=zero, released=zero, gained=zero),
            stored_rows=jnp.zeros((), int),
            stride=jnp.ones((), int),
            landing=jnp.asarray(False),
            length=jnp.asarray(problem.step),
        )

        def flight(walk: "_Walk") -> "_Walk":
            touch = next_phase(ADVANCE, 0, 0.0, EVENT_CODE["touch"])
            surface = problem.array.onset(walk.carry.d)
            c = land(problem, options, walk.carry, surface, touch, 0.0, samples=False)
            walk = replace(walk, carry=c, contact_steps=jnp.zeros((), int), released=zero, gained=zero)
            return _store(walk, problem.array, rows, c.mode == ADVANCE)

        def contact(walk: "_Walk") -> "_Walk":
            stepped = self._step(problem, walk)  # a rejected step leaves no row
            return _store(stepped, problem.array, rows, stepped.contact_steps > walk.contact_steps)

        def running(walk: "_Walk"):
            return walk.carry.mode != DONE

        def advance(walk: "_Walk") -> "_Walk":
            return jax.lax.cond(walk.carry.mode == FLIGHT, flight, contact, walk)

        end = jax.lax.while_loop(running, advance, start)
        outcome = replace(finish(end.carry), first_contact_stored_energy=end.first.stored)
        array = problem.array
        relaxed = Relaxed(
            array.springs_of(end.springs), array.spacing, array.count, end.first.released, end.first.gained
        )
        return outcome, relaxed

    def _step(self, problem: ViscoelasticProblem, walk: "_Walk") -> "_Walk":
        """One step of the implicit midpoint rule, with its events; a receding step that would
        end moving inward while attached is rejected, and retaken (`landing`) with the length that
        lands on v' = 0, where the body is captured."""
        c, array, h = walk.carry, problem.array, walk.length

        springs, totals, half = self._midpoint(problem, walk)
        v = c.v - totals.impulse
        d = c.d + h * half
        t = c.t + h
        force = array.force(springs)
        attached = array.engaged(springs)
        inward = c.mode == ADVANCE
        turned = inward & (v <= 0.0)
        separated = ~inward & ~attached
        returning = ~inward & attached & (v > 0.0)
        landing = returning & ~walk.landing  # retake this step to end where v = 0
        captured = ~inward & attached & (walk.landing | returning)
        overflow = array.overflows(springs)
        out_of_time = t > problem.motion.time_limit
        exhausted = walk.contact_steps + 1 >= self.max_steps
        # Where the body let go: the last spring's release inside the step (on the straight path).
        release = jnp.where(jnp.isfinite(totals.last_release), totals.last_release, h)
        end_time = jnp.where(separated, c.t + release, t)
        end_depth = jnp.where(separated, c.d + half * release, d)
        # Where v = 0 at a constant deceleration: the turn of loading, or a receding step's length
        # that lands where the body turns inward.
        turn = h * c.v / jnp.where(turned | landing, c.v - v, 1.0)
        deepest = jnp.where(turned, c.d + 0.5 * c.v * turn, jnp.maximum(c.d, d))
        c = log_event(c, c.t + turn, EVENT_CODE["max_indentation"], turned)
        c = log_event(c, end_time, EVENT_CODE["separation"], separated)
        c = log_event(c, t, EVENT_CODE["capture"], captured)
        stops = overflow | out_of_time | exhausted
        c = log_event(c, t, EVENT_CODE["limit"], (out_of_time | exhausted) & ~separated & ~captured)
        viscous = totals.dissipation
        summary = ContactSummary(
            work=half * totals.impulse - viscous,
            lowest_force=jnp.minimum(walk.force, force),
            highest_force=jnp.maximum(walk.force, force),
            deepest=deepest,
            viscous_work=viscous,
        )
        c = record_contact(c, (end_time, end_depth, v), summary, separated, captured)
        status = Status.where(
            overflow,
            Status.radius_overflow,
            Status.where(out_of_time, Status.time_limit, Status.where(exhausted, Status.solver_failure, c.status)),
        )
        status = Status.where(captured & ~stops, Status.captured, status)
        following = jnp.where(separated, FLIGHT, jnp.where(turned | ~inward, RECEDE, ADVANCE))
        phases = c.phases + jnp.asarray(separated | captured | turned, int)
        c = replace(c, mode=jnp.where(stops | captured, DONE, following), status=status, phases=phases)
        c = replace(c, steps=c.steps + 1, accepted=c.accepted + 1)
        released, gained = walk.released + totals.released, walk.gained + totals.gained
        now = _FirstContact(stored=array.stored(springs), released=released, gained=gained)
        ended = (c.contacts == 1) & (separated | captured)
        stepped = replace(
            walk,
            carry=c,
            springs=springs,
            force=force,
            contact_steps=walk.contact_steps + 1,
            released=released,
            gained=gained,
            first=where(ended, now, walk.first),
        )
        retake = replace(
            walk,
            carry=replace(walk.carry, steps=walk.carry.steps + 1, rejected=walk.carry.rejected + 1),
            landing=jnp.asarray(True),
            length=turn,
        )
        return where(landing, retake, stepped)

    def _midpoint(self, problem: ViscoelasticProblem, walk: "_Walk"):
        """The step's springs, totals and v½ = (v + v')/2 of the implicit midpoint rule: fixed-point
        evaluations from v½ = v − h·F/2 (scaled mass 1). The evaluations are the iterations of
        one loop, so that the array's step is compiled once."""
        c, array, h = walk.carry, problem.array, walk.length

        def evaluation(iteration, evaluated):
            half = evaluated[2]
            springs, totals = array.advance(walk.springs, c.d, half, h)
            corrected = jnp.where(iteration < self.ITERATIONS - 1, c.v - 0.5 * totals.impulse, half)
            return springs, totals, corrected

        start = c.v - 0.5 * h * walk.force
        zero = jnp.zeros_like(start)  # the first iteration overwrites the springs and the totals
        totals = StepTotals(impulse=zero, dissipation=zero, released=zero, gained=zero, last_release=zero)
        return jax.lax.fori_loop(0, self.ITERATIONS, evaluation, (walk.springs, totals, start))


class _FirstContact(eqx.Module):
    stored: jax.Array  # elastic energy the medium holds when the first contact ends
    released: jax.Array
    gained: jax.Array


class _Walk(eqx.Module):
    """State of the stepping loop."""

    carry: Carry
    springs: Any  # the array's state: SpringStates, or ZoneSprings of a zone array
    force: jax.Array  # F at the current state
    contact_steps: jax.Array
    released: jax.Array  # snaps of the contact under way
    gained: jax.Array
    first: _FirstContact
    stored_rows: jax.Array  # trajectory rows written
    stride: jax.Array  # steps between stored rows (doubles whenever the rows fill up)
    landing: jax.Array  # the step under way is the retaken one that ends where the body turns inward
    length: jax.Array  # the step's length (scaled): the fixed step, or the landing step's


def _store(walk: _Walk, array: ViscoelasticArray | DugdaleZoneArray, rows: int, valid) -> _Walk:
    """The walk with its state (t, d, v, F, a) kept among its trajectory rows (`keep_row`)."""
    if rows == 0:
        return walk
    c = walk.carry
    row = jnp.stack([c.t, c.d, c.v, walk.force, array.contact_radius(walk.springs)])
    kept = keep_row(c.trajectory, walk.stored_rows, walk.stride, walk.contact_steps, row, valid)
    carry = replace(c, trajectory=kept.trajectory)
    return replace(walk, carry=carry, stored_rows=kept.stored, stride=kept.stride)
