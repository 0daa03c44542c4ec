"""`impact fit`: the drop-test example end to end (progress, fit.yaml, fit.h5 and fit.png that
round-trip), and bad fit files refused with exit code 2, the field named and nothing written."""

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from impact._io.fit import fit_summary, read_fit
from impact._run.fit import fit_spec
from impact._scene.fit_spec import load_fit, read_table
from tests.command import invoke
from tests.scenes import FITS

DROP_TEST = FITS / "drop_test.yaml"


@pytest.fixture(scope="module")
def fitted(tmp_path_factory):
    folder = tmp_path_factory.mktemp("fit") / "drop_test"
    return folder, invoke("fit", DROP_TEST, "-o", folder)


def test_fit_prints_its_steps_and_writes_three_files(fitted):
    folder, result = fitted
    assert result.exit_code == 0, result.output
    assert "step   0  χ² = " in result.output and "converged after" in result.output
    said = "fitting 2 values to 30 rows with model 'theory' (Levenberg–Marquardt; its steps are printed when it ends)"
    assert result.output.splitlines()[0] == said
    assert {entry.name for entry in folder.iterdir()} == {"fit.yaml", "fit.h5", "fit.png"}
    assert (folder / "fit.png").read_bytes().startswith(b"\x89PNG")


def test_fit_yaml_and_fit_h5_round_trip(fitted):
    folder, _ = fitted
    summary = yaml.safe_load((folder / "fit.yaml").read_text())
    stored = read_fit(folder / "fit.h5")
    assert list(summary) == ["parameters", "correlation", "chi2", "dof", "converged", "iterations"] + [
        "sigma_source",
        "model",
        "unidentifiable",
    ]
    assert stored["parameters"] == summary["parameters"]
    for key in ("chi2", "dof", "converged", "iterations", "sigma_source", "model", "unidentifiable"):
        assert stored[key] == summary[key]
    np.testing.assert_array_equal(stored["correlation"], summary["correlation"])
    table = read_table(FITS / "drops.csv")
    for column, values in stored["data"].items():
        np.testing.assert_array_equal(values, table[column])
    errors = [entry["standard_error"] for entry in summary["parameters"].values()]
    np.testing.assert_allclose(np.sqrt(np.diag(stored["covariance"])), errors, rtol=1e-12)
    assert stored["jacobian"].shape == (2 * 30, 2)
    assert stored["source"] == DROP_TEST.read_text()
    assert summary["dof"] == 58 and summary["converged"] and summary["sigma_source"].startswith("given")


def test_fit_summary_writes_null_for_an_undetermined_error():
    spec = load_fit(DROP_TEST)
    only = dataclasses.replace(spec, observables={"restitution": spec.observables["restitution"]})
    summary = fit_summary(fit_spec(only, "theory"))
    assert all(entry["standard_error"] is None for entry in summary["parameters"].values())
    assert summary["unidentifiable"][0].startswith("restitution alone fixes only a combination")
    assert math.isfinite(summary["chi2"])


def _bad_copy(tmp_path: Path, example: Path, change=None, csv=None) -> Path:
    """The fit file `example` and its data copied to `tmp_path`, its keys changed by `change` and
    its data text by `csv`; a scene given as a file is named by its absolute path."""
    data = yaml.safe_load(example.read_text())
    if isinstance(data["scene"], str):
        data["scene"] = str((example.parent / data["scene"]).resolve())
    text = (example.parent / data["data"]).read_text()
    (tmp_path / data["data"]).write_text(csv(text) if csv else text)
    data.update(change or {})
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(data))
    return path


def _refused(tmp_path: Path, path: Path, field: str, message: str) -> None:
    """`impact fit path` exits 2 naming the field and the message, without a traceback, writing nothing."""
    folder = tmp_path / "out"
    result = invoke("fit", path, "-o", folder)
    assert result.exit_code == 2, result.output
    assert f"{field}: {message}" in " ".join(result.output.split()), result.output
    assert "Traceback" not in result.output
    assert not folder.exists()


ADHESION = "effects.adhesion.work_of_adhesion"
SIGMAS = {"restitution": {"sigma": "restitution_sigma"}}


