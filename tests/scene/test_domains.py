"""Physical ranges and what the scaled problem can represent: each scene value outside its
domain, or a scene whose units float64 cannot carry, is refused before any work (exit 2, the
field, its value and the allowed range; nothing written), for a scene as for each point of a
sweep."""

import gc

import pytest
import yaml
from pydantic import BaseModel, model_validator

import impact
from impact._scene import sweep_points
from impact._scene.paths import assign, resolve_field
from impact._scene.representable import limits_of
from impact._scene.sweep import load_sweep
from tests.command import invoke
from tests.scenes import CONFIGS, THORNTON_NING

# (override, the refusal's line): the three known failures first (a ZeroDivisionError traceback,
# unbounded_contact with −inf m, solver_failure at 4e111 Gm), then the checks across fields.
REFUSALS = [
    ("body.profile.R=1e300", "body.profile.R: 1e+300 m is outside the allowed range [1e-12, 1000] m"),
    ("initial.velocity=1e300", "initial.velocity: 1e+300 m/s is outside the allowed range 0 or [1e-20, 1e4] m/s"),
    ("body.mass=1e308", "body.mass: 1e+308 kg is outside the allowed range [1e-30, 1e6] kg"),
    (
        "initial.velocity=1e4",
        "initial.velocity: 10000 m/s is outside the allowed range [0, 437.019] m/s: the body would be "
        "pressed in about 1.22e-05 m, deeper than its size body.profile.R = 1e-06 m",
    ),
    (
        "effects.adhesion.work_of_adhesion=1e-30",
        "effects.adhesion.work_of_adhesion: 1e-30 J/m² is outside the allowed range 0 or [5.848e-26, 1e4] J/m²: "
        "the detachment length is 4.1e-15 of the indentation, below what float64 resolves (1e-12)",
    ),
    (  # found by the long fuzzer: the detachment length underflowed to 0 (a ZeroDivisionError)
        "effects.adhesion={work_of_adhesion: 2.225073858507e-311, approach_work_of_adhesion: 0.0}",
        "effects.adhesion.work_of_adhesion: 2.22507e-311 J/m² is outside the allowed range 0 or [5.848e-26, 1e4] "
        "J/m²: the detachment length is 0 of the indentation, below what float64 resolves (1e-12)",
    ),
    (
        "body.profile={shape: power_law, n: 2, c: 1e300}",
        "body: the scene's radial unit 1e-200 (SI) is outside the allowed range [1e-150, 1e150]",
    ),
]


@pytest.mark.parametrize("override, line", REFUSALS, ids=[case[0] for case in REFUSALS])
def test_out_of_range_is_refused_before_any_work(override, line, tmp_path):
    result = invoke("run", THORNTON_NING, "--set", override, "-o", tmp_path / "out")
    assert result.exit_code == 2, result.output
    assert line in " ".join(result.output.split())
    assert "Traceback" not in result.output
    assert not (tmp_path / "out").exists()


def test_python_api_raises_scene_error_with_the_same_message():
    data = yaml.safe_load(THORNTON_NING.read_text())
    data["initial"]["velocity"] = 1e300
    with pytest.raises(impact.SceneError, match=r"initial\.velocity: 1e\+300 m/s is outside the allowed range"):
        impact.simulate(data)


def test_a_drop_too_high_names_the_gap():
    data = yaml.safe_load(THORNTON_NING.read_text())
    data["initial"] = {"velocity": 0.0, "gap": 100.0}
    data["effects"]["gravity"] = {}
    data["body"]["mass"] = 1e-9  # a 44 m/s touch presses it in deeper than R
    with pytest.raises(impact.SceneError) as error:
        impact.load_scene(data)
    assert error.value.problems[0][0] == "initial.gap"
    assert error.value.problems[0][1].startswith("100 m is outside the allowed range [0, ")


@pytest.mark.slow
def test_every_example_scene_and_sweep_validates():
    scenes = sorted(CONFIGS.glob("*.yaml")) + sorted((CONFIGS / "hard").glob("*.yaml"))
    assert len(scenes) == 53
    for scene in scenes:
        assert impact.load_scene(scene).name
    for sweep in sorted((CONFIGS / "sweeps").glob("*.yaml")):
        assert load_sweep(sweep).paths


SWEPT_REFUSALS = {
    # the body pressed in deeper than its size (the energetic depth against R)
    "depth": ("thornton_ning.yaml", "initial.velocity", [1.0, 1e4, 2.0, 5e3, 3e3, 2e3, 1.5e3, 3.0]),
    # the adhesion below what float64 resolves against the impact (the units' ratio)
    "adhesion": ("thornton_ning.yaml", "effects.adhesion.work_of_adhesion", [0.05, 1e-28, 1e-20, 1e-30, 1e-27]),
    # a yielding body pressed in deeper than its radius (Thornton's closed form, checked alone)
    "plastic": ("plastic_steel.yaml", "initial.velocity", [10.0, 1e3, 100.0, 2e3]),
    # the modulus: a soft body pressed in deeper than its size (E* among the units' inputs)
    "modulus": ("thornton_ning.yaml", "material.E_star", [1e9, 1e3, 2e9, 1e2, 5e8]),
    # a combination: the depth of a heavy body, at each of its velocities
    "mass": ("thornton_ning.yaml", "body.mass", [1e-14, 1e6, 1e-13, 10.0]),
    # a swept profile: built point by point, its size the swept radius
    "radius": ("thornton_ning.yaml", "body.profile.R", [1e-6, 1e-9, 2e-6, 1e-8, 1e-5]),
}


