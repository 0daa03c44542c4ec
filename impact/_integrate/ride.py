"""The contact phase of every adaptive integrator, written once: a ride with diffrax from the
carry's state to the phase's first located event, the trajectory samples, what the phase did and
what comes next, booked in the carry.

A riding integrator (`AbstractRidingIntegrator`) supplies what differs between laws, as
diffrax's Runge–Kutta solvers supply their tableaux to one stepping loop: how the body flies to
the contact, the ride's arguments and start state, its vector field and event conditions, what
its end means (`PhaseEnd`) and what the law amends in the booked carry (statuses it detects,
memory it keeps). The phase loop around it is `carry.run_phases`.
"""

import abc
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, ClassVar, Generic, TypeVar

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.pytree import replace, where
from .base import AbstractAdaptiveIntegrator, ProblemT, located_end, ride_steps
from .carry import Carry, Outcome, close_phase, run_phases, store_samples
from .codes import ADVANCE, HOLD, RECEDE
from .problem import AbstractProblem, Motion, Options
from .transitions import Next
from .work import ContactSummary

if TYPE_CHECKING:
    import diffrax as dfx


class AbstractPhaseArgs(eqx.Module):
    """What every ride's vector field and conditions read besides the law's own arguments."""

    motion: eqx.AbstractVar[Motion]  # the body's motion (gravity, time limit)
    speed_scale: eqx.AbstractVar[jax.Array]  # 1 + the speeds of the phase's start and of the touch


Args = TypeVar("Args", bound=AbstractPhaseArgs)


def speed_scale(problem: AbstractProblem, c: Carry) -> jax.Array:
    """The speed a phase's turnaround condition is relative to: 1 + |v| at its start + the touch speed."""
    return 1.0 + jnp.abs(c.v) + problem.motion.touch_speed


def branch_rates(v, force, slope, gravity) -> jax.Array:
    """(a', v', t') of a ride along a branch d = h(a) in the pseudo-time s, with h' = `slope`:
    a' = v·q, v' = (g − F)·h'·q, t' = h'·q, q = 1/√(1 + h'²) (`continuum`)."""
    pace = 1.0 / jnp.sqrt(1.0 + slope**2)
    return jnp.stack([v * pace, (gravity - force) * slope * pace, slope * pace])


class Ride(eqx.Module):
    """A finished ride: diffrax's solution and where it ended (`base.located_end`)."""

    solution: "dfx.Solution"
    found: jax.Array  # it ended at its event (else the solver failed)
    y_end: jax.Array  # the state at its end
    turned: jax.Array  # the event was the turnaround
    out_of_time: jax.Array  # the event was the time limit


class PhaseEnd(eqx.Module):
    """What a contact phase comes to: the state (t, d, v) the next phase starts from, the
    trajectory rows of the ride ([samples, 5]: t, d, v, F, a), what it did, the phase after it
    and the law's memory after it."""

    t: jax.Array
    d: jax.Array
    v: jax.Array
    rows: jax.Array | None
    summary: ContactSummary
    nxt: Next
    memory: Any


def in_contact(c: Carry) -> jax.Array:
    """Whether the carry's phase is a contact phase (loading, hold or unloading)."""
    return (c.mode == ADVANCE) | (c.mode == HOLD) | (c.mode == RECEDE)


class AbstractRidingIntegrator(AbstractAdaptiveIntegrator[ProblemT], Generic[ProblemT, Args]):
    """An adaptive diffrax solver over the contact phases of a law, each a ride ended by its
    located event (`contact`); a subclass supplies the law's part."""

    # Whether the phase loop runs a flight, the contact it lands in and the flight that contact
    # ends in as one turn (`run_phases`): for contact phases that take no diffrax ride.
    landed_contact: ClassVar[bool] = False

    @abc.abstractmethod
    def flight(self, problem: ProblemT, options: Options) -> Callable[[Carry], Carry]:
        """The flight from the carry's state to the next contact (`flight.land`), built once
        outside the phase loop."""

    @abc.abstractmethod
    def phase(self, problem: ProblemT, options: Options, c: Carry) -> Args:
        """The ride's arguments for the phase starting from the carry."""

    def start(self, options: Options, args: Args, c: Carry) -> jax.Array:
        """The ride's initial state: by default (radius, v, t), the branch ridden in the carry's
        radius (or the curve's parameter)."""
        return jnp.stack([c.radius, c.v, c.t])

    @abc.abstractmethod
    def vector_field(self, options: Options) -> Callable[[Any, jax.Array, Args], jax.Array]:
        """The ride's vector field f(s, y, args) in its (pseudo-)time s."""

    @abc.abstractmethod
    def conditions(self, y: jax.Array, args: Args) -> list[jax.Array]:
        """The law's event conditions of the ride, [turnaround, end of the segment, …], each
        negative until its event and of relative size (`all_conditions` adds the time limit)."""

    def all_conditions(self, y: jax.Array, args: Args) -> jax.Array:
        """Every event condition of the ride in the order (turnaround, end of the segment, time
        limit, …) of `base.located_end`: the law's, and the time limit (t − t_max)."""
        turnaround, end, *others = self.conditions(y, args)
        time_limit = (y[2] - args.motion.time_limit) / (1.0 + jnp.abs(y[2]))
        return jnp.stack([turnaround, end, time_limit, *others])

    @abc.abstractmethod
    def end(self, problem: ProblemT, options: Options, c: Carry, args: Args, ride: Ride) -> PhaseEnd:
        """What the ride came to."""

    def amend(
        self, problem: ProblemT, options: Options, c: Carry, args: Args, ride: Ride, end: PhaseEnd, booked: Carry
    ) -> Carry:
        """The booked carry with what the law detects on top (a status that ends the run); as
        booked by default."""
        return booked

    def memory(self, problem: ProblemT) -> Any:
        """The law's memory before the first contact (None: a law without one)."""
        return None

    def dense(self, options: Options) -> bool:
        """Whether the ride keeps its dense output (for trajectory samples)."""
        return options.samples_per_phase > 0

    def integrate(self, problem: ProblemT, options: Options) -> Outcome:
        return run_phases(
            problem,
            options,
            self.flight(problem, options),
            lambda c: self.contact(problem, options, c),
            memory=self.memory(problem),
            landed_contact=self.landed_contact,
        )

    def contact(self, problem: ProblemT, options: Options, c: Carry) -> Carry:
        """One contact phase: a ride with diffrax to its located event, booked in the carry."""
        active = in_contact(c)
        args = self.phase(problem, options, c)

        def first_event(t, y, args, **kwargs):  # crosses zero upwards when the first condition does
            return jnp.max(self.all_conditions(y, args))

        solution = self.ride(
            self.vector_field(options),
            first_event,
            self.start(options, args, c),
            args,
            active=active,
            dense=self.dense(options),
        )
        found, y_end, turned, out_of_time = located_end(solution, self.all_conditions, args)
        ride = Ride(solution=solution, found=found, y_end=y_end, turned=turned, out_of_time=out_of_time)
        end = self.end(problem, options, c, args, ride)
        if end.rows is not None:
            c = where(active, store_samples(c, options, end.rows), c)
        booked = close_phase(
            c, active, found, ride_steps(solution), (end.t, end.d, end.v), end.nxt, out_of_time, end.summary
        )
        booked = replace(booked, memory=where(active, end.memory, c.memory))
        return self.amend(problem, options, c, args, ride, end, booked)
