"""Impacts: a scene of kind `impact` → its integrator, parameters and options → one solve →
the result in SI units."""

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._integrate.base import AbstractIntegrator
from .._integrate.codes import EVENT_KINDS, RESULT_CODES, is_success
from .._integrate.problem import Options, Physics
from .._scene.scene import Scene
from .losses import adhesion_hysteresis, plastic_work, unrecovered_elastic_energy
from .parameters import integrator_for, options_for, physics_for
from .programs import solve_by_field


@dataclass(frozen=True)
class Result:
    """Outcome of one impact, in SI units.

    `restitution` and `contact_time` describe the first contact (rebound speed over touch
    speed); `stuck` says whether the body ended captured. Speeds and the dissipated energy are
    those of the relative motion (reduced mass) when the scene has a counterpart; the lab-frame
    velocities after the first contact are positive along the body's approach. Trajectory arrays hold samples of
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
    dissipated_energy: float  # J lost in the first contact: ∮F dd (elastic and viscous force)
    plastic_work: float  # J of it dissipated by plastic flow (effects.plasticity); 0 without
    viscous_work: float  # J of it dissipated by damping, ∫F_visc ḋ dt (effects.damping); 0 without
    # (the rest of dissipated_energy: with adhesion the adhesion hysteresis, `adhesion_hysteresis`;
    # damped without adhesion the elastic energy left in the surface, `unrecovered_elastic_energy`)
    tabor_parameter: float  # Λ (3.172): Maugis–Dugdale on a paraboloid, Greenwood–Johnson's Λ(k); else nan
    centre_of_mass_velocity: float  # m/s, lab frame; 0 for a rigid flat at rest
    body_velocity_after: float  # m/s, lab frame, after the first contact (< 0: rebounding)
    counterpart_velocity_after: float  # m/s, lab frame, after the first contact (0 for the flat)
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

    @property
    def adhesion_hysteresis(self) -> float:
        """J of the first contact's loss dissipated neither by plastic flow nor by damping: the
        jump-in and the snap-off of the adhesive contact (0 without adhesion)."""
        return float(
            adhesion_hysteresis(self.scene.adhesive, self.dissipated_energy, self.plastic_work, self.viscous_work)
        )

    @property
    def unrecovered_elastic_energy(self) -> float:
        """J of the first contact's loss that a damped contact without adhesion leaves in the
        surface as elastic energy (it lets go at F = 0, still indented); 0 otherwise."""
        damped = self.scene.effects.damping is not None
        return float(unrecovered_elastic_energy(self.scene.adhesive, damped, self.dissipated_energy, self.viscous_work))

    @property
    def body_velocity_after_cm(self) -> float:
        """The body's velocity after the first contact in the centre-of-mass frame (m/s)."""
        return self.body_velocity_after - self.centre_of_mass_velocity

    @property
    def counterpart_velocity_after_cm(self) -> float:
        """The counterpart's velocity after the first contact in the centre-of-mass frame (m/s)."""
        return self.counterpart_velocity_after - self.centre_of_mass_velocity


def simulate_impact(scene: Scene, trajectory: bool = True) -> Result:
    """Run one scene of kind `impact`; `trajectory=False` skips the time series (faster)."""
    return solve_scene(scene, integrator_for(scene), options_for(scene, trajectory))


def solve_scene(scene: Scene, integrator: AbstractIntegrator, options: Options) -> Result:
    """The scene's impact run by `integrator` with `options` (the scene's own in
    `simulate_impact`; a caller's where it shares one program between scenes, e.g. traced
    tolerances or a spring capacity)."""
    physics = physics_for(scene)
    scales, outcome = solve_by_field(integrator, physics, options)
    return to_result(scene, scales, outcome, integrator, physics)


def tabor_parameter(scene: Scene) -> float:
    """Λ of the scene's adhesion model (3.172): Maugis–Dugdale on a paraboloid, Greenwood–Johnson's
    Λ(k) (`theory.double_hertz_tabor_parameter`); nan else."""
    adhesion = scene.active_adhesion
    return float("nan") if adhesion is None else adhesion.tabor_parameter(scene)


def velocities_after(scene: Scene, separation_velocity: "float | np.ndarray") -> tuple[Any, Any, Any]:
    """(centre-of-mass velocity, body's, counterpart's) in the lab frame (m/s, positive along the
    body's approach) once the surfaces separate at the relative speed `separation_velocity`
    (floats; or arrays, elementwise, for a scene holding arrays of a sweep's points):
    u₁ = V − m₂/(m₁ + m₂)·v_sep, u₂ = V + m₁/(m₁ + m₂)·v_sep, V = (m₁v₁ − m₂v₂)/(m₁ + m₂)."""
    if scene.counterpart is None:
        return 0.0, -separation_velocity, 0.0
    mass, other = scene.body.resolved_mass, scene.counterpart.resolved_mass
    total = mass + other
    centre = (mass * scene.start.velocity - other * scene.counterpart.velocity) / total
    return centre, centre - other / total * separation_velocity, centre + mass / total * separation_velocity


def to_result(
    scene: Scene,
    scales: Mapping[str, Any],
    outcome: Mapping[str, Any],
    integrator: AbstractIntegrator,
    physics: Physics,
) -> Result:
    """Scaled outcome → SI result (the fields of `Scales` and `Outcome` by name) of the scene
    solved by `integrator` with `physics`."""
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
    dissipated = float(o["first_contact_work"]) * force * length
    rebound = separation * speed if is_success(o["status"]) else float("nan")
    centre, body_after, counterpart_after = velocities_after(scene, rebound)
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
        dissipated_energy=dissipated,
        plastic_work=float(plastic_work(integrator, physics, float(o["max_indentation"]) * length, dissipated)),
        viscous_work=float(o["first_contact_viscous_work"]) * force * length,
        tabor_parameter=tabor_parameter(scene),
        centre_of_mass_velocity=centre,
        body_velocity_after=body_after,
        counterpart_velocity_after=counterpart_after,
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
