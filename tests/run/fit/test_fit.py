"""`impact.fit`: the Thornton–Ning drop test recovers its parameters within their error bars in
few steps, a linear model meets ordinary least squares exactly, bounds hold, and a combination
the data cannot separate is reported in words."""

import math

import jax.numpy as jnp
import numpy as np
import pytest

import impact
from impact._run.fit.bounds import Bounds
from impact._run.fit.uncertainty import uncertainty
from impact._scene.fit_spec import ParameterSpec
from tests.compilations import Compiles
from tests.run.fit.fit_examples import fit_script
from tests.scenes import CONFIGS

ADHESION, MODULUS = "effects.adhesion.work_of_adhesion", "material.E_star"
PARAMETERS = {
    ADHESION: {"start": 0.02, "min": 1.0e-4, "max": 1.0, "scale": "log"},
    MODULUS: {"start": 5.0e8, "scale": "log"},
}
OBSERVABLES = {"restitution": {"sigma": "restitution_sigma"}, "max_force": {"sigma": 0.02, "relative": True}}


DROPS = fit_script("make_drop_data")


@pytest.fixture(scope="module")
def scene():
    return impact.load_scene(CONFIGS / "thornton_ning.yaml")


@pytest.fixture(scope="module")
def drop_fit(scene):
    return impact.fit(scene, DROPS.drop_data(seed=3), PARAMETERS, OBSERVABLES, ["initial.velocity"], model="theory")


def test_drop_test_recovers_work_of_adhesion_and_modulus_within_three_standard_errors(drop_fit):
    for path, true in ((ADHESION, DROPS.WORK_OF_ADHESION), (MODULUS, DROPS.E_STAR)):
        assert abs(drop_fit.values[path] - true) < 3 * drop_fit.standard_errors[path]
        assert drop_fit.standard_errors[path] < 0.02 * true  # the data do determine it
    assert abs(drop_fit.chi2 - drop_fit.dof) < 5 * math.sqrt(2 * drop_fit.dof)  # χ² of 58 dof
    assert drop_fit.dof == 2 * DROPS.ROWS - 2
    assert drop_fit.unidentifiable == []


def test_two_parameter_fit_to_thirty_points_converges_in_at_most_fifteen_steps(drop_fit):
    assert drop_fit.converged
    assert drop_fit.iterations <= 15


def test_a_second_fit_of_other_data_compiles_nothing(scene, drop_fit):
    moved = {path: {**entry, "start": 2 * entry["start"]} for path, entry in PARAMETERS.items()}
    data = DROPS.drop_data(seed=5)
    with Compiles() as compiles:
        impact.fit(scene, data, moved, OBSERVABLES, ["initial.velocity"], model="theory")
    assert compiles.count == 0


def test_restitution_alone_reports_the_combination_it_fixes(scene):
    data = DROPS.drop_data(seed=4)
    result = impact.fit(
        scene, data, PARAMETERS, {"restitution": OBSERVABLES["restitution"]}, ["initial.velocity"], model="theory"
    )
    # e depends on W ∝ Δγ^(5/3) E*^(-2/3) (3.51) alone: only Δγ·E*^(-2/5) is determined.
    (message,) = result.unidentifiable
    assert message.startswith(f"restitution alone fixes only a combination of {ADHESION} and {MODULUS}")
    assert message.endswith(f"the data determine {ADHESION} · {MODULUS}^-0.4")
    assert all(math.isnan(error) for error in result.standard_errors.values())
    invariant = result.values[ADHESION] * result.values[MODULUS] ** -0.4
    assert invariant == pytest.approx(DROPS.WORK_OF_ADHESION * DROPS.E_STAR**-0.4, rel=0.02, abs=0.0)


