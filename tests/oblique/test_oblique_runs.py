"""Oblique impacts with adhesion (the Thornton–Ning micro-sphere under both friction limits), in a
sweep, in run files and on the command line; the angle without friction."""

import math

import numpy as np
import pytest
import yaml
from typer.testing import CliRunner

import impact
from impact._io.run import read_run, write_run
from impact.cli import app

THORNTON_NING = "configs/thornton_ning.yaml"
MU, G_STAR = 0.3, 0.8235e9
R, E_STAR, WORK = 1e-6, 1e9, 0.05
MASS = 1.0472e-14
INERTIA = 0.4 * MASS * R**2


def adhesive(angle=0.5, limit="per_spring", springs=400, friction=True):
    """The 1 µm Thornton–Ning sphere (JKR, Δγ = 0.05 J/m², 0.6 m/s) on N springs, with friction."""
    data = yaml.safe_load(open(THORNTON_NING))
    data["contact"] = {"springs": springs}
    data["solver"] = {}
    data["initial"]["angle"] = angle
    data["material"]["G_star"] = G_STAR
    if friction:
        data["effects"]["friction"] = {"coefficient": MU, "limit": limit}
    return data


def balance(result, spin=0.0):
    speed = result.scene.start.velocity
    before = 0.5 * MASS * speed**2 + 0.5 * INERTIA * spin**2
    after = 0.5 * MASS * (result.separation_velocity**2 + result.tangential_velocity_after**2)
    after += 0.5 * INERTIA * result.spin_after**2
    return (before - after - result.dissipated_energy - result.friction_work) / before


@pytest.mark.parametrize("limit", ["per_spring", "thornton"])
def test_adhesive_impacts_keep_their_normal_restitution_and_energy(limit):
    """With JKR adhesion friction still leaves the normal impact bitwise as the frictionless
    array's (the jump-in, the snap-off: e = 0.8176 at θ = 0.5 rad), and the energy balance closes
    to 1e-12 with the adhesion hysteresis in ∮F dd."""
    result = impact.simulate(adhesive(limit=limit))
    plain = impact.simulate(adhesive(friction=False))
    assert result.restitution == plain.restitution and result.contact_time == plain.contact_time
    assert result.restitution == pytest.approx(0.8176, abs=1e-4)
    assert abs(balance(result)) <= 1e-12
    assert result.friction_work > 0.0


def test_the_friction_limits_differ_with_adhesion():
    """Thornton's whole-contact limit μ|F_n + 2F_c| lets the contact carry more tangential force
    than Coulomb's law on the compressed springs alone: at θ = 0.5 rad the Thornton–Ning sphere
    leaves sliding at 0.56 of its tangential speed (per spring: 0.81) and spins more than twice
    as fast."""
    per_spring = impact.simulate(adhesive(limit="per_spring"))
    thornton = impact.simulate(adhesive(limit="thornton"))
    assert per_spring.tangential_restitution == pytest.approx(0.81, abs=0.01)
    assert thornton.tangential_restitution == pytest.approx(0.56, abs=0.01)
    assert thornton.spin_after > 2.0 * per_spring.spin_after


def test_thorntons_limit_bounds_the_tangential_force():
    """Under Thornton's limit (μ = 0.05, θ = 0.6 rad) |Q| ≤ μ(F_n + 2F_c) at every sample in
    contact (F_c = (3/2)πRΔγ; F_n + 2F_c > 0 as JKR lets go at F_n ≥ −F_c), with equality (1e-12
    of μF_c) wherever the whole contact slides (stick radius 0): most of the contact here."""
    data = adhesive(0.6, limit="thornton")
    data["effects"]["friction"]["coefficient"] = 0.05
    result = impact.simulate(data)
    pull_off = 1.5 * math.pi * R * WORK
    touching = result.contact_radius > 0
    most = 0.05 * (result.force[touching] + 2.0 * pull_off)
    force = np.abs(result.tangential_force[touching])
    assert np.all(most > 0.0) and np.all(force <= most + 1e-12 * 0.05 * pull_off)
    sliding = result.stick_radius[touching] == 0.0
    assert np.mean(sliding) > 0.5
    assert np.max(np.abs(force[sliding] - most[sliding])) <= 1e-12 * 0.05 * pull_off


