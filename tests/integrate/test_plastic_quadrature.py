"""`solver.method: quadrature` with Thornton's plastic law and Thornton & Ning's adhesive one: each
contact phase ended by its energy balance and timed by quadrature, against the closed forms,
Hertz's contact time below the yield velocity, and the same impacts integrated by dopri8 at rtol
1e-13."""

import math

import jax
import numpy as np
import pytest
import yaml

import impact
from impact import simulate, theory
from impact._integrate import adhesive_plastic_quadrature
from impact._integrate.codes import RESULT_CODE
from impact._run.parameters import integrator_for, options_for, physics_for
from impact._run.sweep import sweep
from impact._scene.paths import with_values
from impact._scene.scene import load_scene
from impact._scene.sweep import make_spec
from impact._scene.sweep_method import CHOSEN, FASTER, NAMED
from tests.run.bitwise import COMPARED, assert_bitwise, assert_chunks_agree
from tests.run.passive import assert_passive
from tests.scenes import CONFIGS

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
    """Bitwise the same results alone, in calls of 6 and in one call of 24 (calls of 6: the
    program `fast` compiles)."""
    axes = {"initial.velocity": list(np.geomspace(0.5, 1e4, 24) * YIELD_VELOCITY)}
    assert_chunks_agree(steel(QUADRATURE), axes, (1, len(RATIOS)))


# The Wall et al. particle (sticks below 9.45 m/s): captures, one just above the sticking
# velocity, its own 20 m/s and five times that.
WALL_VELOCITIES = [0.3, 5.0, 9.4, 9.5, 20.0, 100.0]


def wall_particle(solver: dict, **values) -> impact.Scene:
    return with_values(
        load_scene(CONFIGS / "wall_particle.yaml"), {f"solver.{k}": v for k, v in solver.items()} | values
    )


@pytest.fixture(scope="module")
def wall() -> dict:
    return sweep(wall_particle(QUADRATURE), {"initial.velocity": WALL_VELOCITIES}, order="given").results


def test_adhesive_plastic_quadrature_meets_the_closed_forms(wall):
    """Captures below the sticking velocity; above it restitution, deepest indentation and largest
    force (JKR's on the dent, 4E*a_m³/(3R_p) − √(8πΔγE*a_m³)) within 1e-12 of Thornton & Ning's
    closed forms (`theory.adhesive_plastic_*`; measured ≤ 3e-13, at 9.5 m/s where e = 0.02);
    the kinetic energy lost is the dissipated energy to 1e-13 of the touch energy."""
    scene = load_scene(CONFIGS / "wall_particle.yaml")
    mass, radius, modulus = scene.reduced_mass, scene.contact_profile.R, scene.material.effective_modulus
    work, pressure = scene.effects.adhesion.work_of_adhesion, scene.effects.plasticity.yield_pressure
    velocities = np.asarray(WALL_VELOCITIES)
    captured = velocities < 9.45
    expected_status = np.where(captured, RESULT_CODE["captured"], RESULT_CODE["separated"])
    assert np.array_equal(wall["status"], expected_status) and np.all(wall["steps"] == 0)
    separated = ~captured
    law = (mass, radius, modulus, work, pressure)

    def closed_form(function, *args) -> np.ndarray:  # one scalar call a velocity (each a bisection)
        return np.array([float(function(*point, *args)) for point in velocities[:, None]])

    restitution = closed_form(lambda v, *args: theory.adhesive_plastic_restitution(v, *args), *law)
    deepest = closed_form(lambda v, *args: theory.adhesive_plastic_max_indentation(v, *args), *law)
    deepest_radius = closed_form(lambda v, *args: theory.adhesive_plastic_max_radius(v, *args), *law)
    dent_radius = np.array(
        [float(theory.adhesive_plastic_dent(a, radius, modulus, work, pressure)[0]) for a in deepest_radius]
    )
    force = 4 * modulus * deepest_radius**3 / (3 * dent_radius) - np.sqrt(
        8 * np.pi * work * modulus * deepest_radius**3
    )
    for name, expected in (("restitution", restitution), ("max_indentation", deepest), ("max_force", force)):
        assert np.all(np.abs(wall[name][separated] / expected[separated] - 1.0) <= 1e-12), name
    touch_energy = 0.5 * mass * velocities**2
    lost = 0.5 * mass * (wall["touch_velocity"] ** 2 - wall["separation_velocity"] ** 2)
    assert np.all(np.abs(lost - wall["dissipated_energy"])[separated] <= 1e-13 * touch_energy[separated])


@pytest.mark.slow
def test_adhesive_plastic_quadrature_is_the_tight_integration(wall):
    """Statuses equal; the rebound energy e² within 2e-11 of the touch energy (dopri8 at rtol
    1e-13 misses it by 4.8e-12 at 9.5 m/s, where e = 0.02 is 2.8e-9 off the closed form), deepest
    indentation and force extremes within 1e-10 (measured ≤ 3.6e-11, the tight run's own error:
    the quadrature meets the closed forms to 3e-13), contact times within 1e-9 (measured ≤ 5.5e-11)."""
    tight = sweep(wall_particle(TIGHT), {"initial.velocity": WALL_VELOCITIES}, order="given").results
    assert np.array_equal(wall["status"], tight["status"])
    assert np.all(np.abs(wall["restitution"] ** 2 - tight["restitution"] ** 2) <= 2e-11)
    for name in ("max_indentation", "max_force", "min_force"):
        assert np.all(np.abs(wall[name] / tight[name] - 1.0) <= 1e-10), name
    separated = np.isfinite(tight["contact_time"])
    assert np.array_equal(np.isfinite(wall["contact_time"]), separated)
    times = wall["contact_time"][separated] / tight["contact_time"][separated]
    assert np.all(np.abs(times - 1.0) <= 1e-9)


