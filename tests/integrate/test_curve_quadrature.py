"""`solver.method: quadrature` on the curve laws (Maugis–Dugdale, with and without approach
hysteresis, Greenwood–Johnson): each ride along a rising segment of the equilibrium curve ended
by its energy balance and timed by quadrature, against the same impacts integrated by dopri8 at
rtol 1e-13 and against the quadrature itself at twice its resolution."""

import jax
import numpy as np
import pytest
import yaml
from typer.testing import CliRunner

import impact
from impact import simulate
from impact._integrate import curve_quadrature
from impact._integrate.codes import RESULT_CODE
from impact._run.parameters import integrator_for, options_for, physics_for
from impact._run.sweep import sweep
from impact._scene.paths import with_values
from impact._scene.scene import load_scene
from impact.cli import app
from tests.run.bitwise import assert_chunks_agree
from tests.run.passive import assert_passive
from tests.scenes import CONFIGS, quadrature_refusal

QUADRATURE = {"solver.method": "quadrature"}
TIGHT = {"solver.method": "dopri8", "solver.rtol": 1e-13, "solver.atol": 1e-15}
# From captures (the lowest two or three) to 33 times each scene's own velocity.
VELOCITIES = [0.05, 0.15, 0.6, 2.0, 20.0]
SCENES = [
    "maugis_dugdale.yaml",
    "maugis_dugdale_hysteresis.yaml",
    "greenwood_johnson.yaml",
    "hard/17_maugis_small_tabor.yaml",
    "hard/18_maugis_large_tabor.yaml",
    "hard/19_greenwood_johnson_extremes.yaml",
]
COMPARED = ("restitution", "max_indentation", "max_force", "min_force")
CONVERGED_VELOCITIES = (0.15, 0.6, 20.0)


@pytest.mark.parametrize("config", SCENES)
@pytest.mark.slow
def test_curve_quadrature_is_the_tight_integration(config):
    """Statuses equal (captures and separations); restitution, deepest indentation and force
    extremes within 5e-8 of the tight run's largest value, contact times within 2e-9 (the tight
    run's own error: measured 3e-8 in e for hard/17 at 0.05 m/s, where dopri8 at rtol 1e-14 moves
    4× closer to the quadrature; ≤ 3e-11 elsewhere; times ≤ 2.4e-9)."""
    scene = load_scene(CONFIGS / config)
    axes = {"initial.velocity": VELOCITIES}
    fast = sweep(with_values(scene, QUADRATURE), axes, order="given").results
    tight = sweep(with_values(scene, TIGHT), axes, order="given").results
    assert np.array_equal(fast["status"], tight["status"])
    assert set(fast["status"]) <= {RESULT_CODE["separated"], RESULT_CODE["captured"]}
    assert np.all(fast["steps"] == 0)
    for name, tolerance in [*((name, 5e-8) for name in COMPARED), ("contact_time", 2e-9)]:
        mine, theirs = np.asarray(fast[name]), np.asarray(tight[name])
        finite = np.isfinite(theirs)
        assert np.array_equal(np.isfinite(mine), finite), name
        scale = np.abs(theirs[finite]) if name == "contact_time" else np.max(np.abs(theirs[finite]))
        assert np.all(np.abs(mine[finite] - theirs[finite]) <= tolerance * scale), name


@pytest.mark.parametrize("config", ["maugis_dugdale_hysteresis.yaml", "hard/19_greenwood_johnson_extremes.yaml"])
@pytest.mark.slow
def test_curve_quadrature_is_converged(config, monkeypatch):
    """At twice the nodes of every rule and scan the results move by round-off: restitution,
    deepest indentation and force extremes by ≤ 1e-12 relative, contact times by ≤ 1e-9
    (measured ≤ 3e-13 and ≤ 8e-10, hard/17 at 0.05 m/s)."""
    scene = load_scene(CONFIGS / config)
    results = _points_results(scene, CONVERGED_VELOCITIES)
    for name, value in (("_SCAN_CELLS", 16), ("_CELL_NODES", 32), ("_SUB_CELLS", 16), ("_NEWTON_STEPS", 16)):
        monkeypatch.setattr(curve_quadrature, name, value)
    monkeypatch.setattr(curve_quadrature, "_PANEL_NODES", 24)
    rule = curve_quadrature._rule()
    for name, value in zip(("_FRACTION", "_TIME_WEIGHTS", "_WORK_MATRIX"), rule, strict=True):
        monkeypatch.setattr(curve_quadrature, name, value)
    finer = _points_results(scene, CONVERGED_VELOCITIES)
    for coarse, fine in zip(results, finer, strict=True):
        assert coarse["status"] == fine["status"]
        for name in ("separation_velocity", "max_indentation", "max_force", "min_force"):
            assert coarse[name] == pytest.approx(fine[name], rel=1e-12, abs=0.0), name
        assert coarse["contact_time"] == pytest.approx(fine["contact_time"], rel=1e-9, abs=0.0)


