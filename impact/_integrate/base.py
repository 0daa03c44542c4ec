"""The integrator interface: every way of stepping an impact builds a scaled problem from the
physics and integrates it, phase by phase, to an `Outcome`.

An integrator is an `equinox.Module` whose fields are its settings (solver, tolerances, step).
Its string and integer settings are static; its float settings are static too when given as
Python floats (a new value recompiles) and traced when given as arrays (a benchmark sweeps them).

diffrax and optimistix are imported where a ride is traced, not with this module: a run whose
program comes from the compilation cache (`impact._run.programs`) never loads them.
"""

import abc
from typing import TYPE_CHECKING, ClassVar, Generic, TypeVar

import equinox as eqx
import jax
import jax.numpy as jnp

from .._law.scales import Scales
from .carry import Outcome
from .problem import AbstractProblem, Options, Physics

if TYPE_CHECKING:
    import diffrax as dfx

# The diffrax solvers a scene may name for the adaptive integrators: scene name → diffrax class.
SOLVERS = {
    "tsit5": "Tsit5",
    "dopri5": "Dopri5",
    "dopri8": "Dopri8",
    "bosh3": "Bosh3",
    "heun": "Heun",
    "kvaerno3": "Kvaerno3",
    "kvaerno5": "Kvaerno5",
}

# Where a contact phase's end state comes from (`impact._integrate.continuum`): the solver's
# dense output at the located event, or the phase's energy balance.
PHASE_ENDS = ("integrated", "energy")

# How a ride is differentiated: diffrax's default (reverse mode through checkpoints), or
# forward mode (`jax.jvp`, `jax.jacfwd`); each fails under the other kind of derivative.
ADJOINTS = {"checkpoint": "RecursiveCheckpointAdjoint", "forward": "ForwardMode"}

# Events are located inside the step that crossed (`rootfind.BracketIllinois`), to a bracket of
# 1e-14 relative (+1e-15 absolute) in pseudo-time: a few ulps.
_ROOT_RTOL, _ROOT_ATOL = 1e-14, 1e-15

# A Runge–Kutta step loops over its stages in a plain `lax.while_loop` (diffrax's default is a
# checkpointed loop, there for reverse-mode derivatives). Reverse mode never runs through a ride
# (the phase loop around it is a `lax.while_loop`; `impact.as_function` differentiates in
# forward mode), and XLA compiles both to the same optimized program, but the checkpointed loop
# takes much longer to trace.
_STAGE_LOOP = "lax"

# A contact phase lasts O(1) in scaled time; this horizon only stops a runaway solve. It is a
# constant of the program (a Python float): diffrax rounds a step that ends within 100 ulps of
# the horizon to it, and XLA then folds the chain of 100 `nextafter`s that computes that bound.
PHASE_HORIZON = 1.0e4
# Where the ride of a lane that is not in contact ends (its result is discarded): at once.
_IDLE_HORIZON = 1e-9

# A ride's state is padded with zeros to a multiple of this many components, so that a point's
# result does not depend on its batch. A Runge–Kutta step sums its stages with the tableau's
# constant weights; under vmap that sum is one matrix–vector product over every lane's
# components, which XLA:CPU computes in tiles of 4 rows, with fused multiply–adds where the
# process has them (`impact._core.runtime.NO_FMA_FLAG`), and the rows left over one at a time
# without: with 3 components, the last lane of a batch of 7 rounded differently from the same
# point in a batch of 8.
_STATE_TILE = 4


ProblemT = TypeVar("ProblemT", bound=AbstractProblem)


class AbstractIntegrator(eqx.Module, Generic[ProblemT]):
    """Integrates one impact (possibly several bounces) from SI parameters to scaled results."""

    # Lanes a compiled batch of this integrator runs at most per CPU device (None: any number):
    # a sweep splits its chunks into calls of at most this many points. XLA:CPU only: a GPU
    # runs each lane as a thread of the same code whatever the batch.
    most_lanes: ClassVar[int | None] = None

    @abc.abstractmethod
    def build(self, physics: Physics, options: Options) -> ProblemT:
        """The scaled problem."""

    @abc.abstractmethod
    def integrate(self, problem: ProblemT, options: Options) -> Outcome:
        """Run the problem to its outcome, in its scaled units."""

    def solve(self, physics: Physics, options: Options) -> tuple[Scales, Outcome]:
        """Scale, tabulate and integrate: (the units, the scaled outcome)."""
        problem = self.build(physics, options)
        return problem.scales, self.integrate(problem, options)


