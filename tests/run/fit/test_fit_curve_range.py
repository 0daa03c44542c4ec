"""`impact.fit` of AFM curves with attach hysteresis (Δγa < Δγ) and with adhesion of finite range
(Maugis–Dugdale): the closed-form model meets the quasi-static march on approach and retract,
its derivatives meet central differences, a hysteresis fit recovers both works of adhesion
within 3 standard errors, and what the model cannot describe is refused by name."""

import jax
import jax.numpy as jnp
import numpy as np
import pytest
import yaml

import impact
from impact._run.fit.curve import IndentationCurve
from impact._scene.scene import scene_yaml
from tests.run.fit.fit_examples import FITS, fit_script

ADHESION, APPROACH, MODULUS = (
    "effects.adhesion.work_of_adhesion",
    "effects.adhesion.approach_work_of_adhesion",
    "material.E_star",
)
RANGE = "effects.adhesion.range"


MAUGIS = fit_script("make_maugis_data")
MAUGIS_FIT = yaml.safe_load((FITS / "afm_maugis.yaml").read_text())
MAUGIS_SCENE = {
    **MAUGIS_FIT["scene"],
    "material": {"E_star": MAUGIS.E_STAR},
    "effects": {
        "adhesion": {"model": "maugis_dugdale", "work_of_adhesion": MAUGIS.WORK_OF_ADHESION, "range": MAUGIS.RANGE}
    },
}


def hysteresis_scene(control: str, approach: float) -> dict:
    """A 50 nm paraboloid, Δγ = 0.1 J/m² and the approach work of adhesion `approach`."""
    return {
        "name": "hysteresis",
        "kind": "indentation",
        "control": control,
        "program": {"peak": 3.0e-9 if control == "displacement" else 6.0e-8},
        "body": {"profile": {"shape": "paraboloid", "R": 5.0e-8}},
        "material": {"E_star": 0.8e9},
        "effects": {"adhesion": {"work_of_adhesion": 0.1, "approach_work_of_adhesion": approach}},
    }


def single_points(values: np.ndarray) -> np.ndarray:
    """Indices of the march's points whose control value occurs once (a jump shows as two points
    at one value: its two states, of which the model gives the one on the row's branch)."""
    _, index, counts = np.unique(values, return_index=True, return_counts=True)
    return np.sort(index[counts == 1])


@pytest.mark.slow
@pytest.mark.parametrize(("control", "approach"), [("displacement", 0.03), ("displacement", 0.0), ("force", 0.03)])
def test_the_hysteresis_curve_meets_the_quasi_static_march(control, approach):
    """Approach on the Δγa branch (jump-in at touch, or Hertz from a = 0 for Δγa = 0), the hold
    at a_max after the peak, the detach criterion and the Δγ branch down to the pull-off: every
    state of the march in contact to 1e-8 (measured: 2e-14)."""
    scene = impact.load_scene(hysteresis_scene(control, approach))
    run = impact.simulate(scene)
    controlled, observed = ("indentation", "force") if control == "displacement" else ("force", "indentation")
    in_contact = np.flatnonzero(run.contact_radius > 0)[:-1]  # the last: the pull-off state
    values, legs = getattr(run, controlled)[in_contact], run.leg[in_contact]
    values = np.where(legs == 0, np.maximum(values, 0.0), values)  # the jump-in lands at d = −1e-24
    model = IndentationCurve(scene_yaml(scene), (), (observed, "contact_radius"))
    with jax.enable_x64(True):
        states = np.asarray(model.batched(jnp.zeros(0), jnp.asarray(np.stack([values, legs], axis=1), float)))
    expected = getattr(run, observed)[in_contact]
    np.testing.assert_allclose(states[:, 0], expected, rtol=1e-8, atol=1e-8 * np.abs(expected).max())
    np.testing.assert_allclose(states[:, 1], run.contact_radius[in_contact], rtol=1e-8)
    held = (legs == 1) & (run.contact_radius[in_contact] == run.max_contact_radius)
    assert held.sum() > 5 and set(legs) == {0, 1}  # the hold after the peak is tested


