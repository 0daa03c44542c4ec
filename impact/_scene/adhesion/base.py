"""What every adhesion model of a scene is: a section of the scene file whose `model` names it,
and what the model decides for a run — its contact law's traced parameters, the integrator that
rides it, the static choices it compiles, the scene checks it adds and the words and closed
forms that describe it. Each model is its own module (`jkr`, `maugis_dugdale`,
`greenwood_johnson`); the union of them is `impact._scene.adhesion.AdhesionSpec`."""

import abc
import math
from typing import TYPE_CHECKING, Any, ClassVar, get_args

import numpy as np
from pydantic import Field, model_validator

from ..._integrate.base import AbstractIntegrator
from ..._integrate.continuum import Continuum
from ..._integrate.quadrature import Quadrature
from ..._integrate.spring_quadrature import SpringQuadrature
from ..._integrate.springs import SpringArray
from ..._integrate.verlet import Verlet
from ..._law.base import AbstractContactLaw
from ...profiles import Profile
from ..errors import FieldProblem
from ..sections import QUADRATURE, Section, WorkOfAdhesion
from ..springs import spring_capacity

if TYPE_CHECKING:
    from ..scene import Scene


class AbstractAdhesion(Section):
    """Adhesion of the interface; `model` names the law."""

    model: str  # each model narrows it to its own name (the union's tag)
    work_of_adhesion: WorkOfAdhesion = Field(
        description="work of adhesion Δγ (J/m²), the Dupré energy of separation, not a surface energy γ"
    )

    # Keys of the other models given to this one: {key: why it is refused here}.
    foreign_keys: ClassVar[dict[str, str]] = {}
    # Zero range (JKR): the law damping, energy ends and Thornton & Ning's plasticity build on.
    zero_range: ClassVar[bool] = False
    # The adhesion fields the model's curve depends on (an indentation fit varies them).
    curve_fields: ClassVar[tuple[str, ...]] = ("work_of_adhesion",)

    @model_validator(mode="before")
    @classmethod
    def _no_foreign_keys(cls, data: Any) -> Any:
        if isinstance(data, dict):
            for key, why in cls.foreign_keys.items():
                if data.get(key) is not None:
                    raise FieldProblem(key, why)
        return data

    @classmethod
    def model_name(cls) -> str:
        """The model's name in a scene file: its `model` tag."""
        return get_args(cls.model_fields["model"].annotation)[0]

    @classmethod
    def section(cls, **values: Any) -> dict[str, Any]:
        """The `effects.adhesion` section of a scene file of this model with `values`."""
        return {"model": cls.model_name(), **values}

    @property
    def name(self) -> str:
        """The model's name in a scene file."""
        return self.model_name()

    @property
    def approach(self) -> float:
        """Δγa (J/m²), the work of adhesion on approach: Δγ unless the model takes another."""
        return self.work_of_adhesion

    @property
    def hysteretic(self) -> bool:
        """Whether attaching takes less work than detaching, Δγa < Δγ."""
        return self.approach < self.work_of_adhesion

    @property
    def unit_work_of_adhesion(self) -> float:
        """The work of adhesion (J/m²) that sets the adhesive units of an impact (`representable`)."""
        return self.work_of_adhesion

    @abc.abstractmethod
    def law(self, xp: Any = np) -> AbstractContactLaw:
        """The contact law with this section's values (arrays of a sweep's points with `xp`
        numpy; each point's law without adhesion where its Δγ is 0)."""

    @abc.abstractmethod
    def integrator(self, scene: "Scene") -> AbstractIntegrator:
        """The integrator that runs an impact of the scene on this law."""

    @abc.abstractmethod
    def describe(self) -> str:
        """The model and its values in words and SI units (`impact validate`)."""

    def check(self, scene: "Scene") -> None:
        """Refuse (`FieldProblem`, relative to the scene) what the model cannot run in `scene`."""

    def tip_search(self) -> bool:
        """Whether the attach edge's turn may lie decades below the branch grid (`Tabulation`)."""
        return False

    def loads_in_time(self, scene: "Scene", profile: Profile) -> bool:
        """Whether loading may have to be integrated in time (`Options.timed_loading`)."""
        return False

    def curve_pieces(self, springs: int | str) -> int:
        """Pieces of the spring curve a spring array of this law rides (0: none)."""
        return 0

    def curve_hysteresis(self) -> bool:
        """Whether the law's equilibrium curve is the path of an approach hysteresis."""
        return False

    def tabor_parameter(self, scene: "Scene") -> float:
        """Λ of the law where the chapter defines it (3.172), else nan."""
        return math.nan

    def dmt_pull_off(self, profile: Profile) -> float | None:
        """The pull-off force (N) of the law's DMT limit (the indentation plot's reference
        curve), or None for a zero-range law."""
        return None

    def closed_form_name(self, scene: "Scene") -> str:
        """Which closed form a sweep compares this law's restitution with (the figure's label)."""
        return "closed form"


def adaptive(scene: "Scene") -> dict[str, Any]:
    """The settings every adaptive (diffrax) integrator takes from a scene."""
    solver = scene.solver
    return {"method": solver.method, "rtol": solver.rtol, "atol": solver.atol, "max_steps": solver.max_steps}


def edge_integrator(scene: "Scene") -> AbstractIntegrator:
    """The integrator of the continuum MDR law (zero range, or no adhesion): a diffrax solver, or
    quadrature; a spring array, event by event, each contact whole from prefix sums
    ('quadrature'), or stepped with Verlet."""
    solver = scene.solver
    springs = scene.contact.springs
    if springs == "continuum" and solver.method == QUADRATURE:
        return Quadrature()
    if springs == "continuum":
        return Continuum(**adaptive(scene), phase_ends=scene.phase_ends)
    if solver.method == QUADRATURE:
        return SpringQuadrature(capacity=spring_capacity(springs))
    if solver.method == "verlet":
        assert solver.dt is not None, "validated: method 'verlet' takes dt"
        return Verlet(dt=solver.dt)
    return SpringArray()


def loads_from_the_tip(profile: Profile) -> bool:
    """Whether loading that starts at a = 0 on the profile's own ĝ (no adhesion, or attach on
    touch) must be integrated in time: a body ĝ = Â·aⁿ with n ≥ 1 rises from the tip with a
    finite slope, so the radius rides and no radius table is built per point."""
    form = profile.power_form()
    return form is None or float(form[1]) < 1.0


def value(xp: Any, number: Any) -> Any:
    """A scene value as a float64 array of `xp` (jax.numpy, or numpy for a sweep's points)."""
    return xp.asarray(number, dtype=xp.float64)
