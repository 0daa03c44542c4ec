"""The scene file: a validated description of one impact, in SI units.

Every section forbids unknown keys. Numbers may be written as YAML numbers or numeric strings
(PyYAML reads `1e-3` as a string). `load_scene` turns a YAML file or a mapping into a `Scene`,
or raises `SceneError` naming each bad field by its dotted path.
"""

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Literal, get_args

import yaml
from pydantic import BaseModel, ConfigDict, Field, ValidationError, field_validator, model_validator

from .profiles import Number, ProfileSpec

SOLVER_METHODS = ("tsit5", "dopri5", "dopri8", "bosh3", "heun", "kvaerno3", "kvaerno5")
# Fixed-step integrators of the spring array (contact.springs: N).
SPRING_METHODS = ("verlet",)
MASS_OR_DENSITY = "give exactly one of mass (kg) and density (kg/m³)"


class SceneError(ValueError):
    """A scene that cannot be run; `problems` lists (dotted.path, message) pairs."""

    def __init__(self, problems: list[tuple[str, str]]):
        self.problems = problems
        super().__init__("\n".join(f"{path}: {message}" if path else message for path, message in problems))


class FieldProblem(ValueError):
    """A cross-field check's complaint about one field, named relative to the section."""

    def __init__(self, field: str, message: str):
        super().__init__(message)
        self.field = field


class _Section(BaseModel):
    model_config = ConfigDict(extra="forbid")


def _poisson(meaning: str):
    return Field(None, gt=-1.0, lt=0.5, description=f"Poisson's ratio of {meaning}, in (-1, 0.5)")


