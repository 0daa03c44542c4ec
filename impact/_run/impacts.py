"""Impacts: a scene of kind `impact` → its integrator, parameters and options → one solve →
the result in SI units."""

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from .._integrate.base import AbstractIntegrator
from .._integrate.codes import EVENT_KINDS, RESULT_CODES, is_success
from .._integrate.problem import Options, Physics
from .._integrate.viscoelastic import ViscoelasticSprings
from .._scene.friction import lever_arm
from .._scene.scene import Scene
from .losses import adhesion_hysteresis, plastic_work, unrecovered_elastic_energy
from .parameters import concrete_physics, integrator_for, options_for
from .programs import solve_by_field
from .tangential import tangential_results
from .viscoelastic import Relaxation, relaxation_of, solve_relaxing

if TYPE_CHECKING:
    import pandas
    import xarray


@dataclass(frozen=True)
class Result:
    """Outcome of one impact, in SI units.

    `restitution` and `contact_time` describe the first contact; `stuck` says whether the body
    ended captured. Speeds and the dissipated energy are those of the relative motion (reduced
    mass) when the scene has a counterpart; the lab-frame velocities after the first contact are
    positive along the body's approach. The trajectory arrays hold samples of every phase in time
    order (a jump of the contact shows as two samples at the same time).

    Attributes:
        scene: The scene that was run.
        status: How the run ended: `separated` or `captured` (the physical outcomes), else why it
            stopped (`bounce_limit`, `time_limit`, `solver_failure`, ...; the user guide lists
            them).
        restitution: Rebound speed over touch speed of the first contact, dimensionless; 0 if
            captured, nan without a physical outcome.
        stuck: Whether the body ended captured.
        contact_time: Duration of the first contact [s]; inf when it never ends, nan without a
            touch.
        max_indentation: Deepest indentation [m].
        max_force: Largest compressive force [N].
        min_force: Most adhesive (most negative) force [N].
        bounces: Contacts simulated.
        touch_velocity: Speed at the first touch [m/s].
        separation_velocity: Speed when the first contact let go [m/s]; 0 if captured.
        dissipated_energy: Energy lost in the first contact, ∮F dd of the elastic and viscous
            force [J]. The named losses below, `adhesion_hysteresis` and
            `unrecovered_elastic_energy` add up to it.
        plastic_work: The part of `dissipated_energy` lost to plastic flow (`effects.plasticity`)
            [J]; 0 without.
        viscous_work: The part of `dissipated_energy` lost to damping, ∫F_visc ḋ dt
            (`effects.damping`), or in the dashpots of a viscoelastic medium
            (`effects.viscoelasticity`) [J]; 0 without.
        tabor_parameter: Λ (3.172), dimensionless, of a Maugis–Dugdale scene on a paraboloid, the
            equivalent Λ(k) of a Greenwood–Johnson scene; nan otherwise.
        centre_of_mass_velocity: Velocity of the centre of mass, lab frame [m/s]; 0 against a
            rigid flat at rest.
        body_velocity_after: The body's velocity after the first contact, lab frame [m/s]
            (< 0: rebounding).
        counterpart_velocity_after: The counterpart's velocity after the first contact, lab
            frame [m/s]; 0 for the flat.
        tangential_velocity_after: Velocity of the body's centre along the surface after the
            first contact [m/s], along its sliding before (`initial.angle`); nan unless it
            separated. Without `effects.friction` the body slides on unchanged.
        spin_after: The body's spin after the first contact in radians per second [s⁻¹], > 0
            rolling it along its sliding; nan unless it separated.
        tangential_restitution: |v_t′|/v_t of the centre, dimensionless (as Kharaz et al. and
            DEM codes define it); nan without sliding before.
        contact_point_tangential_restitution: −w′/w of the contact point, w = v_t − Rω,
            dimensionless: −1 slides on unchanged, +1 reversed (Maw, Barber & Fawcett's β).
        rebound_angle: Angle of the rebound from the surface normal, atan(v_t′/v_n′), in radians
            (dimensionless).
        friction_work: Energy lost to friction in the first contact [J] (0 without friction):
            the kinetic energy in, translational and rotational, is the energy out plus
            `dissipated_energy` plus this.
        t: Time of each trajectory sample [s].
        indentation: Indentation d at each sample [m], > 0 pressed in.
        velocity: Approach speed ḋ at each sample [m/s], towards the surface positive.
        force: Contact force at each sample [N], compressive positive.
        contact_radius: Contact radius a at each sample [m].
        tangential_force: Tangential force Q on the body at each sample [N], > 0 against its
            sliding (0 without friction).
        stick_radius: Inner radius c of the slip zone at each sample [m]: the contact radius
            where no spring slips, 0 where the whole contact slides (also without friction).
        events: The events in time order, as (time [s], kind) pairs; the kinds are listed in
            the user guide.
        stats: Solver steps (`steps`, `accepted_steps`, `rejected_steps`) and the run's
            `scales`; read back by `impact.open_run`, the `provenance` of the file (the versions
            that wrote it).
        relaxation: A viscoelastic half-space (`effects.viscoelasticity`): its springs when the
            run ends (places and displacements [m]) and the first contact's stored and snap
            energies [J] (`impact.Relaxation`); None otherwise.
    """

    scene: Scene
    status: str  # one of codes.RESULT_CODES
    restitution: float
    stuck: bool
    contact_time: float
    max_indentation: float
    max_force: float
    min_force: float
    bounces: int
    touch_velocity: float
    separation_velocity: float
    dissipated_energy: float
    plastic_work: float
    viscous_work: float
    tabor_parameter: float
    centre_of_mass_velocity: float
    body_velocity_after: float
    counterpart_velocity_after: float
    tangential_velocity_after: float
    spin_after: float
    tangential_restitution: float
    contact_point_tangential_restitution: float
    rebound_angle: float
    friction_work: float
    t: np.ndarray = field(repr=False)
    indentation: np.ndarray = field(repr=False)
    velocity: np.ndarray = field(repr=False)
    force: np.ndarray = field(repr=False)
    contact_radius: np.ndarray = field(repr=False)
    tangential_force: np.ndarray = field(repr=False)
    stick_radius: np.ndarray = field(repr=False)
    events: list[tuple[float, str]] = field(repr=False)  # kinds: codes.EVENT_KINDS
    stats: dict = field(repr=False)
    relaxation: Relaxation | None = field(default=None, repr=False)

    @property
    def success(self) -> bool:
        """Whether the run ended in a physical outcome (separated or captured)."""
        return self.status in ("separated", "captured")

    @property
    def adhesion_hysteresis(self) -> float:
        """The part of the first contact's loss dissipated neither by plastic flow nor by damping
        [J]: the jump-in and the snap-off of the adhesive contact (0 without adhesion)."""
        return float(
            adhesion_hysteresis(
                self.scene.adhesive, self.dissipated_energy, self.plastic_work, self.viscous_work, self.stored_energy
            )
        )

    @property
    def stored_energy(self) -> float:
        """The elastic energy a viscoelastic medium still held when the first contact ended [J]
        (0 for an elastic one)."""
        return 0.0 if self.relaxation is None else self.relaxation.stored_energy

    @property
    def unrecovered_elastic_energy(self) -> float:
        """The part of the first contact's loss left in the surface as elastic energy [J]: by a
        damped contact without adhesion (it lets go at F = 0, still indented), by a viscoelastic
        medium (its springs still strained); 0 otherwise."""
        damped = self.scene.effects.damping is not None
        return float(
            unrecovered_elastic_energy(
                self.scene.adhesive, damped, self.dissipated_energy, self.viscous_work, self.stored_energy
            )
        )

    def to_xarray(self) -> "xarray.Dataset":
        """The run as an `xarray.Dataset` (needs the extra `impact-mdr[analysis]`): the time
        series along `sample` with the coordinate `time` (s), every scalar result as a 0-d
        variable (`status` as CF flags), the events along `event`; `units` and `description`
        on each, the scene (YAML) and versions as attributes. See `SweepResult.to_xarray`."""
        from .labelled import run_dataset

        return run_dataset(self)

    def to_pandas(self) -> "pandas.DataFrame":
        """The time series as a `pandas.DataFrame`, one row a sample (time, indentation,
        velocity, contact_radius, force); `attrs["units"]` their units (needs the extra
        `impact-mdr[analysis]`)."""
        from .labelled import run_frame

        return run_frame(self)

    @property
    def body_velocity_after_cm(self) -> float:
        """The body's velocity after the first contact in the centre-of-mass frame [m/s]."""
        return self.body_velocity_after - self.centre_of_mass_velocity

    @property
    def counterpart_velocity_after_cm(self) -> float:
        """The counterpart's velocity after the first contact in the centre-of-mass frame [m/s]."""
        return self.counterpart_velocity_after - self.centre_of_mass_velocity


