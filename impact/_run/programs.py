"""The program of one impact: scale, tabulate and integrate, traced once per machine.

`solve` is the jitted solve (traced in every process); `solve_by_field` runs it through the
programs kept across processes (`impact._core.stored`): a run whose program is in the cache skips
tracing it (about a second of Python) as well as compiling it.
"""

import equinox as eqx
import jax

from .._core.pytree import fields
from .._core.stored import call_stored
from .._integrate.base import AbstractIntegrator
from .._integrate.carry import Outcome
from .._integrate.problem import Options, Physics
from .._law.scales import Scales

Fields = dict[str, jax.Array]


@eqx.filter_jit
def solve(integrator: AbstractIntegrator, physics: Physics, options: Options) -> tuple[Scales, Outcome]:
    """Scale, tabulate and integrate one impact; returns (scales, scaled outcome)."""
    return integrator.solve(physics, options)


def solve_by_field(integrator: AbstractIntegrator, physics: Physics, options: Options) -> tuple[Fields, Fields]:
    """`solve`, with the scales and the outcome as {field name: array}; traced only where the
    cache holds no program of its key."""
    return call_stored(_solve_by_field, integrator, physics, options, once=True)


def _solve_by_field(integrator: AbstractIntegrator, physics: Physics, options: Options) -> tuple[Fields, Fields]:
    scales, outcome = integrator.solve(physics, options)
    found = fields(outcome)
    tangential = found.pop("tangential")  # an oblique impact's results, by field name
    if tangential is not None:
        found["tangential"] = fields(tangential)
    return fields(scales), found
