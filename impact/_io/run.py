"""One run in an HDF5 file laid out after H5MD 1.1, and atomic file writes.

Layout (DESIGN.md §5), all values SI with a `unit` attribute (omitted when dimensionless):

    h5md/                      version = [1, 1]; author (name), creator (name, version),
                               modules/units (system = "SI")
    particles/body/            box (dimension 1, boundary "none")
        position/{step, time, value[T, 1, 1]}   the indentation d (m), pressed in > 0
        velocity/{step, time, value[T, 1, 1]}   ḋ (m/s), towards the surface > 0
    observables/
        contact/{indentation, contact_radius, force}/{step, time, value[T]}
        restitution, stuck, status, contact_time, max_indentation, max_force, min_force,
        bounces, touch_velocity, separation_velocity, dissipated_energy,
        tabor_parameter   (scalars; Λ is nan unless Maugis–Dugdale on a paraboloid)
        events/{time, kind}
    parameters/
        config.yaml            the resolved scene YAML; provenance attributes
        solver_stats/          steps, accepted_steps, rejected_steps, (wall_time),
                               scales/{radial, normal, force, time}

`step` and `time` of every time series are hard links to those of the body position.
"""

import getpass
import os
import uuid
from contextlib import contextmanager
from pathlib import Path

import diffrax
import h5py
import jax
import numpy as np
import yaml

from .._core.package import __version__
from .._scene.scene import load_scene, scene_yaml
from .._run.simulate import Result

H5MD_VERSION = (1, 1)

# Scalar results under observables/: name → unit ("" for dimensionless).
SCALAR_UNITS = {
    "restitution": "",
    "stuck": "",
    "status": "",
    "contact_time": "s",
    "max_indentation": "m",
    "max_force": "N",
    "min_force": "N",
    "bounces": "",
    "touch_velocity": "m s-1",
    "separation_velocity": "m s-1",
    "dissipated_energy": "J",
    "tabor_parameter": "",
}
# Time series under observables/contact/: Result field → (unit, description).
CONTACT_SERIES = {
    "indentation": ("m", "indentation d of the half-space; > 0 pressed in, < 0 a gap"),
    "contact_radius": ("m", "contact radius a"),
    "force": ("N", "normal force on the body; > 0 compressive, < 0 adhesive"),
}
SCALE_UNITS = {"radial": "m", "normal": "m", "force": "N", "time": "s"}
STEP_COUNTS = ("steps", "accepted_steps", "rejected_steps")


@contextmanager
def atomic_path(path: str | Path):
    """Yield a fresh temporary path beside `path` (hidden, same suffix) to write; on success it
    is renamed onto `path` in one step (`os.replace`), on an exception it is deleted."""
    path = Path(path)
    temporary = path.with_name(f".{path.stem}.{uuid.uuid4().hex[:12]}.tmp{path.suffix}")
    try:
        yield temporary
        os.replace(temporary, path)
    finally:
        temporary.unlink(missing_ok=True)


def write_text(path: str | Path, text: str) -> None:
    """Write a text file atomically."""
    with atomic_path(path) as temporary:
        temporary.write_text(text)


def write_run(result: Result, path: str | Path, *, wall_time: float | None = None, author: str | None = None) -> Path:
    """Store a result (and the wall time of its simulation, s) as an H5MD file, atomically."""
    path = Path(path)
    with atomic_path(path) as temporary, h5py.File(temporary, "w") as file:
        _write_h5md(file.create_group("h5md"), author or _user())
        clock = _write_body(file.create_group("particles/body"), result)
        _write_observables(file.create_group("observables"), result, clock)
        _write_parameters(file.create_group("parameters"), result, wall_time)
    return path


def read_run(path: str | Path) -> Result:
    """The Result stored by `write_run` (the scene rebuilt from the stored YAML).

    Raises FileNotFoundError for a missing file and ValueError for a file that is not a run."""
    with _open_run(path) as file:
        observables = file["observables"]
        contact = observables["contact"]
        position = file["particles/body/position"]
        events = observables["events"]
        stats = file["parameters/solver_stats"]
        scalars = {name: _scalar(observables[name]) for name in SCALAR_UNITS}
        return Result(
            scene=load_scene(yaml.safe_load(_string(file["parameters/config.yaml"]))),
            **scalars,
            t=position["time"][()],
            indentation=position["value"][()].reshape(-1),
            velocity=file["particles/body/velocity/value"][()].reshape(-1),
            force=contact["force/value"][()],
            contact_radius=contact["contact_radius/value"][()],
            events=[(float(t), str(kind)) for t, kind in zip(events["time"][()], events["kind"].asstr()[()])],
            stats={
                **{name: int(stats[name][()]) for name in STEP_COUNTS},
                "scales": {name: float(stats["scales"][name][()]) for name in SCALE_UNITS},
            },
        )


