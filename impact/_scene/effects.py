"""The `effects` section of a scene file: adhesion (one of the models of `adhesion`), gravity,
plasticity, damping and a viscoelastic medium (`viscoelasticity`), each a pydantic model in SI
units forbidding unknown keys."""

from typing import TYPE_CHECKING, Annotated, Any, Literal

import numpy as np
from pydantic import Field, model_validator

from .._integrate.adhesive_plastic import AdhesivePlastic
from .._integrate.adhesive_plastic_quadrature import AdhesivePlasticQuadrature
from .._integrate.base import AbstractIntegrator
from .._integrate.plastic import Plastic
from .._integrate.plastic_quadrature import PlasticQuadrature
from .._law.jkr import JKR
from .._law.thornton import Thornton, ThorntonNing
from . import domains as d
from .adhesion import AbstractAdhesion, AdhesionSpec
from .adhesion.base import adaptive, value
from .domains import within
from .errors import FieldProblem
from .friction import FrictionSection
from .profiles import Number
from .sections import QUADRATURE, Section
from .viscoelasticity import Viscoelasticity

if TYPE_CHECKING:
    from .scene import Scene


class Gravity(Section):
    """A constant acceleration towards the surface."""

    g: Annotated[Number, within(d.GRAVITY)] = Field(
        9.81, description="gravitational acceleration towards the surface (m/s²)"
    )


class Plasticity(Section):
    """Thornton's (1997) elastic–perfectly plastic contact of a paraboloid: the contact
    pressure is limited to p_y."""

    yield_pressure: Annotated[Number, within(d.STRESS)] = Field(
        description="limiting contact pressure p_y (Pa): the Hertzian peak pressure 2E*a/(πR) where the contact yields"
    )

    def law(self, adhesion: AbstractAdhesion | None, xp: Any = np) -> Thornton | ThorntonNing:
        """Thornton's law, or with (JKR) adhesion Thornton & Ning's (the scene validates it)."""
        if adhesion is None:
            return Thornton(yield_pressure=value(xp, self.yield_pressure))
        jkr = adhesion.law(xp)
        assert isinstance(jkr, JKR), "validated: Thornton & Ning's law is JKR's"
        return ThorntonNing(
            work_of_adhesion=jkr.work_of_adhesion,
            approach_work_of_adhesion=jkr.approach_work_of_adhesion,
            yield_pressure=value(xp, self.yield_pressure),
        )

    def integrator(self, scene: "Scene") -> AbstractIntegrator:
        """Thornton & Ning's adhesive law where adhesion is simulated (Δγ > 0), else Thornton's;
        each with its phases timed by quadrature where the scene names `solver.method: quadrature`."""
        if scene.solver.method == QUADRATURE:
            return AdhesivePlasticQuadrature() if scene.adhesive else PlasticQuadrature()
        return AdhesivePlastic(**adaptive(scene)) if scene.adhesive else Plastic(**adaptive(scene))


class Damping(Section):
    """A viscous force on the springs in contact: viscoelastic (Brilliantov et al. 1996),
    F_visc = 2E*·a·A·ḋ, or linear (DEM-style), F_visc = c·ḋ."""

    model: Literal["viscoelastic", "linear"] = Field(
        description="'viscoelastic' (dissipative_constant A) or 'linear' (coefficient c)"
    )
    dissipative_constant: Annotated[Number, within(d.DISSIPATIVE_CONSTANT)] | None = Field(
        None, description="A (s) of model 'viscoelastic': F = (4/3)E*√R(δ^(3/2) + (3/2)A·δ^(1/2)·δ̇) for a paraboloid"
    )
    coefficient: Annotated[Number, within(d.DAMPING_COEFFICIENT)] | None = Field(
        None, description="c (N·s/m) of model 'linear': F_visc = c·δ̇ while in contact"
    )

    @model_validator(mode="after")
    def _parameter_of_the_model(self):
        given, other = ("dissipative_constant", "coefficient")[:: 1 if self.model == "viscoelastic" else -1]
        if getattr(self, other) is not None:
            raise FieldProblem(other, f"not for model {self.model!r}, which takes {given}")
        if getattr(self, given) is None:
            raise FieldProblem(given, f"missing (required for model {self.model!r})")
        return self

    @property
    def viscoelastic(self) -> bool:
        """Whether the model is Brilliantov et al.'s viscoelastic one (else linear)."""
        return self.model == "viscoelastic"

    def describe(self) -> str:
        """The damping and its value in words and SI units (`impact validate`)."""
        if self.viscoelastic:
            return f"viscoelastic damping (A = {self.viscoelastic_constant:.6g} s)"
        return f"linear damping (c = {self.linear_coefficient:.6g} N·s/m)"

    @property
    def viscoelastic_constant(self) -> float:
        """A (s); 0 for the linear model."""
        if not self.viscoelastic:
            return 0.0
        assert self.dissipative_constant is not None, "validated: model 'viscoelastic' takes dissipative_constant"
        return self.dissipative_constant

    @property
    def linear_coefficient(self) -> float:
        """c (N·s/m); 0 for the viscoelastic model."""
        if self.viscoelastic:
            return 0.0
        assert self.coefficient is not None, "validated: model 'linear' takes coefficient"
        return self.coefficient


class Effects(Section):
    """The effects the scene names; those left out are not simulated at all."""

    adhesion: AdhesionSpec | None = None
    gravity: Gravity | None = None
    plasticity: Plasticity | None = None
    damping: Damping | None = None
    viscoelasticity: Viscoelasticity | None = None
    friction: FrictionSection | None = None
