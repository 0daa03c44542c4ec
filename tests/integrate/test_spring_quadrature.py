"""`solver.method: quadrature` on a spring array (`contact.springs: N`): each contact computed
whole from prefix sums over the springs (`_integrate.spring_quadrature`), against the exact event
loop (`_integrate.springs`, the default on a spring array), which advances the same arcs one
spring event after another."""

import json
import math
import os
import subprocess
import sys

import jax
import numpy as np
import pytest
import yaml

from impact import simulate, theory
from impact._integrate.codes import RESULT_CODE
from impact._integrate.spring_quadrature import SpringQuadrature, angle
from impact._integrate.springs import SpringArray
from impact._run.parameters import integrator_for, options_for, physics_for
from impact._run.sweep import sweep
from impact._scene.method_support import SPRING_QUADRATURE_MAX_SPRINGS
from impact._scene.paths import with_values
from impact._scene.scene import load_scene
from tests.scenes import CONFIGS, E_STAR, MASS, ROOT, WORK, quadrature_refusal

QUADRATURE = {"solver.method": "quadrature"}
SPRINGS = CONFIGS / "spring_array.yaml"  # the micro-sphere on 2000 springs, v_s ≈ 0.303 m/s
# A cone of θ = 0.3 on 256 springs under the reversible JKR law, at 1, 2 and 3 times its sticking
# velocity (3.82): captured at v_s (the array of 256 springs loses a little more than the
# continuum), separated above it.
CONE_THETA = 0.3
CONE = {"contact": {"springs": 256}, "body": {"profile": {"shape": "cone", "theta": CONE_THETA}, "mass": MASS}}
CONE_STICKING = float(theory.power_law_sticking_velocity(MASS, 1.0, math.tan(CONE_THETA), E_STAR, WORK))
CONE_VELOCITIES = [factor * CONE_STICKING for factor in (1.0, 2.0, 3.0)]
# (changes to the scene file's sections, velocities in m/s): captured and separated points of
# each; the event loop measured against these ≤ 6e-14 apart (restitution, force extremes,
# depth, contact time).
CASES = {
    "jkr": ({"contact": {"springs": 256}}, [0.1, 0.29, 0.32, 0.6, 3.0]),
    "attach_on_touch_cone": (
        {
            "contact": {"springs": 300},
            "body": {"profile": {"shape": "cone", "theta": 0.3}, "mass": 1.0472e-14},
            "effects": {"adhesion": {"work_of_adhesion": 0.05, "approach_work_of_adhesion": 0.0}},
        },
        [0.01, 0.05, 0.3, 1.0],
    ),
    "partial_approach_hysteresis": (
        {"effects": {"adhesion": {"work_of_adhesion": 0.05, "approach_work_of_adhesion": 0.01}}},
        [0.2, 0.5, 2.0],
    ),
    "no_adhesion": ({"contact": {"springs": 100}, "effects": {}}, [0.1, 1.0]),
    "reversible_jkr_cone": (CONE, CONE_VELOCITIES),
}
MEASURED = ("restitution", "max_indentation", "max_force", "min_force", "contact_time")


def _both(changes: dict, velocities: list[float]):
    scene = load_scene({**yaml.safe_load(SPRINGS.read_text()), **changes})
    axes = {"initial.velocity": velocities}
    fast = sweep(with_values(scene, QUADRATURE), axes, order="given").results
    exact = sweep(scene, axes, order="given").results
    return fast, exact


@pytest.mark.parametrize("case", sorted(CASES))
def test_prefix_sums_give_the_event_loop_to_round_off(case):
    """Statuses equal; restitution (relative to the largest), deepest indentation, force
    extremes and contact time to 1e-12 relative; no step taken."""
    fast, exact = _both(*CASES[case])
    assert np.array_equal(fast["status"], exact["status"])
    assert np.all(fast["steps"] == 0)
    for name in MEASURED:
        mine, theirs = np.asarray(fast[name]), np.asarray(exact[name])
        finite = np.isfinite(theirs)
        assert np.array_equal(np.isfinite(mine), finite), name
        scale = np.max(np.abs(theirs[finite])) if name == "restitution" else np.abs(theirs[finite])
        assert np.all(np.abs(mine[finite] - theirs[finite]) <= 1e-12 * scale), name


