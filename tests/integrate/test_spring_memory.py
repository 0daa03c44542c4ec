"""The spring array keeps nothing of size N (issue #6, case 14): the same state and compiled
memory for N = 10 and N = 10⁶, one compilation for every N, and a running sum S_k that stays
within round-off of the exact sum over millions of attach and detach events."""

import functools
import math

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
import pytest

from impact import load_scene
from impact._integrate import springs
from impact._integrate.problem import build_problem
from impact._integrate.springs import SpringArrayProblem
from impact._law.springs import Attached
from impact._run.parameters import integrator_for, options_for, physics_for
from impact._run.programs import solve
from tests.scenes import HARD

COUNTS = (10, 1_000_000)


@pytest.fixture(scope="module")
def case():
    scene = load_scene(HARD / "14_springs_1e6.yaml")
    return physics_for(scene), (integrator_for(scene), options_for(scene, trajectory=False))


def test_array_and_contact_state_have_no_dimension_n(case):
    """The spring array (`ComputedSpringArray`) and `Attached`: the same scalar leaves for N = 10 and 10⁶."""
    physics, (_, options) = case

    def state(count):
        array = springs.build_array(build_problem(physics, options), count, physics.spring_length)
        return array, array.cascade(Attached.none(), 0.0, True)

    small, large = (jax.eval_shape(functools.partial(state, count)) for count in COUNTS)
    assert jax.tree.structure(small) == jax.tree.structure(large)
    for leaf_small, leaf_large in zip(jax.tree.leaves(small), jax.tree.leaves(large), strict=True):
        assert leaf_small.shape == leaf_large.shape == ()


def with_count(physics, count):
    return eqx.tree_at(lambda p: p.spring_count, physics, jnp.asarray(float(count)))


def test_compiled_memory_is_small_for_any_n(case):
    """`solve` compiled once (N traced, as scenes run) for N = 10 and N = 10⁶: its buffers are
    a few kB, the old arrays alone took 24 MB at N = 10⁶."""
    physics, numerics = case
    program = (
        jax.jit(lambda p: solve.__wrapped__(numerics[0], p, numerics[1]))
        .lower(with_count(physics, COUNTS[1]))
        .compile()
    )
    memory = program.memory_analysis()
    assert memory.temp_size_in_bytes + memory.argument_size_in_bytes + memory.output_size_in_bytes < 1 << 20
    for count in COUNTS:
        _, outcome = program(with_count(physics, count))
        assert int(outcome.status) == 0  # separated


@pytest.mark.slow
def test_one_compilation_serves_every_n(case):
    """`solve` with N traced gives the results of a program compiled for each N, from one
    compilation."""
    physics, (integrator, options) = case
    traced = jax.jit(lambda p: solve.__wrapped__(integrator, p, options))

    def static_count(p, n):
        problem = build_problem(p, options)
        return integrator.integrate(
            SpringArrayProblem(problem, springs.build_array(problem, n, p.spring_length)), options
        )

    for count in (10, 37, 300):
        static = jax.jit(lambda p, n=count: static_count(p, n))(physics)
        _, outcome = traced(with_count(physics, count))
        assert float(outcome.separation_velocity) == pytest.approx(
            float(static.separation_velocity), rel=1e-14, abs=0.0
        )
        assert int(outcome.steps) == int(static.steps)
    assert traced._cache_size() == 1


@pytest.mark.slow
def test_running_sum_stays_exact_over_millions_of_events(case):
    """S_k after sweeps up and down a 10⁶-spring array (3·10⁶ events) and a random walk of 10⁶
    events: within 4 ulps of S_k summed exactly (math.fsum of the same float64 terms).
    Measured: ≤ 1 ulp (relative error ≤ 1.6e-16); a plain running sum, like the cumulative sum
    of the former prefix array, is off by up to 2.8e-14."""
    physics, (_, options) = case
    count = COUNTS[1]
    array = springs.build_array(build_problem(physics, options), count, physics.spring_length)
    terms = np.asarray(jax.jit(lambda: array.law.g(array.position(jnp.arange(count))))())
    exact = np.array([0.0] + [math.fsum(terms[:k]) for k in (count // 2, count)])

    @jax.jit
    def sweeps(attached):
        out = [attached.profile_sum()]
        for target, inward in ((count, True), (count // 2, False), (count, True), (count // 2, False)):
            attached = jax.lax.while_loop(
                lambda a, target=target, inward=inward: jnp.where(inward, a.count < target, a.count > target),
                lambda a, inward=inward: array.change(a, inward),
                attached,
            )
            out.append(attached.profile_sum())
        return attached, jnp.stack(out)

    attached, sums = sweeps(Attached.none())
    expected = exact[[0, 2, 1, 2, 1]]
    assert int(attached.count) == count // 2
    assert np.all(np.abs(np.asarray(sums) - expected) <= 4 * np.spacing(expected)), np.asarray(sums) - expected

    steps = np.random.default_rng(6).choice([True, False], size=count)

    @jax.jit
    def walk(attached):
        def step(a, inward):
            inward = (inward | (a.count == 0)) & (a.count < count)
            return array.change(a, inward), None

        return jax.lax.scan(step, attached, jnp.asarray(steps))[0]

    attached = walk(attached)
    reference = math.fsum(terms[: int(attached.count)])
    assert abs(float(attached.profile_sum()) - reference) <= 4 * np.spacing(reference)