def _in_row_3(column: int, value: str):
    """A change of the data text: `value` in `column` of data row 3."""

    def changed(text: str) -> str:
        lines = text.splitlines()
        fields = lines[6].split(",")  # three comment lines, the header, then rows 1, 2 and 3
        fields[column] = value
        lines[6] = ",".join(fields)
        return "\n".join(lines) + "\n"

    return changed


def _restitution_twice(text: str) -> str:
    return "\n".join(line if line.startswith("#") else f"{line},{line.split(',')[1]}" for line in text.splitlines())


def _one_row(text: str) -> str:
    return "\n".join(text.splitlines()[:5])  # three comment lines, the header and row 1


VELOCITY_RANGE = (
    "m/s is outside the allowed range 0 or [1e-20, 1e4] m/s: 0 for a body dropped by gravity; above 10 km/s an "
    "impact is no elastic contact"
)


@pytest.mark.parametrize(
    ("change", "csv", "field", "message"),
    [
        (
            {"parameters": {"material.E_starr": {"start": 1.0e9}}},
            None,
            "parameters.material.E_starr",
            "no field 'material.E_starr' in the scene; material takes: E, E_body, E_star, G_star, nu, nu_body",
        ),
        (
            {"inputs": ["contact.springs"]},
            None,
            "inputs.contact.springs",
            "is a static choice ('continuum'; changing it compiles anew), not a traced value",
        ),
        (
            {"inputs": ["initial.velocity", "body.mass"]},
            None,
            "inputs.body.mass",
            "no column 'body.mass' in the data; its columns: initial.velocity, restitution, restitution_sigma, "
            "max_force",
        ),
        (
            {"observables": {**SIGMAS, "max_force": {"sigma": -0.02, "relative": True}}},
            None,
            "observables.max_force.sigma",
            "must be > 0, got -0.02",
        ),
        ({}, _in_row_3(1, "nan"), "data", "column 'restitution' holds nan in row 3"),
        (
            {},
            _in_row_3(0, "-0.35"),
            "data",
            f"column 'initial.velocity', data row 3: -0.35 is refused by initial.velocity: -0.35 {VELOCITY_RANGE}",
        ),
        (
            {},
            _in_row_3(0, "1e300"),
            "data",
            f"column 'initial.velocity', data row 3: 1e+300 is refused by initial.velocity: 1e+300 {VELOCITY_RANGE}",
        ),
        (
            {},
            _in_row_3(0, "0"),
            "data",
            "data row 3 (initial.velocity = 0.0) makes the scene invalid: initial.velocity: must be > 0 (or name "
            "gravity and a gap > 0 to drop the body)",
        ),
        (
            {},
            _one_row,
            "data",
            "1 data row(s) × 2 observable(s) = 2 measured value(s) for 2 parameter(s): a fit needs more measured "
            "values than parameters (at least 3), to leave degrees of freedom for χ² and the standard errors",
        ),
        (
            {},
            _in_row_3(2, "1e-300"),
            "observables.restitution",
            "(model − measured)/σ is 2.3e+299 in data row 3 at the parameters' start: beyond 1e+150, χ² overflows "
            "float64; check the measured value 0.668837 and its σ",
        ),
        (
            {"parameters": {ADHESION: {"start": 2.0, "min": 1.0e-4, "max": 1.0, "scale": "log"}}},
            None,
            f"parameters.{ADHESION}.start",
            "2 lies outside the bounds (0.0001, 1)",
        ),
    ],
    ids=[
        "unknown path",
        "static input",
        "missing column",
        "negative sigma",
        "nan in data",
        "negative velocity",
        "huge velocity",
        "zero velocity",
        "one row",
        "overflowing residual",
        "start outside bounds",
    ],
)
def test_bad_fit_files_exit_2_naming_the_field_and_write_nothing(tmp_path, change, csv, field, message):
    _refused(tmp_path, _bad_copy(tmp_path, DROP_TEST, change, csv), field, message)