def test_a_captured_body_has_no_tangential_rebound():
    """Below the sticking velocity (0.6 m/s at θ = 1.1 rad: v_n = 0.27 < v_s = 0.303 m/s) the
    body is captured: restitution 0, the tangential results after the first contact nan."""
    result = impact.simulate(adhesive(1.1))
    assert result.status == "captured" and result.restitution == 0.0
    assert math.isnan(result.tangential_velocity_after) and math.isnan(result.rebound_angle)


def test_an_angle_without_friction_only_slows_the_approach():
    """Without friction the normal speed is V·cos θ and nothing tangential is computed: the
    continuum Thornton–Ning impact at θ = 0.5 rad equals the one at V·cos θ head-on (1e-12), and
    the body slides on with V·sin θ."""
    data = yaml.safe_load(open(THORNTON_NING))
    oblique = impact.simulate({**data, "initial": {"velocity": 0.6, "angle": 0.5}})
    head_on = impact.simulate({**data, "initial": {"velocity": 0.6 * math.cos(0.5)}})
    assert oblique.restitution == pytest.approx(head_on.restitution, rel=1e-12, abs=0.0)
    assert oblique.tangential_velocity_after == 0.6 * math.sin(0.5)
    assert oblique.tangential_restitution == 1.0 and oblique.friction_work == 0.0
    assert oblique.rebound_angle == pytest.approx(
        math.atan2(0.6 * math.sin(0.5), oblique.separation_velocity), rel=1e-6, abs=0.0
    )


def test_a_sweep_gives_each_point_its_simulate_result():
    """A sweep over the angle and μ holds the tangential columns, each point's equal to
    `simulate` of its scene to 1e-12."""
    base = adhesive(springs=200)
    result = impact.sweep(base, {"initial.angle": [0.3, 0.6], "effects.friction.coefficient": [0.1, 0.3]})
    assert result.tangential_restitution is not None and result.tangential_restitution.shape == (2, 2)
    for i, angle in enumerate((0.3, 0.6)):
        for j, mu in enumerate((0.1, 0.3)):
            single = adhesive(angle, springs=200)
            single["effects"]["friction"]["coefficient"] = mu
            one = impact.simulate(single, trajectory=False)
            for name in ("tangential_velocity_after", "spin_after", "friction_work", "rebound_angle"):
                assert getattr(result, name)[i, j] == pytest.approx(getattr(one, name), rel=1e-12, abs=0.0), name


def test_run_files_keep_the_tangential_results(tmp_path):
    """run.h5 stores the tangential results and the series Q(t), c(t); they read back equal."""
    result = impact.simulate(adhesive(springs=200))
    again = read_run(write_run(result, tmp_path / "run.h5"))
    for name in ("tangential_velocity_after", "spin_after", "tangential_restitution", "friction_work"):
        assert getattr(again, name) == getattr(result, name), name
    np.testing.assert_array_equal(again.tangential_force, result.tangential_force)
    np.testing.assert_array_equal(again.stick_radius, result.stick_radius)


def test_impact_run_of_the_kharaz_example(tmp_path):
    """`impact run configs/oblique_kharaz.yaml` exits 0 and prints the tangential results."""
    outcome = CliRunner().invoke(app, ["run", "configs/oblique_kharaz.yaml", "-o", str(tmp_path / "run")])
    assert outcome.exit_code == 0, outcome.output
    assert "tangential restitution" in outcome.output and "spin after" in outcome.output
    stored = impact.open_run(tmp_path / "run")
    assert stored.scene.effects.friction is not None and stored.spin_after > 0.0


@pytest.mark.slow
def test_tangential_results_are_differentiable():
    """`impact.as_function` of v_t′ and ω′ against μ and θ (Kharaz example on 200 springs): the
    forward-mode Jacobian (exact on the piece of the spring events and stick–slip pattern the
    point lies on) agrees with central differences of relative step 1e-4 to 1e-8 (measured ≤ 5e-10)."""
    import jax
    import jax.numpy as jnp

    data = yaml.safe_load(open("configs/oblique_kharaz.yaml"))
    data["contact"]["springs"] = 200
    f = impact.as_function(
        data, ["effects.friction.coefficient", "initial.angle"], ["tangential_velocity_after", "spin_after"]
    )
    x = np.array([0.092, 0.5235987755982988])
    jacobian = np.asarray(jax.jacfwd(f)(jnp.asarray(x)))
    for column in range(2):
        step = np.zeros(2)
        step[column] = 1e-4 * x[column]
        central = (np.asarray(f(x + step)) - np.asarray(f(x - step))) / (2 * step[column])
        np.testing.assert_allclose(jacobian[:, column], central, rtol=1e-8)
