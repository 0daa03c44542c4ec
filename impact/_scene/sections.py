"""The sections of a scene file: pydantic models in SI units, each forbidding unknown keys.

Numbers may be written as YAML numbers or numeric strings (PyYAML reads `1e-3` as a string).
Cross-field checks raise `FieldProblem` to name the field at fault.
"""

import math
from typing import Annotated, Any, Literal

import jax
import numpy as np
from pydantic import BaseModel, ConfigDict, Field, ValidationInfo, field_validator, model_validator

from .. import theory
from .._integrate.base import PHASE_ENDS, SOLVERS
from . import domains as d
from .cost import STEP_BUDGET
from .domains import within
from .errors import FieldProblem
from .profiles import Number, ParaboloidSpec, ProfileSpec

# Adaptive diffrax methods of the continuum law (and of a spring array), by their scene names.
SOLVER_METHODS = tuple(SOLVERS)
# Fixed-step integrators of the spring array (contact.springs: N): velocity Verlet, and the
# implicit midpoint rule of a viscoelastic half-space's springs (effects.viscoelasticity).
MIDPOINT = "midpoint"
SPRING_METHODS = ("verlet", MIDPOINT)
# The continuum law (or a curve law's continuum curve) without an ODE solve: each phase ended by
# its energy and timed by quadrature.
QUADRATURE = "quadrature"
QUADRATURE_SHAPES = ("paraboloid", "cone", "power_law")  # g = A·xⁿ: the work along a branch in closed form
METHODS = SOLVER_METHODS + SPRING_METHODS + (QUADRATURE,)
MASS_OR_DENSITY = "give exactly one of mass (kg) and density (kg/m³)"
# Oblique impacts: the angle of incidence from the normal, the spin, the moment of inertia.
INCIDENCE = d.Domain(0.0, math.pi / 2, "rad", open_high=True, reason="from the normal up to grazing (π/2 excluded)")
SPIN = d.Domain(-1e9, 1e9, "rad/s", reason="a billion radians a second either way")
INERTIA = d.Domain(1e-80, 1e12, "kg m2", reason="from a nanoparticle's to a thousand-tonne body's")


class Section(BaseModel):
    """A section of the scene file: unknown keys are refused."""

    model_config = ConfigDict(extra="forbid")


def _poisson(meaning: str):
    return Field(None, description=f"Poisson's ratio of {meaning}")


Poisson = Annotated[Number, within(d.POISSON)]
Modulus = Annotated[Number, within(d.MODULUS)]
Length = Annotated[Number, within(d.LENGTH)]
WorkOfAdhesion = Annotated[Number, within(d.WORK_OF_ADHESION)]


class Body(Section):
    """The rigid falling body: its profile and its mass (or density)."""

    profile: ProfileSpec
    mass: Annotated[Number, within(d.MASS)] | None = Field(None, description="mass (kg)")
    density: Annotated[Number, within(d.DENSITY)] | None = Field(
        None, description="density (kg/m³); mass = density × volume of the closed body"
    )
    inertia: Annotated[Number, within(INERTIA)] | None = Field(
        None,
        description=(
            "moment of inertia about the centre (kg·m²) for effects.friction; default (2/5)mR², the solid sphere "
            "of the paraboloid's or sphere's radius R"
        ),
    )

    @model_validator(mode="after")
    def _one_of_mass_and_density(self):
        # Neither is refused by the scene for impacts (an indentation needs no mass).
        if self.mass is not None and self.density is not None:
            raise ValueError(MASS_OR_DENSITY)
        if self.density is not None and body_volume(self.profile) is None:
            raise ValueError(
                f"density needs a closed body, and shape {self.profile.shape!r} has no volume; give mass instead"
            )
        return self

    @property
    def resolved_mass(self) -> float:
        """Mass in kg (from density and volume if needed)."""
        if self.mass is not None:
            return self.mass
        volume = body_volume(self.profile)
        assert self.density is not None and volume is not None, MASS_OR_DENSITY  # validated
        return self.density * volume


