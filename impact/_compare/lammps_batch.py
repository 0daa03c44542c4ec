"""One LAMMPS run of a whole velocity sweep, as a user batches it: one particle per speed on a
wall (or one pair of particles per speed), spaced so that they never meet, all in one run.

What is measured, per particle, by LAMMPS itself at every step (fix store/state of atom-style
variables): whether it is in contact (a nonzero force on it: only the contact acts), the number
of steps in contact, the largest compressive force and the most adhesive force (the force along
the approach, +z on the body, and its most negative value). The run stops once every particle
has left its contact, or at `duration`; a particle still in contact then is captured
(restitution 0, contact time inf). The restitution is the rebound speed over the approach speed
(with a counterpart, of the relative motion); the contact time is the steps in contact times dt.
"""

import math
import time
from dataclasses import dataclass

import numpy as np

from .lammps_library import open_lammps
from .lammps_model import LammpsModel

# Checks of "has every particle left its contact?" over the longest run allowed.
_CHECKS = 200
# Centre-to-centre spacing of neighbouring particles (or pairs), in particle diameters.
_SPACING = 2.0
# Overlap at the start, relative to the distance of the centres at the touch: the contact starts
# at the first force evaluation (t = 0, δ ≈ 0) as impact's does, not one step later at δ = v₀dt
# (a first-order error: the jump-in's force missed over v₀dt).
_START_OVERLAP = 1e-12
# LAMMPS's library interface: per-atom data (style) held as an array (type).
_PER_ATOM, _ARRAY = 1, 2


class LammpsFailed(RuntimeError):
    """LAMMPS stopped with an error (its message)."""


@dataclass(frozen=True)
class BatchResult:
    """Per speed of one LAMMPS run: restitution (0 if captured), contact time (s; inf if
    captured), largest compressive and most adhesive forces (N) and whether it was captured; the time step (s), the
    steps run, the wall time (s) of the input and the run (after the library has loaded), the
    LAMMPS release and the input as run."""

    restitution: np.ndarray
    contact_time: np.ndarray
    max_force: np.ndarray
    min_force: np.ndarray
    captured: np.ndarray
    dt: float
    steps: int
    seconds: float
    version: str
    commands: tuple[str, ...]


def run_batch(model: LammpsModel, velocities: np.ndarray, dt: float, duration: float) -> BatchResult:
    """Run every speed of `velocities` (m/s, the body's towards the surface) as one LAMMPS batch
    with time step `dt` (s) for at most `duration` (s)."""
    instance = open_lammps()
    start = time.perf_counter()
    try:
        commands = setup_commands(model, np.asarray(velocities, dtype=float), dt)
        _execute(instance, commands)
        steps = _run_until_separated(instance, math.ceil(duration / dt), len(velocities))
        result = _read(instance, model, np.asarray(velocities, dtype=float), dt)
        version = str(instance.version())
    finally:
        instance.close()
    return BatchResult(
        **result,
        dt=dt,
        steps=steps,
        seconds=time.perf_counter() - start,
        version=version,
        commands=(*commands, f"run {steps}"),
    )


