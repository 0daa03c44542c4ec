"""The `effects.viscoelasticity` section: a half-space relaxing as a Prony series, and what a
scene with it can and cannot run (each refusal with its reason)."""

from typing import TYPE_CHECKING, Annotated, Any

import numpy as np
from pydantic import Field

from .._integrate.viscoelastic import ViscoelasticSprings
from .._law.jkr import JKR
from .._law.maugis_dugdale import MaugisDugdale
from .._law.viscoelastic import Viscoelastic, ViscoelasticDugdale
from . import domains as d
from .adhesion import AbstractAdhesion
from .adhesion.base import value
from .adhesion.maugis_dugdale import MaugisDugdaleAdhesion
from .domains import within
from .errors import FieldProblem
from .profiles import Number
from .sections import MIDPOINT, Section
from .springs import spring_capacity

if TYPE_CHECKING:
    from .scene import Scene

MAX_TERMS = 16  # Prony terms: each adds an internal variable to every spring


class PronyTerm(Section):
    """One Maxwell arm of the medium: E_i·e^(−t/τ_i) in its relaxation modulus."""

    modulus: Annotated[Number, within(d.MODULUS)] = Field(description="E_i (Pa), added to the effective modulus `E*`")
    time: Annotated[Number, within(d.RELAXATION_TIME)] = Field(description="relaxation time τ_i (s)")