def body_volume(profile) -> float | None:
    """Volume (m³) of the closed body a profile belongs to: a sphere of radius R for the
    paraboloid and the sphere, the spheroid of semi-axes 1/k, 1/k, R for the ellipsoid."""
    if profile.shape in ("paraboloid", "sphere"):
        return 4.0 / 3.0 * math.pi * profile.R**3
    if profile.shape == "ellipsoid":
        return 4.0 / 3.0 * math.pi * profile.R / profile.k**2
    return None


class Counterpart(Section):
    """A second free body the first one hits, instead of the rigid flat of infinite mass: its
    profile (a paraboloid, or flat when left out), its mass (or density) and its speed. Its
    material is the scene's `material.E`, `material.nu` (the half-space's), the first body's is
    `material.E_body`, `material.nu_body`; the contact takes the effective radius
    1/R = 1/R₁ + 1/R₂, E* and the reduced mass m₁m₂/(m₁ + m₂)."""

    profile: ProfileSpec | None = Field(
        None, description="shape of the counterpart's surface: a paraboloid (R); default: flat"
    )
    mass: Annotated[Number, within(d.MASS)] | None = Field(None, description="mass of the counterpart (kg)")
    density: Annotated[Number, within(d.DENSITY)] | None = Field(
        None, description="density of the counterpart (kg/m³); mass = density × volume of its sphere"
    )
    velocity: Annotated[Number, within(d.COUNTERPART_VELOCITY)] = Field(
        0.0, description="speed of the counterpart towards the body (m/s); default: at rest"
    )

    @model_validator(mode="after")
    def _a_paraboloid_of_one_mass(self):
        if self.profile is not None and self.profile.shape not in COUNTERPART_SHAPES:
            raise FieldProblem(
                "profile.shape",
                f"a counterpart is a paraboloid or flat (leave out profile), not {self.profile.shape!r}: "
                "only two paraboloids sum to a profile of the same kind (1/R = 1/R₁ + 1/R₂)",
            )
        if (self.mass is None) == (self.density is None):
            raise ValueError(MASS_OR_DENSITY)
        if self.density is not None and self.profile is None:
            raise FieldProblem("density", "a flat counterpart has no volume; give its mass instead")
        return self

    @property
    def radius(self) -> float | None:
        """The paraboloid's R (m); None for a flat."""
        if self.profile is None:
            return None
        assert isinstance(self.profile, ParaboloidSpec), "validated: a counterpart is a paraboloid or flat"
        return self.profile.R

    @property
    def resolved_mass(self) -> float:
        """Mass in kg (from density and the volume of the sphere of radius R if needed)."""
        if self.mass is not None:
            return self.mass
        assert self.density is not None and self.radius is not None, "validated: mass, or density of a paraboloid"
        return self.density * 4.0 / 3.0 * math.pi * self.radius**3


# Counterpart profiles: their gap adds to a paraboloid body's into a paraboloid.
COUNTERPART_SHAPES = ("paraboloid",)


class Material(Section):
    """The elastic half-space (or counterpart) and body: E* directly, or Young's moduli and
    Poisson's ratios."""

    E_star: Modulus | None = Field(None, description="effective modulus E* (Pa)")
    E: Modulus | None = Field(None, description="Young's modulus of the half-space or counterpart (Pa)")
    nu: Poisson | None = _poisson("the half-space or counterpart")
    E_body: Modulus | None = Field(None, description="Young's modulus of the body (Pa); omit for a rigid body")
    nu_body: Poisson | None = _poisson("the body")
    G_star: Modulus | None = Field(
        None,
        description=(
            "effective shear modulus `G*` (Pa) of effects.friction, beside E_star; with E and nu it follows from "
            "them, `1/G* = (2 − ν)/(4G) + (2 − ν_body)/(4G_body)`"
        ),
    )

    @model_validator(mode="after")
    def _one_description(self):
        moduli = (self.E, self.nu, self.E_body, self.nu_body)
        if self.G_star is not None and self.E_star is None:
            raise FieldProblem("G_star", "only beside E_star: with E and nu, G* follows from them")
        if self.E_star is not None:
            if any(value is not None for value in moduli):
                raise ValueError("give either E_star or E and nu (with E_body and nu_body), not both")
            return self
        if self.E is None or self.nu is None:
            raise ValueError("give E_star, or E and nu of the half-space")
        if (self.E_body is None) != (self.nu_body is None):
            raise ValueError("give E_body and nu_body together (omit both for a rigid body)")
        return self

    @property
    def effective_modulus(self) -> float:
        """E* (Pa): 1/E* = (1 − ν²)/E + (1 − ν_body²)/E_body."""
        if self.E_star is not None:
            return self.E_star
        assert self.E is not None and self.nu is not None, "validated: E_star, or E and nu"
        compliance = (1.0 - self.nu**2) / self.E
        if self.E_body is not None:
            assert self.nu_body is not None, "validated: E_body comes with nu_body"
            compliance += (1.0 - self.nu_body**2) / self.E_body
        return 1.0 / compliance

    @property
    def tangential_modulus(self) -> Any:
        """G* (Pa) of friction: `G_star`, else from E and ν (`theory.effective_shear_modulus`);
        None for E_star alone. A float for a scene's numbers, an array for a sweep's."""
        if self.G_star is not None:
            return self.G_star
        if self.E is None:
            return None
        assert self.nu is not None, "validated: E comes with nu"
        values = (self.E, self.nu) if self.E_body is None else (self.E, self.nu, self.E_body, self.nu_body)
        return theory.effective_shear_modulus(*values)