def test_an_impact_that_never_yields_is_the_elastic_adhesive_quadrature():
    """With p_y = 1e13 Pa the impact is the elastic adhesive impact by quadrature, to the bit."""
    plastic = wall_particle(QUADRATURE, **{"effects.plasticity.yield_pressure": 1e13})
    data = yaml.safe_load((CONFIGS / "wall_particle.yaml").read_text())
    del data["effects"]["plasticity"]
    elastic = load_scene(data | {"solver": QUADRATURE})
    axes = {"initial.velocity": [0.3, 20.0]}
    mine, theirs = sweep(plastic, axes).results, sweep(elastic, axes).results
    columns = (*COMPARED, "max_indentation")
    assert_bitwise({name: mine[name] for name in columns}, {name: theirs[name] for name in columns}, "p_y = 1e13 Pa")


@pytest.mark.slow
def test_an_adhesive_plastic_trajectory_is_the_tight_one():
    """The same events (touch, yield, the deepest point, separation) at the same times to 1e-10
    of the contact; a passive body."""
    fast, tight = simulate(wall_particle(QUADRATURE)), simulate(wall_particle(TIGHT))
    assert fast.status == tight.status == "separated"
    assert [kind for _, kind in fast.events] == [kind for _, kind in tight.events]
    times, expected = (np.array([time for time, _ in run.events]) for run in (fast, tight))
    assert np.allclose(times, expected, rtol=0.0, atol=1e-10 * tight.contact_time)
    assert_passive(fast)


def test_an_adhesive_plastic_sweep_point_does_not_depend_on_its_batch():
    """Bitwise the same results alone, in calls of 6 and in one call of 24 (calls of 6 and of 2
    are the programs `wall` and the never-yielding impact's sweep compile)."""
    axes = {"initial.velocity": list(np.geomspace(0.3, 100.0, 24))}
    assert_chunks_agree(wall_particle(QUADRATURE), axes, (1, len(WALL_VELOCITIES)))


@pytest.mark.slow
def test_plastic_loading_past_every_rung_is_a_failure_not_a_number(monkeypatch):
    """Plastic loading whose turnaround lies beyond the ladder's last rung (here one rung, √2 times
    the onset of flow, at 20 m/s) is not followed: the run ends with solver_failure."""
    monkeypatch.setattr(adhesive_plastic_quadrature, "_LADDER_RUNGS", 1)
    scene = wall_particle(QUADRATURE)
    integrator, options = integrator_for(scene), options_for(scene, trajectory=False)
    _, outcome = jax.jit(lambda physics: integrator.solve(physics, options))(physics_for(scene))
    assert int(outcome.status) == RESULT_CODE["solver_failure"]


def test_a_sweep_of_a_plastic_scene_that_names_no_method_runs_the_quadrature():
    """Without `solver.method` a sweep of either plastic law runs the quadrature; a scene that names
    its method keeps it (the examples do)."""
    for config in ("wall_particle.yaml", "plastic_steel.yaml"):
        data = yaml.safe_load((CONFIGS / config).read_text())
        named = make_spec(load_scene(data), {"initial.velocity": [0.5, 1.0]})
        assert (named.method, named.method_choice) == (data["solver"]["method"], NAMED + FASTER)
        del data["solver"]
        spec = make_spec(load_scene(data), {"initial.velocity": [0.5, 1.0]})
        assert (spec.method, spec.method_choice) == ("quadrature", CHOSEN)


@pytest.mark.slow
def test_adhesive_plastic_bounces_under_gravity_as_the_tight_integration_does():
    """The bead of gravity_bounces.yaml yielding at p_y = 20 MPa, thrown down at 1 cm/s: the same
    four contacts (the first yields, the later ones ride its dent) and capture, every event at the
    same time to 1e-10 of the last; restitution within 1e-10 (measured 1.1e-11)."""
    data = yaml.safe_load((CONFIGS / "gravity_bounces.yaml").read_text())
    data["effects"]["plasticity"] = {"yield_pressure": 2e7}
    data["initial"]["velocity"] = 0.01
    runs = [simulate(load_scene(data | {"solver": solver})) for solver in (QUADRATURE, TIGHT)]
    fast, tight = runs
    assert fast.status == tight.status == "captured" and fast.bounces == tight.bounces == 4
    kinds = [kind for _, kind in fast.events]
    assert kinds == [kind for _, kind in tight.events]
    assert kinds[:4] == ["touch", "yield", "max_indentation", "separation"] and kinds[-1] == "capture"
    times, expected = (np.array([time for time, _ in run.events]) for run in runs)
    assert np.allclose(times, expected, rtol=0.0, atol=1e-10 * expected[-1])
    assert fast.restitution == pytest.approx(tight.restitution, rel=1e-10, abs=0.0)
    assert_passive(fast)
