"""The scene file: a validated description of one impact or indentation test, in SI units.

`load_scene` turns a YAML file or a mapping into a `Scene`, or raises `SceneError` naming each
bad field by its dotted path; `scene_yaml` writes a scene back, defaults filled in.
"""

from collections.abc import Mapping
from pathlib import Path
from typing import Any, Literal

import numpy as np
import yaml
from pydantic import Field, ValidationError, field_validator, model_validator

from .. import theory
from .._integrate.base import AbstractIntegrator
from .._law.base import AbstractContactLaw
from .._law.jkr import Elastic
from .adhesion import AbstractAdhesion
from .adhesion.base import edge_integrator
from .cost import check_run_cost
from .effects import Effects
from .errors import FieldProblem, SceneError, problems_of
from .method_support import energy_ends_refusal, quadrature_refusal
from .profiles import ParaboloidSpec, ProfileSpec
from .reading import read_yaml
from .representable import check_representable, time_unit
from .sections import (
    MASS_OR_DENSITY,
    QUADRATURE,
    SOLVER_METHODS,
    Body,
    Contact,
    Counterpart,
    Initial,
    Limits,
    Material,
    Program,
    Section,
    Solver,
)
from .shear import Shear
from .viscoelasticity import medium_problem

MAX_NAME = 100  # characters of a scene's name (its runs' folder; file names end at 255 bytes)

# Sections that only an impact reads: an indentation refuses them rather than ignore them.
_IMPACT_ONLY = {
    "initial": "an indentation is quasi-static: it has no initial velocity or gap",
    "solver": "an indentation needs no ODE solver (its march along the branches is exact)",
    "limits": "an indentation ends at pull-off (no bounces or duration to limit)",
    "counterpart": "an indentation presses the body into a fixed half-space",
}