def _trigonometric(angle: Any, name: str) -> Any:
    """cos or sin (`name`) of a scene's angle: a number, a sweep's numpy array or a traced value."""
    return getattr(jax.numpy if isinstance(angle, jax.Array) else np, name)(angle)


class Initial(Section):
    """Where the body starts: its speed, the direction of its motion and its spin, and its
    distance from the surface."""

    velocity: Annotated[Number, within(d.VELOCITY)] = Field(
        description=(
            "speed of the body (m/s), towards the surface at `angle` from its normal; 0 only when gravity drops "
            "the body from a gap"
        ),
    )
    angle: Annotated[Number, within(INCIDENCE)] = Field(
        0.0,
        description=(
            "angle of incidence from the surface normal (rad): the body approaches at velocity·cos(angle) and "
            "slides along the surface at velocity·sin(angle)"
        ),
    )
    spin: Annotated[Number, within(SPIN)] = Field(
        0.0,
        description="spin ω of the body (rad/s) about the axis across its sliding; > 0 rolls it along its sliding",
    )
    gap: Annotated[Number, within(d.GAP)] = Field(
        0.0,
        description=(
            "initial distance between tip and surface (m); with maugis_dugdale adhesion, beyond the range h; "
            "with greenwood_johnson, beyond the onset d₀ = −k·c₀²/R"
        ),
    )

    @property
    def normal_velocity(self) -> Any:
        """The speed towards the surface (m/s): velocity·cos(angle) (the velocity itself at 0)."""
        if isinstance(self.angle, (int, float)) and self.angle == 0:
            return self.velocity
        return self.velocity * _trigonometric(self.angle, "cos")

    @property
    def tangential_velocity(self) -> Any:
        """The speed along the surface (m/s): velocity·sin(angle)."""
        return self.velocity * _trigonometric(self.angle, "sin")


class Contact(Section):
    """How the MDR spring foundation is discretised."""

    springs: Literal["continuum"] | Annotated[int, within(d.SPRINGS)] = Field(
        "continuum", description="'continuum' (N → ∞) or the number N of springs of the array"
    )
    length: Length | None = Field(
        None,
        description=(
            "radius covered by the spring array (m); default: the body's extent or twice the energy radius "
            "(maugis_dugdale: 1.25 times a bound on the largest contact radius)"
        ),
    )


