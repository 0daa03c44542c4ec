"""`simulate` for an indentation test of a viscoelastic half-space: its program at a rate, on the
spring array (`impact._integrate.viscoelastic_indentation`), results in SI with the time of every
point (`IndentationResult.time`)."""

from types import SimpleNamespace

import jax.numpy as jnp

from .._core.pytree import fields
from .._core.stored import call_stored
from .._integrate.viscoelastic_indentation import RateLoading, RateNumerics, march_at_rate
from .._scene.scene import Scene
from .._scene.springs import spring_capacity
from .indentation import IndentationResult, indentation_loading, to_indentation_result


def rate_numerics(scene: Scene) -> RateNumerics:
    """The static choices of the test (validated: a spring array)."""
    springs = scene.contact.springs
    assert isinstance(springs, int), "validated: a viscoelastic half-space runs on a spring array"
    return RateNumerics(
        adhesive=scene.adhesive,
        capacity=spring_capacity(springs),
        force_control=scene.control == "force",
        cycles=scene.loading.cycles,
    )


def rate_loading(scene: Scene) -> RateLoading:
    """The traced SI parameters of the test."""
    program = scene.loading
    assert program.rate is not None, "validated: a viscoelastic test has a rate"
    return RateLoading(
        loading=indentation_loading(scene),
        rate=jnp.asarray(program.rate, jnp.float64),
        hold=jnp.asarray(program.hold, jnp.float64),
    )


def simulate_rate_test(scene: Scene, numerics: RateNumerics | None = None) -> IndentationResult:
    """Run the viscoelastic indentation scene (its program traced once per machine and
    structure) with its own static choices, or `numerics` (e.g. a larger capacity, shared)."""
    numerics = rate_numerics(scene) if numerics is None else numerics
    scales, outcome = call_stored(_march_by_field, rate_loading(scene), numerics, once=True)
    return to_indentation_result(scene, SimpleNamespace(**scales), SimpleNamespace(**outcome))


def _march_by_field(program: RateLoading, numerics: RateNumerics) -> tuple[dict, dict]:
    scales, outcome = march_at_rate(program, numerics)
    return fields(scales), fields(outcome)
