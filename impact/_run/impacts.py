"""Impacts: a scene of kind `impact` → its integrator, parameters and options → one solve →
the result in SI units."""

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .. import theory
from .._integrate.codes import EVENT_KINDS, RESULT_CODES, is_success
from .._scene.scene import Scene
from .parameters import integrator_for, options_for, physics_for
from .programs import solve_by_field


@dataclass(frozen=True)
class Result:
    """Outcome of one impact, in SI units.

    `restitution` and `contact_time` describe the first contact (rebound speed over touch
    speed); `stuck` says whether the body ended captured. Trajectory arrays hold samples of
    every phase in time order (a jump of the contact shows as two samples at the same time).
    """

    scene: Scene
    status: str  # one of phases.RESULT_CODES
    restitution: float
    stuck: bool
    contact_time: float  # s; inf when the first contact never ends
    max_indentation: float  # m
    max_force: float  # N, compressive positive
    min_force: float  # N, most adhesive (negative) force
    bounces: int  # contacts simulated
    touch_velocity: float  # m/s at the first touch
    separation_velocity: float  # m/s when the first contact let go (0 if captured)
    dissipated_energy: float  # J lost in the first contact: ∮F dd
    tabor_parameter: float  # Λ (3.172): Maugis–Dugdale on a paraboloid, Greenwood–Johnson's Λ(k); else nan
    t: np.ndarray = field(repr=False)  # s
    indentation: np.ndarray = field(repr=False)  # m
    velocity: np.ndarray = field(repr=False)  # m/s, towards the surface positive
    force: np.ndarray = field(repr=False)  # N
    contact_radius: np.ndarray = field(repr=False)  # m
    events: list[tuple[float, str]] = field(repr=False)  # (time in s, kind)
    stats: dict = field(repr=False)  # solver steps; scales of the run

    @property
    def success(self) -> bool:
        return self.status in ("separated", "captured")


def simulate_impact(scene: Scene, trajectory: bool = True) -> Result:
    """Run one scene of kind `impact`; `trajectory=False` skips the time series (faster)."""
    scales, outcome = solve_by_field(integrator_for(scene), physics_for(scene), options_for(scene, trajectory))
    return to_result(scene, scales, outcome)


def tabor_parameter(scene: Scene) -> float:
    """Λ = (3Rσ0²/(πhE*²))^(1/3) (3.172) of a Maugis–Dugdale scene on a paraboloid, or the
    equivalent Λ(k) of a Greenwood–Johnson scene (`theory.double_hertz_tabor_parameter`); nan else."""
    adhesion = scene.active_adhesion
    if adhesion is not None and adhesion.model == "greenwood_johnson":
        return float(theory.double_hertz_tabor_parameter(adhesion.double_hertz_factor))
    if adhesion is None or adhesion.model != "maugis_dugdale" or scene.body.profile.shape != "paraboloid":
        return float("nan")
    return float(
        theory.tabor_parameter(
            scene.body.profile.R, adhesion.adhesive_stress, adhesion.adhesion_range, scene.material.effective_modulus
        )
    )


def to_result(scene: Scene, scales: Mapping[str, Any], outcome: Mapping[str, Any]) -> Result:
    """Scaled outcome → SI result (the fields of `Scales` and `Outcome` by name)."""
    o = {name: np.asarray(value) for name, value in outcome.items()}
    s = {name: float(value) for name, value in scales.items()}
    time, length, force = s["time"], s["normal"], s["force"]
    speed = length / time
    status = RESULT_CODES[int(o["status"])]
    touch = float(o["touch_velocity"])
    separation = float(o["separation_velocity"])
    restitution = separation / touch if touch > 0 and is_success(o["status"]) else float("nan")
    touched, let_go = float(o["touch_time"]), float(o["separation_time"])
    if not np.isfinite(touched):
        contact_time = float("nan")  # never touched
    elif not np.isfinite(let_go):
        contact_time = float("inf")  # captured, or stopped in contact
    else:
        contact_time = (let_go - touched) * time
    rows = o["trajectory"]
    rows = rows[np.isfinite(rows[:, 0])]
    repeated = np.zeros(len(rows), dtype=bool)
    repeated[1:] = np.all(rows[1:] == rows[:-1], axis=1)
    rows = rows[~repeated]  # zero-length phases repeat their single state
    kinds = o["event_kinds"]
    used = kinds >= 0
    events = [(float(t) * time, EVENT_KINDS[int(k)]) for t, k in zip(o["event_times"][used], kinds[used], strict=True)]
    return Result(
        scene=scene,
        status=status,
        restitution=restitution,
        stuck=bool(o["stuck"]),
        contact_time=contact_time,
        max_indentation=float(o["max_indentation"]) * length,
        max_force=float(o["max_force"]) * force,
        min_force=float(o["min_force"]) * force,
        bounces=int(o["contacts"]),
        touch_velocity=touch * speed,
        separation_velocity=separation * speed,
        dissipated_energy=float(o["first_contact_work"]) * force * length,
        tabor_parameter=tabor_parameter(scene),
        t=rows[:, 0] * time,
        indentation=rows[:, 1] * length,
        velocity=rows[:, 2] * speed,
        force=rows[:, 3] * force,
        contact_radius=rows[:, 4] * s["radial"],
        events=events,
        stats={
            "steps": int(o["steps"]),
            "accepted_steps": int(o["accepted_steps"]),
            "rejected_steps": int(o["rejected_steps"]),
            "scales": s,
        },
    )
