"""One impact run in an HDF5 file laid out after H5MD 1.1.

Layout (H5MD 1.1: de Buyl et al., Comput. Phys. Commun. 185, 1546 (2014)), all values SI with a
`unit` attribute (omitted when dimensionless):

    h5md/                      version = [1, 1]; author (name), creator (name, version),
                               modules/units (system = "SI")
    particles/body/            box (dimension 1, boundary "none")
        position/{step, time, value[T, 1, 1]}   the indentation d (m), pressed in > 0
        velocity/{step, time, value[T, 1, 1]}   ḋ (m/s), towards the surface > 0
    observables/
        contact/{indentation, contact_radius, force}/{step, time, value[T]}
                 {tangential_force, stick_radius}/...   (where the scene names friction)
        restitution, stuck, status, contact_time, max_indentation, max_force, min_force,
        bounces, touch_velocity, separation_velocity, dissipated_energy, plastic_work, viscous_work,
        adhesion_hysteresis   (where the scene names adhesion), unrecovered_elastic_energy (where
                              it names damping): the rest of dissipated_energy
        tabor_parameter   (scalars; Λ: Maugis–Dugdale on a paraboloid, Greenwood–Johnson; else nan)
        centre_of_mass_velocity, body_velocity_after, counterpart_velocity_after
                          (lab frame, along the body's approach; speeds above are relative)
        tangential_velocity_after, spin_after, tangential_restitution,
        contact_point_tangential_restitution, rebound_angle, friction_work
        events/{time, kind}
        relaxation/            a viscoelastic half-space only: its springs when the run ends,
                               spring_position[N] (m), displacement[N] (m), arm_stretch[N, M] (m),
                               attached[N]; and the first contact's stored_energy,
                               released_energy, gained_energy (J)
    parameters/
        config.yaml            the resolved scene YAML; provenance attributes
        solver_stats/          steps, accepted_steps, rejected_steps, (wall_time),
                               scales/{radial, normal, force, time}

`step` and `time` of every time series are hard links to those of the body position.
"""

from pathlib import Path
from typing import Any

import h5py
import numpy as np

from .._run.impacts import Result
from .._run.losses import NAMED_LOSSES
from .._run.tangential import TANGENTIAL_SERIES
from .._run.units import CONTACT_SERIES, DERIVED_LOSSES, RELAXATION_FIELDS, SCALAR_UNITS, VELOCITY_SERIES
from .._run.viscoelastic import Relaxation
from .h5md import new_h5md, open_run, read_scales, read_scene, read_string, write_run_stats, write_scene

SCALE_UNITS = {"radial": "m", "normal": "m", "force": "N", "time": "s"}
STEP_COUNTS = ("steps", "accepted_steps", "rejected_steps")


def write_run(result: Result, path: str | Path, *, wall_time: float | None = None, author: str | None = None) -> Path:
    """Store a result (and the wall time of its simulation, s) as an H5MD file, atomically."""
    path = Path(path)
    with new_h5md(path, author) as file:
        clock = _write_body(file.create_group("particles/body"), result)
        _write_observables(file.create_group("observables"), result, clock)
        _write_parameters(file.create_group("parameters"), result, wall_time)
    return path


def read_run(path: str | Path) -> Result:
    """The Result stored by `write_run` (the scene rebuilt from the stored YAML).

    Raises FileNotFoundError for a missing file and ValueError for a file that is not a run."""
    with open_run(path) as file:
        observables = file["observables"]
        contact = observables["contact"]
        position = file["particles/body/position"]
        events = observables["events"]
        stats = file["parameters/solver_stats"]
        scalars = {name: _scalar(observables[name]) for name in SCALAR_UNITS if name in observables}
        scalars.setdefault("viscous_work", 0.0)  # files written before damping existed
        for name in SCALAR_UNITS:
            scalars.setdefault(name, float("nan"))  # files written before oblique impacts existed
        frames = len(position["time"])
        series: dict[str, Any] = {
            name: contact[f"{name}/value"][()] if name in contact else np.zeros(frames) for name in TANGENTIAL_SERIES
        }
        relaxation = _read_relaxation(observables["relaxation"]) if "relaxation" in observables else None
        return Result(
            scene=read_scene(file),
            **scalars,
            t=position["time"][()],
            indentation=position["value"][()].reshape(-1),
            velocity=file["particles/body/velocity/value"][()].reshape(-1),
            force=contact["force/value"][()],
            contact_radius=contact["contact_radius/value"][()],
            **series,
            events=[
                (float(t), str(kind)) for t, kind in zip(events["time"][()], events["kind"].asstr()[()], strict=True)
            ],
            stats={
                **{name: int(stats[name][()]) for name in STEP_COUNTS},
                "scales": read_scales(stats, SCALE_UNITS),
            },
            relaxation=relaxation,
        )


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
    _link_clock(
        position,
        _series(
            body.create_group("velocity"),
            result.velocity.reshape(frames, 1, 1),
            *VELOCITY_SERIES,
        ),
    )
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
    series = {**CONTACT_SERIES, **(TANGENTIAL_SERIES if result.scene.effects.friction is not None else {})}
    for name, (unit, description) in series.items():
        _link_clock(clock, _series(contact.create_group(name), getattr(result, name), unit, description))
    derived = {name: "J" for name in DERIVED_LOSSES if NAMED_LOSSES[name](result.scene)}
    for name, unit in {**SCALAR_UNITS, **derived}.items():
        dataset = observables.create_dataset(name, data=getattr(result, name))
        if unit:
            dataset.attrs["unit"] = unit
    events = observables.create_group("events")
    times = np.array([time for time, _ in result.events], dtype=np.float64)
    kinds = np.array([kind for _, kind in result.events], dtype=object)
    events.create_dataset("time", data=times).attrs["unit"] = "s"
    events.create_dataset("kind", data=kinds, dtype=h5py.string_dtype())
    if result.relaxation is not None:
        _write_relaxation(observables.create_group("relaxation"), result.relaxation)


def _write_relaxation(group: h5py.Group, relaxation: Relaxation) -> None:
    group.attrs["description"] = "the viscoelastic medium's springs when the run ends, and the first contact's energies"
    for name, (unit, description) in RELAXATION_FIELDS.items():
        dataset = group.create_dataset(name, data=getattr(relaxation, name))
        dataset.attrs["description"] = description
        if unit:
            dataset.attrs["unit"] = unit


def _read_relaxation(group: h5py.Group) -> Relaxation:
    return Relaxation(
        spring_position=group["spring_position"][()],
        displacement=group["displacement"][()],
        arm_stretch=group["arm_stretch"][()],
        attached=group["attached"][()],
        stored_energy=float(group["stored_energy"][()]),
        released_energy=float(group["released_energy"][()]),
        gained_energy=float(group["gained_energy"][()]),
    )


def _write_parameters(parameters: h5py.Group, result: Result, wall_time: float | None) -> None:
    write_scene(parameters, result.scene)
    stats = parameters.create_group("solver_stats")
    for name in STEP_COUNTS:
        stats.create_dataset(name, data=np.int64(result.stats[name]))
    write_run_stats(stats, wall_time, result.stats["scales"], SCALE_UNITS, of="integration")


def _scalar(dataset: h5py.Dataset):
    if dataset.dtype.kind in "OSU":
        return read_string(dataset)
    value = dataset[()]
    if dataset.dtype.kind == "b":
        return bool(value)
    if dataset.dtype.kind in "iu":
        return int(value)
    return float(value)
