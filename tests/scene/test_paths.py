"""`with_values`, the unvalidated copy of a scene by dotted paths that sweeps and the tests use:
it sets the fields a section has, and refuses a path that names no field or a change of a
section's kind (which would keep the old section's class and run its law)."""

import pytest

from impact._scene.paths import with_values
from impact._scene.scene import load_scene
from tests.scenes import THORNTON_NING


def test_a_field_is_set_and_the_original_is_left_alone():
    scene = load_scene(THORNTON_NING)
    changed = with_values(scene, {"initial.velocity": 0.3, "effects.adhesion.work_of_adhesion": 0.02})
    assert (changed.initial.velocity, changed.effects.adhesion.work_of_adhesion) == (0.3, 0.02)
    assert (scene.initial.velocity, scene.effects.adhesion.work_of_adhesion) == (0.6, 0.05)


@pytest.mark.parametrize(
    ("values", "message"),
    [
        ({"effects.adhesion.stress": 1e6}, "JKRAdhesion has no field 'stress': with_values sets existing fields"),
        (
            {"effects.adhesion.model": "maugis_dugdale", "effects.adhesion.stress": 1e6},
            "model = 'maugis_dugdale' changes the kind of JKRAdhesion: load a new scene to change it",
        ),
        (
            {"body.profile.shape": "cone"},
            "shape = 'cone' changes the kind of ParaboloidSpec: load a new scene to change it",
        ),
    ],
    ids=["no such field", "another adhesion model", "another profile shape"],
)
def test_a_path_that_names_no_field_or_changes_a_kind_is_refused(values, message):
    with pytest.raises(ValueError) as error:
        with_values(load_scene(THORNTON_NING), values)
    assert str(error.value) == message
