"""Greenwood–Johnson double-Hertz adhesion (§3.9) in impacts: the body rides the curve of
(3.198)–(3.201); energy balance, the loop area against quadrature of the closed forms, the
pull-off force, Thornton–Ning as k grows, the reversible DMT side, sweeps and refusals."""

import math

import numpy as np
import pytest
from scipy.integrate import fixed_quad
from scipy.optimize import brentq
from typer.testing import CliRunner

import impact
from impact import load_scene, simulate, theory
from impact._io.run import read_run
from impact._scene.scene import SceneError
from impact.cli import app
from tests.scenes import CONFIGS, E_STAR, MASS, WORK, R, micro_sphere

CONFIG = CONFIGS / "greenwood_johnson.yaml"


def gj_scene(k=10.0, velocity=0.6, profile=None, **extra):
    scene = micro_sphere(velocity, {"adhesion": {"model": "greenwood_johnson", "work_of_adhesion": WORK, "k": k}})
    if profile is not None:
        scene["body"]["profile"] = profile
    return load_scene({"name": "gj", **scene, **extra})


def loop_area(k):
    """∮F dd of a quasi-static cycle on the curve (J): for k > 1 the part of the unloading branch
    below the jump-in, ∫F d'(a) da from the jump-in radius a₁ (d(a₁) = d₀, by Brent's method) down
    to the minimum of d, by 200-point Gauss–Legendre quadrature of the closed forms (d' by
    central differences); 0 for k ≤ 1 (nothing jumps)."""
    if k <= 1:
        return 0.0
    turn = float(theory.double_hertz_pull_off(k, R, E_STAR, WORK, 1)[0])
    onset = float(theory.double_hertz_onset(k, R, E_STAR, WORK)[1])

    def depth(a):
        return np.asarray(theory.double_hertz_indentation(a, k, R, E_STAR, WORK))

    jump_in = brentq(lambda a: float(depth(a)) - onset, turn, 100 * turn, xtol=1e-22, rtol=1e-15)
    step = 1e-6 * turn

    def integrand(a):
        slope = (depth(a + step) - depth(a - step)) / (2 * step)
        return np.asarray(theory.double_hertz_force(a, k, R, E_STAR, WORK)) * slope

    return -fixed_quad(integrand, turn, jump_in, n=200)[0]


@pytest.mark.slow
@pytest.mark.parametrize("k", [1e-3, 0.3, 3.0, 1e3])
def test_energy_balance_loop_area_and_pull_off(k):
    """Kinetic energy lost = ∮F dd (1e-7 of the impact energy) = the curve's loop area by
    quadrature (1e-6 of the impact energy); the least force is the force-controlled pull-off
    (rtol 1e-8), the reported Λ is Λ(k)."""
    result = simulate(gj_scene(k))
    assert result.status == "separated"
    energy = 0.5 * MASS * result.touch_velocity**2
    lost = energy - 0.5 * MASS * result.separation_velocity**2
    assert abs(lost - result.dissipated_energy) <= 1e-7 * energy
    assert abs(result.dissipated_energy - loop_area(k)) <= 1e-6 * energy
    pull_off = float(theory.double_hertz_pull_off(k, R, E_STAR, WORK, 3)[2])
    assert result.min_force == pytest.approx(pull_off, rel=1e-8, abs=0.0)
    assert result.tabor_parameter == pytest.approx(float(theory.double_hertz_tabor_parameter(k)), rel=1e-12, abs=0.0)


def test_restitution_converges_to_thornton_ning_as_k_grows():
    """e − e_TN > 0 falls monotonically and like k^(-1/3) (fitted order within 0.05), as the
    equivalent Λ ∝ k^(1/3) grows; below 3e-3 at k = 1e6."""
    expected = float(theory.thornton_ning_restitution(0.6, MASS, R, E_STAR, WORK))
    factors = np.array([1e2, 1e3, 1e4, 1e5, 1e6])
    excess = np.array([simulate(gj_scene(k)).restitution for k in factors]) - expected
    assert np.all(excess > 0) and np.all(np.diff(excess) < 0)
    order = np.polyfit(np.log(factors), np.log(excess), 1)[0]
    assert abs(order + 1 / 3) < 0.05
    assert excess[-1] < 3e-3