class Body(_Section):
    """The rigid falling body: its profile and its mass (or density)."""

    profile: ProfileSpec
    mass: Number | None = Field(None, gt=0, description="mass (kg), > 0")
    density: Number | None = Field(
        None, gt=0, description="density (kg/m³); mass = density × volume of the closed body"
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
        return self.density * body_volume(self.profile)


def body_volume(profile) -> float | None:
    """Volume (m³) of the closed body a profile belongs to: a sphere of radius R for the
    paraboloid and the sphere, the spheroid of semi-axes 1/k, 1/k, R for the ellipsoid."""
    if profile.shape in ("paraboloid", "sphere"):
        return 4.0 / 3.0 * math.pi * profile.R**3
    if profile.shape == "ellipsoid":
        return 4.0 / 3.0 * math.pi * profile.R / profile.k**2
    return None


class Material(_Section):
    """The elastic half-space (and body): E* directly, or Young's moduli and Poisson's ratios."""

    E_star: Number | None = Field(None, gt=0, description="effective modulus E* (Pa), > 0")
    E: Number | None = Field(None, gt=0, description="Young's modulus of the half-space (Pa), > 0")
    nu: Number | None = _poisson("the half-space")
    E_body: Number | None = Field(
        None, gt=0, description="Young's modulus of the body (Pa), > 0; omit for a rigid body"
    )
    nu_body: Number | None = _poisson("the body")

    @model_validator(mode="after")
    def _one_description(self):
        moduli = (self.E, self.nu, self.E_body, self.nu_body)
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
        compliance = (1.0 - self.nu**2) / self.E
        if self.E_body is not None:
            compliance += (1.0 - self.nu_body**2) / self.E_body
        return 1.0 / compliance


class Initial(_Section):
    """Where the body starts: its approach speed and its distance from the surface."""

    velocity: Number = Field(
        ge=0, description="approach speed towards the surface (m/s), > 0 (0 allowed when gravity drops the body from a gap)"
    )
    gap: Number = Field(
        0.0,
        ge=0,
        description="initial distance between tip and surface (m), >= 0; with maugis_dugdale adhesion, beyond the range h",
    )


ADHESION_MODELS = ("jkr", "maugis_dugdale")
# Profiles the Maugis–Dugdale zone is built for: smooth, unbounded, with a finite slope at the
# tip (the zone's radius must grow from 0 where the tip comes within range).
DUGDALE_SHAPES = ("paraboloid", "power_law", "cone")


class Adhesion(_Section):
    """Adhesion: JKR (zero range) by the rule of Heß, with hysteretic attachment; or
    Maugis–Dugdale (a constant stress σ0 up to the range h, Δγ = σ0·h)."""

    model: Literal[ADHESION_MODELS] = Field(
        "jkr", description="'jkr' (zero range, rule of Heß) or 'maugis_dugdale' (stress σ0 up to the range h)"
    )
    work_of_adhesion: Number = Field(
        ge=0, description="work of adhesion Δγ (J/m²), the Dupré energy of separation, not a surface energy γ"
    )
    approach_work_of_adhesion: Number | None = Field(
        None,
        ge=0,
        description="jkr only: work of adhesion on approach Δγa (J/m²), 0 ≤ Δγa ≤ Δγ; default Δγ (JKR jump-in); 0 attaches on touch",
    )
    stress: Number | None = Field(
        None, gt=0, description="maugis_dugdale only: adhesive stress σ0 (Pa), > 0; or give range"
    )
    range: Number | None = Field(
        None, gt=0, description="maugis_dugdale only: range h (m) of the adhesive stress, > 0; or give stress"
    )

    @model_validator(mode="after")
    def _approach_not_above(self):
        if self.approach_work_of_adhesion is not None and self.approach_work_of_adhesion > self.work_of_adhesion:
            raise FieldProblem("approach_work_of_adhesion", "must not exceed work_of_adhesion")
        return self

    @model_validator(mode="after")
    def _parameters_of_the_model(self):
        if self.model == "jkr":
            for name in ("stress", "range"):
                if getattr(self, name) is not None:
                    raise FieldProblem(name, "only for model 'maugis_dugdale' (jkr has zero range)")
            return self
        if self.approach_work_of_adhesion is not None:
            raise FieldProblem(
                "approach_work_of_adhesion",
                "only for model 'jkr': Maugis–Dugdale attaches where its zone equilibrium jumps",
            )
        if (self.stress is None) == (self.range is None):
            raise FieldProblem("stress", "model 'maugis_dugdale' needs exactly one of stress (Pa) and range (m): Δγ = σ0·h")
        if self.work_of_adhesion == 0:
            raise FieldProblem("work_of_adhesion", "must be > 0 for model 'maugis_dugdale' (drop adhesion for none)")
        return self

    @property
    def approach(self) -> float:
        """Δγa (J/m²), defaulting to Δγ."""
        return self.work_of_adhesion if self.approach_work_of_adhesion is None else self.approach_work_of_adhesion

    @property
    def adhesive_stress(self) -> float:
        """σ0 (Pa) of the Maugis–Dugdale model: given, or Δγ/h."""
        return self.stress if self.stress is not None else self.work_of_adhesion / self.range

    @property
    def adhesion_range(self) -> float:
        """h (m) of the Maugis–Dugdale model: given, or Δγ/σ0."""
        return self.range if self.range is not None else self.work_of_adhesion / self.stress


class Gravity(_Section):
    g: Number = Field(9.81, gt=0, description="gravitational acceleration towards the surface (m/s²)")


class Effects(_Section):
    """The effects the scene names; those left out are not simulated at all."""

    adhesion: Adhesion | None = None
    gravity: Gravity | None = None


class Contact(_Section):
    """How the MDR spring foundation is discretised."""

    springs: Literal["continuum"] | int = Field(
        "continuum", description="'continuum' (N → ∞) or the number N >= 1 of springs of the array"
    )
    length: Number | None = Field(
        None, gt=0, description="radius covered by the spring array (m); default: the body's extent or twice the energy radius"
    )

    @field_validator("springs")
    @classmethod
    def _springs_positive(cls, springs):
        if isinstance(springs, int) and springs < 1:
            raise ValueError("springs must be 'continuum' or an integer >= 1")
        return springs


class Solver(_Section):
    """Integrator of the continuum law (diffrax) and its tolerances, in scaled units; or
    'verlet', a fixed-step velocity Verlet on a spring array (contact.springs: N) with step dt."""

    method: Literal[SOLVER_METHODS + SPRING_METHODS] = "tsit5"
    rtol: Number = Field(1e-10, gt=0, lt=1, description="relative tolerance, in (0, 1)")
    atol: Number = Field(1e-12, gt=0, description="absolute tolerance in scaled units, > 0")
    max_steps: int = Field(4096, ge=16, description="solver steps allowed per phase")
    dt: Number | None = Field(None, gt=0, description="time step (s) of method 'verlet', > 0; only for it")

    @model_validator(mode="after")
    def _step_with_verlet_only(self):
        if self.method == "verlet" and self.dt is None:
            raise FieldProblem("dt", "missing: method 'verlet' needs its fixed time step (s)")
        if self.method != "verlet" and self.dt is not None:
            raise FieldProblem("dt", f"only for method 'verlet'; method {self.method!r} is adaptive (rtol, atol)")
        return self


class Limits(_Section):
    """Bounds that end a run which would otherwise not end (e.g. elastic bouncing)."""

    max_bounces: int = Field(64, ge=1, description="contacts simulated at most")
    duration: Number | None = Field(None, gt=0, description="simulated time at most (s); default: no bound")


class Program(_Section):
    """The loading program of a quasi-static indentation: load to the peak, unload; repeated."""

    peak: Number = Field(
        ge=0, description="largest load of every cycle: force (N) under force control, indentation (m) under displacement control; >= 0"
    )
    cycles: int = Field(1, ge=1, description="load–unload cycles; the last one retracts to pull-off")
    unload_to: Number | None = Field(
        None, description="where the cycles before the last stop unloading (N or m, below peak); default: each retracts to pull-off"
    )

    @model_validator(mode="after")
    def _unload_below_peak(self):
        if self.unload_to is not None and self.unload_to >= self.peak:
            raise FieldProblem("unload_to", "must lie below peak")
        return self


# Sections that only an impact reads: an indentation refuses them rather than ignore them.
_IMPACT_ONLY = {
    "initial": "an indentation is quasi-static: it has no initial velocity or gap",
    "solver": "an indentation needs no ODE solver (its march along the branches is exact)",
    "limits": "an indentation ends at pull-off (no bounces or duration to limit)",
}


class Scene(_Section):
    """One impact (`kind: impact`, the default) or one quasi-static indentation test
    (`kind: indentation`: `control` and `program`, no mass, initial state or solver)."""

    name: str = Field("scene", pattern=r"^[A-Za-z0-9_.-]+$", description="name of the run (file-name safe)")
    kind: Literal["impact", "indentation"] = Field(
        "impact", description="'impact' (a body hits the surface) or 'indentation' (quasi-static loading, §3.3)"
    )
    control: Literal["force", "displacement"] | None = Field(
        None, description="indentation only: what the program drives, 'force' (ξ = 3) or 'displacement' (ξ = 1)"
    )
    program: Program | None = Field(None, description="indentation only: the loading program")
    body: Body
    material: Material
    initial: Initial | None = None
    effects: Effects = Effects()
    contact: Contact = Contact()
    solver: Solver = Solver()
    limits: Limits = Limits()

    @model_validator(mode="after")
    def _sections_of_the_kind(self):
        if self.kind == "impact":
            for name in ("control", "program"):
                if getattr(self, name) is not None:
                    raise FieldProblem(name, "only for kind 'indentation'")
            if self.initial is None:
                raise FieldProblem("initial", "missing (required)")
            if self.body.mass is None and self.body.density is None:
                raise FieldProblem("body", MASS_OR_DENSITY)
            return self
        for name in ("control", "program"):
            if getattr(self, name) is None:
                raise FieldProblem(name, "missing (required for kind 'indentation')")
        for name, why in _IMPACT_ONLY.items():
            if name in self.model_fields_set:
                raise FieldProblem(name, f"not for kind 'indentation': {why}")
        for name in ("mass", "density"):
            if getattr(self.body, name) is not None:
                raise FieldProblem(f"body.{name}", "not for kind 'indentation': a quasi-static test needs no mass")
        if self.effects.gravity is not None:
            raise FieldProblem("effects.gravity", "not for kind 'indentation': the program sets the load")
        return self

    @model_validator(mode="after")
    def _reaches_the_surface(self):
        if self.kind != "impact":
            return self
        falls = self.effects.gravity is not None and self.initial.gap > 0
        if self.initial.velocity <= 0 and not falls:
            raise FieldProblem("initial.velocity", "must be > 0 (or name gravity and a gap > 0 to drop the body)")
        return self

    @model_validator(mode="after")
    def _verlet_steps_springs(self):
        if self.solver.method == "verlet" and self.contact.springs == "continuum":
            raise FieldProblem(
                "contact.springs",
                "solver.method 'verlet' steps a spring array: give the number of springs N "
                "(the continuum law takes a diffrax method: " + ", ".join(SOLVER_METHODS) + ")",
            )
        return self

    @model_validator(mode="after")
    def _dugdale_supported(self):
        adhesion = self.effects.adhesion
        if adhesion is None or adhesion.model != "maugis_dugdale":
            return self
        if self.kind != "impact":
            raise FieldProblem("effects.adhesion.model", "maugis_dugdale is simulated in impacts only (kind 'impact')")
        profile = self.body.profile
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
        if self.contact.springs != "continuum":
            raise FieldProblem("contact.springs", "maugis_dugdale runs on the continuum law only ('continuum')")
        return self

    @property
    def adhesive(self) -> bool:
        """Whether adhesion is simulated (named, with Δγ > 0)."""
        adhesion = self.effects.adhesion
        return adhesion is not None and adhesion.work_of_adhesion > 0


def _profile_shapes() -> tuple[str, ...]:
    union = get_args(ProfileSpec)[0]
    return tuple(model.model_fields["shape"].default for model in get_args(union))


# Tags pydantic inserts into error locations for unions; they are not scene keys.
_UNION_TAGS = set(_profile_shapes()) | {"int", "literal['continuum']"}


def _dotted(location: tuple) -> str:
    return ".".join(str(part) for part in location if not (isinstance(part, str) and part in _UNION_TAGS))


def _path_and_message(error) -> tuple[str, str]:
    path = _dotted(error["loc"])
    cause = error.get("ctx", {}).get("error")
    if isinstance(cause, FieldProblem):
        return ".".join(part for part in (path, cause.field) if part), str(cause)
    text = error["msg"]
    if text.startswith("Value error, "):
        text = text[len("Value error, "):]
    if error["type"] == "extra_forbidden":
        text = "unknown key"
    elif error["type"] == "missing":
        text = "missing (required)"
    elif error["type"] == "union_tag_invalid":
        text = f"unknown shape {error['ctx']['tag']!r}; known shapes: {', '.join(_profile_shapes())}"
        path = ".".join(part for part in (path, "shape") if part)
    elif error["type"] == "union_tag_not_found":
        text = f"missing shape; known shapes: {', '.join(_profile_shapes())}"
        path = ".".join(part for part in (path, "shape") if part)
    return path, text


def problems_of(error: ValidationError) -> list[tuple[str, str]]:
    """(dotted.path, message) for each error of a pydantic validation."""
    problems = []
    for item in error.errors():
        entry = _path_and_message(item)
        if entry not in problems:
            problems.append(entry)
    return problems


def read_yaml(path: str | Path) -> dict:
    """A YAML mapping from a file, or SceneError (missing file, invalid YAML, not a mapping)."""
    path = Path(path)
    if not path.is_file():
        raise SceneError([("", f"no such file: {path}")])
    try:
        data = yaml.safe_load(path.read_text())
    except yaml.YAMLError as error:
        raise SceneError([("", f"invalid YAML in {path}: {error}")]) from None
    if not isinstance(data, dict):
        raise SceneError([("", f"{path} must hold a mapping of scene keys")])
    return data


def load_scene(source: "str | Path | Mapping | Scene") -> Scene:
    """A validated Scene from a YAML file path, a mapping, or a Scene."""
    if isinstance(source, Scene):
        return source
    data = dict(source) if isinstance(source, Mapping) else read_yaml(source)
    try:
        return Scene.model_validate(data)
    except ValidationError as error:
        raise SceneError(problems_of(error)) from None


def scene_yaml(scene: Scene) -> str:
    """The resolved scene (defaults filled in) as YAML."""
    skipped = set(_IMPACT_ONLY) if scene.kind == "indentation" else None  # refused there
    return yaml.safe_dump(scene.model_dump(mode="json", exclude_none=True, exclude=skipped), sort_keys=False)