class Solver(Section):
    """Integrator of the continuum law (diffrax) and its tolerances, in scaled units; or
    'quadrature', the continuum law's phases (or a curve law's rides) timed by quadrature without
    an ODE solve (on a JKR spring array, each contact computed whole from prefix sums); or
    'verlet', a fixed-step velocity Verlet on a spring array (contact.springs: N) with step dt;
    or 'midpoint', the implicit midpoint rule on the spring array of a viscoelastic half-space
    (effects.viscoelasticity), its springs advanced exactly over each step dt."""

    method: str = Field(
        "tsit5",
        description=(
            "integrator: "
            + ", ".join(METHODS)
            + " ('quadrature': no ODE solve, each contact phase ended by its energy "
            "balance and timed by Gauss quadrature of dt = dd/v; undamped continuum JKR law on a paraboloid, cone or "
            "power law, or the continuum curve of maugis_dugdale or greenwood_johnson; on a spring array of the "
            "JKR law, each contact whole from prefix sums over the springs; rtol and atol unused); "
            "default: tsit5, and in a sweep 'quadrature' where every point allows it"
        ),
    )
    rtol: Annotated[Number, within(d.RTOL)] = Field(1e-10, description="relative tolerance")
    atol: Annotated[Number, within(d.ATOL)] = Field(1e-12, description="absolute tolerance in scaled units")
    max_steps: Annotated[int, within(d.MAX_STEPS)] = Field(4096, description="solver steps allowed per phase")
    phase_ends: str | None = Field(
        None,
        description=(
            "where a contact phase's end comes from: 'integrated' (the solver's dense output at the located event) "
            "or 'energy' (the phase's energy balance: the restitution exact to round-off at any rtol, the times "
            "still the solver's; continuum JKR law without damping or plasticity); default: 'energy' where it "
            "applies, else 'integrated' (where 'energy' applies, an 'integrated' phase whose speed drifts from its "
            "energy balance ends the run with status energy_drift)"
        ),
    )
    dt: Annotated[Number, within(d.TIME_STEP)] | None = Field(
        None, description="time step (s) of the fixed-step methods 'verlet' and 'midpoint'; only for them"
    )

    @field_validator("method", "phase_ends")
    @classmethod
    def _known_choice(cls, choice: str | None, info: ValidationInfo) -> str | None:
        assert info.field_name is not None, "a field validator knows its field"
        allowed = {"method": METHODS, "phase_ends": PHASE_ENDS}[info.field_name]
        if choice is not None and choice not in allowed:
            raise ValueError(f"unknown {info.field_name} {choice!r}; expected one of: {', '.join(allowed)}")
        return choice

    @model_validator(mode="after")
    def _step_with_verlet_only(self):
        stepped = self.method in SPRING_METHODS
        if stepped and self.dt is None:
            raise FieldProblem("dt", f"missing: method {self.method!r} needs its fixed time step (s)")
        if not stepped and self.dt is not None:
            methods = " and ".join(map(repr, SPRING_METHODS))
            raise FieldProblem("dt", f"only for methods {methods}; method {self.method!r} takes no time step")
        return self


class Limits(Section):
    """Bounds that end a run which would otherwise not end (e.g. elastic bouncing)."""

    max_bounces: Annotated[int, within(d.BOUNCES)] = Field(64, description="contacts simulated at most")
    duration: Annotated[Number, within(d.DURATION)] | None = Field(
        None, description="simulated time at most (s); default: no bound"
    )
    step_budget: Annotated[Number, within(d.STEP_BUDGET)] = Field(
        STEP_BUDGET,
        description=(
            "solver steps a run may take, estimated before it compiles (a spring array's events, Verlet's steps); "
            "a scene estimated beyond it is refused: raise it for a longer run (or run with --allow-long)"
        ),
    )


class Program(Section):
    """The loading program of a quasi-static indentation: load to the peak, unload; repeated."""

    peak: Annotated[Number, within(d.PEAK)] = Field(
        description=(
            "largest load of every cycle: force (N) under force control, indentation (m) under displacement control"
        ),
    )
    cycles: Annotated[int, within(d.CYCLES)] = Field(
        1, description="load–unload cycles; the last one retracts to pull-off"
    )
    unload_to: Annotated[Number, within(d.UNLOAD_TO)] | None = Field(
        None,
        description=(
            "where the cycles before the last stop unloading (N or m, below peak); default: each retracts to pull-off"
        ),
    )
    rate: Annotated[Number, within(d.LOADING_RATE)] | None = Field(
        None,
        description=(
            "viscoelastic half-space only (required there): the speed of loading and unloading, m/s under "
            "displacement control, N/s under force control"
        ),
    )
    hold: Annotated[Number, within(d.HOLD)] = Field(
        0.0, description="viscoelastic half-space only: time (s) each cycle holds its peak before unloading"
    )

    @model_validator(mode="after")
    def _unload_below_peak(self):
        if self.unload_to is not None and self.unload_to >= self.peak:
            raise FieldProblem("unload_to", "must lie below peak")
        return self
