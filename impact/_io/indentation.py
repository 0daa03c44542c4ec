"""One indentation test (scene kind `indentation`) in an HDF5 file after H5MD 1.1.

Layout (the impact run's, `impact._io.run`, with a curve in program order instead of a trajectory
in time; values SI with a `unit` attribute):

    h5md/                      version, author, creator, modules/units (system = "SI")
    observables/
        curve/{contact_radius, indentation, force, leg}/{step, value[P]}
                               the (a, d, F) points in program order; `step` numbers the points
                               (a hard link shared by all four); leg: 0 first loading, 1 first
                               unloading, ...
        curve/time/{step, value[P]}   a viscoelastic half-space's test at a rate: the time (s)
                               of each point
        pull_off/{contact_radius, indentation, force}   the last stable state before the
                               contact is lost (nan if it never was)
        status, max_force, max_indentation, max_contact_radius           (scalars)
        events/{point, kind}   touch, snap_in, snap_out, pull_off, reversal
    parameters/
        config.yaml            the resolved scene YAML; provenance attributes
        stats/                 steps, reach (m), (wall_time), scales/{radial, normal, force}

The root carries the attribute `impact_kind = "indentation"`.
"""

from pathlib import Path

import h5py
import numpy as np

from .._run.indentation import IndentationResult, PullOff
from .._run.units import CURVE_TIME, INDENTATION_CURVE, MAXIMA_UNITS, PULL_OFF_UNITS
from .h5md import (
    holds_kind,
    new_h5md,
    open_kind,
    read_provenance,
    read_scales,
    read_scene,
    read_string,
    write_points,
    write_run_stats,
    write_scene,
)

KIND = "indentation"
SCALES = {"radial": "m", "normal": "m", "force": "N"}


def is_indentation_run(path: str | Path) -> bool:
    """Whether an HDF5 file holds an indentation test (False for anything else, or no file)."""
    return holds_kind(path, KIND)


def write_indentation(
    result: IndentationResult, path: str | Path, *, wall_time: float | None = None, author: str | None = None
) -> Path:
    """Store an indentation result (and the wall time of its simulation, s), atomically."""
    path = Path(path)
    with new_h5md(path, author) as file:
        file.attrs["impact_kind"] = KIND
        observables = file.create_group("observables")
        timed = {} if result.time is None else {"time": CURVE_TIME}
        write_points(observables.create_group("curve"), INDENTATION_CURVE | timed, result)
        pull_off = observables.create_group("pull_off")
        pull_off.attrs["description"] = "the last stable state before the contact is lost"
        for name, unit in PULL_OFF_UNITS.items():
            pull_off.create_dataset(name, data=float(getattr(result.pull_off, name))).attrs["unit"] = unit
        observables.create_dataset("status", data=result.status, dtype=h5py.string_dtype())
        for name, unit in MAXIMA_UNITS.items():
            observables.create_dataset(name, data=getattr(result, name)).attrs["unit"] = unit
        events = observables.create_group("events")
        events.create_dataset("point", data=np.array([i for i, _ in result.events], dtype=np.int64))
        events.create_dataset(
            "kind", data=np.array([k for _, k in result.events], dtype=object), dtype=h5py.string_dtype()
        )
        parameters = file.create_group("parameters")
        write_scene(parameters, result.scene)
        stats = parameters.create_group("stats")
        stats.create_dataset("steps", data=np.int64(result.stats["steps"]))
        stats.create_dataset("reach", data=float(result.stats["reach"])).attrs["unit"] = "m"
        write_run_stats(stats, wall_time, result.stats["scales"], SCALES, of="march")
    return path


def read_indentation(path: str | Path) -> IndentationResult:
    """The IndentationResult stored by `write_indentation` (the scene rebuilt from its YAML).

    Raises FileNotFoundError for a missing file and ValueError for a file that is not one."""
    with open_kind(path, KIND) as file:
        observables = file["observables"]
        curve = observables["curve"]
        pull_off = observables["pull_off"]
        events = observables["events"]
        stats = file["parameters/stats"]
        return IndentationResult(
            scene=read_scene(file),
            status=read_string(observables["status"]),
            pull_off=PullOff(**{name: float(pull_off[name][()]) for name in PULL_OFF_UNITS}),
            contact_radius=curve["contact_radius/value"][()],
            indentation=curve["indentation/value"][()],
            force=curve["force/value"][()],
            leg=curve["leg/value"][()].astype(int),
            events=[(int(i), str(k)) for i, k in zip(events["point"][()], events["kind"].asstr()[()], strict=True)],
            stats={
                "steps": int(stats["steps"][()]),
                "reach": float(stats["reach"][()]),
                "scales": read_scales(stats, SCALES),
            },
            time=curve["time/value"][()] if "time" in curve else None,
        )


def read_indentation_provenance(path: str | Path) -> dict:
    """Versions (impact, jax, diffrax), x64 flag and wall time (s, or None) of a stored test,
    as `h5md.read_provenance` gives them for an impact run."""
    return read_provenance(path, "parameters/stats")
