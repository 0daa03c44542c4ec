"""The sections of a quasi-static indentation scene (kind, control, program): what they take,
what they refuse by field and in words, and the impact scene's sections unchanged beside them."""

import pytest
import yaml

from impact._scene.scene import SceneError, load_scene, scene_yaml
from tests.scenes import CONFIGS, indentation_scene


def base(**changes):
    data = indentation_scene(dict(shape="paraboloid", R=1e-6), "force", 1e-7)
    data.update(changes)
    return data


def problems(data):
    with pytest.raises(SceneError) as error:
        load_scene(data)
    return error.value.problems


def test_schema_kind_control_program(thornton_ning_scene):
    indentation = load_scene(base())
    assert indentation.kind == "indentation" and indentation.initial is None and indentation.body.mass is None
    assert load_scene(base(program={"peak": "1e-7", "cycles": 2, "unload_to": 0})).program.peak == 1e-7
    impact_scene = thornton_ning_scene
    assert impact_scene.kind == "impact" and impact_scene.control is None
    assert load_scene(yaml.safe_load(scene_yaml(indentation))) == indentation  # resolved YAML round-trips
    assert "solver" not in scene_yaml(indentation) and "initial" not in scene_yaml(indentation)


@pytest.mark.parametrize(
    "changes, path, message",
    [
        ({"initial": {"velocity": 1.0}}, "initial", "not for kind 'indentation'"),
        ({"body": {"profile": {"shape": "paraboloid", "R": 1e-6}, "mass": 1e-12}}, "body.mass", "needs no mass"),
        ({"body": {"profile": {"shape": "paraboloid", "R": 1e-6}, "density": 2500}}, "body.density", "needs no mass"),
        ({"effects": {"gravity": {}}}, "effects.gravity", "not for kind 'indentation'"),
        ({"solver": {"rtol": 1e-8}}, "solver", "needs no ODE solver"),
        ({"limits": {"max_bounces": 3}}, "limits", "ends at pull-off"),
        ({"control": None}, "control", "missing (required for kind 'indentation')"),
        ({"program": None}, "program", "missing (required for kind 'indentation')"),
        ({"control": "velocity"}, "control", "Input should be 'force' or 'displacement'"),
        ({"program": {"peak": -1e-7}}, "program.peak", "-1e-07 N or m is outside the allowed range [0, 1e6] N or m"),
        ({"program": {"peak": 1e-7, "unload_to": 2e-7}}, "program.unload_to", "below peak"),
        ({"program": {"peak": 1e-7, "cycles": 0}}, "program.cycles", "0 is outside the allowed range [1, 100]"),
        ({"kind": "drop"}, "kind", "Input should be 'impact' or 'indentation'"),
    ],
)
def test_schema_refusals(changes, path, message):
    data = base(**changes)
    data = {k: v for k, v in data.items() if v is not None}
    found = problems(data)
    assert any(p == path and message in m for p, m in found), found


def test_schema_impact_scenes_unchanged():
    data = yaml.safe_load((CONFIGS / "thornton_ning.yaml").read_text())
    assert ("initial", "missing (required)") in problems({k: v for k, v in data.items() if k != "initial"})
    body = dict(data["body"])
    del body["mass"]
    assert ("body", "give exactly one of mass (kg) and density (kg/m³)") in problems({**data, "body": body})
    assert ("control", "only for kind 'indentation'") in problems({**data, "control": "force"})
    assert ("program", "only for kind 'indentation'") in problems({**data, "program": {"peak": 1.0}})
