"""The fixed-step velocity Verlet on the spring array (impact.verlet): first order in Δt against
the exact event-driven model of the same array, its discrete energy balance, and the scene
switch `solver: {method: verlet, dt}`."""

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
import pytest
from typer.testing import CliRunner

from impact import simulate, theory
from impact._integrate.problem import build_problem
from impact._integrate.springs import SpringArray, build_array
from impact._integrate.verlet import Verlet
from impact._law.springs import Attached
from impact._run.parameters import options_for, physics_for
from impact._run.programs import solve
from impact._scene.scene import load_scene, scene_yaml
from impact.cli import app
from tests.scenes import E_STAR, MASS, WORK, R, micro_sphere

COUNT = 300
STEPS = np.geomspace(1e-2, 1e-5, 13)  # scaled time


def scene(velocity_factor=2.0, effects=None, **extra):
    """The micro-sphere at `velocity_factor` times its sticking velocity, JKR unless `effects`."""
    v_s = float(theory.thornton_ning_sticking_velocity(MASS, R, E_STAR, WORK))
    effects = {"adhesion": {"work_of_adhesion": WORK}} if effects is None else effects
    return micro_sphere(velocity_factor * v_s, effects, name="verlet", **extra)


@pytest.fixture(scope="module")
def sweep():
    """Exact model and Verlet over Δt (one compile each), Thornton–Ning at 2·v_s, N = 300."""
    loaded = load_scene(scene())
    physics = physics_for(loaded)
    options = options_for(loaded, trajectory=False)
    physics = eqx.tree_at(lambda p: p.spring_count, physics, jnp.asarray(float(COUNT)))
    _, exact = solve(SpringArray(), physics, options)
    problem = build_problem(physics, options)
    stepped = jax.jit(lambda p, step: Verlet(dt=step * problem.scales.time).solve(p, options)[1])
    outcomes = [stepped(physics, jnp.asarray(step)) for step in STEPS]
    array = build_array(problem, COUNT, jnp.nan)
    jump_in = array.cascade(Attached.none(), 0.0, True)
    touch_acceleration = float(-array.force(jump_in, 0.0))
    return exact, outcomes, touch_acceleration


def restitution(outcome):
    return float(outcome.separation_velocity) / float(outcome.touch_velocity)


@pytest.mark.slow
def test_every_step_size_separates(sweep):
    _, outcomes, _ = sweep
    assert all(int(o.status) == 0 for o in outcomes)  # separated
    assert [int(o.steps) for o in outcomes] == sorted(int(o.steps) for o in outcomes)


def test_first_order_in_dt_against_the_exact_discrete_model(sweep):
    """|e_verlet − e_exact| ≈ C·Δt: fitted order 0.8–1.2 over three decades (measured: 1.0–1.1;
    the error is noisy, each attach or detach lands anywhere in its step), and below 0.3·Δt."""
    exact, outcomes, _ = sweep
    errors = np.abs([restitution(o) - restitution(exact) for o in outcomes])
    order = np.polyfit(np.log(STEPS), np.log(errors), 1)[0]
    assert 0.8 <= order <= 1.2, order
    assert np.all(errors <= 0.3 * STEPS), errors / STEPS


def test_discrete_energy_balance_is_exact(sweep):
    """Velocity Verlet's identity: KE lost = Σ ½(F + F')·Δd + ⅛Δt²(a_touch² − a_end²), to round-off.

    ∮F dd is summed with the mean of the two forces each step's kicks use; a_end = 0 once the
    last spring let go (no gravity)."""
    _, outcomes, touch_acceleration = sweep
    for step, outcome in zip(STEPS, outcomes, strict=True):
        lost = 0.5 * (float(outcome.touch_velocity) ** 2 - float(outcome.separation_velocity) ** 2)
        balance = float(outcome.first_contact_work) + step**2 / 8.0 * touch_acceleration**2
        assert lost == pytest.approx(balance, rel=1e-11, abs=1e-13), step


def test_loop_work_converges_to_the_exact_dissipation(sweep):
    """The loop area of the stepped path tends to the exact model's at first order."""
    exact, outcomes, _ = sweep
    work = float(exact.first_contact_work)
    errors = np.abs([float(o.first_contact_work) - work for o in outcomes]) / work
    assert np.all(errors <= 5.0 * STEPS), errors / STEPS
    assert errors[-1] < 1e-3


@pytest.mark.slow
def test_scene_runs_verlet_with_its_step_in_seconds():
    """`solver: {method: verlet, dt}` with `contact.springs` runs the same stepper (dt in s)."""
    loaded = load_scene(scene())
    physics = physics_for(loaded)
    options = options_for(loaded, trajectory=False)
    time_unit = float(build_problem(physics, options).scales.time)
    step = 1e-3
    result = simulate(scene(solver={"method": "verlet", "dt": step * time_unit}, contact={"springs": COUNT}))
    arrayed = eqx.tree_at(lambda p: p.spring_count, physics, jnp.asarray(float(COUNT)))
    direct = jax.jit(lambda p: Verlet(dt=step * time_unit).solve(p, options)[1])(arrayed)
    assert result.status == "separated"
    assert result.restitution == pytest.approx(restitution(direct), rel=1e-12, abs=0.0)
    assert result.stats["steps"] == int(direct.steps)
    assert [kind for _, kind in result.events] == ["touch", "max_indentation", "separation"]
    # The trajectory is thinned evenly into the rows it has, in time order.
    assert len(result.t) > 1000 and np.all(np.diff(result.t) >= 0)
    assert result.contact_time == pytest.approx(result.events[-1][0] - result.events[0][0], rel=1e-6, abs=0.0)


@pytest.mark.slow
def test_without_adhesion_the_bounce_is_elastic():
    """Δγ = 0: e → 1 and the Hertz contact time, to the spatial and time-stepping errors."""
    velocity = 0.5
    data = scene(effects={}, initial={"velocity": velocity}, contact={"springs": 2000})
    probe = load_scene(data)
    time_unit = float(build_problem(physics_for(probe), options_for(probe)).scales.time)
    data["solver"] = {"method": "verlet", "dt": 1e-4 * time_unit}
    result = simulate(data)
    assert result.status == "separated"
    assert result.restitution == pytest.approx(1.0, abs=1e-3)
    assert result.contact_time == pytest.approx(
        float(theory.hertz_contact_time(velocity, MASS, R, E_STAR)), rel=1e-3, abs=0.0
    )


@pytest.mark.slow
def test_below_the_sticking_velocity_verlet_captures():
    data = scene(0.5, contact={"springs": COUNT}, solver={"method": "verlet", "dt": 1e-11})
    result = simulate(data)
    assert result.status == "captured" and result.stuck and result.restitution == 0.0


def test_validate_prints_the_verlet_step_not_tolerances(tmp_path):
    path = tmp_path / "verlet.yaml"
    path.write_text(scene_yaml(load_scene(scene(solver={"method": "verlet", "dt": 1e-12}, contact={"springs": COUNT}))))
    result = CliRunner().invoke(app, ["validate", str(path)])
    assert result.exit_code == 0
    assert "verlet, dt 1e-12 s" in result.output and "rtol" not in result.output