@pytest.mark.slow
def test_a_hysteresis_fit_recovers_both_works_of_adhesion_within_three_standard_errors():
    """Data: the march at Δγa = 0.03, Δγ = 0.1 J/m² (40 states on approach, 40 on retract) with
    Gaussian noise of 0.5 nN; Δγa and Δγ fitted from afar."""
    scene = impact.load_scene(hysteresis_scene("displacement", 0.03))
    run = impact.simulate(scene)
    points = single_points(run.indentation)
    points = points[run.contact_radius[points] > 0]
    rows = np.concatenate(
        [points[run.leg[points] == leg][:: max(1, np.sum(run.leg[points] == leg) // 40)] for leg in (0, 1)]
    )
    noise = np.random.default_rng(5).standard_normal(rows.size) * 0.5e-9
    data = {
        "indentation": run.indentation[rows],
        "force": run.force[rows] + noise,
        "branch": np.where(run.leg[rows] == 1, "retract", "approach"),
    }
    parameters = {
        APPROACH: {"start": 0.01, "min": 1.0e-4, "max": 1.0, "scale": "log"},
        ADHESION: {"start": 0.05, "min": 1.0e-4, "max": 1.0, "scale": "log"},
    }
    start = hysteresis_scene("displacement", 0.01) | {
        "effects": {"adhesion": {"work_of_adhesion": 0.05, "approach_work_of_adhesion": 0.01}}
    }
    result = impact.fit(start, data, parameters, {"force": {"sigma": 0.5e-9}}, model="theory", branch="branch")
    assert result.converged and result.iterations <= 15
    for path, true in ((APPROACH, 0.03), (ADHESION, 0.1)):
        assert abs(result.values[path] - true) < 3 * result.standard_errors[path], result.values
        assert result.standard_errors[path] < 0.05 * true


TRUE_MAUGIS = np.array([MAUGIS.E_STAR, MAUGIS.WORK_OF_ADHESION, MAUGIS.RANGE])
# Where the derivatives are checked: on approach in compression, on retract where F is adhesive.
DERIVATIVE_ROWS = np.array([[1.8e-9, 0.0], [-0.2e-9, 1.0], [-0.9e-9, 1.0]])


@pytest.fixture(scope="module")
def maugis():
    """The march of the example's true scene, its states that are no jump (the snap-in at d = −h
    left out too), the example's data rows and `DERIVATIVE_ROWS`: and the model's values and
    Jacobian in E*, Δγ and h at all of them, one compiled program (one shape) for every value."""
    run = impact.simulate(impact.load_scene(MAUGIS_SCENE))
    points = single_points(run.indentation)
    points = points[~np.isclose(run.indentation[points], -MAUGIS.RANGE, rtol=1e-9, atol=0.0)]
    data = MAUGIS.maugis_data()
    rows = np.concatenate(
        [
            np.stack([run.indentation[points], run.leg[points]], axis=1),
            data_rows_of(data),
            DERIVATIVE_ROWS,
        ]
    ).astype(float)
    model = IndentationCurve(
        scene_yaml(impact.load_scene(MAUGIS_SCENE)), (MODULUS, ADHESION, RANGE), ("force", "contact_radius")
    )

    def twice(values):
        states = model.batched(values, rows)
        return states, states

    with jax.enable_x64(True):
        compiled = jax.jit(jax.jacfwd(twice, has_aux=True))  # the Jacobian, and the values as its aux

    def evaluate(values):
        with jax.enable_x64(True):
            jacobian, states = compiled(jnp.asarray(values))
        return np.asarray(states), np.asarray(jacobian)

    return run, points, data_rows_of(data), evaluate


def data_rows_of(data) -> np.ndarray:
    return np.stack([data["indentation"], data["branch"] == "retract"], axis=1).astype(float)


@pytest.mark.slow
def test_the_maugis_curve_meets_the_march_and_the_closed_form(maugis):
    """Every state of the march that is no jump (to 1e-8; measured 1e-14), and the force of
    make_maugis_data.py (brentq on (3.171)) at its rows."""
    run, points, data_rows, evaluate = maugis
    assert run.status == "separated"
    states, _ = evaluate(TRUE_MAUGIS)
    march, closed = states[: len(points)], states[len(points) : len(points) + len(data_rows), 0]
    np.testing.assert_allclose(march[:, 0], run.force[points], rtol=1e-8, atol=1e-8 * np.abs(run.force).max())
    np.testing.assert_allclose(march[:, 1], run.contact_radius[points], rtol=1e-8, atol=1e-8 * run.contact_radius.max())
    exact = [MAUGIS.maugis_curve_force(d, back) for d, back in data_rows]
    np.testing.assert_allclose(closed, exact, rtol=1e-8, atol=1e-8 * np.abs(exact).max())
    assert np.sum(run.force[points] < 0) > 10 and set(run.leg[points]) == {0, 1}


@pytest.mark.slow
def test_the_maugis_derivatives_meet_central_differences(maugis):
    """d(F, a)/d(E*, Δγ, h) by nested implicit roots, on approach in compression and on retract
    where the force is adhesive, against central differences of the model (steps 1e-6)."""
    *_, evaluate = maugis
    count = len(DERIVATIVE_ROWS)
    states, jacobian = (part[-count:] for part in evaluate(TRUE_MAUGIS))
    steps = 1e-6 * TRUE_MAUGIS * np.eye(3)
    shifted = [evaluate(TRUE_MAUGIS + sign * step)[0][-count:] for step in steps for sign in (1, -1)]
    central = np.stack([(shifted[2 * i] - shifted[2 * i + 1]) / (2 * steps[i, i]) for i in range(3)], axis=-1)
    assert states[0, 0] > 0 and np.all(states[1:, 0] < 0)
    scale = np.abs(central).max(axis=0, keepdims=True)  # per observable and parameter
    np.testing.assert_allclose(jacobian / scale, central / scale, rtol=1e-5, atol=1e-9)


def test_what_the_maugis_curve_cannot_describe_is_refused_by_name():
    """Force control (its landings at constant force are not modelled), and a field the scene
    leaves out (it gives the range h, not the stress σ0)."""
    data = MAUGIS.maugis_data()
    scene = MAUGIS_SCENE | {"control": "force", "program": {"peak": 1.0e-8}}
    with pytest.raises(impact.FitError) as caught:
        impact.fit(scene, data, MAUGIS_FIT["parameters"], {"indentation": {}}, model="theory", branch="branch")
    assert caught.value.problems == [
        ("scene.control", "model 'theory' of a maugis_dugdale curve takes displacement control only")
    ]
    stress = {"effects.adhesion.stress": {"start": 1.0e8, "scale": "log"}}
    with pytest.raises(impact.FitError) as caught:
        impact.fit(MAUGIS_SCENE, data, stress, MAUGIS_FIT["observables"], model="theory", branch="branch")
    assert caught.value.problems == [
        ("parameters.effects.adhesion.stress", "is not set in the scene; give it a value there to fit or vary it")
    ]
