"""What a run will cost, estimated before it compiles, and the budgets it must stay within.

A scene can be valid field by field and still ask for a computation that would not end in a
lifetime (a Verlet step of 1e-30 s: 4e22 steps) or that needs more memory than the machine has
(an indentation on 10⁹ springs). The estimates, in the scene's own numbers:

- solver steps: each spring of an array attaches and detaches once a contact (about N events);
  a Verlet contact lasts about π time units of the scaled problem, in steps of `solver.dt`; an
  indentation's march on springs takes 2·N events a cycle. With gravity every bounce up to
  `limits.max_bounces` counts as a contact. The continuum law's solvers are bounded by
  `solver.max_steps` per phase and not estimated here.
- memory: an indentation on springs keeps its march's events, `INDENTATION_SPRING_BYTES` a
  spring and cycle;
- the points of a sweep (`SWEEP_POINTS`), and the memory of their parameters and results.

A scene beyond `limits.step_budget` (default `STEP_BUDGET`) or `MEMORY_BUDGET`, or a sweep beyond
`SWEEP_POINTS`, is refused when it is validated, naming the estimate and how to raise the budget;
`allow_long()` (the command line's `--allow-long`) lifts every budget but the machine's memory.
"""

import contextlib
import contextvars
import math
import os
from collections.abc import Iterator

from .errors import FieldProblem

STEP_BUDGET = 1e7  # solver steps of one run: seconds of stepping (user guide, "Long runs and Ctrl-C")
MEMORY_BUDGET = 4e9  # bytes of the arrays of one run or sweep
SWEEP_POINTS = 10**7  # points of one sweep
# Bytes an indentation on springs holds per spring and cycle (the user guide gives the measured
# figure).
INDENTATION_SPRING_BYTES = 3000.0
# Scaled time units a Verlet contact lasts (about π from just above v_s to a thousand times it).
_CONTACT_TIME_UNITS = math.pi
# Bytes a sweep holds per point: its parameters and some 30 results in float64, the values its
# check reads as Python floats.
SWEEP_POINT_BYTES = 600
ALLOW = "run with --allow-long (in Python: `with impact.allow_long():`)"

_allowed: contextvars.ContextVar[bool] = contextvars.ContextVar("allow_long", default=False)


@contextlib.contextmanager
def allow_long() -> Iterator[None]:
    """Within this context, scenes and sweeps beyond the budgets are accepted: a run's estimated
    solver steps (`limits.step_budget`, default 10⁷: a spring array's events, Verlet's steps), the
    memory of its arrays (4 GB) and a sweep's points (10⁷); only what exceeds the machine's memory
    is still refused. The command line's `--allow-long`:

        with impact.allow_long():
            result = impact.simulate("verlet.yaml")  # a scene file or mapping, read within
    """
    token = _allowed.set(True)
    try:
        yield
    finally:
        _allowed.reset(token)


def long_allowed() -> bool:
    """Whether the budgets are lifted (`allow_long`)."""
    return _allowed.get()


def physical_memory() -> float:
    """The machine's memory (bytes); inf where the system does not say."""
    try:
        return float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))
    except (ValueError, OSError, AttributeError):
        return math.inf


def check_memory(field: str, estimate: float, what: str, budget: float = MEMORY_BUDGET) -> None:
    """Refuse (FieldProblem on `field`) an estimated `estimate` bytes of arrays (`what` says of
    what) beyond `budget`, or beyond the machine's memory even where long runs are allowed."""
    memory = physical_memory()
    if estimate > memory:
        raise FieldProblem(
            field, f"{what} would need about {_bytes(estimate)}, more than this machine's {_bytes(memory)}"
        )
    if estimate > budget and not long_allowed():
        raise FieldProblem(
            field, f"{what} would need about {_bytes(estimate)}, beyond the budget of {_bytes(MEMORY_BUDGET)}: {ALLOW}"
        )


def check_run_cost(scene, time_unit: float | None) -> None:
    """Refuse a scene whose estimated solver steps exceed its budget (`limits.step_budget` of an
    impact) or whose arrays exceed the memory budget. `time_unit`: the scaled problem's (s), for
    a Verlet scene."""
    springs = scene.contact.springs
    if springs == "continuum":
        return
    if scene.kind == "indentation":
        cycles = scene.loading.cycles
        _check_steps("contact.springs", 2.0 * springs * cycles, STEP_BUDGET, f"{springs} springs × {cycles} cycle(s)")
        check_memory("contact.springs", INDENTATION_SPRING_BYTES * springs * cycles, "the march on springs")
        return
    contacts = scene.limits.max_bounces if scene.effects.gravity is not None else 1
    budget = scene.limits.step_budget
    if scene.solver.method == "verlet":
        assert time_unit is not None, "a Verlet scene's cost needs its time unit"
        dt, contact = scene.solver.dt, _CONTACT_TIME_UNITS * time_unit
        simulated = (
            contacts * contact if scene.limits.duration is None else min(contacts * contact, scene.limits.duration)
        )
        how = f"{simulated:.2g} s of contact in steps of {dt:g} s, and {springs} springs"
        _check_steps("solver.dt", simulated / dt + contacts * springs, budget, how)
    else:
        _check_steps("contact.springs", contacts * springs, budget, f"{springs} springs × {contacts} contact(s)")


def _check_steps(field: str, steps: float, budget: float, how: str) -> None:
    if steps > budget and not long_allowed():
        raise FieldProblem(
            field,
            f"the run would take about {steps:.2g} solver steps ({how}), beyond the budget of {budget:.3g} "
            f"(limits.step_budget): raise it, or {ALLOW}",
        )


def check_sweep_cost(points: int) -> None:
    """Refuse (FieldProblem on `axes`) a sweep of more points than `SWEEP_POINTS`, or whose
    parameters and results would not fit in memory; before any array of its points is made."""
    if points > SWEEP_POINTS and not long_allowed():
        raise FieldProblem(
            "axes", f"the sweep has {points:.3g} points, beyond the budget of {SWEEP_POINTS:.0e}: {ALLOW}"
        )
    check_memory("axes", float(points) * SWEEP_POINT_BYTES, f"the sweep's {points:.3g} points", math.inf)


def _bytes(count: float) -> str:
    """'3.2 GB', '512 MB'."""
    return f"{count / 1e9:.3g} GB" if count >= 1e9 else f"{count / 1e6:.3g} MB"
