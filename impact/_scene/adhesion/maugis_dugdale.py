"""Maugis–Dugdale adhesion (§3.8): a constant stress σ0 up to the range h = Δγ/σ0 (3.4), with
approach hysteresis Δγa ≤ Δγ (the stress attaches over ha = Δγa/σ0)."""

from typing import TYPE_CHECKING, Annotated, Any, ClassVar, Literal

import numpy as np
from pydantic import Field, model_validator

from ... import theory
from ..._integrate.base import AbstractIntegrator
from ..._integrate.curve import CurveIntegrator
from ..._integrate.curve_quadrature import CurveQuadrature
from ..._integrate.dugdale import DugdaleSpringIntegrator
from ..._law.maugis_dugdale import MaugisDugdale
from ...profiles import Profile
from .. import domains as d
from ..domains import within
from ..errors import FieldProblem
from ..profiles import Number
from ..sections import QUADRATURE, SOLVER_METHODS, Length, WorkOfAdhesion
from ..springs import DUGDALE_MAX_SPRINGS, spring_capacity, unresolved_zone
from .base import adaptive, value
from .hysteresis import AbstractHystereticAdhesion

if TYPE_CHECKING:
    from ..scene import Scene

# Profiles the Maugis–Dugdale zone is built for: smooth, unbounded, with a finite slope at the
# tip (the zone's radius must grow from 0 where the tip comes within range).
DUGDALE_SHAPES = ("paraboloid", "power_law", "cone")
# The least Δγa/Δγ of approach hysteresis: its approach range ha = Δγa/σ0 must be resolved by
# the approach curve (docs/src/finite-range.md, "Approach hysteresis", Limits).
DUGDALE_LEAST_APPROACH = 1e-9


