"""Scene-file models of the body profile: one pydantic model per shape, tagged by `shape`.

Every model forbids unknown keys, takes SI values, accepts ints and numeric strings (PyYAML reads
`1e-3` as a string) and builds its `impact.profiles.Profile` with `build()`. `ProfileSpec` is the
discriminated union to use as a field type, e.g. `profile: ProfileSpec`.
"""

import abc
import math
from itertools import pairwise
from typing import Annotated, Any, Literal

import numpy as np
from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, field_validator, model_validator

from .. import profiles
from . import domains as d
from .domains import within

__all__ = [
    "ProfileSpec",
    "ParaboloidSpec",
    "SphereSpec",
    "EllipsoidSpec",
    "ConeSpec",
    "PowerLawSpec",
    "FlatPunchSpec",
    "TruncatedConeSpec",
    "TruncatedParaboloidSpec",
    "CappedFlatPunchSpec",
    "CappedConeSpec",
    "CappedParaboloidSpec",
    "RoundedFlatPunchSpec",
    "WavyParaboloidSpec",
    "ConstantStressSpec",
    "TabulatedSpec",
]


def _number(value):
    """Coerce numeric strings ('1e-3') to float; refuse booleans, other strings, NaN and ±inf."""
    if isinstance(value, bool):
        raise ValueError(f"expected a number, got the boolean {value}")
    if isinstance(value, str):
        try:
            value = float(value)
        except ValueError:
            raise ValueError(f"expected a number such as 1e-3, got the string {value!r}") from None
    if isinstance(value, float) and not math.isfinite(value):
        raise ValueError(f"expected a finite number, got {value}")
    return value


Number = Annotated[float, BeforeValidator(_number), Field(allow_inf_nan=False)]
Angle = Annotated[Number, within(d.ANGLE)]
Length = Annotated[Number, within(d.LENGTH)]
Modulus = Annotated[Number, within(d.MODULUS)]
Coordinate = Annotated[Number, within(d.LENGTH_OR_ZERO)]


def _length(meaning: str) -> Any:
    return Field(description=f"{meaning} (m)")


def _angle() -> Any:
    return Field(description="slope angle of the cone flank against the contact plane (rad)")


class _Spec(BaseModel):
    model_config = ConfigDict(extra="forbid")

    @abc.abstractmethod
    def build(self) -> profiles.Profile:
        """The `impact.profiles` body this entry describes."""


class ParaboloidSpec(_Spec):
    """Paraboloid f = r²/(2R)."""

    shape: Literal["paraboloid"] = "paraboloid"
    R: Length = _length("radius of curvature at the tip")

    def build(self) -> profiles.Paraboloid:
        return profiles.Paraboloid(R=self.R)


class SphereSpec(_Spec):
    """Exact sphere f = R - sqrt(R² - r²); contact radius up to R."""

    shape: Literal["sphere"] = "sphere"
    R: Length = _length("sphere radius")

    def build(self) -> profiles.Sphere:
        return profiles.Sphere(R=self.R)


class EllipsoidSpec(_Spec):
    """Ellipsoid of revolution f = R(1 - sqrt(1 - k²r²)); tip curvature radius 1/(R k²)."""

    shape: Literal["ellipsoid"] = "ellipsoid"
    R: Length = _length("height scale R of f = R(1 - sqrt(1 - k²r²)), the semi-axis along the symmetry axis")
    k: Annotated[Number, within(d.INVERSE_LENGTH)] = Field(
        description="inverse equatorial semi-axis k (1/m); contact radius up to 1/k"
    )

    def build(self) -> profiles.Ellipsoid:
        return profiles.Ellipsoid(R=self.R, k=self.k)


class ConeSpec(_Spec):
    """Cone f = r tan(theta)."""

    shape: Literal["cone"] = "cone"
    theta: Angle = _angle()

    def build(self) -> profiles.Cone:
        return profiles.Cone(theta=self.theta)