def simulate_impact(scene: Scene, trajectory: bool = True) -> Result:
    """Run one scene of kind `impact`; `trajectory=False` skips the time series (faster)."""
    return solve_scene(scene, integrator_for(scene), options_for(scene, trajectory))


def solve_scene(scene: Scene, integrator: AbstractIntegrator, options: Options) -> Result:
    """The scene's impact run by `integrator` with `options` (the scene's own in
    `simulate_impact`; a caller's where it shares one program between scenes, e.g. traced
    tolerances or a spring capacity)."""
    physics = concrete_physics(scene)
    if isinstance(integrator, ViscoelasticSprings):
        scales, outcome, medium = solve_relaxing(integrator, physics, options)
        result = to_result(scene, scales, outcome, integrator, physics)
        return dataclasses.replace(result, relaxation=relaxation_of(scales, outcome, medium))
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


def slid(scene: Scene, tangential: Mapping[str, Any] | None, scales: Mapping[str, float], rebound: float) -> dict:
    """The tangential results (`tangential.TANGENTIAL_RESULTS`) of a run whose first contact let
    go at the normal speed `rebound` (m/s; nan where it did not), from the integrator's scaled
    `tangential` results (None without friction: the body slides on unchanged)."""
    start = scene.start
    before = (float(start.tangential_velocity), start.spin)
    lever = lever_arm(scene.body.profile) or 0.0
    if tangential is None:
        after, work = before, 0.0
    else:
        speed = scales["normal"] / scales["time"]
        after = (float(tangential["velocity"]) * speed, float(tangential["surface_speed"]) * speed / lever)
        work = float(tangential["friction_work"]) * scales["force"] * scales["normal"]
    if not np.isfinite(rebound):
        after = (float("nan"), float("nan"))
    return {name: float(value) for name, value in tangential_results(before, after, lever, rebound, work).items()}


def to_result(
    scene: Scene,
    scales: Mapping[str, Any],
    outcome: Mapping[str, Any],
    integrator: AbstractIntegrator,
    physics: Physics,
) -> Result:
    """Scaled outcome → SI result (the fields of `Scales` and `Outcome` by name) of the scene
    solved by `integrator` with `physics`."""
    tangential = outcome.get("tangential")
    o = {name: np.asarray(value) for name, value in outcome.items() if name != "tangential"}
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
    sliding = slid(scene, tangential, s, rebound if np.isfinite(let_go) else float("nan"))
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
        **sliding,
        t=rows[:, 0] * time,
        indentation=rows[:, 1] * length,
        velocity=rows[:, 2] * speed,
        force=rows[:, 3] * force,
        contact_radius=rows[:, 4] * s["radial"],
        tangential_force=rows[:, 5] * force if rows.shape[1] > 5 else np.zeros(len(rows)),
        stick_radius=rows[:, 6] * s["radial"] if rows.shape[1] > 5 else np.zeros(len(rows)),
        events=events,
        stats={
            "steps": int(o["steps"]),
            "accepted_steps": int(o["accepted_steps"]),
            "rejected_steps": int(o["rejected_steps"]),
            "scales": s,
        },
    )
