"""A program that runs once per run (a scene's solve, an indentation test's march) compiles at
XLA:CPU's backend optimization level 0 (`runtime.RUN_ONCE`, issue #42 item 5: a first run's
latency is mostly compiling), a sweep's batch at the default level; both give the same bits."""

import jax
import numpy as np
import pytest

from impact._core.pytree import fields
from impact._core.runtime import RUN_ONCE, compiler_options
from impact._run import programs
from impact._run.parameters import integrator_for, options_for, physics_for


def test_a_configured_process_compiles_what_runs_once_quickly_and_a_batch_as_usual():
    assert compiler_options(once=True) == RUN_ONCE == {"xla_backend_optimization_level": 0}
    assert compiler_options() == {}  # a sweep's batch, a fit's programs


@pytest.mark.slow
def test_a_scene_solved_once_gives_the_bits_of_the_default_level(thornton_ning_scene):
    """Every field of the scaled outcome and of the scales (the trajectory included) equals the one
    the solve compiled at the default level gives, to the bit."""
    integrator, physics = integrator_for(thornton_ning_scene), physics_for(thornton_ning_scene)
    options = options_for(thornton_ning_scene, trajectory=True)
    quick_scales, quick = programs.solve_by_field(integrator, physics, options)
    scales, outcome = programs.solve(integrator, physics, options)
    default = fields(outcome)
    default.pop("tangential")
    quick.pop("tangential", None)
    for name, (mine, theirs) in {"scales": (quick_scales, fields(scales)), "outcome": (quick, default)}.items():
        assert mine.keys() == theirs.keys(), name
        for key in theirs:
            pairs = zip(jax.tree.leaves(mine[key]), jax.tree.leaves(theirs[key]), strict=True)
            assert all(np.array_equal(np.asarray(a), np.asarray(b), equal_nan=True) for a, b in pairs), (name, key)
