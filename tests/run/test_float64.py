"""Every public entry point computes in float64 with JAX's 64-bit flag off (the default of a
fresh interpreter that never called `impact.configure()`), and leaves the flag as it found it."""

import math

import jax
import numpy as np
import pytest

import impact
from impact import theory
from tests.scenes import E_STAR, MASS, THORNTON_NING, WORK, R

SCENE = THORNTON_NING


@pytest.fixture(autouse=True)
def float32_process():
    """JAX's global flag off for each test of this module (the suite's conftest turns it on)."""
    jax.config.update("jax_enable_x64", False)
    yield
    assert jax.config.read("jax_enable_x64") is False, "an entry point changed the global flag"
    jax.config.update("jax_enable_x64", True)


def thornton_ning(velocity: float) -> float:
    """(3.50–51) in Python floats: W = (1 + ∛864)/10 · ∛(R⁴(πΔγ)⁵/E*²), e = √(1 − W/(½mv²))."""
    loss = math.cbrt(R**4 * (math.pi * WORK) ** 5 / E_STAR**2) * (1 + math.cbrt(864.0)) / 10
    return math.sqrt(1 - loss / (0.5 * MASS * velocity**2))


def test_closed_forms_answer_in_float64():
    e = theory.thornton_ning_restitution(0.6, MASS, R, E_STAR, WORK)
    assert e.dtype == np.float64
    assert float(e) == pytest.approx(thornton_ning(0.6), rel=1e-13, abs=0.0)


def test_simulate_answers_in_float64():
    scene = impact.load_scene(SCENE)
    result = impact.simulate(scene)
    assert result.status == "separated"
    assert result.restitution == pytest.approx(thornton_ning(scene.start.velocity), rel=1e-8, abs=0.0)


@pytest.mark.slow
def test_sweep_answers_in_float64():
    velocities = [0.5, 0.6]
    result = impact.sweep(SCENE, {"initial.velocity": velocities}, chunk=2)
    assert result.restitution.dtype == np.float64
    for velocity, e, e_theory in zip(velocities, result.restitution, result.theory_restitution, strict=True):
        assert e == pytest.approx(thornton_ning(velocity), rel=1e-8, abs=0.0)
        assert e_theory == pytest.approx(thornton_ning(velocity), rel=1e-13, abs=0.0)
