"""Damping in impacts: the flat punch against the exact linear spring–dashpot, the viscoelastic
paraboloid against Schwager & Pöschel's series, convergence under tolerance refinement, the
energy balance with adhesion, the overdamped contact, the damped drop, traced parameters and
refusals."""

import math

import equinox as eqx
import h5py
import jax
import jax.numpy as jnp
import numpy as np
import pytest
import yaml
from typer.testing import CliRunner

import impact
from impact import simulate, theory
from impact._io.run import read_run, write_run
from impact._run.impacts import solve_scene
from impact._run.parameters import integrator_for, options_for
from impact.cli import app

R, MASS, E_STAR, SPEED = 1e-2, 1e-3, 1e7, 1.0  # a 1 g paraboloid on a soft polymer at 1 m/s
PUNCH = 1e-3  # flat punch radius (m): stiffness k = 2E*a = 2e4 N/m
UNIT_BETA = float(theory.viscoelastic_beta(1.0, MASS, R, E_STAR))  # β per second of A
C1 = 1.0 - float(theory.viscoelastic_restitution_first_order(1.0, 1.0))


def scene(damping: dict, shape: str = "paraboloid", **effects) -> dict:
    profile = {"shape": "paraboloid", "R": R} if shape == "paraboloid" else {"shape": "flat_punch", "radius": PUNCH}
    return {
        "body": {"profile": profile, "mass": MASS},
        "material": {"E_star": E_STAR},
        "initial": {"velocity": SPEED},
        "effects": {"damping": damping, **effects},
    }


def viscoelastic(constant: float) -> dict:
    return {"model": "viscoelastic", "dissipative_constant": constant}


def undamped(damping: dict) -> dict:
    """The same damping model with a zero coefficient: no damping, run by the damped program."""
    coefficient = "coefficient" if damping["model"] == "linear" else "dissipative_constant"
    return {**damping, coefficient: 0.0}


def simulate_at_tolerance(data: dict, rtol: float) -> impact.Result:
    """`simulate(data)` with the tolerances traced (rtol, atol = rtol/100, as
    the default 1e-10, 1e-12): one compiled program serves every tolerance and every value of
    the scene's traced fields."""
    loaded = impact.load_scene(data)
    tolerances = (jnp.asarray(rtol), jnp.asarray(rtol * 1e-2))
    integrator = eqx.tree_at(lambda solver: (solver.rtol, solver.atol), integrator_for(loaded), tolerances)
    return solve_scene(loaded, integrator, options_for(loaded, trajectory=False))


def kinetic_energy_lost(result) -> float:
    return 0.5 * MASS * (result.touch_velocity**2 - result.separation_velocity**2)


def test_first_order_coefficient_is_schwager_poeschels():
    assert C1 == pytest.approx(1.15345, abs=5e-6)  # Γ(3/5)√π/(2^(1/5)5^(2/5)Γ(21/10))


@pytest.mark.slow
@pytest.mark.parametrize(
    ("damping", "ratio"),
    [
        ({"model": "linear", "coefficient": 2.0}, 2.0 / (2 * math.sqrt(2 * E_STAR * PUNCH * MASS))),  # ζ = 0.224
        (viscoelastic(1e-5), 2 * E_STAR * PUNCH * 1e-5 / (2 * math.sqrt(2 * E_STAR * PUNCH * MASS))),  # ζ = 0.022
        ({"model": "linear", "coefficient": 20.0}, 20.0 / (2 * math.sqrt(2 * E_STAR * PUNCH * MASS))),  # ζ = 2.24
    ],
    ids=["linear", "viscoelastic", "overdamped"],
)
def test_flat_punch_is_the_exact_spring_dashpot(damping, ratio, tmp_path):
    # A flat punch on the MDR foundation is a linear spring k = 2E*a; both models damp it
    # linearly (c, or 2E*a·A), and the contact ends where k·x + c·ẋ = 0.
    result = simulate(scene(damping, "flat_punch"))
    stiffness = 2 * E_STAR * PUNCH
    e = float(theory.dashpot_restitution(ratio))
    assert result.status == "separated"
    assert result.restitution == pytest.approx(e, rel=1e-9, abs=0.0)
    assert result.contact_time == pytest.approx(
        float(theory.dashpot_contact_time(ratio, stiffness, MASS)), rel=1e-6, abs=0.0
    )
    # Energy: the kinetic energy lost is ∫F dd, of which the spring keeps ½k·x_s² at the release
    # (x_s = c·e·v₀/k, where the force vanishes) and the dashpot dissipated the rest.
    energy = 0.5 * MASS * SPEED**2
    coefficient = ratio * 2 * math.sqrt(stiffness * MASS)
    stored = 0.5 * stiffness * (coefficient * e * SPEED / stiffness) ** 2
    assert abs(kinetic_energy_lost(result) - result.dissipated_energy) <= 1e-10 * energy
    assert result.viscous_work == pytest.approx(energy * (1 - e**2) - stored, rel=1e-8, abs=0.0)
    assert result.unrecovered_elastic_energy == pytest.approx(stored, rel=1e-6, abs=0.0)
    # run.h5 keeps them beside the other energies (no adhesion named: no hysteresis)
    assert read_run(write_run(result, tmp_path / "run.h5")).viscous_work == result.viscous_work
    with h5py.File(tmp_path / "run.h5", "r") as file:
        assert file["observables/unrecovered_elastic_energy"][()] == result.unrecovered_elastic_energy
        assert "adhesion_hysteresis" not in file["observables"]


