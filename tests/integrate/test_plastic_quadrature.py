"""`solver.method: quadrature` with Thornton's plastic law (no adhesion): each contact phase ended
by its energy balance and timed by quadrature, against Thornton's closed forms, Hertz's contact
time below the yield velocity, and the same impacts integrated by dopri8 at rtol 1e-13."""

import math

import numpy as np
import pytest

import impact
from impact import simulate, theory
from impact._integrate.codes import RESULT_CODE
from impact._run.sweep import sweep
from impact._scene.paths import with_values
from impact._scene.scene import load_scene
from tests.run.bitwise import assert_chunks_agree
from tests.run.passive import assert_passive
from tests.scenes import CONFIGS, quadrature_refusal

# The steel ball of tests/law/test_thornton.py: p_y/E* small enough that 10⁴ v_y presses it in by
# a third of its radius.
R, DENSITY, E_STAR, P_Y = 5e-3, 7850.0, 115e9, 5e8
MASS = DENSITY * 4 / 3 * math.pi * R**3
YIELD_VELOCITY = float(theory.thornton_yield_velocity(MASS, R, E_STAR, P_Y))
RATIOS = np.array([0.5, 1.01, 3.0, 30.0, 1e3, 1e4])  # v₀/v_y
QUADRATURE = {"method": "quadrature"}
TIGHT = {"method": "dopri8", "rtol": 1e-13, "atol": 1e-15}


def steel(solver: dict, **effects) -> impact.Scene:
    """The steel ball on a steel plate (E* = 115 GPa, p_y = 0.5 GPa), solved by `solver`."""
    return load_scene(
        {
            "body": {"profile": {"shape": "paraboloid", "R": R}, "density": DENSITY},
            "material": {"E_star": E_STAR},
            "initial": {"velocity": YIELD_VELOCITY},
            "effects": {"plasticity": {"yield_pressure": P_Y}, **effects},
            "solver": solver,
        }
    )


def results(solver: dict) -> dict:
    """The sweep columns of the ball at each of `RATIOS`."""
    axes = {"initial.velocity": list(RATIOS * YIELD_VELOCITY)}
    return sweep(steel(solver), axes, order="given").results


@pytest.fixture(scope="module")
def fast() -> dict:
    return results(QUADRATURE)


def test_plastic_quadrature_meets_thorntons_closed_forms(fast):
    """Restitution, deepest indentation and largest force (F_y + πp_yR(δ_max − δ_y) beyond the
    yield depth, Hertz's below) within 1e-14 of Thornton's closed forms (measured ≤ 7e-16); the
    kinetic energy lost is the plastic work to 1e-13 of the touch energy; no solver step."""
    velocities = RATIOS * YIELD_VELOCITY
    assert np.all(fast["status"] == RESULT_CODE["separated"]) and np.all(fast["steps"] == 0)
    restitution = np.asarray(theory.thornton_restitution(velocities, YIELD_VELOCITY))
    deepest = np.asarray(theory.thornton_max_indentation(velocities, MASS, R, E_STAR, P_Y))
    yield_depth = float(theory.thornton_yield_indentation(R, E_STAR, P_Y))
    force = np.where(
        deepest > yield_depth,
        float(theory.thornton_yield_force(R, E_STAR, P_Y)) + math.pi * P_Y * R * (deepest - yield_depth),
        4 / 3 * E_STAR * math.sqrt(R) * deepest**1.5,
    )
    for name, expected in (("restitution", restitution), ("max_indentation", deepest), ("max_force", force)):
        assert np.all(np.abs(fast[name] / expected - 1.0) <= 1e-14), name
    touch_energy = 0.5 * MASS * velocities**2
    lost = 0.5 * MASS * (fast["touch_velocity"] ** 2 - fast["separation_velocity"] ** 2)
    assert np.all(np.abs(lost - fast["plastic_work"]) <= 1e-13 * touch_energy)
    assert np.all(fast["plastic_work"][RATIOS > 1.0] > 0.0) and fast["plastic_work"][0] == 0.0


def test_below_the_yield_velocity_the_contact_lasts_hertzs_time(fast):
    """At 0.5 v_y the impact is Hertz's: its contact time within 1e-12 (measured 3e-13)."""
    hertz = float(theory.hertz_contact_time(0.5 * YIELD_VELOCITY, MASS, R, E_STAR))
    assert fast["contact_time"][0] == pytest.approx(hertz, rel=1e-12, abs=0.0)


@pytest.mark.slow
def test_plastic_quadrature_is_the_tight_integration(fast):
    """Statuses equal; restitution, deepest indentation and largest force within 3e-11 of dopri8
    at rtol 1e-13 (its own error: measured ≤ 1.1e-11 against the closed forms, ≤ 2.5e-12 at rtol
    1e-14), contact times within 1e-10 (measured ≤ 1.7e-12)."""
    tight = results(TIGHT)
    assert np.array_equal(fast["status"], tight["status"])
    for name, tolerance in (("restitution", 3e-11), ("max_indentation", 3e-11), ("max_force", 3e-11)):
        assert np.all(np.abs(fast[name] / tight[name] - 1.0) <= tolerance), name
    assert np.all(np.abs(fast["contact_time"] / tight["contact_time"] - 1.0) <= 1e-10)


@pytest.mark.slow
def test_plastic_bounces_under_gravity_as_the_tight_integration_does():
    """Three bounces under gravity on the dent of the first: the same touches, turnarounds and
    separations at the same times to 1e-10 of the last. A later contact comes back at the speed
    the first left with and turns exactly at the first's deepest point, where loading would flow
    on: the quadrature turns there (to round-off), dopri8 flows for a stretch of its own error
    first (a `yield` event just before the turnaround), so those are left out."""
    runs = [
        simulate(
            with_values(steel(solver, gravity={}), {"initial.velocity": 30 * YIELD_VELOCITY, "limits.max_bounces": 3})
        )
        for solver in (QUADRATURE, TIGHT)
    ]
    fast, tight = runs
    assert fast.status == tight.status == "bounce_limit" and fast.bounces == tight.bounces == 3
    events = [[(time, kind) for time, kind in run.events if kind != "yield" or time < run.events[3][0]] for run in runs]
    assert [kind for _, kind in events[0]] == [kind for _, kind in events[1]]
    first, second = ["touch", "yield", "max_indentation", "separation"], ["touch", "max_indentation"]
    assert [kind for _, kind in events[0]][:6] == first + second
    times, expected = (np.array([time for time, _ in run]) for run in events)
    assert np.allclose(times, expected, rtol=0.0, atol=1e-10 * expected[-1])
    assert fast.max_indentation == pytest.approx(tight.max_indentation, rel=3e-11, abs=0.0)
    assert_passive(fast)


def test_a_plastic_sweep_point_does_not_depend_on_its_batch():
    """Bitwise the same results alone, in calls of 5 and in one call of 24."""
    axes = {"initial.velocity": list(np.geomspace(0.5, 1e4, 24) * YIELD_VELOCITY)}
    assert_chunks_agree(steel(QUADRATURE), axes, (1, 5))


def test_the_quadrature_refuses_thornton_and_nings_law():
    """With adhesion the plastic law is Thornton & Ning's, which the quadrature does not time."""
    assert quadrature_refusal(CONFIGS / "wall_particle.yaml", {}) == (
        "'quadrature' not with effects.plasticity and adhesion (Thornton & Ning's law): its phases end where the "
        "solver locates them; leave solver.method out"
    )
