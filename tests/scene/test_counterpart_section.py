"""The counterpart section (two free bodies): what it refuses, by field and in words."""

import pytest

import impact
from impact._scene.scene import load_scene
from tests.scenes import two_spheres

BAD = [
    ({"mass": -1.0, "density": None}, "counterpart.mass: -1 kg is outside the allowed range [1e-30, 1e6] kg"),
    (
        {"profile": {"shape": "cone", "theta": 0.1}},
        "counterpart.profile.shape: a counterpart is a paraboloid or flat (leave out profile), not 'cone': "
        "only two paraboloids sum to a profile of the same kind (1/R = 1/R₁ + 1/R₂)",
    ),
    ({"profile": {"shape": "blob"}}, "counterpart.profile.shape: unknown shape 'blob'; known shapes: paraboloid,"),
    ({"profile": None}, "counterpart.density: a flat counterpart has no volume; give its mass instead"),
    ({"mass": 1e-9}, "counterpart: give exactly one of mass (kg) and density (kg/m³)"),
    (
        {"velocity": -3.0},
        "counterpart.velocity: -3 m/s is outside the allowed range 0 or [1e-20, 1e4] m/s: its speed towards "
        "the body, 0 at rest",
    ),
]


@pytest.mark.parametrize(("counterpart", "message"), BAD)
def test_bad_counterparts_are_refused(counterpart, message):
    with pytest.raises(impact.SceneError) as error:
        load_scene(two_spheres(**counterpart))
    assert str(error.value).startswith(message)


def test_a_paraboloid_counterpart_needs_a_paraboloid_body():
    scene = two_spheres()
    scene["body"] = {"profile": {"shape": "cone", "theta": 0.1}, "mass": 1e-12}
    with pytest.raises(impact.SceneError, match=r"^body\.profile\.shape: a paraboloid counterpart needs a paraboloid"):
        load_scene(scene)


def test_gravity_is_refused_with_a_counterpart():
    scene = two_spheres()
    scene["effects"]["gravity"] = {"g": 9.81}
    with pytest.raises(impact.SceneError, match=r"^effects\.gravity: not with a counterpart: gravity accelerates"):
        load_scene(scene)