def _points_results(scene, velocities) -> list[dict]:
    """Each impact's scaled outcome, by one program traced afresh (a cached program would not see
    a patched rule) and called at each velocity (a traced field of the Physics)."""
    scene = with_values(scene, QUADRATURE)
    integrator, options = integrator_for(scene), options_for(scene, trajectory=False)
    solve = jax.jit(lambda physics: integrator.solve(physics, options)[1])
    outcomes = [solve(physics_for(with_values(scene, {"initial.velocity": velocity}))) for velocity in velocities]
    return [
        {
            "status": int(outcome.status),
            "separation_velocity": float(outcome.separation_velocity),
            "max_indentation": float(outcome.max_indentation),
            "max_force": float(outcome.max_force),
            "min_force": float(outcome.min_force),
            "contact_time": float(outcome.separation_time - outcome.touch_time),
        }
        for outcome in outcomes
    ]


@pytest.mark.slow
def test_a_curve_sweep_point_does_not_depend_on_its_batch():
    """Bitwise the same results alone, in calls of 5 and in one call of 96 (the curve quadrature
    puts no cap on the lanes of a call; calls of 5 are the program the comparison with the tight
    integration compiles for its five velocities)."""
    scene = with_values(load_scene(CONFIGS / "maugis_dugdale.yaml"), QUADRATURE)
    axes = {"initial.velocity": list(np.geomspace(0.05, 20.0, 96))}
    assert_chunks_agree(scene, axes, (1, len(VELOCITIES)))


@pytest.mark.slow
def test_a_hysteretic_trajectory_is_the_tight_one():
    """The same events (touch, deepest point, the switch onto the detach curve, separation) at
    the same times to 1e-9 of the contact; a passive body (`assert_passive`) whose samples lie on
    the tight trajectory (depth and speed within 1e-3 of their largest values)."""
    scene = load_scene(CONFIGS / "maugis_dugdale_hysteresis.yaml")
    fast, tight = simulate(with_values(scene, QUADRATURE)), simulate(with_values(scene, TIGHT))
    assert fast.status == tight.status == "separated"
    assert [kind for _, kind in fast.events] == [kind for _, kind in tight.events]
    times, expected = (np.array([time for time, _ in run.events]) for run in (fast, tight))
    assert np.allclose(times, expected, rtol=0.0, atol=1e-9 * tight.contact_time)
    assert_passive(fast)
    for name in ("indentation", "velocity"):
        mine, theirs = getattr(fast, name), np.interp(fast.t, tight.t, getattr(tight, name))
        assert np.max(np.abs(mine - theirs)) <= 1e-3 * np.max(np.abs(getattr(tight, name))), name


@pytest.mark.slow
def test_curve_bounces_under_gravity_as_the_tight_integration_does():
    """The bead of gravity_bounces.yaml with Maugis–Dugdale adhesion (Λ = 1): the same ten contacts
    and capture, every event at the same time to 1e-9 of the last; restitution and contact time to
    1e-11 (measured 1.5e-12)."""
    data = yaml.safe_load((CONFIGS / "gravity_bounces.yaml").read_text())
    data["effects"]["adhesion"] = {"model": "maugis_dugdale", "work_of_adhesion": 0.1, "stress": 2.19e7}
    scene = impact.load_scene(data)
    fast, tight = simulate(with_values(scene, QUADRATURE)), simulate(with_values(scene, TIGHT))
    assert fast.status == tight.status == "captured" and fast.bounces == tight.bounces == 10
    assert [kind for _, kind in fast.events] == [kind for _, kind in tight.events]
    times, expected = (np.array([time for time, _ in run.events]) for run in (fast, tight))
    assert np.allclose(times, expected, rtol=0.0, atol=1e-9 * expected[-1])
    assert fast.restitution == pytest.approx(tight.restitution, rel=1e-11, abs=0.0)
    assert fast.contact_time == pytest.approx(tight.contact_time, rel=1e-11, abs=0.0)


@pytest.mark.parametrize(
    ("change", "why"),
    [
        (
            {"contact": {"springs": 64}},
            "'quadrature' computes the spring array of the zero-range (JKR) law only, not of adhesion model "
            "'maugis_dugdale': leave solver.method out (its springs ride their curve), or use contact.springs: "
            "continuum",
        ),
        ({"limits": {"duration": 1e-6}}, "'quadrature' does not stop a phase midway: leave limits.duration out"),
    ],
)
def test_curve_quadrature_is_refused_where_it_does_not_apply(change, why):
    assert quadrature_refusal(CONFIGS / "maugis_dugdale.yaml", change) == why


def test_validate_shows_the_curve_quadrature():
    path = str(CONFIGS / "greenwood_johnson.yaml")
    result = CliRunner().invoke(app, ["validate", path, "--set", "solver.method=quadrature"])
    assert result.exit_code == 0, result.output
    shown = " ".join(result.output.split())
    assert "│ solver │ quadrature, phase ends from the energy, timed by quadrature │" in shown