def setup_commands(model: LammpsModel, velocities: np.ndarray, dt: float) -> list[str]:
    """The LAMMPS input of the batch up to its run: SI units, the particles just touching their
    surface (the gap adds only flight without gravity), the contact model, the integrator and
    the per-particle measurements."""
    particles = model.particles
    n, r1, r2 = len(velocities), particles.body_radius, particles.counterpart_radius
    width = 2 * (r1 + (r2 if particles.pair else 0.0))
    spacing = _SPACING * width
    lowest = -2 * r2 if particles.pair else 0.0
    commands = [
        "units si",
        "newton off",  # mdr requires it; the other models do not care
        f"atom_style {model.model.traits.atom_style}",
        "atom_modify map array sort 0 0",
        "comm_modify vel yes",
        "boundary f f m",
        f"region box block 0 {n * spacing:.17g} {-spacing:.17g} {spacing:.17g} {lowest:.17g} {4 * r1:.17g} units box",
        f"create_box {2 if particles.pair else 1} box",
    ]
    body_z = (r1 + (r2 if particles.pair else 0.0)) * (1 - _START_OVERLAP)
    commands += [f"create_atoms 1 single {(i + 0.5) * spacing:.17g} 0 {body_z:.17g} units box" for i in range(n)]
    commands += [f"set type 1 diameter {2 * r1:.17g}", f"set type 1 mass {particles.body_mass:.17g}"]
    commands += [f"set atom {i + 1} vz {-v:.17g}" for i, v in enumerate(velocities)]
    body, counterpart = (model.normal_model(material) for material in model.materials)
    if particles.pair:
        commands += [f"create_atoms 2 single {(i + 0.5) * spacing:.17g} 0 0 units box" for i in range(n)]
        commands += [
            f"set type 2 diameter {2 * r2:.17g}",
            f"set type 2 mass {particles.counterpart_mass:.17g}",
            f"set type 2 vz {particles.counterpart_velocity:.17g}",
            "pair_style granular",
            *(
                [f"pair_coeff * * {body}"]  # one material (mdr takes one normal model only)
                if body == counterpart
                else [f"pair_coeff 1 1 {body}", f"pair_coeff 2 2 {counterpart}"]  # LAMMPS mixes 1-2: E*, γ, η₀
            ),
            f"neighbor {min(r1, r2) / 2:.17g} bin",
        ]
    else:
        commands.append(f"fix wall all wall/gran granular {body} zplane 0.0 NULL")
    return [
        *commands,
        "group body type 1",
        "fix move all nve/sphere",
        "variable largest_force atom 0.5*(f_history[1]+fz+abs(f_history[1]-fz))",
        "variable steps_in_contact atom f_history[2]+(fz!=0)",
        "variable most_adhesive_force atom 0.5*(f_history[3]+fz-abs(f_history[3]-fz))",
        "fix history body store/state 1 v_largest_force v_steps_in_contact v_most_adhesive_force",
        f"timestep {dt:.17g}",
    ]


def _execute(instance, commands: list[str]) -> None:
    for command in commands:
        try:
            instance.command(command)
        except Exception as error:  # the lammps module raises a bare Exception with LAMMPS's message
            raise LammpsFailed(f"{command!r}: {str(error).strip()}") from None


def _run_until_separated(instance, most_steps: int, bodies: int) -> int:
    """Run in blocks until every body has left its contact (it touched, and no force acts on it)
    or `most_steps` have run; return the steps run."""
    block = max(1, math.ceil(most_steps / _CHECKS))
    done = 0
    while done < most_steps:
        steps = min(block, most_steps - done)
        _execute(instance, [f"run {steps} pre {'yes' if done == 0 else 'no'} post no"])
        done += steps
        force, touched = _body_columns(instance, bodies)
        if np.all((touched > 0) & (force == 0)):
            break
    return done


def _body_columns(instance, bodies: int) -> tuple[np.ndarray, np.ndarray]:
    """(fz, steps in contact) of the bodies, by atom id."""
    order = _order(instance)[:bodies]
    force = np.array(instance.numpy.extract_atom("f"))[order, 2]
    touched = np.array(instance.numpy.extract_fix("history", _PER_ATOM, _ARRAY))[order, 1]
    return force, touched


def _order(instance) -> np.ndarray:
    """Local indices of the atoms in order of their ids (1, 2, ...)."""
    count = int(instance.extract_global("nlocal"))
    return np.argsort(np.array(instance.numpy.extract_atom("id"))[:count])


def _read(instance, model: LammpsModel, velocities: np.ndarray, dt: float) -> dict[str, np.ndarray]:
    n = len(velocities)
    order = _order(instance)
    speed = np.array(instance.numpy.extract_atom("v"))[order, 2]
    force = np.array(instance.numpy.extract_atom("f"))[order, 2][:n]
    history = np.array(instance.numpy.extract_fix("history", _PER_ATOM, _ARRAY))[order][:n]
    captured = force != 0
    if model.particles.pair:
        separation = (speed[:n] - speed[n:]) / (velocities + model.particles.counterpart_velocity)
    else:
        separation = speed[:n] / velocities
    return {
        "restitution": np.where(captured, 0.0, separation),
        "contact_time": np.where(captured, np.inf, history[:, 1] * dt),
        "max_force": history[:, 0],
        "min_force": history[:, 2],
        "captured": captured,
    }
