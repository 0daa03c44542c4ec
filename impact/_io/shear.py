"""One shear test (an indentation scene with `shear`) in an HDF5 file after H5MD 1.1.

Layout (values SI with a `unit` attribute):

    h5md/                      version, author, creator, modules/units (system = "SI")
    observables/
        shear/{displacement, force, stick_radius, leg}/{step, value[P]}
                               the program's points in order; `step` numbers them (a hard link
                               shared by all four); leg: 0 first loading, 1 first reversal, ...
        held/{normal_force, indentation, contact_radius}   the normal state held
        status
    parameters/
        config.yaml            the resolved scene YAML; provenance attributes
        stats/                 springs, spacing (m), (wall_time)

The root carries the attribute `impact_kind = "shear"`.
"""

from pathlib import Path
from typing import Any

import h5py
import numpy as np

from .._run.shear import HELD_UNITS, SHEAR_CURVE, ShearResult
from .files import atomic_path
from .h5md import current_user, open_run, read_provenance, read_scene, read_string, write_header, write_scene

KIND = "shear"


def is_shear_run(path: str | Path) -> bool:
    """Whether an HDF5 file holds a shear test (False for anything else, or no file)."""
    try:
        with h5py.File(path, "r") as file:
            return file.attrs.get("impact_kind") == KIND
    except OSError:
        return False


def write_shear(result: ShearResult, path: str | Path, *, wall_time: float | None = None, author: str | None = None):
    """Store a shear result (and the wall time of its simulation, s), atomically."""
    path = Path(path)
    with atomic_path(path) as temporary, h5py.File(temporary, "w") as file:
        file.attrs["impact_kind"] = KIND
        write_header(file.create_group("h5md"), author or current_user())
        observables = file.create_group("observables")
        curve = observables.create_group("shear")
        step = None
        for name, (unit, description) in SHEAR_CURVE.items():
            group = curve.create_group(name)
            if step is None:
                step = group.create_dataset("step", data=np.arange(len(result.force), dtype=np.int64))
            else:
                group["step"] = step
            value = group.create_dataset("value", data=getattr(result, name))
            value.attrs["description"] = description
            if unit:
                value.attrs["unit"] = unit
        held = observables.create_group("held")
        held.attrs["description"] = "the normal state held through the program"
        for name, unit in HELD_UNITS.items():
            held.create_dataset(name, data=float(getattr(result, name))).attrs["unit"] = unit
        observables.create_dataset("status", data=result.status, dtype=h5py.string_dtype())
        parameters = file.create_group("parameters")
        write_scene(parameters, result.scene)
        stats = parameters.create_group("stats")
        stats.create_dataset("springs", data=np.int64(result.stats["springs"]))
        stats.create_dataset("spacing", data=float(result.stats["spacing"])).attrs["unit"] = "m"
        if wall_time is not None:
            stats.create_dataset("wall_time", data=float(wall_time)).attrs["unit"] = "s"
    return path


def read_shear(path: str | Path) -> ShearResult:
    """The ShearResult stored by `write_shear` (the scene rebuilt from its YAML).

    Raises FileNotFoundError for a missing file and ValueError for a file that is not one."""
    with open_run(path) as file:
        if file.attrs.get("impact_kind") != KIND:
            raise ValueError(f"{path} is not a shear run")
        observables = file["observables"]
        curve, held, stats = observables["shear"], observables["held"], file["parameters/stats"]
        values: dict[str, Any] = {name: float(held[name][()]) for name in HELD_UNITS}
        values.update({name: curve[f"{name}/value"][()] for name in SHEAR_CURVE})
        return ShearResult(
            scene=read_scene(file),
            status=read_string(observables["status"]),
            **values,
            stats={"springs": int(stats["springs"][()]), "spacing": float(stats["spacing"][()])},
        )


def read_shear_provenance(path: str | Path) -> dict:
    """Versions (impact, jax, diffrax), x64 flag and wall time (s, or None) of a stored test."""
    return read_provenance(path, "parameters/stats")
