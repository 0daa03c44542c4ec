"""bench.h5, the HDF5 file of a benchmark run: every measured number under its group (times in
s; the Verlet steps Δt both in scaled time and in s).

Layout: root attributes = the provenance; `continuum/` (cases, references, velocities, rtol and
one group per solver), `scipy/<method>/`, `springs/` (attributes reference and time_unit;
`exact/`, `cost/`, `verlet/N<count>/`) and `equal_error/` (targets and the cheapest time of each
method at each target)."""

from pathlib import Path

import h5py
import numpy as np

from .files import atomic_path


def write_bench_h5(path: str | Path, data: dict) -> None:
    """Write a benchmark run's measurements (the dict `impact._bench` builds) to `path`, atomically."""
    with atomic_path(path) as temporary, h5py.File(temporary, "w") as file:
        for key, value in data["provenance"].items():
            file.attrs[key] = value
        _write_continuum(file.create_group("continuum"), data)
        scipy_group = file.create_group("scipy")
        for method, record in data["scipy"].items():
            _put(scipy_group, method, record)
        _write_springs(file.create_group("springs"), data["springs"])
        summary = file.create_group("equal_error")
        _put(summary, "targets", data["equal"]["targets"])
        for name, costs in data["equal"]["cost"].items():
            _put(summary, name.replace(", ", "_").replace(" ", "_"), costs)


def _put(group: h5py.Group, name, value) -> None:
    """A dict as a subgroup, a string as an attribute, a list of strings as a string dataset,
    anything else as a numeric dataset."""
    if isinstance(value, dict):
        sub = group.create_group(str(name))
        for key, item in value.items():
            _put(sub, key, item)
    elif isinstance(value, str):
        group.attrs[name] = value
    elif isinstance(value, (list, tuple)) and value and isinstance(value[0], str):
        group.create_dataset(name, data=np.asarray(value, dtype=h5py.string_dtype()))
    else:
        group.create_dataset(name, data=np.asarray(value))


def _write_continuum(group: h5py.Group, data: dict) -> None:
    continuum = data["continuum"]
    _put(group, "cases", continuum["cases"])
    _put(group, "references", np.asarray([case.reference for case in data["cases"]]))
    _put(group, "velocities", np.asarray([case.velocity for case in data["cases"]]))
    _put(group, "rtol", continuum["rtols"])
    for solver, record in continuum["solvers"].items():
        _put(group, solver, record)


def _write_springs(group: h5py.Group, springs: dict) -> None:
    group.attrs["reference"] = springs["reference"]
    group.attrs["time_unit"] = springs["time_unit"]
    _put(group, "exact", springs["exact"])
    _put(group, "cost", springs["cost"])
    verlet = group.create_group("verlet")
    for count, row in springs["verlet"].items():
        _put(verlet, f"N{count}", row)