def test_the_cases_capture_and_separate():
    """The cases above hold both outcomes: a body captured below the sticking velocity and one
    that separates above it."""
    fast, _ = _both(*CASES["jkr"])
    assert fast["status"][0] == RESULT_CODE["captured"] and fast["restitution"][0] == 0.0
    assert fast["status"][-1] == RESULT_CODE["separated"] and fast["restitution"][-1] > 0.5


# The event loop of the cone run by `impact.simulate` in a process that never called
# `impact.configure()`, where XLA:CPU fuses multiply–adds: prints [status, restitution, contact
# time] of each velocity, or null where this CPU fuses none.
_FUSED_EVENT_LOOP = """
import json, sys
from impact._core.runtime import contracts_multiply_adds
if not contracts_multiply_adds():
    print("null")
    raise SystemExit
from impact import simulate
from impact._scene.paths import with_values
from impact._scene.scene import load_scene
scene = load_scene(json.loads(sys.argv[1]))
runs = [simulate(with_values(scene, {"initial.velocity": v}), trajectory=False) for v in json.loads(sys.argv[2])]
print(json.dumps([[run.status, run.restitution, run.contact_time] for run in runs]))
"""


def test_the_event_loop_separates_from_a_cone_where_multiply_adds_are_fused():
    """The cone's detach thresholds rounded otherwise where the arc reached them than where the
    cascade tested them again (fused multiply–adds): its deepest spring stayed attached at its
    own threshold and every event found it again at the same time, to the event limit (status
    phase_limit). Each threshold is now computed once: the event loop there gives the prefix
    sums' status, restitution and contact time to 1e-12 relative (the prefix sums run in this
    process, without fused multiply–adds)."""
    data = {**yaml.safe_load(SPRINGS.read_text()), **CONE}
    environment = {key: value for key, value in os.environ.items() if key != "XLA_FLAGS"}
    command = [sys.executable, "-c", _FUSED_EVENT_LOOP, json.dumps(data), json.dumps(CONE_VELOCITIES)]
    shown = subprocess.run(command, capture_output=True, text=True, env=environment, cwd=ROOT, check=True)
    fused = json.loads(shown.stdout)
    if fused is None:
        pytest.skip("this CPU's XLA fuses no multiply–adds")
    axes = {"initial.velocity": CONE_VELOCITIES}
    fast = sweep(with_values(load_scene(data), QUADRATURE), axes, order="given").results
    assert [status for status, _, _ in fused] == ["captured", "separated", "separated"]
    assert np.array_equal([RESULT_CODE[status] for status, _, _ in fused], fast["status"])
    for index, (_, restitution, contact_time) in enumerate(fused):
        assert restitution == pytest.approx(float(fast["restitution"][index]), rel=1e-12, abs=0.0)
        assert contact_time == pytest.approx(float(fast["contact_time"][index]), rel=1e-12, abs=0.0)


def test_bounces_under_gravity_are_the_event_loop():
    """A glass bead dropped onto the array: the same contacts, status, restitution, extremes and
    energy lost (every bounce's flight analytic in both), to 1e-12."""
    data = {
        "body": {"profile": {"shape": "paraboloid", "R": 1e-3}, "density": 2500.0},
        "material": {"E_star": 1e10},
        "initial": {"velocity": 2e-3, "gap": 1.5e-7},
        "effects": {"adhesion": {"work_of_adhesion": 0.1}, "gravity": {"g": 9.81}},
        "contact": {"springs": 128},
        "limits": {"max_bounces": 16},
    }
    exact = simulate(load_scene(data), trajectory=False)
    data["solver"] = {"method": "quadrature"}
    fast = simulate(load_scene(data), trajectory=False)
    assert fast.status == exact.status
    assert fast.bounces == exact.bounces > 1
    for name in ("restitution", "max_indentation", "max_force", "min_force", "contact_time", "dissipated_energy"):
        assert getattr(fast, name) == pytest.approx(getattr(exact, name), rel=1e-12, abs=0.0), name


