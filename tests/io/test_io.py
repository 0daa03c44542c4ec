"""HDF5 runs: lossless round trip (of an impact and of an indentation test), the H5MD 1.1 layout,
atomic writes, refusal of foreign files."""

import dataclasses
import math

import h5py
import numpy as np
import pytest

import impact
from impact._io.h5md import read_provenance
from impact._io.indentation import is_indentation_run, read_indentation, write_indentation
from impact._io.run import read_run, write_run
from impact._scene.scene import load_scene, scene_yaml
from tests.scenes import CONFIGS, THORNTON_NING


@pytest.fixture(scope="module")
def separated():
    return impact.simulate(THORNTON_NING)


@pytest.fixture(scope="module")
def captured():
    """Below the sticking velocity (0.303 m/s): contact_time is inf, restitution 0."""
    scene = load_scene(THORNTON_NING).model_copy(deep=True)
    scene.initial.velocity = 0.2
    return impact.simulate(scene)


def assert_same_result(stored, original):
    for field in dataclasses.fields(original):
        a, b = getattr(stored, field.name), getattr(original, field.name)
        if isinstance(b, np.ndarray):
            assert a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes(), field.name
        else:
            assert type(a) is type(b) and (a == b or (isinstance(b, float) and math.isnan(a) and math.isnan(b))), (
                field.name
            )


@pytest.mark.parametrize("name", ["separated", "captured"])
def test_write_then_read_is_lossless(name, request, tmp_path):
    result = request.getfixturevalue(name)
    assert result.status == name
    write_run(result, tmp_path / "run.h5", wall_time=1.25)
    assert_same_result(read_run(tmp_path / "run.h5"), result)
    provenance = read_provenance(tmp_path / "run.h5")
    assert provenance["wall_time"] == 1.25 and provenance["x64"] is True


def test_file_follows_h5md_layout(separated, tmp_path):
    write_run(separated, tmp_path / "run.h5", author="tester")
    frames = len(separated.t)
    with h5py.File(tmp_path / "run.h5", "r") as file:
        h5md = file["h5md"]
        assert list(h5md.attrs["version"]) == [1, 1]
        assert h5md["author"].attrs["name"] == "tester"
        assert h5md["creator"].attrs["name"] == "impact"
        assert h5md["creator"].attrs["version"] == impact.__version__
        assert h5md["modules/units"].attrs["system"] == "SI"

        body = file["particles/body"]
        assert body["box"].attrs["dimension"] == 1 and list(body["box"].attrs["boundary"]) == ["none"]
        for element, unit in (("position", "m"), ("velocity", "m s-1")):
            assert body[element]["value"].shape == (frames, 1, 1)
            assert body[element]["value"].attrs["unit"] == unit
            assert body[element]["step"].dtype.kind == "i" and body[element]["time"].attrs["unit"] == "s"
        assert "indentation" in body["position/value"].attrs["description"]
        np.testing.assert_array_equal(body["position/value"][:, 0, 0], separated.indentation)

        contact = file["observables/contact"]
        for element, unit in (("indentation", "m"), ("contact_radius", "m"), ("force", "N")):
            assert contact[element]["value"].shape == (frames,)
            assert contact[element]["value"].attrs["unit"] == unit
            assert contact[element]["time"] == body["position/time"]  # one shared clock (hard link)

        observables = file["observables"]
        for name, unit in (
            ("contact_time", "s"),
            ("max_indentation", "m"),
            ("max_force", "N"),
            ("min_force", "N"),
            ("touch_velocity", "m s-1"),
            ("dissipated_energy", "J"),
        ):
            assert observables[name].shape == () and observables[name].attrs["unit"] == unit
        assert observables["status"].asstr()[()] == "separated"
        # the scene names adhesion, not damping: the hysteresis is written (not read back)
        assert observables["adhesion_hysteresis"][()] == separated.adhesion_hysteresis > 0
        assert observables["adhesion_hysteresis"].attrs["unit"] == "J"
        assert "unrecovered_elastic_energy" not in observables
        assert observables["restitution"][()] == separated.restitution
        assert list(observables["events/kind"].asstr()[()]) == [kind for _, kind in separated.events]
        assert observables["events/time"].attrs["unit"] == "s"

        config = file["parameters/config.yaml"]
        assert config.asstr()[()] == scene_yaml(separated.scene)
        assert config.attrs["impact_version"] == impact.__version__
        assert {"jax_version", "diffrax_version", "x64"} <= set(config.attrs)
        assert file["parameters/solver_stats/steps"][()] == separated.stats["steps"]
        assert file["parameters/solver_stats/scales/time"].attrs["unit"] == "s"


def test_failed_write_keeps_the_old_file_and_leaves_no_temporary(separated, tmp_path):
    path = tmp_path / "run.h5"
    write_run(separated, path)
    broken = dataclasses.replace(separated, status=object())  # h5py cannot store it
    with pytest.raises(TypeError):
        write_run(broken, path)
    assert [entry.name for entry in tmp_path.iterdir()] == ["run.h5"]
    assert_same_result(read_run(path), separated)


def test_failed_first_write_leaves_nothing(separated, tmp_path):
    with pytest.raises(TypeError):
        write_run(dataclasses.replace(separated, status=object()), tmp_path / "run.h5")
    assert list(tmp_path.iterdir()) == []


def test_read_refuses_what_is_not_a_run(tmp_path):
    with pytest.raises(FileNotFoundError, match="no such file"):
        read_run(tmp_path / "absent.h5")
    (tmp_path / "text.h5").write_text("not HDF5")
    with pytest.raises(ValueError, match="not an HDF5 file"):
        read_run(tmp_path / "text.h5")
    with h5py.File(tmp_path / "other.h5", "w") as file:
        file["data"] = 1.0
    with pytest.raises(ValueError, match="not an impact run"):
        read_run(tmp_path / "other.h5")


def test_an_indentation_test_round_trips(tmp_path):
    result = impact.simulate(CONFIGS / "indentation_paraboloid.yaml")
    path = write_indentation(result, tmp_path / "run.h5", wall_time=1.5)
    assert is_indentation_run(path) and not is_indentation_run(tmp_path / "missing.h5")
    back = read_indentation(path)
    assert back.scene == result.scene and back.status == result.status and back.pull_off == result.pull_off
    for name in ("contact_radius", "indentation", "force", "leg"):
        np.testing.assert_array_equal(getattr(back, name), getattr(result, name))
    assert back.events == result.events and back.stats == result.stats