@pytest.mark.parametrize("k", [1e-3, 1.0])
def test_dmt_side_is_reversible(k):
    """For k ≤ 1, d(a) rises from the onset: no jump, e = 1 to 1e-7; the contact starts and ends
    at d₀ with the force F₀ = −2πRΔγ/(1 + k) (rtol 1e-10 on the first trajectory sample)."""
    result = simulate(gj_scene(k))
    assert abs(1.0 - result.restitution) < 1e-7
    assert [kind for _, kind in result.events] == ["touch", "max_indentation", "separation"]
    _, onset_depth, onset_force = map(float, theory.double_hertz_onset(k, R, E_STAR, WORK))
    in_contact = np.flatnonzero(result.contact_radius > 0)
    first = in_contact[0] - 1 if result.force[in_contact[0] - 1] != 0 else in_contact[0]
    assert result.indentation[first] == pytest.approx(onset_depth, rel=1e-10, abs=0.0)
    assert result.force[first] == pytest.approx(onset_force, rel=1e-8, abs=0.0)


@pytest.mark.slow
def test_slow_impacts_are_captured_and_sphere_tips_ride_the_paraboloid():
    """Below the sticking speed the body is captured; a sphere's tip is its paraboloid r²/(2R):
    the same restitution to 1e-9 (its units differ: round-off)."""
    result = simulate(gj_scene(1e3, velocity=0.05))
    assert result.status == "captured" and result.stuck and result.restitution == 0.0
    paraboloid = simulate(gj_scene(3.0))
    sphere = simulate(gj_scene(3.0, profile={"shape": "sphere", "R": R}))
    assert sphere.restitution == pytest.approx(paraboloid.restitution, rel=1e-9, abs=0.0)


@pytest.mark.slow
def test_gravity_drop_bounces_then_is_captured():
    """A bead dropped onto the double-Hertz surface (k = 10): the bounces lose energy in the
    jumps until it is captured, each bounce logged with its touch."""
    scene = load_scene(
        {
            "body": {"profile": {"shape": "paraboloid", "R": 1.0e-3}, "density": 2500.0},
            "material": {"E_star": 1.0e10},
            "initial": {"velocity": 0.0, "gap": 1.5e-7},
            "effects": {
                "adhesion": {"model": "greenwood_johnson", "work_of_adhesion": 0.1, "k": 10.0},
                "gravity": {"g": 9.81},
            },
        }
    )
    result = simulate(scene)
    assert result.status == "captured" and result.stuck
    assert 2 <= result.bounces < scene.limits.max_bounces
    kinds = [kind for _, kind in result.events]
    assert kinds.count("touch") == result.bounces and kinds[-1] == "capture"
    assert 0.0 < result.restitution < 1.0


@pytest.mark.slow
def test_sweep_over_k_balances_energy_and_equals_simulate():
    """`impact.sweep` over k ∈ [1e-3, 1e3] (one compiled group: k is traced): energy balance at
    every point (1e-7 of the impact energy), simulate's values with the sweep's method named (rtol
    1e-12; the quadrature: the scene names none), Thornton–Ning as the closed form."""
    factors = [1e-3, 1.0, 1e3]
    result = impact.sweep(gj_scene(velocity=0.5), {"effects.adhesion.k": factors}, chunk=3)
    touch, separation = np.asarray(result.touch_velocity), np.asarray(result.separation_velocity)
    lost = 0.5 * MASS * (touch**2 - separation**2)
    assert np.all(np.abs(lost - np.asarray(result.dissipated_energy)) <= 1e-7 * 0.5 * MASS * touch**2)
    assert result.spec.method == "quadrature"
    single = simulate(gj_scene(factors[-1], velocity=0.5, solver={"method": "quadrature"}))
    assert math.isclose(float(result.restitution[-1]), single.restitution, rel_tol=1e-12)
    expected = float(theory.thornton_ning_restitution(0.5, MASS, R, E_STAR, WORK))
    assert np.allclose(np.asarray(result.theory_restitution), expected, rtol=1e-14, atol=0.0)


