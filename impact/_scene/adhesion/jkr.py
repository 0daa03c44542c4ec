"""JKR adhesion (zero range) by the rule of Heß, with hysteretic attachment Δγa ≤ Δγ."""

from typing import TYPE_CHECKING, Any, ClassVar, Literal

import numpy as np
from pydantic import Field, model_validator

from ..._integrate.base import AbstractIntegrator
from ..._law.jkr import JKR
from ...profiles import Profile
from ..errors import FieldProblem
from ..profiles import PowerLawSpec
from ..sections import WorkOfAdhesion
from .base import AbstractAdhesion, edge_integrator, loads_from_the_tip, value

if TYPE_CHECKING:
    from ..scene import Scene

_ZERO_RANGE = "only for model 'maugis_dugdale' (jkr has zero range)"


class JKRAdhesion(AbstractAdhesion):
    """JKR adhesion (zero range): the edge spring lets go at the elongation `√(2πxΔγ/E*)` (rule of
    Heß, (3.26)); on approach the next one attaches at `√(2πxΔγa/E*)`, 0 ≤ Δγa ≤ Δγ (Δγa = Δγ: the
    reversible JKR law with its jump-in; 0: attach on touch)."""

    model: Literal["jkr"] = Field(
        "jkr",
        description=(
            "'jkr' (zero range, rule of Heß), 'maugis_dugdale' (stress σ0 up to the range h) or "
            "'greenwood_johnson' (double Hertz of factor k, §3.9)"
        ),
    )
    approach_work_of_adhesion: WorkOfAdhesion | None = Field(
        None,
        description=(
            "work of adhesion on approach Δγa (J/m²), 0 ≤ Δγa ≤ Δγ; default Δγ (no hysteresis); 0 attaches on touch"
        ),
    )

    foreign_keys: ClassVar[dict[str, str]] = {
        "k": "only for model 'greenwood_johnson' (jkr has no double-Hertz factor)",
        "stress": _ZERO_RANGE,
        "range": _ZERO_RANGE,
    }
    zero_range: ClassVar[bool] = True
    curve_fields: ClassVar[tuple[str, ...]] = ("work_of_adhesion", "approach_work_of_adhesion")

    @model_validator(mode="after")
    def _approach_not_above(self):
        approach_not_above(self.approach_work_of_adhesion, self.work_of_adhesion)
        return self

    @property
    def approach(self) -> float:
        return self.work_of_adhesion if self.approach_work_of_adhesion is None else self.approach_work_of_adhesion

    @property
    def unit_work_of_adhesion(self) -> float:
        return self.approach

    def law(self, xp: Any = np) -> JKR:
        adhesive = xp.asarray(self.work_of_adhesion) > 0
        return JKR(
            work_of_adhesion=value(xp, xp.where(adhesive, self.work_of_adhesion, 0.0)),
            approach_work_of_adhesion=value(xp, xp.where(adhesive, self.approach, 0.0)),
        )

    def integrator(self, scene: "Scene") -> AbstractIntegrator:
        return edge_integrator(scene)

    def describe(self) -> str:
        return f"adhesion (Δγ = {self.work_of_adhesion:g} J/m², Δγa = {self.approach:g} J/m²)"

    def tip_search(self) -> bool:
        # Only a partial approach work of adhesion puts the attach edge's turn decades below the
        # branch grid (Δγa = Δγ turns at the jump-in scale, Δγa = 0 does not turn).
        return self.approach > 0.0 and self.hysteretic

    def loads_in_time(self, scene: "Scene", profile: Profile) -> bool:
        """Without an approach work (Δγa = 0) loading starts from the tip on ĝ itself
        (`loads_from_the_tip`). Otherwise for n ≤ 1/2 the attach edge h = g − λa·√x rises from
        the tip (no jump-in); above, the jump-in radius, ∝ λa^(1/(n − 1/2)) in units of the
        impact energy, may lie below the smallest float for n < 1 or a small approach work
        Δγa < Δγ (Δγa/Δγ = 1e-100 at n = 1 is lost without the timed path). With n ≥ 1 and
        Δγa = Δγ (the closed form (3.81–82)) the jump-in is found as for the paraboloid, and no
        step solves for a radius."""
        if self.approach == 0.0:
            return loads_from_the_tip(profile)
        body = scene.contact_profile
        return isinstance(body, PowerLawSpec) and (body.n < 1.0 or self.hysteretic)

    def closed_form_name(self, scene: "Scene") -> str:
        shape = scene.contact_profile.shape
        if shape == "paraboloid":
            if self.approach == self.work_of_adhesion:
                return "Thornton–Ning (3.50–51)"
            if self.approach == 0:
                return "attach on touch (theory.attach_on_touch_restitution)"
        if shape in ("power_law", "cone") and self.approach == self.work_of_adhesion:
            return "power law (3.81–82)"
        return "closed form"


def approach_not_above(approach: float | None, work_of_adhesion: float) -> None:
    """Refuse Δγa > Δγ: attaching cannot gain more energy than detaching costs."""
    if approach is not None and approach > work_of_adhesion:
        raise FieldProblem(
            "approach_work_of_adhesion",
            f"{approach:g} J/m² is above work_of_adhesion ({work_of_adhesion:g} J/m²): "
            "0 ≤ Δγa ≤ Δγ (attaching cannot gain more energy than detaching costs)",
        )