def test_a_column_named_twice_is_refused(tmp_path):
    """Not the last copy silently: both columns named."""
    path = _bad_copy(tmp_path, DROP_TEST, csv=_restitution_twice)
    message = f"{tmp_path / 'drops.csv'}: column 'restitution' appears twice in the header (columns 2 and 5)"
    _refused(tmp_path, path, "data", message)


# --- indentation curves (the AFM use) and --set ----------------------------------------------

AFM_CURVE = FITS / "afm_curve.yaml"


def _without_indentation(text: str) -> str:
    return "\n".join(line.partition(",")[2] if not line.startswith("#") else line for line in text.splitlines())


def _misspelt_retract(text: str) -> str:
    return text.replace("retract", "retrat", 1)


@pytest.mark.parametrize(
    ("change", "csv", "field", "message"),
    [
        (
            {},
            _without_indentation,
            "data",
            "no column 'indentation': the controlled value of a displacement-controlled scene, the input of each "
            "row; its columns: force, branch",
        ),
        (
            {},
            _misspelt_retract,
            "branch",
            "column 'branch', data row 41: 'retrat' is not a branch; expected approach or retract",
        ),
        ({"branch": "direction"}, None, "branch", "no column 'direction' in the data"),
        (
            {"observables": {"max_force": {"sigma": 1.0e-9}}},
            None,
            "observables.max_force",
            "unknown observable; known: force, contact_radius",
        ),
        (
            {"model": "simulation"},
            None,
            "model",
            "the quasi-static march of an indentation scene is not differentiable",
        ),
    ],
    ids=["missing control column", "unknown branch label", "missing branch column", "impact observable", "simulation"],
)
def test_bad_indentation_fit_files_exit_2_naming_the_field_and_write_nothing(tmp_path, change, csv, field, message):
    _refused(tmp_path, _bad_copy(tmp_path, AFM_CURVE, change, csv), field, message)


@pytest.mark.slow
def test_the_afm_example_fits_with_set_overrides(tmp_path):
    """`--set` changes a start and a σ of the fit file; the fit finds the true values of
    make_afm_data.py and fit.h5 stores the fit file as overridden."""
    folder = tmp_path / "afm"
    start, sigma = "parameters.material.E_star.start=2.0e9", "observables.force.sigma=1.0e-9"
    result = invoke("fit", AFM_CURVE, "-o", folder, "--set", start, "--set", sigma)
    assert result.exit_code == 0, result.output
    assert "step   0  χ² = " in result.output and "material.E_star = 2e+09" in result.output
    summary = yaml.safe_load((folder / "fit.yaml").read_text())
    stored = yaml.safe_load(read_fit(folder / "fit.h5")["source"])
    assert stored["parameters"]["material.E_star"] == {"start": 2.0e9, "scale": "log"}
    assert stored["observables"]["force"] == {"sigma": 1.0e-9}
    for path, true in (("material.E_star", 0.8e9), ("effects.adhesion.work_of_adhesion", 0.1)):
        entry = summary["parameters"][path]
        assert abs(entry["value"] - true) < 3 * entry["standard_error"]
    assert summary["converged"] and summary["iterations"] <= 15


@pytest.mark.parametrize(
    ("assignment", "field", "message"),
    [
        ("foo=1", "--set", "no field 'foo' in a fit file; it takes: branch, data, inputs, model, observables"),
        (
            "parameters.material.E_star.strat=1",
            "parameters.material.E_star.strat",
            "no field 'strat' of an entry of parameters (start, min, max, scale); set one, or the whole entry to a "
            "mapping",
        ),
        ("scene.body.profile.Q=1", "--set", "no field 'body.profile.Q' in the scene; body.profile takes: R, shape"),
        ("model", "--set", "expected dotted.path=value, got 'model'"),
    ],
)
def test_bad_set_exits_2_naming_the_field_and_writes_nothing(tmp_path, assignment, field, message):
    folder = tmp_path / "out"
    result = invoke("fit", AFM_CURVE, "-o", folder, "--set", assignment)
    assert result.exit_code == 2, result.output
    assert f"{field}: {message}" in " ".join(result.output.split()), result.output
    assert not folder.exists()
