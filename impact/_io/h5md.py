"""What every impact HDF5 file shares (after H5MD 1.1: de Buyl et al., Comput. Phys. Commun.
185, 1546 (2014)): the `h5md` header, string datasets, the stored scene with its provenance
(package, jax and diffrax versions, x64), and opening a stored run for reading."""

import getpass
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import h5py
import numpy as np
import yaml

from .._core.package import __version__
from .._core.runtime import provenance
from .._scene.scene import Scene, load_scene, scene_yaml
from .files import atomic_path

H5MD_VERSION = (1, 1)
CONFIG = "parameters/config.yaml"


def current_user() -> str:
    """The login name of the user writing a file ("unknown" where there is none)."""
    try:
        return getpass.getuser()
    except (KeyError, OSError):
        return "unknown"


def write_header(h5md: h5py.Group, author: str) -> None:
    """The `h5md` group: version, author, creator (impact and its version), SI units."""
    h5md.attrs["version"] = np.array(H5MD_VERSION, dtype=np.int32)
    h5md.create_group("author").attrs["name"] = author
    creator = h5md.create_group("creator")
    creator.attrs["name"] = "impact"
    creator.attrs["version"] = __version__
    units = h5md.create_group("modules/units")
    units.attrs["version"] = np.array((1, 0), dtype=np.int32)
    units.attrs["system"] = "SI"


@contextmanager
def new_h5md(path: str | Path, author: str | None = None) -> Iterator[h5py.File]:
    """A new H5MD file at `path`, open for writing with its `h5md` header (`author`: the login
    name by default); it appears at `path` only once the block has written it whole."""
    with atomic_path(Path(path)) as temporary, h5py.File(temporary, "w") as file:
        write_header(file.create_group("h5md"), author or current_user())
        yield file


def write_string(group: h5py.Group, name: str, text: str) -> h5py.Dataset:
    """A variable-length UTF-8 string dataset."""
    return group.create_dataset(name, data=text, dtype=h5py.string_dtype())


def write_points(group: h5py.Group, fields: Mapping[str, tuple[str, str]], result: Any) -> None:
    """One group `name/{step, value}` under `group` for each of `fields` (name → (unit,
    description)), its values the result's attribute `name`; one `step` dataset numbers the
    points, hard-linked into every group."""
    step = None
    for name, (unit, description) in fields.items():
        values = getattr(result, name)
        series = group.create_group(name)
        if step is None:
            step = series.create_dataset("step", data=np.arange(len(values), dtype=np.int64))
        else:
            series["step"] = step
        value = series.create_dataset("value", data=values)
        value.attrs["description"] = description
        if unit:
            value.attrs["unit"] = unit


def read_string(dataset: h5py.Dataset) -> str:
    return dataset.asstr()[()]


def stamp_provenance(dataset: h5py.Dataset) -> h5py.Dataset:
    """Attach the versions (impact, jax, diffrax) and the x64 flag that produced a file."""
    dataset.attrs.update(provenance())
    return dataset


def stored_provenance(dataset: h5py.Dataset) -> dict[str, str | bool]:
    """The attributes `stamp_provenance` wrote, as `impact._core.runtime.provenance` gives them."""
    attributes = dataset.attrs
    return {
        "impact_version": str(attributes["impact_version"]),
        "jax_version": str(attributes["jax_version"]),
        "diffrax_version": str(attributes["diffrax_version"]),
        "x64": bool(attributes["x64"]),
    }


def write_scene(parameters: h5py.Group, scene: Scene) -> None:
    """`parameters/config.yaml`: the resolved scene YAML, stamped with the provenance."""
    stamp_provenance(write_string(parameters, "config.yaml", scene_yaml(scene)))


def read_scene(file: h5py.File) -> Scene:
    """The scene stored by `write_scene`, validated anew."""
    return load_scene(yaml.safe_load(read_string(file[CONFIG])))


def write_run_stats(stats: h5py.Group, wall_time: float | None, scales: dict, units: dict[str, str], of: str) -> None:
    """A run's wall time (s, where measured) and its internal units (`scales`, SI: each of `units`
    with its unit) in its `stats` group; `of`: what the units are of (the integration, the march)."""
    if wall_time is not None:
        stats.create_dataset("wall_time", data=float(wall_time)).attrs["unit"] = "s"
    group = stats.create_group("scales")
    group.attrs["description"] = f"internal units of the {of}"
    for name, unit in units.items():
        group.create_dataset(name, data=float(scales[name])).attrs["unit"] = unit


def read_scales(stats: h5py.Group, units: dict[str, str]) -> dict[str, float]:
    """The internal units stored by `write_run_stats` (SI)."""
    return {name: float(stats["scales"][name][()]) for name in units}


@contextmanager
def open_run(path: str | Path):
    """The HDF5 file of a stored run (impact or indentation), open for reading.

    FileNotFoundError for a missing file; ValueError for a file that is no HDF5 file, no run,
    or (a KeyError while reading) not a complete run."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"no such file: {path}")
    try:
        file = h5py.File(path, "r")
    except OSError:
        raise ValueError(f"{path} is not an HDF5 file") from None
    with file:
        if "h5md" not in file or CONFIG not in file:
            raise ValueError(f"{path} is not an impact run (no h5md group or parameters/config.yaml)")
        try:
            yield file
        except KeyError as error:
            raise ValueError(f"{path} is not a complete impact run: {error}") from None


def holds_kind(path: str | Path, kind: str) -> bool:
    """Whether an HDF5 file's root says `impact_kind = kind` (False for anything else, or no file)."""
    try:
        with h5py.File(path, "r") as file:
            return file.attrs.get("impact_kind") == kind
    except OSError:
        return False


@contextmanager
def open_kind(path: str | Path, kind: str):
    """`open_run` of a file whose root says `impact_kind = kind`, else ValueError."""
    with open_run(path) as file:
        if file.attrs.get("impact_kind") != kind:
            raise ValueError(f"{path} is not {'an' if kind[0] in 'aeiou' else 'a'} {kind} run")
        yield file


def read_provenance(path: str | Path, stats_group: str = "parameters/solver_stats") -> dict:
    """Versions (impact, jax, diffrax), x64 flag and wall time (s, or None) of a stored run
    (`stats_group`: where its wall time lives)."""
    with open_run(path) as file:
        stored = stored_provenance(file[CONFIG])
        stats = file[stats_group]
        wall_time = float(stats["wall_time"][()]) if "wall_time" in stats else None
    return {
        "impact": stored["impact_version"],
        "jax": stored["jax_version"],
        "diffrax": stored["diffrax_version"],
        "x64": stored["x64"],
        "wall_time": wall_time,
    }
