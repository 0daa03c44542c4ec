"""The `effects.friction` section: Coulomb friction on the tangential MDR springs of an oblique
impact (or of a shear test), and what it can run: its checks, its integrator and its traced
parameters."""

import math
from typing import TYPE_CHECKING, Annotated, Any, Literal

import numpy as np
from pydantic import Field

from .. import theory
from .._effects.friction import Friction
from .._integrate.oblique import ObliqueSpringArray
from .domains import TIME_STEP, Domain, within
from .errors import FieldProblem
from .profiles import Number, ParaboloidSpec, ProfileSpec, SphereSpec
from .sections import Section
from .springs import spring_capacity

if TYPE_CHECKING:
    from .scene import Scene

COEFFICIENT = Domain(0.0, 100.0, "", reason="0 is frictionless; measured coefficients of solids lie below 10")
# Shapes with a lever arm R from the centre to the contact (and the default inertia (2/5)mR²).
LEVER_SHAPES = ("paraboloid", "sphere")
# Springs of an oblique impact at most: each tangential step costs O(N), and the steps of a
# contact grow with N (one at least between two spring events): O(N²) per impact.
MAX_SPRINGS = 16384
# Tangential steps per (Hertzian) contact at most, from `time_step`.
MAX_STEPS = 1e7


def lever_arm(profile: ProfileSpec) -> Any:
    """R (m) from the centre to the contact of a sphere (paraboloid or sphere); None for other shapes."""
    return profile.R if isinstance(profile, (ParaboloidSpec, SphereSpec)) else None


