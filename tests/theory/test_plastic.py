"""Thornton's (1997) closed forms against the energy balance of his law, solved independently."""

import math

import numpy as np
import pytest

from impact import theory

R, E_STAR, P_Y, DENSITY = 5e-3, 115e9, 1e9, 7850.0
MASS = DENSITY * 4 / 3 * math.pi * R**3


def by_energy(velocity: float) -> tuple[float, float]:
    """(e, δ_max) from ½mv₀² = ∫F dd on loading (numerical quadrature, depth by bisection) and the elastic
    unloading energy (2/5)F_max(δ_max − δ_p) with a_max = √(Rδ_max), R_p = 4E*a³/(3F_max)."""
    d_y = (math.pi * P_Y / (2 * E_STAR)) ** 2 * R

    def force(d):
        hertz = 4 / 3 * E_STAR * math.sqrt(R) * np.minimum(d, d_y) ** 1.5
        return hertz + math.pi * P_Y * R * np.maximum(d - d_y, 0.0)

    def loading_work(d):
        x = np.linspace(0.0, d, 200_001)
        return np.trapezoid(force(x), x)

    low, high = 0.0, 1e-2
    for _ in range(60):
        middle = 0.5 * (low + high)
        low, high = (middle, high) if loading_work(middle) < 0.5 * MASS * velocity**2 else (low, middle)
    deepest = 0.5 * (low + high)
    top = float(force(deepest))
    radius = math.sqrt(R * deepest)
    enlarged = 4 * E_STAR * radius**3 / (3 * top)
    rebound = 0.4 * top * radius**2 / enlarged
    return math.sqrt(rebound / (0.5 * MASS * velocity**2)), deepest


def test_yield_velocity_is_thorntons_with_the_exact_coefficient():
    yield_velocity = float(theory.thornton_yield_velocity(MASS, R, E_STAR, P_Y))
    scale = math.sqrt(P_Y**5 / (E_STAR**4 * DENSITY))
    assert yield_velocity == pytest.approx(math.pi**2 / math.sqrt(40) * scale, rel=1e-14, abs=0.0)
    assert yield_velocity == pytest.approx(1.56 * scale, rel=5e-4, abs=0.0)  # Thornton's 1.56 to its digits


@pytest.mark.parametrize("ratio", [1.5, 10.0, 300.0])
def test_restitution_is_the_energy_balance_of_the_law(ratio):
    yield_velocity = float(theory.thornton_yield_velocity(MASS, R, E_STAR, P_Y))
    velocity = ratio * yield_velocity
    restitution, deepest = by_energy(velocity)
    assert float(theory.thornton_restitution(velocity, yield_velocity)) == pytest.approx(restitution, rel=1e-7, abs=0.0)
    assert float(theory.thornton_max_indentation(velocity, MASS, R, E_STAR, P_Y)) == pytest.approx(
        deepest, rel=1e-7, abs=0.0
    )


def test_restitution_is_one_up_to_the_yield_velocity_and_continuous_there():
    assert float(theory.thornton_restitution(0.3, 1.0)) == 1.0
    assert float(theory.thornton_restitution(1.0, 1.0)) == pytest.approx(1.0, abs=1e-15)
    assert 1.0 - float(theory.thornton_restitution(1.0 + 1e-8, 1.0)) < 1e-8
