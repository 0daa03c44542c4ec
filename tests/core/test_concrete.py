"""A run's concrete numbers reach JAX without a compiled program per operation: a scene's physics
and an indentation's loading are copied from NumPy (no program), a figure's profile curve and
a closed form are one program each, with the values that the operations give one by one."""

import contextlib
import logging
from collections.abc import Iterator

import jax
import numpy as np
import pytest

import impact
from impact import theory
from impact._core.concrete import evaluate, on_device
from impact._core.runtime import contracts_multiply_adds
from impact._effects.friction import Friction
from impact._plots.profile_curve import profile_along_radius
from impact._run.indentation import indentation_loading
from impact._run.parameters import concrete_physics, physics_for
from impact.profiles import Paraboloid
from impact.profiles._base import as_float
from tests.scenes import CONFIGS

_LOGGER = "jax._src.interpreters.pxla"  # where JAX logs "Compiling jit(...)" with jax_log_compiles


class _Names(logging.Handler):
    def __init__(self) -> None:
        super().__init__(logging.DEBUG)
        self.names: list[str] = []

    def emit(self, record: logging.LogRecord) -> None:
        message = record.getMessage()
        if message.startswith("Compiling "):
            self.names.append(message.split()[1])


@contextlib.contextmanager
def compiled() -> Iterator[list[str]]:
    """The programs compiled in the block (`jit(name)`, whether XLA compiled them or loaded them
    from the persistent cache), with JAX's in-memory caches cleared first (and the probe of
    fused multiply–adds that a compilation's options read run before)."""
    contracts_multiply_adds()
    jax.clear_caches()
    handler, logger = _Names(), logging.getLogger(_LOGGER)
    level = logger.level
    logger.addHandler(handler)
    logger.setLevel(logging.DEBUG)
    try:
        with jax.log_compiles(True):
            yield handler.names
    finally:
        logger.removeHandler(handler)
        logger.setLevel(level)


@pytest.mark.parametrize("config", ["thornton_ning", "oblique_kharaz", "plastic_steel", "rubber_ball_viscoelastic"])
def test_the_physics_of_a_run_compiles_nothing(config):
    scene = impact.load_scene(CONFIGS / f"{config}.yaml")
    with compiled() as names:
        physics = concrete_physics(scene)
    assert names == []
    leaves = jax.tree.leaves(physics)
    assert leaves and all(isinstance(leaf, jax.Array) and leaf.dtype in (np.float64, np.int64, bool) for leaf in leaves)
    in_numpy = jax.tree.leaves(physics_for(scene, np))
    assert all(np.array_equal(np.asarray(a), b, equal_nan=True) for a, b in zip(leaves, in_numpy, strict=True))


def test_the_loading_of_an_indentation_compiles_nothing():
    scene = impact.load_scene(CONFIGS / "indentation_paraboloid.yaml")
    with compiled() as names:
        loading = indentation_loading(scene)
    assert names == []
    assert loading.legs.weak_type and loading.legs.dtype == np.int64  # as jnp.asarray(int) made it
    assert loading.E_star.dtype == np.float64 and not loading.E_star.weak_type


def test_numbers_copied_into_jax_keep_their_types():
    with compiled() as names:
        zero, step = Friction.none().coefficient, Friction.none().time_step
        number, array = as_float(2.5), as_float(np.float32(0.5))
        copied = on_device({"a": np.arange(3), "b": np.float64(1.5), "c": None, "d": "text"})
    assert names == []
    assert zero.dtype == np.float64 and not zero.weak_type and float(zero) == 0.0
    assert step.weak_type and np.isnan(step)  # as jnp.asarray(jnp.nan) made it
    assert number.dtype == array.dtype == np.float64 and float(number) == 2.5 and float(array) == 0.5
    assert copied["a"].dtype == np.int64 and isinstance(copied["b"], jax.Array) and copied["c"] is None
    assert copied["d"] == "text"


def test_a_figure_s_profile_curve_is_one_program():
    profile = Paraboloid(R=1e-6)
    with compiled() as names:
        radius, g, G = profile_along_radius(profile, 2e-7, 400)
    assert names == ["jit(_sampled)"]
    assert radius[0] == 0.0 and radius[-1] == 2e-7 and len(radius) == 400
    np.testing.assert_allclose(g, radius**2 / 1e-6, rtol=1e-15)
    np.testing.assert_allclose(G, radius**3 / 3e-6, rtol=1e-15)


def test_a_closed_form_is_one_program_with_the_values_op_by_op():
    arguments = (3.0, 1e-12, 5e-6, 1e10, 1e8)
    with compiled() as names:
        once = evaluate(theory.thornton_max_indentation, *arguments)
    assert names == ["jit(thornton_max_indentation)"]
    np.testing.assert_allclose(float(once), float(theory.thornton_max_indentation(*arguments)), rtol=1e-15)