class Viscoelasticity(Section):
    """A viscoelastic half-space: its effective modulus relaxes as `E*(t) = E∞* + Σ E_i·e^(−t/τ_i)`
    (a generalized Maxwell model; one term is the standard linear solid). `material` gives the
    relaxed (long-time) modulus `E∞*`; the instantaneous one is `E₀* = E∞* + Σ E_i`. Runs on a spring
    array (`contact.springs: N`), each spring the medium's element (Popov, Willert & Heß, MDR
    handbook III, Facta Universitatis 16 (2018) 99)."""

    prony: list[PronyTerm] = Field(
        min_length=1, max_length=MAX_TERMS, description="the Prony terms {modulus: E_i (Pa), time: τ_i (s)}"
    )

    def law(self, adhesion: AbstractAdhesion | None, xp: Any = np) -> Viscoelastic:
        """The medium's law with the adhesion's works (0 without adhesion; a sweep's arrays with
        `xp` numpy: the terms along the last axis)."""

        def stacked(name: str):
            return xp.stack(xp.broadcast_arrays(*(value(xp, getattr(term, name)) for term in self.prony)), axis=-1)

        zero = value(xp, 0.0)
        law = None if adhesion is None else adhesion.law(xp)
        assert law is None or isinstance(law, JKR | MaugisDugdale), "validated: JKR or Maugis–Dugdale adhesion"
        terms = {"moduli": stacked("modulus"), "times": stacked("time")}
        if law is None or adhesion is None:
            return Viscoelastic(**terms, work_of_adhesion=zero, approach_work_of_adhesion=zero)
        works = {"work_of_adhesion": law.work_of_adhesion, "approach_work_of_adhesion": law.approach_work_of_adhesion}
        if isinstance(law, MaugisDugdale) and not adhesion.zero_range:
            return ViscoelasticDugdale(**terms, **works, adhesive_stress=law.adhesive_stress)
        return Viscoelastic(**terms, **works)

    def integrator(self, scene: "Scene") -> ViscoelasticSprings:
        """The spring array stepped by the implicit midpoint rule (validated: springs and dt given)."""
        springs, solver = scene.contact.springs, scene.solver
        assert isinstance(springs, int) and solver.dt is not None, "validated: contact.springs N and solver.dt"
        return ViscoelasticSprings(
            capacity=spring_capacity(springs),
            dt=solver.dt,
            max_steps=solver.max_steps,
        )

    def instantaneous_modulus(self, relaxed: float) -> float:
        """E₀* = E∞* + Σ E_i (Pa) for the relaxed modulus `relaxed` (Pa)."""
        return relaxed + sum(term.modulus for term in self.prony)

    def describe(self) -> str:
        """The medium in words and SI units (`impact validate`)."""
        terms = ", ".join(f"E = {term.modulus:.6g} Pa, τ = {term.time:.6g} s" for term in self.prony)
        return f"viscoelastic half-space (Prony terms: {terms})"

    def check(self, scene: "Scene") -> None:
        """Refuse (`FieldProblem`) what a viscoelastic half-space cannot run in `scene`."""
        effects = scene.effects
        refusals = (
            (
                "effects.damping",
                effects.damping,
                "the medium's dashpots already dissipate on the springs in contact, and a damping force on the "
                "same springs would count that dissipation twice",
            ),
            (
                "effects.plasticity",
                effects.plasticity,
                "Thornton's limiting contact pressure is a law of an elastic half-space",
            ),
            (
                "effects.gravity",
                effects.gravity,
                "between bounces the surface still creeps back, which the analytic flight between contacts does "
                "not follow",
            ),
            (
                "effects.friction",
                effects.friction,
                "the tangential springs of a viscoelastic medium (their own relaxation, slip against creep) are "
                "not implemented",
            ),
            ("shear", scene.shear, "the tangential springs of a viscoelastic medium are not implemented"),
        )
        for field, section, why in refusals:
            if section is not None:
                raise FieldProblem(field, f"not with effects.viscoelasticity: {why}")
        adhesion = effects.adhesion
        if isinstance(adhesion, MaugisDugdaleAdhesion):
            self._check_dugdale(scene, adhesion)
        elif adhesion is not None and not adhesion.zero_range:
            raise FieldProblem(
                "effects.adhesion.model",
                f"{adhesion.name!r} not with effects.viscoelasticity: its double-Hertz stress acts at every gap, "
                "so every free spring would carry a load set by its own gap; use model 'jkr' or 'maugis_dugdale'",
            )
        if scene.contact.springs == "continuum":
            raise FieldProblem(
                "contact.springs",
                "a viscoelastic half-space runs on a spring array: give the number of springs N (each spring "
                "carries the medium's history; the continuum law keeps none). The paraboloid's closed forms of "
                "Lee & Radok and Ting are impact.theory.lee_radok_force and impact.theory.ting_force",
            )
        springs = scene.contact.springs
        if springs not in d.VISCOELASTIC_SPRINGS:
            why = f"with effects.viscoelasticity {d.VISCOELASTIC_SPRINGS.reason}"
            raise FieldProblem("contact.springs", d.outside(springs, d.VISCOELASTIC_SPRINGS, why))
        if scene.kind == "impact":
            self._check_impact(scene)
        else:
            self._check_indentation(scene)

    @staticmethod
    def _check_dugdale(scene: "Scene", adhesion: MaugisDugdaleAdhesion) -> None:
        if adhesion.hysteretic:
            raise FieldProblem(
                "effects.adhesion.approach_work_of_adhesion",
                f"{adhesion.approach:g} J/m² (below work_of_adhesion) not with effects.viscoelasticity: the "
                "Dugdale zone of a viscoelastic half-space attaches and detaches over the one range h = Δγ/σ0; "
                "leave approach_work_of_adhesion out",
            )
        if scene.kind != "impact":
            raise FieldProblem(
                "effects.adhesion.model",
                "'maugis_dugdale' with effects.viscoelasticity runs impacts only: the indentation test at a rate "
                "does not step the Dugdale zone's creep; use model 'jkr' for a viscoelastic indentation",
            )

    @staticmethod
    def _check_impact(scene: "Scene") -> None:
        if scene.solver.method != MIDPOINT:
            raise FieldProblem(
                "solver.method",
                f"a viscoelastic impact steps its springs with method {MIDPOINT!r} at a fixed solver.dt (s), "
                f"not {scene.solver.method!r}",
            )

    @staticmethod
    def _check_indentation(scene: "Scene") -> None:
        program = scene.loading
        if program.rate is None:
            raise FieldProblem(
                "program.rate",
                "missing: a viscoelastic half-space answers the rate of loading (m/s under displacement control, "
                "N/s under force control)",
            )
        if not program.peak > 0:
            raise FieldProblem("program.peak", "must be > 0 for a viscoelastic half-space (a ramp at program.rate)")
        if scene.control == "force" and scene.adhesive:
            raise FieldProblem(
                "control",
                "'force' with adhesion on a viscoelastic half-space: its pull-off under force control is a "
                "dynamic instability that a rate-controlled test without inertia cannot follow; use 'displacement'",
            )


def medium_problem(scene: "Scene") -> FieldProblem | None:
    """What a scene without `effects.viscoelasticity` names that only a viscoelastic medium takes."""
    if scene.solver.method == MIDPOINT:
        return FieldProblem(
            "solver.method",
            f"{MIDPOINT!r} steps the springs of a viscoelastic half-space (effects.viscoelasticity); an elastic "
            "spring array takes 'verlet', or a diffrax method for its exact event stepping",
        )
    program = scene.program
    if program is not None and (program.rate is not None or program.hold > 0):
        field = "program.rate" if program.rate is not None else "program.hold"
        return FieldProblem(
            field,
            "only for a viscoelastic half-space (effects.viscoelasticity): an elastic indentation test is "
            "quasi-static, independent of rate and time",
        )
    return None