@pytest.mark.parametrize("pending", [None, 3])
@pytest.mark.parametrize("case", sorted(SWEPT_REFUSALS))
def test_sweep_points_are_refused_as_their_scenes_are(case, pending, monkeypatch):
    """The sweep checks representability in batches (all the points at once, or 3 at a time as
    a long sweep does), passing the points whose units pass every check together: each invalid
    point gets the message its scene alone gets, the points listed in order and the rest counted."""
    if pending is not None:
        monkeypatch.setattr(sweep_points, "_PENDING", pending)
    config, path, values = SWEPT_REFUSALS[case]
    spec = {"scene": str(CONFIGS / config), "axes": {path: values}, "order": "given"}
    expected = []
    for value in values:
        data = yaml.safe_load((CONFIGS / config).read_text())
        assign(data, path.split("."), value)
        try:
            impact.load_scene(data)
        except impact.SceneError as refusal:
            (field, why), *_ = refusal.problems
            expected.append(f"value {value!r} makes the scene invalid: {field}: {why}")
    assert 0 < len(expected) < len(values)
    with pytest.raises(impact.SceneError) as error:
        load_sweep(spec)
    (where, message), *_ = error.value.problems
    assert where == f"axes.{path}"
    more = f"; and {len(expected) - 4} more invalid points" if len(expected) > 4 else ""
    assert message == "; ".join(expected[:4]) + more


class Probed(BaseModel):
    """A section whose validators read its fields in the ways a validator may."""

    swept: float = 1.0
    other: float = 2.0

    @model_validator(mode="after")
    def _by_attribute(self):
        if self.swept <= 0:
            raise ValueError("swept must be > 0")
        return self

    @model_validator(mode="after")
    def _by_getattr_with_a_default(self):
        getattr(self, "swept", None)
        return self

    @model_validator(mode="after")
    def _by_a_dump(self):
        self.model_dump()
        return self

    @model_validator(mode="after")
    def _other_only(self):
        if self.other <= 0:
            raise ValueError("other must be > 0")
        return self


def test_only_the_validators_that_read_a_swept_field_run_per_point(thornton_ning_scene):
    """A validator runs per point when running it on the base reads a swept field: directly,
    through getattr with a default, or through a dump; one that reads none is left out, and the
    tracking leaves the class as it found it."""
    probed = Probed()
    checks = sweep_points._reading_checks([("section", probed)], [(probed, "swept")])
    assert [validator.__name__ for _, _, validator in checks] == [
        "_by_attribute",
        "_by_getattr_with_a_default",
        "_by_a_dump",
    ]
    assert "__getattribute__" not in Probed.__dict__
    probed.__dict__["swept"] = -1.0
    assert sweep_points._validators_problem(checks) == "section: swept must be > 0"
    scene = thornton_ning_scene
    initial = scene.initial
    names = [v.__name__ for _, _, v in sweep_points._reading_checks([("", scene)], [(initial, "velocity")])]
    assert "_reaches_the_surface" in names and "_energy_ends_supported" not in names
    # what the units are checked against: the base's for a velocity, per point for a radius
    assert not sweep_points._reads_swept(limits_of, scene, [(initial, "velocity")])
    assert sweep_points._reads_swept(limits_of, scene, [(scene.body.profile, "R")])
    # the units' inputs read per point: those of the swept field, the rest are the base's
    swept_numbers = {
        "initial.velocity": ["speed"],
        "material.E_star": ["E_star"],
        "body.mass": ["mass"],
        "effects.adhesion.work_of_adhesion": ["approach"],
    }
    for path, names in swept_numbers.items():
        assert list(sweep_points._reading_numbers(scene, [resolve_field(scene, path)])) == names, path


@pytest.mark.parametrize("enabled", [True, False])
def test_points_are_checked_with_the_collector_held_off_and_left_as_found(enabled, monkeypatch):
    """Checking a sweep's points holds the cyclic garbage collector off (their objects hold no
    cycles; the collections cost a third of the check) and leaves it as it found it."""
    seen = []
    checked = sweep_points._fast_problems

    def fast_problems(*args):
        seen.append(gc.isenabled())
        return checked(*args)

    monkeypatch.setattr(sweep_points, "_fast_problems", fast_problems)
    (gc.enable if enabled else gc.disable)()
    try:
        load_sweep({"scene": str(THORNTON_NING), "axes": {"initial.velocity": [0.5, 1.0]}})
        assert seen == [False] and gc.isenabled() is enabled
    finally:
        gc.enable()
