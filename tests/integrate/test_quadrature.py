"""`solver.method: quadrature`: each contact phase ended by its energy balance and timed by
Gauss quadrature of dt = dd/v, against the same impacts integrated by dopri8 at rtol 1e-13."""

import jax
import jax.numpy as jnp
import numpy as np
import pytest
from typer.testing import CliRunner

import impact
from impact import simulate, theory
from impact._integrate import quadrature
from impact._integrate.codes import RESULT_CODE
from impact._run.parameters import integrator_for, options_for, physics_for
from impact._run.sweep import sweep
from impact._scene.paths import with_values
from impact._scene.scene import load_scene
from impact.cli import app
from tests.run.bitwise import assert_chunks_agree
from tests.run.passive import assert_passive
from tests.scenes import CONFIGS

QUADRATURE = {"solver.method": "quadrature"}
TIGHT = {"solver.method": "dopri8", "solver.rtol": 1e-13, "solver.atol": 1e-15}
# Velocities (m/s) of each scene: about its sticking velocity (Thornton–Ning: v_s = 0.3032 m/s,
# 0.30326 is 2e-4 above it: the contact only just lets go), its own and far above.
CASES = {
    "thornton_ning.yaml": [0.25, 0.3033, 0.30326, 0.31, 0.6, 2.0, 20.0],
    "power_law.yaml": [0.1, 0.15, 0.3, 0.9, 5.0],
    "cone.yaml": [0.02, 0.05, 0.1, 0.3, 3.0],
    "attach_on_touch.yaml": [0.3, 0.45, 0.6, 1.8, 10.0],  # a hold after every turnaround
    "two_spheres.yaml": [0.02, 0.05, 0.1, 0.3],
}


@pytest.mark.slow
@pytest.mark.parametrize("config", sorted(CASES))
def test_quadrature_is_the_tight_integration(config):
    """Statuses equal; restitution, deepest indentation and force extremes to 1e-12; contact
    times to 2e-8 (measured ≤ 7.4e-9 over 10⁴ Thornton–Ning velocities from 0.2 to 20 m/s)."""
    scene = load_scene(CONFIGS / config)
    axes = {"initial.velocity": CASES[config]}
    fast = sweep(with_values(scene, QUADRATURE), axes, order="given").results
    tight = sweep(with_values(scene, TIGHT), axes, order="given").results
    assert np.array_equal(fast["status"], tight["status"])
    assert set(fast["status"]) <= {RESULT_CODE["separated"], RESULT_CODE["captured"]}
    assert np.all(fast["steps"] == 0)
    for name, tolerance in [
        ("restitution", 1e-12),
        ("max_indentation", 1e-12),
        ("max_force", 1e-12),
        ("min_force", 1e-12),
        ("contact_time", 2e-8),
        ("dissipated_energy", 1e-9),
    ]:
        mine, theirs = np.asarray(fast[name]), np.asarray(tight[name])
        finite = np.isfinite(theirs)
        assert np.array_equal(np.isfinite(mine), finite), name
        scale = (
            np.max(np.abs(theirs[finite])) if name in ("restitution", "dissipated_energy") else np.abs(theirs[finite])
        )
        assert np.all(np.abs(mine[finite] - theirs[finite]) <= tolerance * scale), name


@pytest.mark.slow
def test_gravity_bounces_as_the_tight_integration_does():
    """Several contacts under gravity (each a jump-in, a ride in and out, a flight), then captured."""
    scene = load_scene(CONFIGS / "gravity_bounces.yaml")
    fast, tight = simulate(with_values(scene, QUADRATURE)), simulate(with_values(scene, TIGHT))
    assert fast.status == tight.status == "captured" and fast.bounces == tight.bounces > 2
    assert abs(fast.restitution - tight.restitution) <= 1e-12
    assert abs(fast.contact_time - tight.contact_time) <= 2e-8 * tight.contact_time
    touches = [time for time, kind in fast.events if kind == "touch"]
    expected = [time for time, kind in tight.events if kind == "touch"]
    assert np.allclose(touches, expected, rtol=2e-8, atol=0.0)
    assert_passive(fast)


@pytest.mark.slow
@pytest.mark.parametrize("config", ["thornton_ning.yaml", "attach_on_touch.yaml", "cone.yaml"])
def test_a_quadrature_trajectory_is_the_tight_one(config):
    """A passive body's (`assert_passive`: time never runs back, the loop is dissipative), whose
    samples lie on the tight trajectory: depth and speed at the sampled times within 1e-3 of
    their largest values (the tight one interpolated linearly between its 64 samples a phase)."""
    scene = load_scene(CONFIGS / config)
    fast, tight = simulate(with_values(scene, QUADRATURE)), simulate(with_values(scene, TIGHT))
    assert_passive(fast)
    assert fast.t[-1] == pytest.approx(tight.t[-1], rel=2e-8, abs=0.0)
    for name in ("indentation", "velocity"):
        mine, theirs = getattr(fast, name), np.interp(fast.t, tight.t, getattr(tight, name))
        assert np.max(np.abs(mine - theirs)) <= 1e-3 * np.max(np.abs(getattr(tight, name))), name


@pytest.mark.slow
def test_a_sweep_point_does_not_depend_on_its_batch(thornton_ning_scene):
    scene = with_values(thornton_ning_scene, QUADRATURE)
    axes = {"initial.velocity": list(np.geomspace(0.2, 20.0, 13))}
    assert_chunks_agree(scene, axes, (1, 7))


