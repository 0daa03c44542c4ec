"""Sweep files (`impact sweep`, `impact.sweep`'s axes): every bad file refused with exit code 2, the
field named and nothing written; the example sweeps valid."""

import pytest
import yaml

from impact._run.sweep import sweep
from impact._scene.errors import SweepError
from impact._scene.sweep import load_sweep
from tests.command import invoke
from tests.scenes import CONFIGS, THORNTON_NING

BAD_SWEEPS = [
    ("unknown dotted path", {"axes": {"initial.speed": [1.0]}}, "axes.initial.speed", "no field 'initial.speed'"),
    ("not a field of the shape", {"axes": {"body.profile.theta": [0.1]}}, "axes.body.profile.theta", "no field"),
    ("non-numeric field", {"axes": {"body.profile.shape": [1.0]}}, "axes.body.profile.shape", "not a numeric field"),
    ("a section", {"axes": {"effects.adhesion": [1.0]}}, "axes.effects.adhesion", "a section"),
    ("absent effect", {"axes": {"effects.gravity.g": [9.81]}}, "axes.effects.gravity.g", "not in the base scene"),
    (
        "generator without num",
        {"axes": {"initial.velocity": {"geomspace": [0.1, 1.0]}}},
        "axes.initial.velocity",
        "[start, stop, num]",
    ),
    (
        "unknown generator",
        {"axes": {"initial.velocity": {"range": [0.1, 1.0, 3]}}},
        "axes.initial.velocity",
        "exactly one of linspace, geomspace, logspace",
    ),
    (
        "geomspace through 0",
        {"axes": {"initial.velocity": {"geomspace": [0.0, 1.0, 3]}}},
        "axes.initial.velocity",
        "nonzero",
    ),
    ("empty list", {"axes": {"initial.velocity": []}}, "axes.initial.velocity", "empty"),
    ("a word", {"axes": {"initial.velocity": [0.5, "fast"]}}, "axes.initial.velocity", "'fast' (#1) is not a number"),
    (
        "negative velocity",
        {"axes": {"initial.velocity": [0.5, -0.6]}},
        "axes.initial.velocity",
        "value -0.6 (#1): -0.6 m/s is outside the allowed range 0 or [1e-20, 1e4] m/s",
    ),
    ("zero velocity", {"axes": {"initial.velocity": [0.0, 0.5]}}, "axes.initial.velocity", "must be > 0"),
    (
        "approach above work",
        {"axes": {"effects.adhesion.approach_work_of_adhesion": [0.01, 0.1]}},
        "axes.effects.adhesion.approach_work_of_adhesion",
        "value 0.1 makes the scene invalid",
    ),
    (
        "a grid point invalid",
        {
            "axes": {
                "effects.adhesion.approach_work_of_adhesion": [0.01, 0.04],
                "effects.adhesion.work_of_adhesion": [0.02, 0.05],
            }
        },
        "axes",
        "approach_work_of_adhesion = 0.04, effects.adhesion.work_of_adhesion = 0.02",
    ),
    ("fractional springs", {"axes": {"contact.springs": [100, 150.5]}}, "axes.contact.springs", "fractional part"),
    (
        "zip of unequal axes",
        {"axes": {"initial.velocity": [0.5, 1.0], "initial.gap": [0.0, 1e-9, 2e-9]}, "mode": "zip"},
        "axes",
        "initial.velocity has 2, initial.gap has 3",
    ),
    ("unknown mode", {"mode": "mesh"}, "mode", "grid, zip"),
    ("unknown key", {"colour": "red"}, "colour", "unknown key"),
    ("no axes", {"axes": None}, "axes", "missing"),
    ("no axis", {"axes": {}}, "axes", "at least one field"),
    ("missing scene file", {"scene": "absent.yaml"}, "scene", "no such file"),
    (
        "set to a bad value",
        {"set": {"solver.rtol": 0}},
        "scene.solver.rtol",
        "0 is outside the allowed range [1e-16, 0.5]",
    ),
    ("set below a value", {"set": {"initial.velocity.x": 1}}, "set.initial.velocity.x", "is a value, not a section"),
    ("bad base scene", {"scene": {"name": "x"}}, "scene.body", "missing"),
]


@pytest.mark.parametrize("case, changes, path, phrase", BAD_SWEEPS, ids=[case[0] for case in BAD_SWEEPS])
def test_bad_sweep_files_are_refused(case, changes, path, phrase, tmp_path):
    data = {"scene": str(THORNTON_NING), "axes": {"initial.velocity": [0.5, 1.0]}}
    for key, value in changes.items():
        if value is None:
            del data[key]
        else:
            data[key] = value
    sweep_file = tmp_path / "bad.yaml"
    sweep_file.write_text(yaml.safe_dump(data, sort_keys=False))
    result = invoke("sweep", sweep_file, "-o", tmp_path / "out")
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output
    assert path in result.output and phrase in " ".join(result.output.split()), result.output
    assert {entry.name for entry in tmp_path.iterdir()} == {"bad.yaml"}


def test_the_example_sweeps_are_valid():
    specs = {path.stem: load_sweep(path) for path in sorted((CONFIGS / "sweeps").glob("*.yaml"))}
    assert specs["thornton_ning"].shape == (400, 3)
    fast = specs["thornton_ning_fast"]
    assert fast.shape == (10000,) and fast.scene.solver.method == "quadrature"  # `set:` changed the base scene
    assert fast.scene.phase_ends == "energy"
    assert specs["attach_on_touch"].paths == ("initial.velocity", "effects.adhesion.approach_work_of_adhesion")
    # a scene that names no method is swept with the quadrature where it runs every point
    methods = {name: spec.method for name, spec in specs.items()}
    assert methods["power_law"] == "quadrature"  # power_law.yaml names none
    assert methods["thornton_ning"] == methods["maugis_tabor"] == "tsit5"  # their scenes name it
    assert methods["rubber_ball_restitution"] == "tsit5"  # damped: the quadrature refuses it


def test_api_refuses_bad_axes():
    with pytest.raises(SweepError) as error:
        sweep(THORNTON_NING, {"initial.velocity": [-1.0]})
    assert error.value.problems[0][0] == "axes.initial.velocity"