class AbstractAdaptiveIntegrator(AbstractIntegrator[ProblemT]):
    """An adaptive diffrax solver over contact phases, each ended by a located event."""

    method: str = eqx.field(default="tsit5", static=True)  # a key of SOLVERS
    rtol: float | jax.Array = 1e-10
    atol: float | jax.Array = 1e-12  # in scaled units
    max_steps: int = eqx.field(default=4096, static=True)  # per phase
    adjoint: str = eqx.field(default="checkpoint", static=True)  # a key of ADJOINTS

    def __check_init__(self):
        if self.method not in SOLVERS:
            raise ValueError(f"unknown solver {self.method!r}; known: {', '.join(SOLVERS)}")
        if self.adjoint not in ADJOINTS:
            raise ValueError(f"unknown adjoint {self.adjoint!r}; known: {', '.join(ADJOINTS)}")

    def ride(self, vector_field, first_event, y0, args, active, dense: bool) -> "dfx.Solution":
        """Integrate one phase from pseudo-time 0 until `first_event(t, y, args)` crosses zero
        upwards (located by the Illinois method to a few ulps) or `PHASE_HORIZON` is reached;
        where not `active` (a lane of a batch in another phase: its result is discarded), until
        the pseudo-time `_IDLE_HORIZON`, at once.

        The state is integrated padded with zeros (`_STATE_TILE`); the solution's `ys` are
        not, its dense output is (`dense_states` strips it)."""
        import diffrax as dfx
        import optimistix as optx

        from .rootfind import BracketIllinois

        size = y0.shape[0]
        padding = jnp.zeros(-size % _STATE_TILE)

        def padded_field(t, y, args):
            return jnp.concatenate([vector_field(t, y[:size], args), padding])

        def event(t, y, args, **kwargs):
            return jnp.where(active, first_event(t, y[:size], args, **kwargs), t - _IDLE_HORIZON)

        def norm(error):  # the padding's zero error left out: the steps of the unpadded state
            return optx.rms_norm(error[:size])

        solution = dfx.diffeqsolve(
            dfx.ODETerm(padded_field),
            getattr(dfx, SOLVERS[self.method])(scan_kind=_STAGE_LOOP),
            t0=0.0,
            t1=PHASE_HORIZON,
            dt0=None,
            y0=jnp.concatenate([y0, padding]),
            args=args,
            saveat=dfx.SaveAt(t1=True, dense=dense),
            stepsize_controller=dfx.PIDController(rtol=self.rtol, atol=self.atol, norm=norm),
            event=dfx.Event(event, root_finder=BracketIllinois(rtol=_ROOT_RTOL, atol=_ROOT_ATOL), direction=True),
            max_steps=self.max_steps,
            adjoint=getattr(dfx, ADJOINTS[self.adjoint])(),
            throw=False,
        )
        assert solution.ys is not None, "a ride saves its end state (SaveAt(t1=True))"
        return eqx.tree_at(lambda s: s.ys, solution, solution.ys[..., :size])


def located_end(solution: "dfx.Solution", conditions, args):
    """Where a ride ended: (event found, state y at the end, turned, out of time).

    `conditions(y, args)` lists the ride's event conditions in the order (turnaround, end of the
    segment, time limit), each negative until its event; the largest at the end is the one that
    fired. A located turnaround has v = y[1] = 0 exactly: round-off of either sign would make the
    next phase's combined condition start positive and mask its other events.
    """
    import diffrax as dfx

    assert solution.ys is not None, "a ride saves its end state (SaveAt(t1=True))"
    event_found = solution.result == dfx.RESULTS.event_occurred
    y_end = solution.ys[-1]
    fired = jnp.argmax(conditions(y_end, args))
    turned, out_of_time = fired == 0, fired == 2
    y_end = y_end.at[1].set(jnp.where(event_found & turned, 0.0, y_end[1]))
    return event_found, y_end, turned, out_of_time


def ride_steps(solution: "dfx.Solution"):
    """The ride's (steps, accepted, rejected): what `carry.close_phase` books of its solver."""
    stats = solution.stats
    return stats["num_steps"], stats["num_accepted_steps"], stats["num_rejected_steps"]


def dense_states(solution: "dfx.Solution", samples: int):
    """The ride's state at `samples` evenly spaced pseudo-times ([samples, 3])."""
    assert solution.ts is not None, "a ride saves its end time (SaveAt(t1=True))"
    assert solution.ys is not None
    pseudo = jnp.linspace(0.0, solution.ts[-1], samples)
    return jax.vmap(solution.evaluate)(pseudo)[:, : solution.ys.shape[-1]]