def test_a_loosely_bound_parameter_is_reported_in_words():
    """Determined, but with a standard error five times its value (as the Maugis–Dugdale range
    near the JKR limit): said in words, beside its error."""
    jacobian = np.array([[100.0, 0.0], [0.0, 2.0]])  # covariance diag(1e-4, 0.25)
    found = uncertainty(jacobian, np.array([1.0, 0.1]), ["a", "b"], ["force"], 1.0)
    assert found.standard_errors == pytest.approx([0.01, 0.5], rel=1e-12, abs=0.0)
    assert found.unidentifiable == [
        "force alone fixes b only to ±500% of its value (0.1 ± 0.5): the model hardly changes with it, "
        "so fix it or add data that depend on it"
    ]


def _line(x):
    """A model linear in its two parameters: y = p0 + p1·input."""
    return jnp.stack([x[0] + x[1] * x[2]])


@pytest.mark.parametrize("known_sigma", [True, False])
def test_linear_model_meets_ordinary_least_squares(scene, known_sigma):
    rng = np.random.default_rng(7)
    x = np.linspace(0.5, 2.0, 20)
    y = 0.3 + 0.2 * x + 0.01 * rng.standard_normal(x.size)
    linear = {"start": 0.1, "scale": "linear"}
    sigma = {"sigma": 0.01} if known_sigma else {}
    result = impact.fit(
        scene,
        {"initial.velocity": x, "restitution": y},
        {ADHESION: linear, MODULUS: linear},
        {"restitution": sigma},
        ["initial.velocity"],
        model=_line,
    )
    design = np.stack([np.ones_like(x), x], axis=1)
    coefficients, rss, *_ = np.linalg.lstsq(design, y)
    variance = 0.01**2 if known_sigma else rss[0] / (x.size - 2)
    errors = np.sqrt(np.diag(variance * np.linalg.inv(design.T @ design)))
    np.testing.assert_allclose(list(result.values.values()), coefficients, rtol=1e-9)
    np.testing.assert_allclose(list(result.standard_errors.values()), errors, rtol=1e-8)
    assert result.sigma_source.startswith("given" if known_sigma else "scatter")


def _undefined_above_one(x):
    """`_line`, but no number where the input exceeds 1 (as a simulation without a physical outcome)."""
    return jnp.where(x[2] > 1.0, jnp.nan, _line(x))


def test_a_model_without_a_number_at_the_start_is_refused_not_fitted(scene):
    """χ² would be NaN: refused before the solve, the rows named (not a fit "NOT converged")."""
    x = np.linspace(0.5, 2.0, 10)
    with pytest.raises(impact.FitError) as caught:
        impact.fit(
            scene,
            {"initial.velocity": x, "restitution": 0.3 + 0.2 * x},
            {ADHESION: {"start": 0.1}, MODULUS: {"start": 0.1}},
            {"restitution": {"sigma": 0.01}},
            ["initial.velocity"],
            model=_undefined_above_one,
        )
    assert caught.value.problems == [
        (
            "observables.restitution",
            f"the model gives no number at the parameters' start ({ADHESION} = 0.1, {MODULUS} = 0.1) in data rows "
            "5, 6, 7, 8 and 2 more: change the start or the data (with model simulation, the run of such a row ends "
            "without a physical outcome there: `impact run` its scene with the row's inputs to see why)",
        )
    ]


def test_a_bound_holds_where_the_data_pull_beyond_it(scene):
    x = np.linspace(0.5, 2.0, 10)
    result = impact.fit(
        scene,
        {"initial.velocity": x, "restitution": 0.3 + 0.2 * x},
        {ADHESION: {"start": 0.1, "max": 0.25}, MODULUS: {"start": 0.1}},
        {"restitution": {"sigma": 0.01}},
        ["initial.velocity"],
        model=_line,
    )
    assert 0.24 < result.values[ADHESION] < 0.25


def test_bounds_map_back_and_forth():
    specs = {
        "both": ParameterSpec(start=0.3, min=0.1, max=2.0, scale="log"),
        "lower": ParameterSpec(start=-1.0, min=-3.0),
        "upper": ParameterSpec(start=5.0, max=7.0),
        "none": ParameterSpec(start=4.0e9, scale="log"),
    }
    bounds = Bounds.of(specs)
    start = np.array([spec.start for spec in specs.values()])
    np.testing.assert_allclose(np.asarray(bounds.physical(jnp.asarray(bounds.internal(start)))), start, rtol=1e-13)
    far = np.asarray(bounds.physical(jnp.array([20.0, -20.0, -20.0, -20.0])))
    assert 0.1 < far[0] <= 2.0 and far[1] > -3.0 and far[2] < 7.0 and far[3] > 0