def read_provenance(path: str | Path, stats_group: str = "parameters/solver_stats") -> dict:
    """Versions (impact, jax, diffrax), x64 flag and wall time (s, or None) of a stored run
    (`stats_group`: where its wall time lives)."""
    with _open_run(path) as file:
        attributes = dict(file["parameters/config.yaml"].attrs)
        stats = file[stats_group]
        wall_time = float(stats["wall_time"][()]) if "wall_time" in stats else None
    return {
        "impact": str(attributes["impact_version"]),
        "jax": str(attributes["jax_version"]),
        "diffrax": str(attributes["diffrax_version"]),
        "x64": bool(attributes["x64"]),
        "wall_time": wall_time,
    }


def _user() -> str:
    try:
        return getpass.getuser()
    except (KeyError, OSError):
        return "unknown"


def _write_h5md(h5md: h5py.Group, author: str) -> None:
    h5md.attrs["version"] = np.array(H5MD_VERSION, dtype=np.int32)
    h5md.create_group("author").attrs["name"] = author
    creator = h5md.create_group("creator")
    creator.attrs["name"] = "impact"
    creator.attrs["version"] = __version__
    units = h5md.create_group("modules/units")
    units.attrs["version"] = np.array((1, 0), dtype=np.int32)
    units.attrs["system"] = "SI"


def _write_body(body: h5py.Group, result: Result) -> h5py.Group:
    """Write position and velocity; return the position group, whose step and time are shared."""
    box = body.create_group("box")
    box.attrs["dimension"] = np.int32(1)
    box.attrs["boundary"] = np.array(["none"], dtype=h5py.string_dtype())
    frames = len(result.t)
    position = _series(
        body.create_group("position"),
        result.indentation.reshape(frames, 1, 1),
        "m",
        "position of the body along the inward surface normal: the indentation d "
        "(0 at first touch, > 0 pressed in, < 0 a gap)",
    )
    position.create_dataset("step", data=np.arange(frames, dtype=np.int64))
    position.create_dataset("time", data=result.t).attrs["unit"] = "s"
    _link_clock(position, _series(
        body.create_group("velocity"),
        result.velocity.reshape(frames, 1, 1),
        "m s-1",
        "velocity ḋ of the body, towards the surface > 0",
    ))
    return position


def _series(group: h5py.Group, values: np.ndarray, unit: str, description: str) -> h5py.Group:
    value = group.create_dataset("value", data=values)
    value.attrs["unit"] = unit
    value.attrs["description"] = description
    return group


def _link_clock(source: h5py.Group, target: h5py.Group) -> None:
    target["step"] = source["step"]
    target["time"] = source["time"]


def _write_observables(observables: h5py.Group, result: Result, clock: h5py.Group) -> None:
    contact = observables.create_group("contact")
    for name, (unit, description) in CONTACT_SERIES.items():
        _link_clock(clock, _series(contact.create_group(name), getattr(result, name), unit, description))
    for name, unit in SCALAR_UNITS.items():
        dataset = observables.create_dataset(name, data=getattr(result, name))
        if unit:
            dataset.attrs["unit"] = unit
    events = observables.create_group("events")
    times = np.array([time for time, _ in result.events], dtype=np.float64)
    kinds = np.array([kind for _, kind in result.events], dtype=object)
    events.create_dataset("time", data=times).attrs["unit"] = "s"
    events.create_dataset("kind", data=kinds, dtype=h5py.string_dtype())


def stamp_provenance(dataset: h5py.Dataset) -> h5py.Dataset:
    """Attach the versions (impact, jax, diffrax) and the x64 flag that produced a file."""
    dataset.attrs["impact_version"] = __version__
    dataset.attrs["jax_version"] = jax.__version__
    dataset.attrs["diffrax_version"] = diffrax.__version__
    dataset.attrs["x64"] = bool(jax.config.jax_enable_x64)
    return dataset


def _write_parameters(parameters: h5py.Group, result: Result, wall_time: float | None) -> None:
    stamp_provenance(parameters.create_dataset("config.yaml", data=scene_yaml(result.scene), dtype=h5py.string_dtype()))
    stats = parameters.create_group("solver_stats")
    for name in STEP_COUNTS:
        stats.create_dataset(name, data=np.int64(result.stats[name]))
    if wall_time is not None:
        stats.create_dataset("wall_time", data=float(wall_time)).attrs["unit"] = "s"
    scales = stats.create_group("scales")
    scales.attrs["description"] = "internal units of the integration"
    for name, unit in SCALE_UNITS.items():
        scales.create_dataset(name, data=float(result.stats["scales"][name])).attrs["unit"] = unit


@contextmanager
def _open_run(path: str | Path):
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"no such file: {path}")
    try:
        file = h5py.File(path, "r")
    except OSError:
        raise ValueError(f"{path} is not an HDF5 file") from None
    with file:
        if "h5md" not in file or "parameters/config.yaml" not in file:
            raise ValueError(f"{path} is not an impact run (no h5md group or parameters/config.yaml)")
        try:
            yield file
        except KeyError as error:
            raise ValueError(f"{path} is not a complete impact run: {error}") from None


def _scalar(dataset: h5py.Dataset):
    if dataset.dtype.kind in "OSU":
        return _string(dataset)
    value = dataset[()]
    if dataset.dtype.kind == "b":
        return bool(value)
    if dataset.dtype.kind in "iu":
        return int(value)
    return float(value)


def _string(dataset: h5py.Dataset) -> str:
    return dataset.asstr()[()]