class FrictionSection(Section):
    """Coulomb friction μ on the tangential springs of the MDR (one per normal spring, stiffness
    G*·Δx): spring by spring (Cattaneo–Mindlin partial slip, Mindlin–Deresiewicz memory), or
    Thornton's whole-contact limit. Normal and tangential are uncoupled (Goodman's approximation):
    friction leaves the normal impact as it is."""

    coefficient: Annotated[Number, within(COEFFICIENT)] = Field(description="friction coefficient μ (0: frictionless)")
    limit: Literal["per_spring", "thornton"] = Field(
        "per_spring",
        description=(
            "'per_spring': each spring sticks while its tangential force is within μ times its normal force "
            "(springs in tension carry none); 'thornton': the whole contact slides at μ|F_n + 2F_c|, "
            "F_c = (3/2)πRΔγ (Thornton 1991, as LAMMPS's jkr model)"
        ),
    )
    time_step: Annotated[Number, within(TIME_STEP)] | None = Field(
        None,
        description=(
            "largest time step of the tangential springs (s); default: 1/1024 of the impact's time unit "
            "√(m/(E*ℓx)), about 1/2700 of a Hertzian contact"
        ),
    )

    def check(self, scene: "Scene") -> None:
        """Refuse (`FieldProblem`, relative to the scene) what friction cannot run in `scene`."""
        where, why = "effects.friction", self._refusal(scene)
        if why is None:
            where, why = self._body_refusal(scene)
        if why is not None:
            raise FieldProblem(where, why)

    def _refusal(self, scene: "Scene") -> str | None:
        """Why the effects, contact or solver of `scene` cannot take friction, or None."""
        adhesion = scene.active_adhesion
        if scene.kind != "impact":
            return None if scene.shear is not None else "an indentation takes friction with a shear program (shear)"
        if scene.counterpart is not None:
            return (
                "not with a counterpart: the tangential motion of two free spinning bodies (two lever arms and "
                "inertias) is not simulated; the body hits a rigid flat"
            )
        if scene.effects.plasticity is not None:
            return "not with effects.plasticity: Thornton's plastic law runs on the continuum law, without springs"
        if scene.effects.damping is not None:
            return "not with effects.damping: the springs' normal forces would hold the viscous force"
        if adhesion is not None and not adhesion.zero_range:
            return (
                f"not with adhesion model {adhesion.name!r}: its springs beyond the contact carry the adhesive "
                "stress along a curve that has no tangential springs; friction takes jkr adhesion or none"
            )
        if scene.contact.springs == "continuum":
            return (
                "runs on a spring array (contact.springs: N): the tangential state is one displacement per "
                "spring, remembered through the contact (Mindlin–Deresiewicz), which the continuum law does not "
                "carry; without effects.friction the body slides on unchanged"
            )
        if scene.solver.method == "verlet":
            return (
                "rides the exact event stepper of the spring array, not 'verlet': leave solver.method and solver.dt out"
            )
        if scene.contact.springs > MAX_SPRINGS:
            return (
                f"takes at most {MAX_SPRINGS} springs, not {scene.contact.springs}: an impact's tangential steps "
                "cost O(N) each and grow with N"
            )
        return self._step_refusal(scene)

    def _step_refusal(self, scene: "Scene") -> str | None:
        """Why `time_step` cannot run (more than `MAX_STEPS` a Hertzian contact), or None."""
        radius = lever_arm(scene.body.profile)
        if self.time_step is None or radius is None:
            return None
        contact = float(
            theory.hertz_contact_time(
                scene.approach_velocity, scene.body.resolved_mass, radius, scene.material.effective_modulus
            )
        )
        if contact / self.time_step > MAX_STEPS:
            return (
                f"time_step {self.time_step:g} s would take {contact / self.time_step:.3g} steps over the Hertzian "
                f"contact time {contact:.3g} s, more than {MAX_STEPS:.0e}"
            )
        return None

    def _body_refusal(self, scene: "Scene") -> tuple[str, str | None]:
        """(field, why) where the body or material cannot take friction; why None where they can."""
        shape = scene.body.profile.shape
        if scene.kind == "impact" and shape not in LEVER_SHAPES:
            return "body.profile.shape", (
                f"friction needs the lever arm R from the centre to the contact of a sphere "
                f"({' or '.join(LEVER_SHAPES)}), not {shape!r}"
            )
        if scene.material.tangential_modulus is None:
            return "material.G_star", (
                "missing: friction needs the tangential modulus G*; give E and nu (with E_body and nu_body), "
                "from which 1/G* = (2 − ν)/(4G) + (2 − ν_b)/(4G_b), or G_star beside E_star"
            )
        return "", None

    def integrator(self, scene: "Scene") -> ObliqueSpringArray:
        """The spring array with tangential springs (validated: a spring array of N springs)."""
        springs = scene.contact.springs
        assert not isinstance(springs, str), "validated: friction runs on a spring array"
        limit = "per_spring" if self.limit == "per_spring" else "whole_contact"
        return ObliqueSpringArray(capacity=spring_capacity(springs), limit=limit)

    def physics(self, scene: "Scene", xp: Any = np) -> Friction:
        """The traced SI parameters (arrays of a sweep's points with `xp` numpy)."""
        radius = lever_arm(scene.body.profile)
        assert radius is not None, "validated: friction in an impact needs a sphere's lever arm"
        mass = scene.body.resolved_mass
        inertia = scene.body.inertia
        adhesion = scene.active_adhesion
        adhesive_load = 0.0
        if self.limit == "thornton" and adhesion is not None:
            adhesive_load = 3.0 * math.pi * radius * adhesion.work_of_adhesion  # 2F_c, F_c = (3/2)πRΔγ

        def value(number):
            return xp.asarray(number, dtype=xp.float64)

        start = scene.start
        return Friction(
            coefficient=value(self.coefficient),
            shear_modulus=value(scene.material.tangential_modulus),
            tangential_velocity=value(start.tangential_velocity),
            spin=value(start.spin),
            inertia=value(0.4 * mass * radius**2 if inertia is None else inertia),
            lever_arm=value(radius),
            adhesive_load=value(adhesive_load),
            time_step=value(np.nan if self.time_step is None else self.time_step),
        )

    def describe(self) -> str:
        """The friction and its limit in words (`impact validate`)."""
        limit = "per spring" if self.limit == "per_spring" else "Thornton's whole-contact limit μ|F_n + 2F_c|"
        return f"friction (μ = {self.coefficient:g}, {limit})"
