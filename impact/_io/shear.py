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
from .h5md import (
    holds_kind,
    new_h5md,
    open_kind,
    read_provenance,
    read_scene,
    read_string,
    write_points,
    write_scene,
)

KIND = "shear"


def is_shear_run(path: str | Path) -> bool:
    """Whether an HDF5 file holds a shear test (False for anything else, or no file)."""
    return holds_kind(path, KIND)


def write_shear(result: ShearResult, path: str | Path, *, wall_time: float | None = None, author: str | None = None):
    """Store a shear result (and the wall time of its simulation, s), atomically."""
    path = Path(path)
    with new_h5md(path, author) as file:
        file.attrs["impact_kind"] = KIND
        observables = file.create_group("observables")
        write_points(observables.create_group("shear"), SHEAR_CURVE, result)
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
    with open_kind(path, KIND) as file:
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
