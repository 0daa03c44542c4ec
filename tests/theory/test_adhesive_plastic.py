"""The adhesive elastic–plastic closed forms (Thornton & Ning 1998 in the MDR): the elastic limit,
continuity at the yield velocity, the energy split, the plastic limit, and an independent
quadrature of the force–indentation path."""

import math

import numpy as np
import pytest

from impact import theory
from tests.scenes import E_STAR, MASS, WORK, R

# The Thornton–Ning example particle (1 µm, E* = 1 GPa, Δγ = 0.05 J/m²) with p_y = 0.1 GPa
P_Y = 1e8  # Pa
YIELD_VELOCITY = float(theory.adhesive_plastic_yield_velocity(MASS, R, E_STAR, WORK, P_Y))


def deepest(velocity):
    return theory.adhesive_plastic_max_indentation(velocity, MASS, R, E_STAR, WORK, P_Y)


def restitution(velocity, yield_pressure=P_Y):
    return float(theory.adhesive_plastic_restitution(velocity, MASS, R, E_STAR, WORK, yield_pressure))


@pytest.mark.parametrize("velocity", [0.31, 0.6, 1.5, 0.999 * YIELD_VELOCITY])
def test_below_the_yield_velocity_it_is_thornton_nings_elastic_restitution(velocity):
    elastic = float(theory.thornton_ning_restitution(velocity, MASS, R, E_STAR, WORK))
    assert restitution(velocity) == pytest.approx(elastic, abs=1e-13)
    assert theory.adhesive_plastic_losses(deepest(velocity), R, E_STAR, WORK, P_Y)[1] == 0.0


def test_a_high_yield_pressure_keeps_the_elastic_sticking_velocity():
    sticking = float(theory.adhesive_plastic_sticking_velocity(MASS, R, E_STAR, WORK, P_Y))
    assert sticking == pytest.approx(
        float(theory.thornton_ning_sticking_velocity(MASS, R, E_STAR, WORK)), rel=1e-12, abs=0.0
    )
    assert restitution(0.999 * sticking) == 0.0 and restitution(1.001 * sticking) > 0.0


def test_restitution_is_continuous_at_the_yield_velocity():
    assert YIELD_VELOCITY == pytest.approx(2.919, rel=1e-3, abs=0.0)
    jumps = [restitution(YIELD_VELOCITY * (1 - eps)) - restitution(YIELD_VELOCITY * (1 + eps)) for eps in (1e-5, 1e-7)]
    # the slope jumps at v_y (plastic work starts linearly), the value does not
    assert 0 < jumps[1] < 1e-5 and jumps[0] / jumps[1] == pytest.approx(100.0, rel=1e-3, abs=0.0)


@pytest.mark.parametrize("velocity", [3.0, 10.0, 100.0])
def test_the_losses_close_the_energy_balance(velocity):
    adhesion, plastic = theory.adhesive_plastic_losses(deepest(velocity), R, E_STAR, WORK, P_Y)
    energy = 0.5 * MASS * velocity**2
    lost = energy * (1 - restitution(velocity) ** 2)
    assert float(adhesion) > 0 and float(plastic) > 0
    assert float(adhesion + plastic) == pytest.approx(lost, rel=1e-11, abs=0.0)


def test_at_high_speed_the_restitution_tends_to_thorntons():
    elastic_plastic = float(theory.thornton_yield_velocity(MASS, R, E_STAR, P_Y))
    gaps = []
    for ratio in (1e2, 1e3, 1e4, 1e5):
        velocity = ratio * elastic_plastic
        gaps.append(1 - restitution(velocity) / float(theory.thornton_restitution(velocity, elastic_plastic)))
    assert all(0 < later < 0.6 * earlier for earlier, later in zip(gaps, gaps[1:], strict=False))
    assert gaps[-1] < 1e-2


def test_a_fresh_dent_is_the_paraboloid_and_a_deep_one_is_flatter():
    a_y = float(theory.adhesive_plastic_yield_radius(R, E_STAR, WORK, P_Y))
    # the JKR pressure at the centre, 2E*a/(πR) − √(2ΔγE*/(πa)), is p_y there
    assert 2 * E_STAR * a_y / (math.pi * R) - math.sqrt(2 * WORK * E_STAR / (math.pi * a_y)) == pytest.approx(
        P_Y, rel=1e-6, abs=0.0
    )
    radius, residual = theory.adhesive_plastic_dent(a_y, R, E_STAR, WORK, P_Y)
    assert float(radius) == pytest.approx(R, rel=1e-14, abs=0.0) and abs(float(residual)) < 1e-15 * R
    radius, residual = theory.adhesive_plastic_dent(3 * a_y, R, E_STAR, WORK, P_Y)
    assert float(radius) > R and float(residual) > 0


def by_quadrature(velocity: float) -> float:
    """e from the force–indentation path integrated numerically: JKR loading (d = a²/R − Δl,
    F = 4E*a³/(3R) − 2E*aΔl) to a_y, plastic loading (F_H = F_H(a_y) + πp_y(a² − a_y²)) to a_m
    where the work reaches ½mv₀², then the JKR branch with R_p and δ_p back to its turning point."""
    a_y = float(theory.adhesive_plastic_yield_radius(R, E_STAR, WORK, P_Y))

    def hertzian(a):
        return np.where(
            a > a_y, 4 * E_STAR * a_y**3 / (3 * R) + math.pi * P_Y * (a**2 - a_y**2), 4 * E_STAR * a**3 / (3 * R)
        )

    def stretch(a):
        return np.sqrt(2 * math.pi * a * WORK / E_STAR)

    def work_along(force, depth):
        """∫F dd by trapezoids: the running sum from the first point."""
        return np.concatenate([[0.0], np.cumsum(0.5 * (force[1:] + force[:-1]) * np.diff(depth))])

    a0 = (2 * math.pi * WORK * R**2 / E_STAR) ** (1 / 3)
    grid = np.geomspace(a0, 100 * a0, 400_001)
    loading = work_along(hertzian(grid) - 2 * E_STAR * grid * stretch(grid), grid**2 / R - stretch(grid))
    a_m = float(np.interp(0.5 * MASS * velocity**2, loading, grid))
    enlarged = 4 * E_STAR * a_m**3 / (3 * float(hertzian(np.array(a_m))))
    residual = a_m**2 / R - a_m**2 / enlarged
    a_c = (E_STAR * math.sqrt(2 * math.pi * WORK / E_STAR) * enlarged / (4 * E_STAR)) ** (2 / 3)
    back = np.linspace(a_c, a_m, 200_001)
    rebound = work_along(
        4 * E_STAR * back**3 / (3 * enlarged) - 2 * E_STAR * back * stretch(back),
        residual + back**2 / enlarged - stretch(back),
    )[-1]
    return math.sqrt(rebound / (0.5 * MASS * velocity**2))


@pytest.mark.parametrize("velocity", [5.0, 30.0])
def test_the_closed_form_meets_a_quadrature_of_the_path(velocity):
    assert restitution(velocity) == pytest.approx(by_quadrature(velocity), abs=1e-6)


def test_the_touch_pressure_is_the_jkr_centre_pressure_at_the_jump_in():
    a0 = (2 * math.pi * WORK * R**2 / E_STAR) ** (1 / 3)
    centre = 2 * E_STAR * a0 / (math.pi * R) - math.sqrt(2 * WORK * E_STAR / (math.pi * a0))
    assert float(theory.adhesive_plastic_touch_pressure(R, E_STAR, WORK)) == pytest.approx(centre, rel=1e-13, abs=0.0)
