"""`simulate(scene)`: one impact from a scene, results back in SI units."""

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import equinox as eqx
import jax.numpy as jnp
import numpy as np

from .._integrate import continuum
from .._integrate import dugdale as dugdale_impact
from .._integrate import springs
from .. import theory
from .._integrate import verlet
from .._integrate.codes import EVENT_KINDS, RESULT_CODES, is_success
from .._scene.scene import Scene, load_scene
from .._integrate.problem import Numerics, Physics, build_problem

if TYPE_CHECKING:
    from .indentation import IndentationResult

_SAMPLES_PER_PHASE = 64
# Profiles whose edge functions may turn many times need more turning points and a finer search.
_MANY_TURNS = {"wavy_paraboloid": (64, 8192), "tabulated": (32, 4096)}


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
    tabor_parameter: float  # Λ (3.172) of Maugis–Dugdale adhesion on a paraboloid; nan otherwise
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


def numerics_for(scene: Scene, trajectory: bool = True) -> Numerics:
    """The static choices of a scene (changing them recompiles)."""
    adhesion = scene.effects.adhesion
    max_turns, turn_grid = _MANY_TURNS.get(scene.body.profile.shape, (4, 384))
    return Numerics(
        adhesive=scene.adhesive,
        gravity=scene.effects.gravity is not None,
        adhesion_model=adhesion.model if scene.adhesive else "jkr",
        method=scene.solver.method,
        dt=scene.solver.dt,
        rtol=scene.solver.rtol,
        atol=scene.solver.atol,
        spring_array=scene.contact.springs != "continuum",
        max_steps=scene.solver.max_steps,
        max_bounces=scene.limits.max_bounces,
        max_turns=max_turns,
        turn_grid=turn_grid,
        # Loading from a = 0 on a steep tip needs the timed path: no jump-in, or a power law
        # (for n ≤ 1/2 the attach edge starts rising from a = 0 even with adhesion).
        timed_loading=not scene.adhesive or adhesion.approach == 0.0 or scene.body.profile.shape == "power_law",
        samples_per_phase=_SAMPLES_PER_PHASE if trajectory else 0,
        # Only a partial approach work of adhesion puts the attach edge's turn decades below the
        # branch grid (Δγa = Δγ turns at the jump-in scale, Δγa = 0 does not turn).
        tip_search=scene.adhesive and 0.0 < adhesion.approach < adhesion.work_of_adhesion,
    )


def physics_for(scene: Scene) -> Physics:
    """The traced SI parameters of a scene."""
    adhesion = scene.effects.adhesion
    dugdale = scene.adhesive and adhesion.model == "maugis_dugdale"
    springs = scene.contact.springs
    gravity = scene.effects.gravity
    duration = scene.limits.duration
    return Physics(
        profile=scene.body.profile.build(),
        E_star=jnp.asarray(scene.material.effective_modulus, jnp.float64),
        mass=jnp.asarray(scene.body.resolved_mass, jnp.float64),
        velocity=jnp.asarray(scene.initial.velocity, jnp.float64),
        gap=jnp.asarray(scene.initial.gap, jnp.float64),
        work_of_adhesion=jnp.asarray(adhesion.work_of_adhesion if scene.adhesive else 0.0, jnp.float64),
        approach_work_of_adhesion=jnp.asarray(adhesion.approach if scene.adhesive else 0.0, jnp.float64),
        adhesive_stress=jnp.asarray(adhesion.adhesive_stress if dugdale else np.nan, jnp.float64),
        gravity=jnp.asarray(gravity.g if gravity else 0.0, jnp.float64),
        time_limit=jnp.asarray(np.inf if duration is None else duration, jnp.float64),
        spring_length=jnp.asarray(np.nan if scene.contact.length is None else scene.contact.length, jnp.float64),
        spring_count=jnp.asarray(np.nan if springs == "continuum" else springs, jnp.float64),
    )


@eqx.filter_jit
def solve(physics: Physics, numerics: Numerics):
    """Scale, tabulate and integrate one impact; returns (scales, scaled outcome)."""
    if numerics.adhesion_model == "maugis_dugdale":
        problem = dugdale_impact.build_dugdale_problem(physics, numerics)
        return problem.scales, dugdale_impact.integrate(problem, numerics)
    problem = build_problem(physics, numerics)
    if not numerics.spring_array:
        return problem.scales, continuum.integrate(problem, numerics)
    count = physics.spring_count.astype(int)
    if numerics.method == "verlet":
        return problem.scales, verlet.integrate(problem, numerics, physics.spring_length, count)
    return problem.scales, springs.integrate(problem, numerics, physics.spring_length, count)


def simulate(scene: "Scene | dict | str | Path", *, trajectory: bool = True) -> "Result | IndentationResult":
    """Run one scene. `trajectory=False` skips the time series (faster). A scene of kind
    `indentation` gives an `indentation.IndentationResult` (its curve is always kept)."""
    scene = load_scene(scene)
    if scene.kind == "indentation":
        from .indentation import simulate_indentation

        return simulate_indentation(scene)
    scales, outcome = solve(physics_for(scene), numerics_for(scene, trajectory))
    return to_result(scene, scales, outcome)


def tabor_parameter(scene: Scene) -> float:
    """Λ = (3Rσ0²/(πhE*²))^(1/3) (3.172) of a Maugis–Dugdale scene on a paraboloid; nan else."""
    adhesion = scene.effects.adhesion
    if not scene.adhesive or adhesion.model != "maugis_dugdale" or scene.body.profile.shape != "paraboloid":
        return float("nan")
    return float(
        theory.tabor_parameter(
            scene.body.profile.R, adhesion.adhesive_stress, adhesion.adhesion_range, scene.material.effective_modulus
        )
    )


def to_result(scene: Scene, scales, outcome) -> Result:
    """Scaled outcome → SI result."""
    o = {name: np.asarray(value) for name, value in vars(outcome).items()}
    s = {name: float(value) for name, value in vars(scales).items()}
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
    events = [(float(t) * time, EVENT_KINDS[int(k)]) for t, k in zip(o["event_times"][used], kinds[used])]
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