class PowerLawSpec(_Spec):
    """Power-law profile f = c rⁿ."""

    shape: Literal["power_law"] = "power_law"
    n: Annotated[Number, within(d.EXPONENT)] = Field(description="exponent n (dimensionless)")
    c: Annotated[Number, within(d.PREFACTOR)] = Field(description="prefactor c (m^(1-n))")

    def build(self) -> profiles.PowerLaw:
        return profiles.PowerLaw(n=self.n, c=self.c)


class FlatPunchSpec(_Spec):
    """Cylindrical flat punch."""

    shape: Literal["flat_punch"] = "flat_punch"
    radius: Length = _length("punch radius")

    def build(self) -> profiles.FlatPunch:
        return profiles.FlatPunch(radius=self.radius)


class TruncatedConeSpec(_Spec):
    """Cone with a flat tip of radius b."""

    shape: Literal["truncated_cone"] = "truncated_cone"
    b: Length = _length("radius of the flat tip")
    theta: Angle = _angle()

    def build(self) -> profiles.TruncatedCone:
        return profiles.TruncatedCone(b=self.b, theta=self.theta)


class TruncatedParaboloidSpec(_Spec):
    """Paraboloid of radius R cut flat at radius b: f = (r² - b²)/(2R) beyond b."""

    shape: Literal["truncated_paraboloid"] = "truncated_paraboloid"
    b: Length = _length("radius of the flat tip")
    R: Length = _length("radius of curvature of the paraboloid")

    def build(self) -> profiles.TruncatedParaboloid:
        return profiles.TruncatedParaboloid(b=self.b, R=self.R)


class CappedFlatPunchSpec(_Spec):
    """Flat punch of radius b whose face is a paraboloid of radius R; contact radius up to b."""

    shape: Literal["capped_flat_punch"] = "capped_flat_punch"
    b: Length = _length("punch radius")
    R: Length = _length("radius of curvature of the parabolic cap")

    def build(self) -> profiles.CappedFlatPunch:
        return profiles.CappedFlatPunch(b=self.b, R=self.R)


class CappedConeSpec(_Spec):
    """Cone with a tangent parabolic tip (cap radius b / tan(theta)) up to radius b."""

    shape: Literal["capped_cone"] = "capped_cone"
    b: Length = _length("radius where the parabolic cap meets the cone")
    theta: Angle = _angle()

    def build(self) -> profiles.CappedCone:
        return profiles.CappedCone(b=self.b, theta=self.theta)


class CappedParaboloidSpec(_Spec):
    """Paraboloid of radius R2 with a flatter parabolic cap of radius R1 >= R2 up to radius b."""

    shape: Literal["capped_paraboloid"] = "capped_paraboloid"
    b: Length = _length("radius where the cap meets the base paraboloid")
    R1: Length = _length("radius of curvature of the cap")
    R2: Length = _length("radius of curvature of the base paraboloid, <= R1")

    @model_validator(mode="after")
    def _cap_flatter(self):
        if self.R1 < self.R2:
            raise ValueError(
                "capped_paraboloid needs cap radius R1 >= base radius R2 (R* = R1 R2/(R1 - R2) > 0, "
                "3.115); otherwise the profile's slope drops at b"
            )
        return self

    def build(self) -> profiles.CappedParaboloid:
        return profiles.CappedParaboloid(b=self.b, R1=self.R1, R2=self.R2)


class RoundedFlatPunchSpec(_Spec):
    """Flat punch with a flat base of radius b and edges rounded with radius R."""

    shape: Literal["rounded_flat_punch"] = "rounded_flat_punch"
    b: Length = _length("radius of the flat base")
    R: Length = _length("radius of the rounded edge")

    def build(self) -> profiles.RoundedFlatPunch:
        return profiles.RoundedFlatPunch(b=self.b, R=self.R)


