"""The Prony element of one spring: its exact step against an ODE solver, its energy identity,
its limits, the series and closed forms of its integrals, and the free spring's retardation."""

import jax
import jax.numpy as jnp
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from impact._law import prony
from impact._law.prony import PronyElement

MODULI = np.array([3.0, 0.5])  # e_i = E_i/E∞
TIMES = np.array([0.7, 20.0])  # τ_i (scaled)
START = np.array([0.3, -0.2])  # q_i
DISPLACEMENT, RATE, STEP = 0.1, -0.8, 1.3


@pytest.fixture(scope="module")
def element():
    with jax.enable_x64(True):
        yield PronyElement(jnp.asarray(MODULI), jnp.asarray(TIMES))


def solved(rhs, start):
    return solve_ivp(rhs, (0.0, STEP), start, method="DOP853", rtol=1e-13, atol=1e-15).y[:, -1]


def test_loaded_step_is_the_exact_solution(element):
    """q̇_i = r − q_i/τ_i with u = u0 + r·s: the stretches, ∫f ds and the dissipation to 1e-13."""
    with jax.enable_x64(True):
        loaded = element.loaded(jnp.asarray(DISPLACEMENT), jnp.asarray(START), jnp.asarray(RATE), jnp.asarray(STEP))

    def rhs(s, y):
        q = y[:2]
        force = DISPLACEMENT + RATE * s + MODULI @ q
        return np.concatenate([RATE - q / TIMES, [force, np.sum(MODULI / TIMES * q**2)]])

    reference = solved(rhs, np.concatenate([START, [0.0, 0.0]]))
    assert np.asarray(loaded.stretches) == pytest.approx(reference[:2], abs=1e-13)
    assert float(loaded.force_integral) == pytest.approx(reference[2], rel=1e-13, abs=0.0)
    assert float(loaded.dissipation) == pytest.approx(reference[3], rel=1e-13, abs=0.0)
    # the energy identity: the work r·∫f ds = change of ½u² + ½Σe_i q_i² + dissipation
    with jax.enable_x64(True):
        change = element.stored(DISPLACEMENT + RATE * STEP, loaded.stretches) - element.stored(DISPLACEMENT, START)
    assert float(RATE * loaded.force_integral - loaded.dissipation - change) == pytest.approx(0.0, abs=1e-15)


def test_free_spring_creeps_back_exactly(element):
    """f = 0: q̇ = A·q, A = 1·cᵀ/e₀ − diag(1/τ); its force stays 0 and the energy it loses is
    its dissipation (to 1e-15)."""
    with jax.enable_x64(True):
        stretches, dissipation = element.free(jnp.asarray(START), jnp.asarray(STEP))
        surface, slope = element.free_surface(jnp.asarray(START), jnp.asarray(STEP))
        displacement = element.free_displacement(stretches)
        lost = element.stored(element.free_displacement(jnp.asarray(START)), START) - element.stored(
            displacement, stretches
        )
        force = element.force(displacement, stretches)
    creep = np.outer(np.ones(2), MODULI / TIMES) / (1 + MODULI.sum()) - np.diag(1 / TIMES)

    def rhs(s, y):
        return np.concatenate([creep @ y[:2], [np.sum(MODULI / TIMES * y[:2] ** 2)]])

    reference = solved(rhs, np.concatenate([START, [0.0]]))
    assert np.asarray(stretches) == pytest.approx(reference[:2], abs=1e-13)
    assert float(dissipation) == pytest.approx(reference[2], rel=1e-12, abs=0.0)
    assert float(surface) == pytest.approx(float(displacement), rel=1e-14, abs=0.0)
    assert float(slope) == pytest.approx(-(MODULI @ (creep @ reference[:2])), rel=1e-12, abs=0.0)
    assert float(force) == pytest.approx(0.0, abs=1e-15)
    assert float(lost - dissipation) == pytest.approx(0.0, abs=1e-15)


def test_standard_linear_solid_retards_with_its_creep_time():
    """One term: the free spring creeps back as e^(−t/τ_r), τ_r = τ·E₀/E∞ (to 1e-14)."""
    with jax.enable_x64(True):
        element = PronyElement(jnp.asarray([4.0]), jnp.asarray([0.5]))
        assert float(element.rates[0]) == pytest.approx(-1.0 / (0.5 * 5.0), rel=1e-14, abs=0.0)


@pytest.mark.parametrize(
    ("time", "stretch", "integral", "dissipation"),
    [
        (1e12, 1.0 - 0.5e-12, 1.5, 2.0 / 3e12),  # glassy: q = u − h²/(2τ), the arm stores, barely dissipating
        (1e-25, 0.0, 0.5, 0.25),  # relaxed: q₀ = ½ relaxes at once (e·q₀²/2) and q stays 0
    ],
)
def test_limits_of_the_relaxation_time(time, stretch, integral, dissipation):
    """e = 2, a unit step at rate 1 from u = 0: τ → ∞ gives f = e₀·u (∫f ds = 3/2, the
    dissipation e·h³/(3τ)); τ → 0 gives f = u (∫f = 1/2) after releasing e·q₀²/2: no digit lost
    to cancellation at either end."""
    with jax.enable_x64(True):
        element = PronyElement(jnp.asarray([2.0]), jnp.asarray([time]))
        start = 0.0 if time > 1 else 0.5
        loaded = element.loaded(jnp.asarray(0.0), jnp.asarray([start]), jnp.asarray(1.0), jnp.asarray(1.0))
    assert float(loaded.stretches[0]) == pytest.approx(stretch, abs=1e-15)
    assert float(loaded.force_integral) == pytest.approx(integral, rel=1e-12, abs=0.0)
    assert float(loaded.dissipation) == pytest.approx(dissipation, rel=1e-10, abs=0.0)


def test_phi_functions_join_their_series():
    """φ₁, K, J₁, J₂ by series below z = ¼ and in closed form above agree across the switch (to
    1e-14) and meet their values at 0 (1, ½, ½, ⅓)."""
    with jax.enable_x64(True):
        below = prony._phi_family(jnp.asarray(np.nextafter(0.25, 0.0)))
        above = prony._phi_family(jnp.asarray(0.25))
        zero = prony._phi_family(jnp.asarray(0.0))
        assert float(prony.phi1(jnp.asarray(1e-300))) == 1.0
    for one, two in zip(below, above, strict=True):
        assert float(one) == pytest.approx(float(two), rel=1e-14, abs=0.0)
    assert [float(value) for value in zero] == pytest.approx([1.0, 0.5, 0.5, 1.0 / 3.0], rel=1e-15, abs=0.0)
