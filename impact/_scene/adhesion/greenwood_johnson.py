"""Greenwood–Johnson double-Hertz adhesion (§3.9) of a paraboloid: the factor k of the second
Hertz distribution (k → ∞: JKR, k → 0: DMT)."""

from typing import TYPE_CHECKING, Annotated, Any, ClassVar, Literal

import numpy as np
from pydantic import Field, model_validator

from ... import theory
from ..._integrate.base import AbstractIntegrator
from ..._integrate.curve import CurveIntegrator
from ..._integrate.curve_quadrature import CurveQuadrature
from ..._law.double_hertz import tip_radius
from ..._law.greenwood_johnson import GreenwoodJohnson
from ...profiles import Profile
from .. import domains as d
from ..domains import within
from ..errors import FieldProblem
from ..profiles import Number
from ..sections import QUADRATURE, WorkOfAdhesion
from .base import AbstractAdhesion, adaptive, value
from .hysteresis import approach_not_above

if TYPE_CHECKING:
    from ..scene import Scene

# Profiles the double Hertz is built for: the paraboloid of §3.9 (and the sphere's tip, its
# paraboloid r²/(2R)).
DOUBLE_HERTZ_SHAPES = ("paraboloid", "sphere")
_FINITE_RANGE = "only for model 'maugis_dugdale' (greenwood_johnson takes k)"


class GreenwoodJohnsonAdhesion(AbstractAdhesion):
    """Greenwood–Johnson adhesion: a double-Hertz stress of factor k (3.198); large k is JKR-like,
    small k DMT-like. It loads and unloads on the stable branches of its curve (no approach
    hysteresis)."""

    model: Literal["greenwood_johnson"]
    k: Annotated[Number, within(d.DOUBLE_HERTZ_FACTOR)] | None = Field(
        None,
        description=(
            "the factor k of the double-Hertz stress (3.198); large k is JKR-like, small k DMT-like "
            "(Tabor Λ = (36k²/(π³(1 + k)))^(1/3))"
        ),
    )

    approach_work_of_adhesion: WorkOfAdhesion | None = Field(
        None, description="not taken: the stable branches load and unload alike (no approach hysteresis)"
    )

    foreign_keys: ClassVar[dict[str, str]] = {"stress": _FINITE_RANGE, "range": _FINITE_RANGE}
    curve_fields: ClassVar[tuple[str, ...]] = ("work_of_adhesion", "k")

    @model_validator(mode="after")
    def _parameters(self):
        approach_not_above(self.approach_work_of_adhesion, self.work_of_adhesion)
        if self.approach_work_of_adhesion is not None:
            raise FieldProblem(
                "approach_work_of_adhesion",
                f"{self.approach_work_of_adhesion:g} J/m² is not taken by model 'greenwood_johnson', which "
                "loads and unloads on the stable branches of its equilibrium curve without approach "
                "hysteresis: leave it out (approach hysteresis: model 'jkr' or 'maugis_dugdale')",
            )
        if self.k is None:
            raise FieldProblem("k", "model 'greenwood_johnson' needs the double-Hertz factor k > 0")
        if self.work_of_adhesion == 0:
            raise FieldProblem("work_of_adhesion", "must be > 0 for model 'greenwood_johnson' (drop adhesion for none)")
        return self

    @property
    def double_hertz_factor(self) -> float:
        """k."""
        assert self.k is not None, "validated: greenwood_johnson takes k"
        return self.k

    def law(self, xp: Any = np) -> GreenwoodJohnson:
        return GreenwoodJohnson(
            work_of_adhesion=value(xp, self.work_of_adhesion), factor=value(xp, self.double_hertz_factor)
        )

    def integrator(self, scene: "Scene") -> AbstractIntegrator:
        if scene.solver.method == QUADRATURE:
            return CurveQuadrature()
        return CurveIntegrator(**adaptive(scene))

    def describe(self) -> str:
        return f"Greenwood–Johnson double-Hertz adhesion (Δγ = {self.work_of_adhesion:g} J/m², k = {self.k:g})"

    def check(self, scene: "Scene") -> None:
        shape = scene.body.profile.shape
        if shape not in DOUBLE_HERTZ_SHAPES:
            raise FieldProblem(
                "effects.adhesion.model",
                f"greenwood_johnson needs a paraboloid ({', '.join(DOUBLE_HERTZ_SHAPES)}): the double-Hertz "
                f"stress of §3.9 holds for f = r²/(2R) only, not {shape!r}",
            )
        if scene.contact.springs != "continuum":
            raise FieldProblem("contact.springs", "greenwood_johnson runs on the continuum law only ('continuum')")

    def tabor_parameter(self, scene: "Scene") -> float:
        """The equivalent Λ(k) (`theory.double_hertz_tabor_parameter`)."""
        return float(theory.double_hertz_tabor_parameter(self.double_hertz_factor))

    def dmt_pull_off(self, profile: Profile) -> float:
        """2πRΔγ (3.141)."""
        return 2 * np.pi * float(tip_radius(profile)) * self.work_of_adhesion

    def closed_form_name(self, scene: "Scene") -> str:
        return "Thornton–Ning (3.50–51): the JKR limit k → ∞ of Greenwood–Johnson"