class WavyParaboloidSpec(_Spec):
    """Paraboloid with periodic roughness f = r²/(2R) + amplitude (1 - cos(2π r / wavelength)).

    f is monotonic (simply connected contact, (3.133)) only if wavelength² >= 8.576 amplitude R.
    """

    shape: Literal["wavy_paraboloid"] = "wavy_paraboloid"
    R: Length = _length("radius of curvature of the paraboloid")
    amplitude: Annotated[Number, within(d.LENGTH_OR_ZERO)] = Field(description="roughness amplitude h (m)")
    wavelength: Length = _length("roughness wavelength λ")

    def build(self) -> profiles.WavyParaboloid:
        return profiles.WavyParaboloid(R=self.R, amplitude=self.amplitude, wavelength=self.wavelength)


class ConstantStressSpec(_Spec):
    """Punch of radius `radius` whose concave face f = (σ0 a/E*)[(4/π)E(r/a) − 2] (3.61) carries a
    uniform tensile stress σ0 against a half-space of modulus E_star (Gao and Yao's optimal tip)."""

    shape: Literal["constant_stress"] = "constant_stress"
    radius: Length = _length("punch radius a")
    stress: Annotated[Number, within(d.STRESS)] = Field(
        description="uniform tensile stress σ0 the face is designed for (Pa)"
    )
    E_star: Modulus = Field(description="effective modulus E* the face is designed against (Pa); use the material's E*")

    def build(self) -> profiles.ConstantStress:
        return profiles.ConstantStress(radius=self.radius, stress=self.stress, E_star=self.E_star)


# Points of a tabulated profile at most: a run evaluates it at thousands of places at once, each
# evaluation a sum over every point (memory and time: the user guide). A longer list is refused
# before its values are checked.
MAX_TABULATED_POINTS = 10_000


class TabulatedSpec(_Spec):
    """Piecewise-linear profile through the points (r, f); continued with its last slope."""

    shape: Literal["tabulated"] = "tabulated"
    r: list[Coordinate] = Field(
        max_length=MAX_TABULATED_POINTS,
        description="radii (m), strictly increasing from r[0] = 0, from 2 to 10⁴ points",
    )
    f: list[Coordinate] = Field(
        max_length=MAX_TABULATED_POINTS, description="heights f(r) above the tip (m), f[0] = 0, same length as r"
    )

    @field_validator("r")
    @classmethod
    def _radii(cls, r: list[float]) -> list[float]:
        if len(r) < 2:
            raise ValueError("tabulated r needs at least 2 points")
        if r[0] != 0:
            raise ValueError("tabulated r must start at r = 0")
        if any(b <= a for a, b in pairwise(r)):
            raise ValueError("tabulated r must be strictly increasing")
        return r

    @field_validator("f")
    @classmethod
    def _heights(cls, f: list[float]) -> list[float]:
        if len(f) < 2:
            raise ValueError("tabulated f needs at least 2 points")
        if f[0] != 0:
            raise ValueError("tabulated f must start at 0 at r = 0")
        return f

    @model_validator(mode="after")
    def _same_length(self):
        if len(self.r) != len(self.f):
            raise ValueError(f"tabulated r and f must have the same length, got {len(self.r)} and {len(self.f)}")
        return self

    def build(self) -> profiles.Tabulated:
        return profiles.Tabulated(r=np.asarray(self.r, float), f=np.asarray(self.f, float))


ProfileSpec = Annotated[
    ParaboloidSpec
    | SphereSpec
    | EllipsoidSpec
    | ConeSpec
    | PowerLawSpec
    | FlatPunchSpec
    | TruncatedConeSpec
    | TruncatedParaboloidSpec
    | CappedFlatPunchSpec
    | CappedConeSpec
    | CappedParaboloidSpec
    | RoundedFlatPunchSpec
    | WavyParaboloidSpec
    | ConstantStressSpec
    | TabulatedSpec,
    Field(discriminator="shape"),
]
"""Any body profile of the scene file, selected by its `shape` key."""