class MaugisDugdaleAdhesion(AbstractHystereticAdhesion):
    """Maugis–Dugdale adhesion: the stress σ0 acts wherever the gap is below the range h,
    Δγ = σ0·h; with Δγa < Δγ it attaches over the range Δγa/σ0 and detaches over h."""

    model: Literal["maugis_dugdale"]
    approach_work_of_adhesion: WorkOfAdhesion | None = Field(
        None,
        description=(
            "work of adhesion on approach Δγa (J/m²), 1e-9·Δγ ≤ Δγa ≤ Δγ; default Δγ (no hysteresis): the "
            "stress attaches over the range Δγa/σ0 and detaches over Δγ/σ0"
        ),
    )
    stress: Annotated[Number, within(d.STRESS)] | None = Field(
        None, description="adhesive stress σ0 (Pa); or give range"
    )
    range: Length | None = Field(None, description="range h (m) of the adhesive stress; or give stress")

    foreign_keys: ClassVar[dict[str, str]] = {
        "k": "only for model 'greenwood_johnson' (maugis_dugdale has no double-Hertz factor)"
    }
    curve_fields: ClassVar[tuple[str, ...]] = ("work_of_adhesion", "stress", "range")

    @model_validator(mode="after")
    def _parameters(self):
        approach = self.approach_work_of_adhesion
        if approach is not None and approach < DUGDALE_LEAST_APPROACH * self.work_of_adhesion:
            raise FieldProblem(
                "approach_work_of_adhesion",
                f"{approach:g} J/m² is below {DUGDALE_LEAST_APPROACH:g}·work_of_adhesion "
                f"({DUGDALE_LEAST_APPROACH * self.work_of_adhesion:g} J/m²): model 'maugis_dugdale' takes "
                f"{DUGDALE_LEAST_APPROACH:g}·Δγ ≤ Δγa ≤ Δγ (its approach range Δγa/σ0 must be resolved; "
                "attach on touch, Δγa = 0, is model 'jkr')",
            )
        if (self.stress is None) == (self.range is None):
            raise FieldProblem(
                "stress", "model 'maugis_dugdale' needs exactly one of stress (Pa) and range (m): Δγ = σ0·h"
            )
        if self.work_of_adhesion == 0:
            raise FieldProblem("work_of_adhesion", "must be > 0 for model 'maugis_dugdale' (drop adhesion for none)")
        return self

    @property
    def adhesive_stress(self) -> float:
        """σ0 (Pa): given, or Δγ/h."""
        return _factor(self.stress, self.work_of_adhesion, self.range)

    @property
    def adhesion_range(self) -> float:
        """h (m): given, or Δγ/σ0."""
        return _factor(self.range, self.work_of_adhesion, self.stress)

    def law(self, xp: Any = np) -> MaugisDugdale:
        return MaugisDugdale(
            work_of_adhesion=value(xp, self.work_of_adhesion),
            approach_work_of_adhesion=value(xp, self.approach),
            adhesive_stress=value(xp, self.adhesive_stress),
        )

    def integrator(self, scene: "Scene") -> AbstractIntegrator:
        springs = scene.contact.springs
        if springs != "continuum":
            return DugdaleSpringIntegrator(**adaptive(scene), capacity=spring_capacity(springs))
        if scene.solver.method == QUADRATURE:
            return CurveQuadrature(hysteresis=self.hysteretic)
        return CurveIntegrator(**adaptive(scene), hysteresis=self.hysteretic)

    def describe(self) -> str:
        hysteresis = (
            f", Δγa = {self.approach:g} J/m², ha = {self.approach / self.adhesive_stress:.6g} m"
            if self.hysteretic
            else ""
        )
        return (
            f"Maugis–Dugdale adhesion (Δγ = {self.work_of_adhesion:g} J/m², "
            f"σ0 = {self.adhesive_stress:.6g} Pa, h = {self.adhesion_range:.6g} m{hysteresis})"
        )

    def check(self, scene: "Scene") -> None:
        profile = scene.body.profile
        if profile.shape not in DUGDALE_SHAPES:
            raise FieldProblem(
                "effects.adhesion.model",
                f"maugis_dugdale needs a smooth unbounded profile ({', '.join(DUGDALE_SHAPES)}), not {profile.shape!r}",
            )
        if profile.shape == "power_law" and profile.n < 1:
            raise FieldProblem(
                "body.profile.n",
                "maugis_dugdale needs n >= 1: for n < 1 the tip's slope is infinite where the zone starts",
            )
        springs = scene.contact.springs
        if springs == "continuum":
            return
        if springs > DUGDALE_MAX_SPRINGS and scene.effects.viscoelasticity is None:
            raise FieldProblem(
                "contact.springs",
                f"maugis_dugdale takes at most {DUGDALE_MAX_SPRINGS} springs, not {springs}: every spring event is "
                "a ride of its own (use 'continuum' for the limit N → ∞)",
            )
        if scene.solver.method == "verlet":
            raise FieldProblem(
                "solver.method",
                "'verlet' steps the JKR spring array only; a maugis_dugdale spring array is ridden by an adaptive "
                "method (" + ", ".join(SOLVER_METHODS) + ")",
            )
        if self.hysteretic:
            raise FieldProblem(
                "effects.adhesion.approach_work_of_adhesion",
                f"{self.approach:g} J/m² is below work_of_adhesion ({self.work_of_adhesion:g} J/m²): a "
                "maugis_dugdale spring array has no approach hysteresis (its curve is built spring by spring for one "
                "range; the frozen zone is derived for the continuum law only): leave it out, or set it to "
                "work_of_adhesion, or use contact.springs: continuum",
            )
        why = unresolved_zone(
            scene.contact_profile, scene.material.effective_modulus, self, scene.contact.length, springs
        )
        if why is not None:
            raise FieldProblem("contact.springs", why)

    def curve_pieces(self, springs: int | str) -> int:
        return 0 if isinstance(springs, str) else spring_capacity(springs) + 1

    def curve_hysteresis(self) -> bool:
        return self.hysteretic

    def tabor_parameter(self, scene: "Scene") -> float:
        """Λ = (3Rσ0²/(πhE*²))^(1/3) (3.172) on a paraboloid; nan on other bodies."""
        profile = scene.contact_profile
        if profile.shape != "paraboloid":
            return float("nan")
        modulus = scene.material.effective_modulus
        return float(theory.tabor_parameter(profile.R, self.adhesive_stress, self.adhesion_range, modulus))

    def dmt_pull_off(self, profile: Profile) -> float:
        """πσ0·b², b the radius where the body's gap reaches the range h."""
        return float(np.pi * self.adhesive_stress * _radius_at_height(profile, self.adhesion_range) ** 2)

    def closed_form_name(self, scene: "Scene") -> str:
        if self.hysteretic:
            return "no closed form (Maugis–Dugdale with approach hysteresis)"
        limit = {
            "paraboloid": "Thornton–Ning (3.50–51)",
            "power_law": "power law (3.81–82)",
            "cone": "power law (3.81–82)",
        }
        return f"{limit[scene.contact_profile.shape]}: the JKR limit Λ → ∞ of Maugis–Dugdale"


def _radius_at_height(profile: Profile, height: float, steps: int = 200) -> float:
    """b with f(b) = h (m), by bisection in log b (f rises from f(0) = 0)."""
    lower, upper = 1e-30, 1e30
    for _ in range(steps):
        middle = np.sqrt(lower * upper)
        lower, upper = (middle, upper) if float(profile.f(middle)) < height else (lower, middle)
    return float(np.sqrt(lower * upper))


def _factor(given: float | None, product: float, other: float | None) -> float:
    """One factor of Δγ = σ0·h: the one `given`, else the `product` over the `other` one."""
    if given is not None:
        return given
    assert other is not None, "validated: maugis_dugdale takes stress or range"
    return product / other