@pytest.mark.slow
def test_viscoelastic_paraboloid_follows_schwager_poeschel():
    # 1 − e = C1·x(1 − (C2/C1)·x + …), x = βv₀^(1/5): the relative error of the first order
    # shrinks like x itself as A → 0, with C2 ≈ 0.798 (Ramírez et al., Phys. Rev. E 60, 4465 (1999)).
    # At the default tolerance, by the program of the next test (traced tolerances).
    orders = np.array([1e-4, 1e-3, 1e-2])
    relative = []
    energy = 0.5 * MASS * SPEED**2
    for x in orders:
        result = simulate_at_tolerance(scene(viscoelastic(x / UNIT_BETA)), 1e-10)
        assert result.status == "separated"
        assert [kind for _, kind in result.events] == ["touch", "max_indentation", "separation"]
        # loading is stiffer than Hertz: the total force peaks above Hertz's at the turn
        assert result.max_force > float(4 / 3 * E_STAR * math.sqrt(R) * result.max_indentation**1.5)
        # ∫F dd is the kinetic energy lost; the viscous work is most of it (the rest stays in
        # the springs released before the indentation returns to zero)
        assert abs(kinetic_energy_lost(result) - result.dissipated_energy) <= 1e-10 * energy
        assert 0.9 * result.dissipated_energy < result.viscous_work < result.dissipated_energy
        first_order = float(theory.viscoelastic_restitution_first_order(SPEED, x))
        relative.append((1 - result.restitution) / (1 - first_order) - 1)
    relative = np.array(relative)
    slopes = np.diff(np.log(-relative)) / np.diff(np.log(orders))
    assert np.all(np.abs(slopes - 1.0) < 0.02), slopes
    assert -relative[0] / orders[0] * C1 == pytest.approx(0.798, abs=0.01)


@pytest.mark.slow
def test_strong_damping_converges_under_tolerance_refinement():
    # βv₀^(1/5) = 1: no series applies; the restitution converges as rtol falls (one program:
    # the tolerances are traced).
    def restitution(rtol):
        result = simulate_at_tolerance(scene(viscoelastic(1.0 / UNIT_BETA)), rtol)
        return result.separation_velocity / result.touch_velocity

    values = np.array([restitution(rtol) for rtol in (1e-6, 1e-8, 1e-10, 1e-12)])
    changes = np.abs(np.diff(values))
    assert 0.2 < values[-1] < 0.7
    assert changes[1] < changes[0] and changes[2] < changes[1]
    assert changes[2] < 1e-9


@pytest.mark.slow
@pytest.mark.parametrize("damping", [viscoelastic(1e-4), {"model": "linear", "coefficient": 0.3}])
def test_adhesive_damped_energy_balance_closes(damping):
    def adhesive(damping: dict) -> dict:
        return scene(damping, adhesion={"work_of_adhesion": 0.5}) | {"initial": {"velocity": 0.05}}

    result = simulate(adhesive(damping))
    free = simulate(adhesive(undamped(damping)))  # the damped run's program
    assert result.status == "separated"
    assert result.min_force < 0  # the adhesive pull before the Heß rule lets go
    assert result.restitution < free.restitution
    energy = 0.5 * MASS * result.touch_velocity**2
    assert abs(kinetic_energy_lost(result) - result.dissipated_energy) <= 1e-9 * energy
    assert result.viscous_work > 0


@pytest.mark.slow
def test_an_overdamped_contact_has_a_named_status():
    # Adhesion with A = 1 s: the body creeps into the adhesive equilibrium without ever turning.
    adhesive = scene(viscoelastic(1.0), adhesion={"work_of_adhesion": 0.5})
    adhesive["initial"]["velocity"] = 0.05
    result = simulate(adhesive)
    assert result.status == "overdamped"
    assert math.isnan(result.restitution)
    assert not result.success