class Scene(Section):
    """One impact (`kind: impact`, the default) or one quasi-static indentation test
    (`kind: indentation`: `control` and `program`, no mass, initial state or solver)."""

    name: str = Field(
        "scene",
        pattern=r"^[A-Za-z0-9_.-]+$",
        description=f"name of the run (file-name safe: letters, digits, _ . -; at most {MAX_NAME} characters)",
    )
    kind: Literal["impact", "indentation"] = Field(
        "impact", description="'impact' (a body hits the surface) or 'indentation' (quasi-static loading, §3.3)"
    )
    control: Literal["force", "displacement"] | None = Field(
        None, description="indentation only: what the program drives, 'force' (ξ = 3) or 'displacement' (ξ = 1)"
    )
    program: Program | None = Field(None, description="indentation only: the loading program")
    body: Body
    material: Material
    counterpart: Counterpart | None = Field(
        None, description="a second free body that the body hits; default: a rigid flat at rest"
    )
    initial: Initial | None = None
    shear: Shear | None = Field(None, description="indentation only: a tangential program at the held peak load")
    effects: Effects = Effects()
    contact: Contact = Contact()
    solver: Solver = Solver()
    limits: Limits = Limits()

    @field_validator("name")
    @classmethod
    def _names_a_folder(cls, name: str) -> str:
        if len(name) > MAX_NAME:
            raise ValueError(f"at most {MAX_NAME} characters (it names the run's folder), got {len(name)}")
        if set(name) == {"."}:
            raise ValueError(f"{name!r} names no folder of its own; use letters or digits")
        return name

    @model_validator(mode="after")
    def _sections_of_the_kind(self):
        if self.kind == "impact":
            for name in ("control", "program"):
                if getattr(self, name) is not None:
                    raise FieldProblem(name, "only for kind 'indentation'")
            if self.initial is None:
                raise FieldProblem("initial", "missing (required)")
            if self.body.mass is None and self.body.density is None:
                raise FieldProblem("body", MASS_OR_DENSITY)
            return self
        for name in ("control", "program"):
            if getattr(self, name) is None:
                raise FieldProblem(name, "missing (required for kind 'indentation')")
        for name, why in _IMPACT_ONLY.items():
            if name in self.model_fields_set:
                raise FieldProblem(name, f"not for kind 'indentation': {why}")
        for name in ("mass", "density"):
            if getattr(self.body, name) is not None:
                raise FieldProblem(f"body.{name}", "not for kind 'indentation': a quasi-static test needs no mass")
        if self.effects.gravity is not None:
            raise FieldProblem("effects.gravity", "not for kind 'indentation': the program sets the load")
        return self

    @model_validator(mode="after")
    def _reaches_the_surface(self):
        if self.kind != "impact":
            return self
        falls = self.effects.gravity is not None and self.initial.gap > 0
        if self.approach_velocity <= 0 and not falls:
            raise FieldProblem("initial.velocity", "must be > 0 (or name gravity and a gap > 0 to drop the body)")
        return self

    @model_validator(mode="after")
    def _counterpart_fits(self):
        if self.counterpart is None:
            return self
        if self.effects.gravity is not None:
            raise FieldProblem(
                "effects.gravity",
                "not with a counterpart: gravity accelerates both free bodies alike and leaves their relative motion",
            )
        if self.counterpart.profile is not None and self.body.profile.shape != "paraboloid":
            raise FieldProblem(
                "body.profile.shape",
                f"a paraboloid counterpart needs a paraboloid body (only two paraboloids sum to a paraboloid, "
                f"1/R = 1/R₁ + 1/R₂), not {self.body.profile.shape!r}; a flat counterpart takes any body",
            )
        return self

    @model_validator(mode="after")
    def _viscoelastic_medium(self):
        medium = self.effects.viscoelasticity
        if medium is not None:
            medium.check(self)
        elif (problem := medium_problem(self)) is not None:
            raise problem
        return self

    @model_validator(mode="after")
    def _verlet_steps_springs(self):
        if self.solver.method == "verlet" and self.contact.springs == "continuum":
            raise FieldProblem(
                "contact.springs",
                "solver.method 'verlet' steps a spring array: give the number of springs N "
                "(the continuum law takes a diffrax method: " + ", ".join(SOLVER_METHODS) + ")",
            )
        return self

    @model_validator(mode="after")
    def _sections_supported(self):  # each refuses (FieldProblem) what it cannot run in this scene
        for section in (self.effects.adhesion, self.shear, self.effects.friction):
            if section is not None:
                section.check(self)
        return self

    @model_validator(mode="after")
    def _plasticity_supported(self):
        if self.effects.plasticity is None:
            return self
        why = None
        if self.kind != "impact":
            why = "simulated in impacts only (kind 'impact')"
        elif self.contact_profile.shape != "paraboloid":
            why = (
                f"Thornton's limiting contact pressure is a law of the paraboloid (the Hertzian peak pressure "
                f"2E*a/(πR)), not of {self.contact_profile.shape!r}"
            )
        elif self.active_adhesion is not None:
            why = self._adhesive_plasticity_problem()
        if why is None and self.contact.springs != "continuum":
            why = "runs on the continuum law only (contact.springs: continuum)"
        if why is not None:
            raise FieldProblem("effects.plasticity", why)
        return self

    def _adhesive_plasticity_problem(self) -> str | None:
        """Why Thornton & Ning's adhesive elastic–plastic law cannot run this scene, or None."""
        adhesion, plasticity = self.effects.adhesion, self.effects.plasticity
        assert adhesion is not None and plasticity is not None, "called with both named"
        if not adhesion.zero_range:
            return f"with adhesion the law of Thornton & Ning (1998) is JKR's, not {adhesion.name!r}"
        if adhesion.approach != adhesion.work_of_adhesion:
            return (
                "with adhesion the law of Thornton & Ning (1998) is the reversible JKR law: "
                f"approach_work_of_adhesion must equal work_of_adhesion ({adhesion.work_of_adhesion:g} J/m²), "
                f"not {adhesion.approach:g}"
            )
        touch = float(
            theory.adhesive_plastic_touch_pressure(
                self.contact_profile.build().radius_scale(), self.material.effective_modulus, adhesion.work_of_adhesion
            )
        )
        yield_pressure = plasticity.yield_pressure
        if yield_pressure <= touch:
            return (
                f"yield_pressure {yield_pressure:g} Pa is at or below the pressure at the centre of the JKR contact "
                f"right after its jump-in, {touch:.6g} Pa: the contact would yield as it forms, where Thornton & "
                "Ning's law is undefined"
            )
        return None

    @model_validator(mode="after")
    def _damping_supported(self):
        if self.effects.damping is None:
            return self
        adhesion = self.active_adhesion
        why = None
        if self.kind != "impact":
            why = "simulated in impacts only (kind 'impact')"
        elif self.effects.plasticity is not None:
            why = "not with effects.plasticity: Thornton's plastic law is simulated undamped only"
        elif adhesion is not None and not adhesion.zero_range:
            why = f"not with adhesion model {adhesion.name!r}: damping acts on the JKR (zero-range) law only"
        elif self.contact.springs != "continuum":
            why = "runs on the continuum law only (contact.springs: continuum)"
        if why is not None:
            raise FieldProblem("effects.damping", why)
        return self

    @model_validator(mode="after")
    def _energy_ends_supported(self):
        why = energy_ends_refusal(self)
        if self.solver.phase_ends == "energy" and why is not None:
            raise FieldProblem("solver.phase_ends", why)
        return self

    @model_validator(mode="after")
    def _quadrature_supported(self):
        if self.solver.method != QUADRATURE:
            return self
        why = quadrature_refusal(self)
        if why is not None:
            raise FieldProblem("solver.method", f"'quadrature' {why}")
        return self

    @model_validator(mode="after")
    def _representable(self):
        if self.kind == "impact":
            check_representable(self)
        return self

    @model_validator(mode="after")
    def _within_budget(self):
        verlet = self.kind == "impact" and self.solver.method == "verlet"
        check_run_cost(self, time_unit(self) if verlet else None)
        return self

    @property
    def contact_profile(self) -> ProfileSpec:
        """The profile of the gap between the two surfaces: the body's against a flat, else the
        paraboloid of the effective radius R₁R₂/(R₁ + R₂) (Hertz)."""
        radius = self.effective_radius
        return self.body.profile if radius is None else ParaboloidSpec.model_construct(R=radius)

    @property
    def effective_radius(self) -> float | None:
        """R₁R₂/(R₁ + R₂) (m) of a paraboloid body and a paraboloid counterpart; None otherwise."""
        other = None if self.counterpart is None else self.counterpart.radius
        if other is None:
            return None
        body = self.body.profile
        assert isinstance(body, ParaboloidSpec), "validated: a paraboloid counterpart needs a paraboloid body"
        return body.R * other / (body.R + other)

    @property
    def reduced_mass(self) -> float:
        """The mass (kg) of the relative motion: m₁m₂/(m₁ + m₂), the body's against a rigid flat."""
        mass = self.body.resolved_mass
        if self.counterpart is None:
            return mass
        other = self.counterpart.resolved_mass
        return mass * other / (mass + other)

    @property
    def approach_velocity(self) -> float:
        """Speed (m/s) at which the surfaces approach at the start: the body's along the normal,
        plus the counterpart's towards it."""
        speed = self.start.normal_velocity
        return speed if self.counterpart is None else speed + self.counterpart.velocity

    @property
    def phase_ends(self) -> str:
        """Where the contact phases end (`solver.phase_ends`): as given, else 'energy' where the
        scene allows it and 'integrated' where not."""
        if self.solver.phase_ends is not None:
            return self.solver.phase_ends
        return "integrated" if energy_ends_refusal(self) is not None else "energy"

    @property
    def active_adhesion(self) -> AbstractAdhesion | None:
        """The adhesion section where adhesion is simulated (named, with Δγ > 0), else None."""
        adhesion = self.effects.adhesion
        return adhesion if adhesion is not None and adhesion.work_of_adhesion > 0 else None

    def contact_law(self, xp: Any = np) -> AbstractContactLaw:
        """The contact law the scene names, with its values (arrays of a sweep's points with
        `xp` numpy): a viscoelastic medium's (with its adhesion's works), its adhesion model's,
        Thornton's where it names plasticity (with adhesion Thornton & Ning's), the MDR without
        adhesion where it names neither."""
        adhesion, plasticity, medium = self.effects.adhesion, self.effects.plasticity, self.effects.viscoelasticity
        if medium is not None:
            return medium.law(adhesion, xp)
        if plasticity is not None:
            return plasticity.law(adhesion, xp)
        return Elastic() if adhesion is None else adhesion.law(xp)

    def integrator(self) -> AbstractIntegrator:
        """The integrator that runs the scene's impact: its viscoelastic medium's, its friction's, its
        plasticity's, or its adhesion model's where adhesion is simulated (Δγ > 0), else the MDR's
        without adhesion."""
        adhesion = self.active_adhesion
        if self.effects.viscoelasticity is not None:
            return self.effects.viscoelasticity.integrator(self)
        if self.effects.friction is not None:
            return self.effects.friction.integrator(self)
        if self.effects.plasticity is not None:
            return self.effects.plasticity.integrator(self)
        return edge_integrator(self) if adhesion is None else adhesion.integrator(self)

    @property
    def adhesive(self) -> bool:
        """Whether adhesion is simulated (named, with Δγ > 0)."""
        return self.active_adhesion is not None

    @property
    def start(self) -> Initial:
        """The initial state of an impact (validated present for kind 'impact')."""
        if self.initial is None:
            raise ValueError(f"scene {self.name!r} of kind {self.kind!r} has no initial state")
        return self.initial

    @property
    def loading(self) -> Program:
        """The loading program of an indentation (validated present for kind 'indentation')."""
        if self.program is None:
            raise ValueError(f"scene {self.name!r} of kind {self.kind!r} has no loading program")
        return self.program


def load_scene(source: "str | Path | Mapping | Scene") -> Scene:
    """A validated Scene from a YAML file path, a mapping, or a Scene."""
    if isinstance(source, Scene):
        return source
    data = dict(source) if isinstance(source, Mapping) else read_yaml(source)
    try:
        return Scene.model_validate(data)
    except ValidationError as error:
        raise SceneError(problems_of(error)) from None


def scene_yaml(scene: Scene) -> str:
    """The resolved scene (defaults filled in) as YAML."""
    skipped = set(_IMPACT_ONLY) if scene.kind == "indentation" else None  # refused there
    return yaml.safe_dump(scene.model_dump(mode="json", exclude_none=True, exclude=skipped), sort_keys=False)