@pytest.mark.parametrize(
    ("change", "field", "message"),
    [
        ({"parameters": {"material.E_starr": {"start": 1.0}}}, "parameters.material.E_starr", "no field"),
        ({"inputs": ["solver.rtol"]}, "inputs.solver.rtol", "is a static choice (1e-10; changing it compiles anew)"),
        ({"inputs": ["body.mass"]}, "inputs.body.mass", "no column 'body.mass' in the data"),
        (
            {"parameters": {ADHESION: {"start": 2.0, "max": 1.0}}},
            f"parameters.{ADHESION}.start",
            "2 lies outside the bounds (-inf, 1)",
        ),
        (
            {"observables": {"restitution": {}, "max_force": {"sigma": 0.02}}},
            "observables",
            "give sigma for every observable or for none",
        ),
    ],
)
def test_bad_specifications_name_the_field(scene, change, field, message):
    arguments = {"parameters": PARAMETERS, "observables": OBSERVABLES, "inputs": ["initial.velocity"]} | change
    with pytest.raises(impact.FitError) as caught:
        impact.fit(scene, DROPS.drop_data(), model="theory", **arguments)
    assert any(path == field and message in text for path, text in caught.value.problems), caught.value.problems


def test_a_relative_sigma_of_a_zero_value_is_refused(scene):
    data = DROPS.drop_data()
    data["max_force"][4] = 0.0
    with pytest.raises(impact.FitError) as caught:
        impact.fit(scene, data, PARAMETERS, OBSERVABLES, ["initial.velocity"], model="theory")
    assert caught.value.problems == [("observables.max_force.relative", "σ·|value| is 0 in row 5")]


@pytest.mark.slow
def test_the_simulation_fits_as_the_closed_form_does_and_a_second_fit_reuses_its_programs(scene, drop_fit):
    """model 'simulation' (impact.as_function through Levenberg–Marquardt, vmapped over the rows
    under optimistix's jit) finds the closed-form fit of the same data (`drop_fit`); a second
    fit of the same model compiles nothing."""
    closed_form = drop_fit
    simulated = impact.fit(scene, DROPS.drop_data(seed=3), PARAMETERS, OBSERVABLES, ["initial.velocity"])
    assert simulated.converged and simulated.iterations <= 15
    for path, value in closed_form.values.items():
        assert simulated.values[path] == pytest.approx(value, rel=1e-6, abs=0.0)
        assert simulated.standard_errors[path] == pytest.approx(closed_form.standard_errors[path], rel=1e-4, abs=0.0)
    other = DROPS.drop_data(seed=4)
    with Compiles() as compiles:
        again = impact.fit(scene, other, PARAMETERS, OBSERVABLES, ["initial.velocity"])
    assert compiles.count == 0 and again.converged


def test_progress_reports_every_step_and_ends_at_the_fit(scene):
    """Each Levenberg–Marquardt step is reported (recorded inside the solve, reported after it):
    steps 0, 1, … in order, one per iteration, the last at the optimum with its χ²."""
    reported = []
    result = impact.fit(
        scene,
        DROPS.drop_data(seed=3),
        PARAMETERS,
        OBSERVABLES,
        ["initial.velocity"],
        model="theory",
        progress=lambda step, chi2, values: reported.append((step, chi2, values)),
    )
    assert [step for step, _, _ in reported] == list(range(result.iterations))
    step, chi2, values = reported[-1]
    assert chi2 == pytest.approx(result.chi2, rel=1e-12, abs=0.0)
    assert values == pytest.approx(result.values, rel=1e-14, abs=0.0)
    assert reported[0][1] > 100 * result.chi2  # the start is far from the optimum