@pytest.mark.slow
def test_a_damped_drop_comes_to_rest():
    dropped = scene(viscoelastic(3e-4), gravity={"g": 9.81})
    dropped["initial"] = {"velocity": 0.0, "gap": 1e-4}
    result = simulate(dropped)
    assert result.status == "captured"
    assert result.bounces >= 2
    assert result.restitution > 0  # the first contact let go


@pytest.mark.slow
def test_damping_parameters_are_traced_inputs():
    # de/dc of the flat punch against the derivative of the exact spring–dashpot
    f = impact.as_function(
        scene({"model": "linear", "coefficient": 2.0}, "flat_punch"), ["effects.damping.coefficient"], "restitution"
    )
    stiffness = 2 * E_STAR * PUNCH
    exact = jax.grad(lambda c: theory.dashpot_restitution(c / (2 * jnp.sqrt(stiffness * MASS))))(2.0)
    assert float(jax.grad(lambda x: f(x))(jnp.array([2.0]))[0]) == pytest.approx(float(exact), rel=1e-7, abs=0.0)


@pytest.mark.parametrize(
    ("effects", "field", "message"),
    [
        ({"damping": viscoelastic(-1e-3)}, "effects.damping.dissipative_constant", "-0.001 s is outside"),
        ({"damping": {"model": "linear", "coefficient": -1.0}}, "effects.damping.coefficient", "is outside"),
        ({"damping": {"model": "kelvin", "coefficient": 1.0}}, "effects.damping.model", "viscoelastic"),
        ({"damping": {"model": "linear"}}, "effects.damping.coefficient", "missing (required for model 'linear')"),
        (
            {"damping": {"model": "linear", "coefficient": 1.0, "dissipative_constant": 1e-3}},
            "effects.damping.dissipative_constant",
            "not for model 'linear'",
        ),
        (
            {"damping": viscoelastic(1e-3), "plasticity": {"yield_pressure": 1e6}},
            "effects.damping",
            "not with effects.plasticity",
        ),
        (
            {
                "damping": viscoelastic(1e-3),
                "adhesion": {"model": "maugis_dugdale", "work_of_adhesion": 0.1, "stress": 1e6},
            },
            "effects.damping",
            "JKR",
        ),
    ],
)
def test_bad_damping_is_refused_naming_the_field(effects, field, message):
    data = scene({})
    data["effects"] = effects
    with pytest.raises(impact.SceneError) as error:
        impact.load_scene(data)
    problems = dict(error.value.problems)
    assert field in problems, problems
    assert message in problems[field]


def test_spring_arrays_refuse_damping():
    data = scene(viscoelastic(1e-4))
    data["contact"] = {"springs": 100}
    with pytest.raises(impact.SceneError) as error:
        impact.load_scene(data)
    why = dict(error.value.problems)["effects.damping"]
    assert why == "runs on the continuum law only (contact.springs: continuum)"


def test_validate_names_the_damping(tmp_path):
    path = tmp_path / "damped.yaml"
    path.write_text(yaml.safe_dump({"name": "damped", **scene(viscoelastic(1e-4))}))
    result = CliRunner().invoke(app, ["validate", str(path)])
    assert result.exit_code == 0, result.output
    assert "viscoelastic damping (A = 0.0001 s)" in " ".join(result.output.split())


def test_dashpot_closed_form_limits():
    # light damping: e = 1 − πζ + O(ζ²); continuous through critical damping (e = exp(−2))
    assert float(theory.dashpot_restitution(1e-6)) == pytest.approx(1 - math.pi * 1e-6, abs=1e-11)
    near = theory.dashpot_restitution(jnp.array([1 - 1e-5, 1 - 1e-7, 1.0, 1 + 1e-7, 1 + 1e-5]))
    assert np.allclose(near, math.exp(-2.0), rtol=1e-4, atol=0.0)
    assert np.all(np.diff(np.asarray(near)) < 0)
    # heavy damping: e = exp(−2ζ·arcosh ζ/√(ζ² − 1)) → 1/(4ζ²)
    assert 4 * 100.0**2 * float(theory.dashpot_restitution(100.0)) == pytest.approx(1.0, abs=1e-3)
    time = theory.dashpot_contact_time(jnp.array([0.0, 1.0]), 4.0, 1.0)  # ω₀ = 2
    assert np.allclose(time, [math.pi / 2, 1.0], rtol=1e-12, atol=0.0)
