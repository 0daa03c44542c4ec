"""`impact fit` of a viscoelastic half-space's Prony term from indentation curves at several rates
(configs/fits/viscoelastic_indentation.yaml, model: theory): the synthetic curves give back
E∞*, E1 and τ within 3 standard errors, the model meets the spring array, and what the closed
forms cannot describe is refused."""

import copy
import math

import numpy as np
import pytest
import yaml

import impact
from impact._run.fit.solve import fit_spec
from impact._run.fit.viscoelastic_curve import viscoelastic_curve_model
from impact._scene.fit_spec import FitError, load_fit, make_fit_spec, read_table
from tests.run.fit.fit_examples import FITS, fit_script

pytestmark = pytest.mark.slow  # fits of their own, compiled for these rates

DATA = fit_script("make_viscoelastic_data")
FIT_FILE = yaml.safe_load((FITS / "viscoelastic_indentation.yaml").read_text())
TRUTH = {
    "material.E_star": DATA.RELAXED,
    "effects.viscoelasticity.prony.0.modulus": DATA.MODULUS,
    "effects.viscoelasticity.prony.0.time": DATA.TIME,
}


@pytest.fixture(scope="module")
def spec():
    return load_fit(FITS / "viscoelastic_indentation.yaml")


@pytest.fixture(scope="module")
def fitted(spec):
    return fit_spec(spec, spec.model)


def test_the_data_file_is_what_its_script_makes():
    columns = read_table(FITS / "viscoelastic_indentation.csv")
    made = DATA.viscoelastic_data()
    for name, column in made.items():
        assert columns[name] == pytest.approx(column, rel=1e-9, abs=1e-18)


def test_three_rates_give_back_the_prony_term(fitted):
    """E∞*, E1, τ within 3 standard errors (each below 0.1 % of its value), χ² within 5σ of its
    degrees of freedom, in at most 15 steps."""
    result = fitted
    assert result.converged and result.iterations <= 15
    for path, true in TRUTH.items():
        assert abs(result.values[path] - true) < 3 * result.standard_errors[path], path
        assert result.standard_errors[path] < 1e-3 * true
    assert result.dof == 3 * DATA.POINTS - 3
    assert abs(result.chi2 - result.dof) < 5 * math.sqrt(2 * result.dof)


def test_the_model_meets_the_spring_array(spec):
    """At the true values the closed form (Lee & Radok, Ting) is the force of 2000 springs
    (to 1e-5 where the force exceeds 5 % of its peak)."""
    model = viscoelastic_curve_model(spec)
    scene = FIT_FILE["scene"]
    true = copy.deepcopy(scene)
    true["material"]["E_star"] = DATA.RELAXED
    true["effects"]["viscoelasticity"]["prony"] = [{"modulus": DATA.MODULUS, "time": DATA.TIME}]
    true["program"]["rate"] = DATA.RATES[1]
    simulated = impact.simulate(true)
    values = np.array(list(TRUTH.values()))
    rows = np.stack([np.full(simulated.time.shape, DATA.RATES[1]), simulated.time, np.zeros_like(simulated.time)], 1)
    closed = np.asarray(model.batched(values, rows))[:, 0]
    checked = closed > 0.05 * closed.max()
    assert np.max(np.abs(simulated.force[checked] / closed[checked] - 1)) < 1e-5


@pytest.mark.parametrize(
    ("change", "field", "message"),
    [
        ({"control": "force"}, "scene.control", "takes displacement control (d linear in time)"),
        ({"body": {"profile": {"shape": "cone", "theta": 0.3}}}, "scene.body.profile.shape", "describes a paraboloid"),
        ({"effects": {"adhesion": {"work_of_adhesion": 0.05}}}, "scene.effects.adhesion", "has no adhesion"),
    ],
)
def test_what_the_closed_forms_cannot_describe_is_refused(change, field, message):
    scene = copy.deepcopy(FIT_FILE["scene"])
    for key, value in change.items():
        scene[key] = {**scene[key], **value} if key == "effects" else value
    data = DATA.viscoelastic_data()
    with pytest.raises(FitError) as error:
        parameters, observables = FIT_FILE["parameters"], FIT_FILE["observables"]
        impact.fit(scene, data, parameters, observables, inputs=["program.rate"], model="theory")
    assert (field, f"model 'theory' of a viscoelastic curve (Lee & Radok, Ting) {message}") in error.value.problems


def test_the_simulation_is_not_the_model():
    with pytest.raises(FitError) as error:
        make_fit_spec(
            FIT_FILE["scene"], DATA.viscoelastic_data(), FIT_FILE["parameters"], FIT_FILE["observables"],
            inputs=["program.rate"], model="simulation",
        )  # fmt: skip
    assert (
        "model",
        "a viscoelastic test at a rate is fitted with model: theory (the closed forms of Lee & Radok and Ting, exact "
        "for a paraboloid under displacement control without adhesion), not through its spring array",
    ) in error.value.problems
