"""The `effects` section of a scene file: adhesion (JKR, Maugis–Dugdale, Greenwood–Johnson),
gravity, plasticity and damping, each a pydantic model in SI units forbidding unknown keys."""

from typing import Annotated, Literal

from pydantic import Field, model_validator

from . import domains as d
from .domains import within
from .errors import FieldProblem
from .profiles import Number
from .sections import Length, Section, WorkOfAdhesion

# Profiles the Maugis–Dugdale zone is built for: smooth, unbounded, with a finite slope at the
# tip (the zone's radius must grow from 0 where the tip comes within range).
DUGDALE_SHAPES = ("paraboloid", "power_law", "cone")
# Springs of a Maugis–Dugdale array: each spring event is a ride (and a quasi-static piece) of its own.
DUGDALE_MAX_SPRINGS = 2048
# The least Δγa/Δγ of Maugis–Dugdale approach hysteresis: its approach range ha = Δγa/σ0 must be
# resolved by the approach curve (measured: Δγa/Δγ = 1e-13 at Λ = 100 and 1e-14 at Λ = 0.1…10 fail;
# e at 1e-9 is within 2e-5 of its value at 1e-12).
DUGDALE_LEAST_APPROACH = 1e-9


# Profiles Greenwood and Johnson's double Hertz is built for: the paraboloid of §3.9 (and the
# sphere's tip, its paraboloid r²/(2R)).
DOUBLE_HERTZ_SHAPES = ("paraboloid", "sphere")


class Adhesion(Section):
    """Adhesion: JKR (zero range) by the rule of Heß, with hysteretic attachment; or
    Maugis–Dugdale (a constant stress σ0 up to the range h, Δγ = σ0·h); or Greenwood–Johnson
    (double Hertz with the factor k)."""

    model: Literal["jkr", "maugis_dugdale", "greenwood_johnson"] = Field(
        "jkr",
        description=(
            "'jkr' (zero range, rule of Heß), 'maugis_dugdale' (stress σ0 up to the range h) or "
            "'greenwood_johnson' (double Hertz of factor k, §3.9)"
        ),
    )
    work_of_adhesion: WorkOfAdhesion = Field(
        description="work of adhesion Δγ (J/m²), the Dupré energy of separation, not a surface energy γ"
    )
    approach_work_of_adhesion: WorkOfAdhesion | None = Field(
        None,
        description=(
            "jkr and maugis_dugdale: work of adhesion on approach Δγa (J/m²), Δγa ≤ Δγ; default Δγ "
            "(no hysteresis); jkr: 0 attaches on touch; maugis_dugdale: ≥ 1e-9·Δγ, the stress attaches "
            "over the range Δγa/σ0 and detaches over Δγ/σ0"
        ),
    )
    stress: Annotated[Number, within(d.STRESS)] | None = Field(
        None, description="maugis_dugdale only: adhesive stress σ0 (Pa); or give range"
    )
    range: Length | None = Field(
        None, description="maugis_dugdale only: range h (m) of the adhesive stress; or give stress"
    )
    k: Annotated[Number, within(d.DOUBLE_HERTZ_FACTOR)] | None = Field(
        None,
        description=(
            "greenwood_johnson only: the factor k of the double-Hertz stress (3.198); "
            "large k is JKR-like, small k DMT-like (Tabor Λ = (36k²/(π³(1 + k)))^(1/3))"
        ),
    )

    @model_validator(mode="after")
    def _approach_not_above(self):
        if self.approach_work_of_adhesion is not None and self.approach_work_of_adhesion > self.work_of_adhesion:
            raise FieldProblem(
                "approach_work_of_adhesion",
                f"{self.approach_work_of_adhesion:g} J/m² is above work_of_adhesion ({self.work_of_adhesion:g} J/m²): "
                "0 ≤ Δγa ≤ Δγ (attaching cannot gain more energy than detaching costs)",
            )
        return self

    @model_validator(mode="after")
    def _parameters_of_the_model(self):
        if self.k is not None and self.model != "greenwood_johnson":
            raise FieldProblem("k", f"only for model 'greenwood_johnson' ({self.model} has no double-Hertz factor)")
        if self.model == "jkr":
            for name in ("stress", "range"):
                if getattr(self, name) is not None:
                    raise FieldProblem(name, "only for model 'maugis_dugdale' (jkr has zero range)")
            return self
        if self.model == "greenwood_johnson":
            return self._double_hertz_parameters()
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

    def _double_hertz_parameters(self):
        for name in ("stress", "range"):
            if getattr(self, name) is not None:
                raise FieldProblem(name, "only for model 'maugis_dugdale' (greenwood_johnson takes k)")
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
    def approach(self) -> float:
        """Δγa (J/m²), defaulting to Δγ."""
        return self.work_of_adhesion if self.approach_work_of_adhesion is None else self.approach_work_of_adhesion

    @property
    def hysteretic(self) -> bool:
        """Whether attaching takes less work than detaching, Δγa < Δγ: the JKR law's attach edge,
        Maugis–Dugdale's frozen zone (`_law.dugdale_hysteresis`)."""
        return self.approach < self.work_of_adhesion

    @property
    def adhesive_stress(self) -> float:
        """σ0 (Pa) of the Maugis–Dugdale model: given, or Δγ/h."""
        if self.stress is not None:
            return self.stress
        assert self.range is not None, "validated: maugis_dugdale takes stress or range"
        return self.work_of_adhesion / self.range

    @property
    def double_hertz_factor(self) -> float:
        """k of the Greenwood–Johnson model."""
        assert self.k is not None, "validated: greenwood_johnson takes k"
        return self.k

    @property
    def adhesion_range(self) -> float:
        """h (m) of the Maugis–Dugdale model: given, or Δγ/σ0."""
        if self.range is not None:
            return self.range
        assert self.stress is not None, "validated: maugis_dugdale takes stress or range"
        return self.work_of_adhesion / self.stress


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
    def viscoelastic_constant(self) -> float:
        """A (s); 0 for the linear model."""
        if self.model != "viscoelastic":
            return 0.0
        assert self.dissipative_constant is not None, "validated: model 'viscoelastic' takes dissipative_constant"
        return self.dissipative_constant

    @property
    def linear_coefficient(self) -> float:
        """c (N·s/m); 0 for the viscoelastic model."""
        if self.model != "linear":
            return 0.0
        assert self.coefficient is not None, "validated: model 'linear' takes coefficient"
        return self.coefficient


class Effects(Section):
    """The effects the scene names; those left out are not simulated at all."""

    adhesion: Adhesion | None = None
    gravity: Gravity | None = None
    plasticity: Plasticity | None = None
    damping: Damping | None = None