@pytest.mark.slow
def test_a_speed_that_is_not_real_inside_a_phase_is_a_failure_not_a_number(monkeypatch, thornton_ning_scene):
    """A leg that ran past its turnaround (here: its end pushed 1e-3 beyond the root) meets v² < 0
    at its nodes: the run ends with solver_failure."""
    scene = with_values(thornton_ning_scene, QUADRATURE)
    ended = quadrature.Leg.end

    def overshoots(self):
        end, turned, settled = ended(self)
        return end + 1e-3 * (end - self.start) * turned, turned, settled

    monkeypatch.setattr(quadrature.Leg, "end", overshoots)
    integrator, options = integrator_for(scene), options_for(scene, trajectory=False)
    _, outcome = jax.jit(lambda physics: integrator.solve(physics, options))(physics_for(scene))
    assert int(outcome.status) == RESULT_CODE["solver_failure"]


# Found as one point of a 10⁷-point sweep: 1.57e-7 below the sticking velocity (3.51) of the
# Thornton–Ning scene, the unloading turnaround is a nearly double root of v² (its minimum lies
# 4e-4 beyond it, at the critical point of the JKR branch).
JUST_BELOW_STICKING = 0.30317878887891037  # m/s
ULP = 2.0**-52


@pytest.mark.slow
def test_quadrature_at_the_sticking_velocity_is_a_physical_outcome():
    """Just below v_s (the point found, ± 4 ulps): captured, e = 0, as dopri8 and the closed form
    say, not solver_failure; at v_s itself (± 4 ulps): a physical outcome, with e within 1e-7 of
    (3.50–51) (e² = 1 − v_s²/v² is round-off there) and the deepest indentation to 1e-12."""
    scene = with_values(load_scene(CONFIGS / "thornton_ning.yaml"), QUADRATURE)
    sticking = float(theory.thornton_ning_sticking_velocity(scene.body.mass, scene.body.profile.R, 1e9, 0.05))
    below = [JUST_BELOW_STICKING * (1.0 + k * ULP) for k in range(-4, 5)]
    at = [sticking * (1.0 + k * ULP) for k in range(-4, 5)]
    fast = sweep(scene, {"initial.velocity": below + at}, order="given").results
    tight = sweep(with_values(scene, TIGHT), {"initial.velocity": below}, order="given").results
    status, restitution = np.asarray(fast["status"]), np.asarray(fast["restitution"])
    assert np.all(status[: len(below)] == RESULT_CODE["captured"]) and np.all(restitution[: len(below)] == 0.0)
    assert np.all(np.asarray(tight["status"]) == RESULT_CODE["captured"])
    assert set(status[len(below) :]) <= {RESULT_CODE["separated"], RESULT_CODE["captured"]}
    assert np.all(np.abs(restitution - np.asarray(fast["theory_restitution"])) <= 1e-7)
    deepest = np.asarray(fast["max_indentation"])[: len(below)]
    assert np.allclose(deepest, np.asarray(tight["max_indentation"]), rtol=1e-12, atol=0.0)


@pytest.mark.slow
@pytest.mark.parametrize("mode", ["reverse", "forward"])
def test_derivatives_are_thornton_nings(mode, thornton_ning_scene):
    """`impact.as_function` differentiates through the quadrature: de/dΔγ and de/dv0 are those
    of (3.50–51) to 1e-10."""
    scene = with_values(thornton_ning_scene, QUADRATURE)
    restitution = impact.as_function(scene, ["effects.adhesion.work_of_adhesion", "initial.velocity"], "restitution")
    mass, radius = scene.body.resolved_mass, scene.body.profile.R
    modulus, work = scene.material.E_star, scene.effects.adhesion.work_of_adhesion
    point = jnp.array([work, 0.6])
    derivatives = (jax.grad if mode == "reverse" else jax.jacfwd)(restitution)(point)
    expected = jax.grad(lambda x: theory.thornton_ning_restitution(x[1], mass, radius, modulus, x[0]))(point)
    np.testing.assert_allclose(np.asarray(derivatives), np.asarray(expected), rtol=1e-10)


@pytest.mark.slow
def test_a_turnaround_whose_search_did_not_settle_is_a_failure_not_a_number(monkeypatch, thornton_ning_scene):
    """With one Illinois step instead of 12 the turnaround lies off the root of v² (by far more
    than 1e-9 of the leg's energies): the run ends with solver_failure, not a restitution that
    lost that energy."""
    scene = with_values(thornton_ning_scene, QUADRATURE)
    integrator, options = integrator_for(scene), options_for(scene, trajectory=False)
    assert _status(integrator, options, scene) == RESULT_CODE["separated"]
    monkeypatch.setattr(quadrature, "_ILLINOIS_STEPS", 1)
    assert _status(integrator, options, scene) == RESULT_CODE["solver_failure"]


def _status(integrator, options, scene) -> int:
    """The run's result code, traced afresh (a cached program would not see a patched constant)."""
    _, outcome = jax.jit(lambda physics: integrator.solve(physics, options))(physics_for(scene))
    return int(outcome.status)


def test_validate_shows_the_quadrature():
    path = str(CONFIGS / "thornton_ning.yaml")
    result = CliRunner().invoke(app, ["validate", path, "--set", "solver.method=quadrature"])
    assert result.exit_code == 0, result.output
    shown = " ".join(result.output.split())
    assert "│ solver │ quadrature, phase ends from the energy, timed by quadrature │" in shown
