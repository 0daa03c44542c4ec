"""`impact.fit` of a quasi-static indentation curve (the AFM use): the closed-form model meets
the quasi-static march on both branches and under both controls, its derivatives meet central
differences, and the synthetic AFM curve gives back its modulus, work of adhesion and tip radius
within 3 standard errors in at most 15 steps."""

import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest
import yaml

import impact
from impact._run.fit.curve import IndentationCurve
from impact._scene.scene import scene_yaml
from tests.compilations import Compiles
from tests.run.fit.fit_examples import FITS, fit_script

ADHESION, MODULUS, RADIUS = "effects.adhesion.work_of_adhesion", "material.E_star", "body.profile.R"


AFM = fit_script("make_afm_data")
FIT_FILE = yaml.safe_load((FITS / "afm_curve.yaml").read_text())
TRUE_SCENE = {
    **FIT_FILE["scene"],
    "material": {"E_star": AFM.E_STAR},
    "effects": {"adhesion": {"work_of_adhesion": AFM.WORK_OF_ADHESION}},
}


@pytest.fixture(scope="module")
def coverage():
    return fit_script("coverage")


@pytest.fixture(scope="module")
def afm_fit():
    scene = impact.load_scene(FIT_FILE["scene"])
    arguments = (scene, AFM.afm_data(seed=3), FIT_FILE["parameters"], FIT_FILE["observables"])
    return arguments, impact.fit(*arguments, model="theory", branch="branch")


def test_afm_curve_recovers_modulus_and_work_of_adhesion_within_three_standard_errors(coverage):
    """One repetition of configs/fits/coverage.py afm_curve (100 seeds: all within 3σ)."""
    pulls, steps = coverage.pulls("afm_curve", [0])
    assert np.all(np.abs(pulls) < 3), pulls
    assert steps[0] <= 15


def test_afm_fit_converges_in_at_most_fifteen_steps_with_tight_error_bars(afm_fit):
    _, result = afm_fit
    assert result.converged and result.iterations <= 15
    for path, true in ((ADHESION, AFM.WORK_OF_ADHESION), (MODULUS, AFM.E_STAR)):
        assert abs(result.values[path] - true) < 3 * result.standard_errors[path]
        assert result.standard_errors[path] < 0.01 * true
    assert result.dof == 2 * AFM.POINTS - 2
    assert abs(result.chi2 - result.dof) < 5 * math.sqrt(2 * result.dof)


def test_rows_in_program_order_need_no_branch_column(afm_fit):
    """Without `branch` the rows up to the deepest indentation are the approach: the same fit,
    from the programs already compiled."""
    arguments, labelled = afm_fit
    scene, data, parameters, observables = arguments
    unlabelled = {name: column for name, column in data.items() if name != "branch"}
    with Compiles() as compiles:
        result = impact.fit(scene, unlabelled, parameters, observables, model="theory")
    assert compiles.count == 0
    assert result.values == labelled.values


@pytest.mark.slow
def test_the_tip_radius_is_recovered_with_a_known_modulus():
    parameters = {RADIUS: {"start": 2.0e-8, "scale": "log"}, ADHESION: FIT_FILE["parameters"][ADHESION]}
    result = impact.fit(
        TRUE_SCENE, AFM.afm_data(seed=4), parameters, FIT_FILE["observables"], model="theory", branch="branch"
    )
    assert result.converged and result.iterations <= 15
    for path, true in ((RADIUS, AFM.RADIUS), (ADHESION, AFM.WORK_OF_ADHESION)):
        assert abs(result.values[path] - true) < 3 * result.standard_errors[path]
        assert result.standard_errors[path] < 0.02 * true


@pytest.mark.slow
@pytest.mark.parametrize("control", ["displacement", "force"])
def test_the_closed_form_curve_meets_the_quasi_static_march(control):
    """Every state of the simulated test in contact (jump-in, both branches) against the model
    at its control value and branch; the pull-off state, where the contact ends, is left out."""
    peak = 3.0e-9 if control == "displacement" else 6.0e-8
    scene = impact.load_scene({**TRUE_SCENE, "control": control, "program": {"peak": peak}})
    run = impact.simulate(scene)
    assert run.status == "separated"
    controlled, observed = ("indentation", "force") if control == "displacement" else ("force", "indentation")
    model = IndentationCurve(scene_yaml(scene), (), (observed, "contact_radius"))
    in_contact = np.flatnonzero(run.contact_radius > 0)[:-1]  # the last: the pull-off state
    values, legs = getattr(run, controlled)[in_contact], run.leg[in_contact]
    values = np.where(legs == 0, np.maximum(values, 0.0), values)  # the jump-in lands at d = −8e-25
    points = np.stack([values, legs.astype(float)], axis=1)
    with jax.enable_x64(True):
        states = np.asarray(jax.vmap(model)(jnp.asarray(points)))
    np.testing.assert_allclose(states[:, 0], getattr(run, observed)[in_contact], rtol=1e-8, atol=1e-8 * peak)
    np.testing.assert_allclose(states[:, 1], run.contact_radius[in_contact], rtol=1e-8)
    assert in_contact.size > 40 and set(run.leg[in_contact]) == {0, 1}


def test_the_model_derivatives_meet_central_differences():
    """d force / d(E*, Δγ, R) on the retract branch near the pull-off (the implicit root)."""
    model = IndentationCurve(scene_yaml(impact.load_scene(TRUE_SCENE)), (MODULUS, ADHESION, RADIUS), ("force",))
    true = np.array([AFM.E_STAR, AFM.WORK_OF_ADHESION, AFM.RADIUS])
    steps = 1e-6 * true * np.eye(3)
    with jax.enable_x64(True):

        def force(values):
            return model(jnp.concatenate([values, jnp.array([-1.0e-9, 1.0])]))[0]

        exact = np.asarray(jax.jit(jax.jacfwd(force))(jnp.asarray(true)))
        shifted = np.asarray(
            jax.jit(jax.vmap(force))(jnp.asarray(np.concatenate([true + steps, true - steps, [true]])))
        )
    central = (shifted[:3] - shifted[3:6]) / (2 * np.diag(steps))
    assert shifted[6] < 0  # on the adhesive part of the retract branch
    np.testing.assert_allclose(exact, central, rtol=1e-6)