def test_a_point_does_not_depend_on_its_batch():
    scene = with_values(load_scene(SPRINGS), {"contact.springs": 256, **QUADRATURE})
    axes = {"initial.velocity": list(np.geomspace(0.1, 3.0, 13))}
    whole = sweep(scene, axes, order="given").results
    for chunk in (1, 7):
        parts = sweep(scene, axes, order="given", chunk=chunk).results
        for name in (*MEASURED, "status"):
            assert np.array_equal(np.asarray(parts[name]), np.asarray(whole[name]), equal_nan=True), (chunk, name)


def test_the_scene_picks_the_prefix_sums_and_sizes_them_to_the_array():
    scene = with_values(load_scene(SPRINGS), QUADRATURE)
    assert integrator_for(scene) == SpringQuadrature(capacity=2048)
    assert isinstance(integrator_for(load_scene(SPRINGS)), SpringArray)


def test_an_array_beyond_the_capacity_is_refused_in_the_run():
    """N traced beyond the compiled slots: status branch_overflow, not a silently shorter array."""
    scene = with_values(load_scene(SPRINGS), {"contact.springs": 100, **QUADRATURE})
    options = options_for(scene, trajectory=False)
    physics = physics_for(with_values(scene, {"contact.springs": 200}))
    _, outcome = jax.jit(lambda p: SpringQuadrature(capacity=128).solve(p, options))(physics)
    assert int(outcome.status) == RESULT_CODE["branch_overflow"]


def test_the_trajectory_holds_the_states_after_the_events():
    """`impact.simulate` keeps the event states of the contact, in time order, from the touch
    (d = 0) through the deepest point to the separation, with the loop's restitution."""
    scene = with_values(load_scene(SPRINGS), {"contact.springs": 64, **QUADRATURE})
    fast, exact = simulate(scene), simulate(with_values(load_scene(SPRINGS), {"contact.springs": 64}))
    assert fast.restitution == pytest.approx(exact.restitution, rel=1e-12, abs=0.0)
    touching = fast.force != 0.0
    assert np.all(np.diff(fast.t) >= 0.0)
    assert np.max(fast.indentation) == pytest.approx(exact.max_indentation, rel=1e-12, abs=0.0)
    assert np.count_nonzero(touching) >= 32


@pytest.mark.parametrize(
    ("change", "why"),
    [
        (
            {"effects": {"adhesion": {"model": "maugis_dugdale", "work_of_adhesion": 0.05, "stress": 1e8}}},
            "'quadrature' computes the spring array of the zero-range (JKR) law only, not of adhesion model "
            "'maugis_dugdale': leave solver.method out (its springs ride their curve), or use contact.springs: "
            "continuum",
        ),
        ({"limits": {"duration": 1e-6}}, "'quadrature' does not stop a contact midway: leave limits.duration out"),
        (
            {"contact": {"springs": SPRING_QUADRATURE_MAX_SPRINGS + 1}},
            f"'quadrature' holds at most {SPRING_QUADRATURE_MAX_SPRINGS} springs (its work and memory grow with N "
            f"at every point), not {SPRING_QUADRATURE_MAX_SPRINGS + 1}: leave solver.method out (the exact event "
            "loop takes any N)",
        ),
    ],
)
def test_prefix_sums_are_refused_where_they_do_not_apply(change, why):
    assert quadrature_refusal(SPRINGS, change) == why


def test_the_vectorised_angle_is_atan2_to_a_few_ulps():
    """Over every octant, 16 decades of each coordinate and the axes: within 8 ulps of the angle
    (measured 6). (A negative zero x reads as +0: the arcs never meet it.)"""
    rng = np.random.default_rng(0)
    x = rng.normal(size=20000) * 10.0 ** rng.uniform(-8, 8, 20000)
    y = rng.normal(size=20000) * 10.0 ** rng.uniform(-8, 8, 20000)
    x = np.concatenate([x, [0.0, 0.0, 1.0, -1.0, 1.0, 0.0, -1.0, 1e-300, 1.0, -1.0]])
    y = np.concatenate([y, [0.0, 1.0, 0.0, 0.0, 1.0, -1.0, 1e-20, 1.0, -1e-300, -1e-17]])
    with jax.enable_x64(True):
        mine = np.asarray(jax.jit(angle)(y, x))
    exact = np.arctan2(y, x)
    assert np.all(np.abs(mine - exact) <= 8 * np.spacing(np.abs(exact)) + 1e-320)