BASE = {"model": "greenwood_johnson", "work_of_adhesion": WORK, "k": 1.0}


@pytest.mark.parametrize(
    "adhesion, extra, field, message",
    [
        (
            {**BASE, "k": 0.0},
            {},
            "effects.adhesion.k",
            "0 is outside the allowed range [1e-6, 1e6]: from DMT (k → 0) to JKR (k → ∞) within float64's reach",
        ),
        (
            {**BASE, "k": -2.0},
            {},
            "effects.adhesion.k",
            "-2 is outside the allowed range [1e-6, 1e6]: from DMT (k → 0) to JKR (k → ∞) within float64's reach",
        ),
        (
            {"work_of_adhesion": WORK, "k": 1.0},
            {},
            "effects.adhesion.k",
            "only for model 'greenwood_johnson' (jkr has no double-Hertz factor)",
        ),
        (
            {"model": "greenwood_johnson", "work_of_adhesion": WORK},
            {},
            "effects.adhesion.k",
            "model 'greenwood_johnson' needs the double-Hertz factor k > 0",
        ),
        (
            {**BASE, "approach_work_of_adhesion": 0.0},
            {},
            "effects.adhesion.approach_work_of_adhesion",
            "0 J/m² is not taken by model 'greenwood_johnson', which loads and unloads on the stable "
            "branches of its equilibrium curve without approach hysteresis: leave it out (approach "
            "hysteresis: model 'jkr' or 'maugis_dugdale')",
        ),
        (
            {**BASE, "stress": 1e7},
            {},
            "effects.adhesion.stress",
            "only for model 'maugis_dugdale' (greenwood_johnson takes k)",
        ),
        (
            BASE,
            {"body": {"profile": {"shape": "cone", "theta": 0.3}, "mass": MASS}},
            "effects.adhesion.model",
            "greenwood_johnson needs a paraboloid (paraboloid, sphere): the double-Hertz stress of §3.9 "
            "holds for f = r²/(2R) only, not 'cone'",
        ),
        (
            BASE,
            {"contact": {"springs": 100}},
            "contact.springs",
            "greenwood_johnson runs on the continuum law only ('continuum')",
        ),
    ],
)
def test_bad_double_hertz_scenes_name_the_field(adhesion, extra, field, message):
    scene = {
        "body": {"profile": {"shape": "paraboloid", "R": R}, "mass": MASS},
        "material": {"E_star": E_STAR},
        "initial": {"velocity": 0.6},
        "effects": {"adhesion": adhesion},
        **extra,
    }
    with pytest.raises(SceneError) as error:
        load_scene(scene)
    assert (field, message) in error.value.problems, error.value.problems


def test_cli_runs_the_config_and_refuses_approach_with_exit_code_2(tmp_path):
    """`impact run` of configs/greenwood_johnson.yaml stores the run (its restitution equals
    simulate's to 1e-12); an approach work of adhesion exits 2, names the field, writes nothing."""
    out = tmp_path / "run"
    ran = CliRunner().invoke(app, ["run", str(CONFIG), "-o", str(out)])
    assert ran.exit_code == 0, ran.output
    stored = read_run(out / "run.h5")
    assert stored.restitution == pytest.approx(simulate(load_scene(CONFIG)).restitution, rel=1e-12, abs=0.0)
    bad = tmp_path / "bad.yaml"
    bad.write_text(CONFIG.read_text().replace("    k: 10.0", "    k: 10.0\n    approach_work_of_adhesion: 0.01"))
    refused = CliRunner().invoke(app, ["run", str(bad), "-o", str(tmp_path / "bad")])
    assert refused.exit_code == 2
    assert "effects.adhesion.approach_work_of_adhesion" in refused.output
    assert "Traceback" not in refused.output and not (tmp_path / "bad").exists()
