"""Adhesion models with approach hysteresis: attaching may take a work of adhesion Δγa below the
Δγ that detaching costs (`approach_work_of_adhesion`, default Δγ)."""

from pydantic import model_validator

from ..errors import FieldProblem
from ..sections import WorkOfAdhesion
from .base import AbstractAdhesion


class AbstractHystereticAdhesion(AbstractAdhesion):
    """An adhesion model that takes an approach work of adhesion 0 ≤ Δγa ≤ Δγ; each model states
    the field's description (and its own bounds)."""

    approach_work_of_adhesion: WorkOfAdhesion | None

    @model_validator(mode="after")
    def _approach_not_above(self):
        approach_not_above(self.approach_work_of_adhesion, self.work_of_adhesion)
        return self

    @property
    def approach(self) -> float:
        return self.work_of_adhesion if self.approach_work_of_adhesion is None else self.approach_work_of_adhesion


def approach_not_above(approach: float | None, work_of_adhesion: float) -> None:
    """Refuse Δγa > Δγ: attaching cannot gain more energy than detaching costs."""
    if approach is not None and approach > work_of_adhesion:
        raise FieldProblem(
            "approach_work_of_adhesion",
            f"{approach:g} J/m² is above work_of_adhesion ({work_of_adhesion:g} J/m²): "
            "0 ≤ Δγa ≤ Δγ (attaching cannot gain more energy than detaching costs)",
        )
