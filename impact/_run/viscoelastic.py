"""Impacts on a viscoelastic half-space: the solve that also returns the medium's springs, and
their state in SI units (`Relaxation`, `Result.relaxation`)."""

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._core.pytree import fields
from .._core.stored import call_stored
from .._integrate.problem import Options, Physics
from .._integrate.viscoelastic import ViscoelasticSprings
from .programs import Fields


@dataclass(frozen=True)
class Relaxation:
    """A viscoelastic medium when the run ends (the body has let go, or is captured), and the
    energy of its first contact, in SI units.

    Attributes:
        spring_position: x of each spring of the array [m].
        displacement: Each spring's displacement u [m], > 0 pressed in: the dent the body leaves,
            still creeping back.
        arm_stretch: The stretch q_i of each spring's Maxwell arms [m], one column per Prony term
            (the arm's force per width is E_i·q_i).
        attached: Whether each spring is still in contact.
        stored_energy: The elastic energy the medium held when the first contact ended [J]
            (`Result.unrecovered_elastic_energy`).
        released_energy: Elastic energy released by the springs that let go with adhesion in
            the first contact [J] (`f²/(2E₀*)` per width each).
        gained_energy: Elastic energy gained by the springs that jumped onto the body [J].
    """

    spring_position: np.ndarray = field(repr=False)
    displacement: np.ndarray = field(repr=False)
    arm_stretch: np.ndarray = field(repr=False)
    attached: np.ndarray = field(repr=False)
    stored_energy: float
    released_energy: float
    gained_energy: float


def solve_relaxing(
    integrator: ViscoelasticSprings, physics: Physics, options: Options
) -> tuple[Fields, Fields, Fields]:
    """(scales, outcome, the medium at the end) by field name, traced where the cache holds no
    program of its key."""
    return call_stored(_solve_relaxing, integrator, physics, options)


def _solve_relaxing(integrator: ViscoelasticSprings, physics: Physics, options: Options):
    problem = integrator.build(physics, options)
    outcome, relaxed = integrator.integrate_with_springs(problem, options)
    springs = relaxed.springs
    medium = {
        "spacing": relaxed.spacing,
        "count": relaxed.count,
        "attached": springs.attached,
        "displacement": springs.displacement,
        "arm_stretch": springs.stretches,
        "released": relaxed.released,
        "gained": relaxed.gained,
    }
    return fields(problem.scales), fields(outcome), medium


def relaxation_of(scales: Mapping[str, Any], outcome: Mapping[str, Any], medium: Mapping[str, Any]) -> Relaxation:
    """The medium at the end of a run in SI units (from scaled fields by name)."""
    radial, normal = float(scales["radial"]), float(scales["normal"])
    energy = float(scales["force"]) * normal
    spacing = float(medium["spacing"])
    count = int(medium["count"])
    return Relaxation(
        spring_position=(np.arange(count) + 0.5) * spacing * radial,
        displacement=np.asarray(medium["displacement"])[:count] * normal,
        arm_stretch=np.asarray(medium["arm_stretch"])[:count] * normal,
        attached=np.asarray(medium["attached"], dtype=bool)[:count],
        stored_energy=float(outcome["first_contact_stored_energy"]) * energy,
        released_energy=float(medium["released"]) * energy,
        gained_energy=float(medium["gained"]) * energy,
    )
