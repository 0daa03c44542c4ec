"""Checks across fields: whether the scaled problem of an impact can represent the scene.

Every field may lie within its own domain (`domains`) while the scene as a whole cannot be
simulated: the adhesion too weak for float64 to resolve against the impact, the body pressed
in deeper than its own size, or the units of the scaled problem outside float64's range. The
units are those the integrators use (`_law.scales`), computed once per scene. Each refusal
names one field, its value and the range it may take with the other fields as they are.
"""

import itertools
import math
from collections.abc import Callable, Mapping, Sequence
from typing import Any, NamedTuple

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np

from .. import theory
from .._core.concrete import evaluate
from .._core.pytree import fields
from .._core.runtime import float64
from .._core.search import log_sign_change
from .._core.stored import call_stored
from .._law.scales import Scales, adhesive_scales, energy_scales
from ..profiles import Profile
from .domains import WORK_OF_ADHESION, Domain, outside
from .errors import FieldProblem

# A run ends in solver_failure once the detachment length Δl(ℓx) = √(2πℓxΔγ/E*) falls below about
# 1e-16 of the indentation unit ℓz, float64's resolution (lowering Δγ, raising E* or lowering R
# on configs/thornton_ning.yaml gets there): the limit keeps four decades of margin.
RESOLVABLE = 1e-12
# The units convert every result to SI; within 1e±150 their products stay finite (an energy unit
# that underflows to 0 turns a run into unbounded_contact with −inf m).
UNIT_RANGE = (1e-150, 1e150)
# Profiles with a size: the estimated indentation must stay below it (deeper, the body is no
# longer the shape the field describes: a paraboloid deeper than R is no sphere's cap).
SIZE_FIELD = {
    "paraboloid": "R",
    "sphere": "R",
    "ellipsoid": "R",
    "wavy_paraboloid": "R",
    "truncated_paraboloid": "R",
    "capped_paraboloid": "R2",
}
_BISECTION_STEPS = 100
# Scenes whose units are computed in one call (a sweep's points; one scene alone takes a batch of 1).
_BATCH = 4096
_UNIT_NAMES = ("radial", "normal", "force", "time", "velocity", "energy")


class UnitInputs(NamedTuple):
    """What the units of an impact scene depend on (SI): its profile, E* (Pa), the approach work
    of adhesion (J/m², 0 without adhesion), the mass (kg) and the speed at the touch (m/s)."""

    profile: Profile
    E_star: float
    approach: float
    mass: float
    speed: float


class Units(NamedTuple):
    """The units of one scene in SI: of the run (by name), and the indentation unit of the impact
    energy alone."""

    values: dict[str, float]
    energetic_depth: float


def _approach(scene) -> float:
    """The work of adhesion (J/m²) that sets the adhesive units (`unit_work_of_adhesion`: JKR's
    approach work, the finite-range laws' work of adhesion), 0 without adhesion."""
    adhesion = scene.active_adhesion
    return 0.0 if adhesion is None else adhesion.unit_work_of_adhesion


def _speed(scene) -> float:
    """The speed (m/s) at the touch: the approach speed, and what a fall adds."""
    return math.sqrt(scene.approach_velocity**2 + _fall(scene))


def _fall(scene) -> float:
    """2·g·gap (m²/s²): what the fall to the touch adds to v0²."""
    gravity = scene.effects.gravity
    return 2.0 * gravity.g * scene.start.gap if gravity is not None else 0.0


# The numbers of `UnitInputs` after the profile, each read from a scene.
UNIT_NUMBERS: dict[str, Callable[[Any], float]] = {
    "E_star": lambda scene: scene.material.effective_modulus,
    "approach": _approach,
    "mass": lambda scene: scene.reduced_mass,
    "speed": _speed,
}


def unit_inputs(scene, profile: Profile | None = None) -> UnitInputs:
    """The numbers the units of an impact scene depend on (`profile`: the scene's, if built)."""
    built = scene.contact_profile.build() if profile is None else profile
    return UnitInputs(built, **{name: read(scene) for name, read in UNIT_NUMBERS.items()})


def _units(inputs: UnitInputs, adhesive: bool) -> tuple[dict[str, jax.Array], dict[str, jax.Array]]:
    """(units of the run, units of the impact energy alone) by name, for a batch of inputs."""

    def one(point: UnitInputs) -> tuple[Scales, Scales]:
        energetic = energy_scales(point.profile, point.E_star, point.mass, point.speed)
        if not adhesive:
            return energetic, energetic
        return adhesive_scales(point.profile, point.E_star, point.approach, point.mass, point.speed), energetic

    run, energetic = jax.vmap(one)(inputs)
    return fields(run), fields(energetic)


@float64
def unit_columns(inputs: Sequence[UnitInputs], adhesive: bool) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """The units of many scenes of one structure, as columns: ({name: unit of each scene},
    energetic depth of each scene)."""
    profile = inputs[0].profile
    if all(point.profile is profile for point in inputs):  # flattened once
        numbers = np.array([point[1:] for point in inputs], np.float64).reshape(len(inputs), len(UNIT_NUMBERS))
        return profile_unit_columns(profile, dict(zip(UNIT_NUMBERS, numbers.T, strict=True)), len(inputs), adhesive)
    leaves = [jax.tree.leaves(point) for point in inputs]
    columns = [np.array([row[k] for row in leaves], np.float64) for k in range(len(leaves[0]))]
    return _batched_units(jax.tree.structure(inputs[0]), columns, len(inputs), adhesive)


@float64
def profile_unit_columns(
    profile: Profile, numbers: Mapping[str, "np.ndarray | float"], count: int, adhesive: bool
) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """`unit_columns` of `count` scenes of one profile, from their `UNIT_NUMBERS` by name: a
    column of `count` values each, or one value that they share."""
    leaves = jax.tree.leaves(profile)
    shared = [np.broadcast_to(np.asarray(leaf, np.float64), (count, *np.shape(leaf))) for leaf in leaves]
    rest = [np.broadcast_to(np.asarray(numbers[name], np.float64), (count,)) for name in UNIT_NUMBERS]
    structure = jax.tree.structure(UnitInputs(profile, **dict.fromkeys(UNIT_NUMBERS, 0.0)))
    return _batched_units(structure, shared + rest, count, adhesive)


def _batched_units(structure, columns: list[np.ndarray], count: int, adhesive: bool):
    """`unit_columns` from the inputs' leaves as columns (`count` rows each), computed in batches
    of `_BATCH` (one compiled program serves every sweep: numbers are traced, the batch shape
    fixed; kept across processes, `call_stored`); one scene's compiles quickly, as a program that
    runs once."""
    size = _BATCH if count > 1 else 1
    values: dict[str, list[np.ndarray]] = {name: [] for name in _UNIT_NAMES}
    depths = []
    for first in range(0, count, _BATCH):
        rows = np.minimum(np.arange(first, first + size), count - 1)  # the last one repeated
        inputs = jax.tree.unflatten(structure, [c[rows] for c in columns])
        run_fields, energetic = call_stored(_units, inputs, adhesive, once=size == 1)
        run = jax.tree.map(np.asarray, Scales(**run_fields))  # its velocity and energy in NumPy: no dispatch
        kept = min(_BATCH, count - first)
        for name in _UNIT_NAMES:
            values[name].append(np.asarray(getattr(run, name))[:kept])
        depths.append(np.asarray(energetic["normal"])[:kept])
    return {name: np.concatenate(parts) for name, parts in values.items()}, np.concatenate(depths)


def units_at(values: dict[str, np.ndarray], depth: np.ndarray, row: int) -> Units:
    """The units of one scene of `unit_columns`."""
    return Units({name: float(column[row]) for name, column in values.items()}, float(depth[row]))


class Limits(NamedTuple):
    """What `check_units` compares the units of a scene with, as numbers: the work of adhesion of
    a JKR adhesion (J/m²; nan: none), E* (Pa), and the size the energetic depth must stay below
    (m; inf: no size; nan: a yielding body, checked alone)."""

    work_of_adhesion: float
    E_star: float
    size: float


def limits_of(scene) -> Limits:
    """The numbers `passes` checks the scene's units against."""
    adhesion = scene.active_adhesion
    work = adhesion.work_of_adhesion if adhesion is not None and adhesion.zero_range else math.nan
    profile = scene.contact_profile
    if scene.effects.plasticity is not None:
        size = math.nan
    else:
        size = getattr(profile, SIZE_FIELD[profile.shape]) if profile.shape in SIZE_FIELD else math.inf
    return Limits(work, scene.material.effective_modulus, size)


def passes(values: dict[str, np.ndarray], depth: np.ndarray, limits: Sequence[Limits]) -> np.ndarray:
    """Which scenes `check_units` would pass, all at once (the same float operations as its
    checks); a scene marked False is one to check alone (`check_units` names the problem)."""
    flat = np.fromiter(itertools.chain.from_iterable(limits), np.float64, count=len(limits) * len(Limits._fields))
    work, E_star, size = flat.reshape(len(limits), len(Limits._fields)).T
    fine = np.ones(len(depth), bool)
    for column in values.values():
        fine &= _within_unit_range(column)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = _detachment_ratio(values, work, E_star)
    fine &= np.isnan(work) | (ratio >= RESOLVABLE)
    return fine & (depth <= size)  # nan (a yielding body) compares False


@float64
def _radius_at_height(spec, height: float) -> float:
    """The radius x (m) where the profile of `spec` has g(x) = height (m)."""
    return float(_root_of_height(spec.build(), np.float64(height)))


@eqx.filter_jit
def _root_of_height(profile, height):
    reference = profile.radius_scale()
    lower, upper = reference * 1e-100, jnp.minimum(profile.extent(), reference * 1e100)
    radius, _ = log_sign_change(lambda x: profile.g(x) - height, lower, upper, _BISECTION_STEPS)
    return radius


@float64
def time_unit(scene) -> float:
    """The time unit (s) of an impact's scaled problem (`_law.scales`)."""
    values, _ = unit_columns([unit_inputs(scene)], scene.active_adhesion is not None)
    return float(values["time"][0])


@float64
def check_representable(scene) -> None:
    """Raise FieldProblem (dotted path from the scene) where the impact cannot be represented."""
    check_units(scene, units_at(*unit_columns([unit_inputs(scene)], scene.active_adhesion is not None), 0))


def check_units(scene, units: Units) -> None:
    """Raise FieldProblem where the scene's units (`unit_columns`, `units_at`) cannot represent its impact."""
    _check_units(units.values)
    adhesion = scene.active_adhesion
    if adhesion is not None and adhesion.zero_range:
        _check_adhesion_resolved(adhesion, scene.material.effective_modulus, units.values)
    if scene.effects.plasticity is not None:
        _check_plastic_depth(scene, _speed(scene), _fall(scene))
    elif scene.contact_profile.shape in SIZE_FIELD:
        _check_depth(scene, units.energetic_depth, _fall(scene))


def _within_unit_range(unit):
    """Whether a unit (SI; a number or an array of them) is finite and within UNIT_RANGE."""
    low, high = UNIT_RANGE
    return np.isfinite(unit) & (low <= unit) & (unit <= high)


def _detachment_ratio(values, work_of_adhesion, E_star):
    """The detachment length at the contact radius unit over the indentation unit,
    √(2π·ℓx·Δγ/E*)/ℓz (units `values` by name; numbers or arrays of them)."""
    return np.sqrt(2.0 * math.pi * values["radial"] * work_of_adhesion / E_star) / values["normal"]


def _check_units(values: dict[str, float]) -> None:
    for name, value in values.items():
        if not _within_unit_range(value):
            raise FieldProblem(
                "body",
                f"the scene's {name} unit {value:g} (SI) is outside the allowed range [1e-150, 1e150]: the "
                "scaled problem cannot represent this body, material and impact together",
            )


def _check_adhesion_resolved(adhesion, E_star: float, values: dict[str, float]) -> None:
    """The detachment length at the contact radius unit must reach RESOLVABLE of the indentation
    unit; it grows as √Δγ, so the least Δγ follows from its value at Δγ = 1 J/m² (a Δγ so small
    that the ratio underflows to 0 is refused with it too)."""
    ratio = float(_detachment_ratio(values, adhesion.work_of_adhesion, E_star))
    if ratio >= RESOLVABLE:
        return
    least = (RESOLVABLE / float(_detachment_ratio(values, 1.0, E_star))) ** 2
    allowed = Domain(least, WORK_OF_ADHESION.high, WORK_OF_ADHESION.unit, zero=True)
    why = (
        f"the detachment length is {ratio:.2g} of the indentation, below what float64 resolves "
        f"({RESOLVABLE:g}); leave out effects.adhesion for a contact without adhesion"
    )
    raise FieldProblem("effects.adhesion.work_of_adhesion", outside(adhesion.work_of_adhesion, allowed, why))


def _check_depth(scene, energetic_depth: float, fall: float) -> None:
    """The indentation the impact energy alone would reach (its unit ℓz, ~0.8 of Hertz's maximum)
    must not exceed the body's size."""
    size_field = SIZE_FIELD[scene.contact_profile.shape]
    size = getattr(scene.contact_profile, size_field)
    if energetic_depth <= size:
        return  # a jump-in deeper than the body is left to run (configs/hard/15_huge_adhesion: 3.4 R)
    why = (
        f"the body would be pressed in about {energetic_depth:.3g} m, deeper than its size "
        f"body.profile.{size_field} = {size:g} m"
    )
    # the impact energy: E*·x·g(x)² at g(x) = size is the most it may be
    most_energy = scene.material.effective_modulus * _radius_at_height(scene.contact_profile, size) * size**2
    _refuse_deeper(scene, most_energy, fall, why)


def _check_plastic_depth(scene, speed: float, fall: float) -> None:
    """A yielding paraboloid must not be pressed in deeper than its radius: the deepest
    indentation of Thornton's law (closed form) against R, the most energy its loading takes."""
    R, E_star = float(scene.contact_profile.build().radius_scale()), scene.material.effective_modulus
    yield_pressure = scene.effects.plasticity.yield_pressure
    depth = float(evaluate(theory.thornton_max_indentation, speed, scene.reduced_mass, R, E_star, yield_pressure))
    if depth <= R:
        return
    why = (
        f"yielding at p_y = {yield_pressure:g} Pa, the body would be pressed in about {depth:.3g} m, deeper than "
        f"its radius {R:g} m"
    )
    _refuse_deeper(scene, float(evaluate(theory.thornton_loading_work, R, R, E_star, yield_pressure)), fall, why)


def _refuse_deeper(scene, most_energy: float, fall: float, why: str) -> None:
    """Refuse the initial velocity (or, for a body dropped from rest, the gap) that brings more
    than `most_energy` (J) into the contact."""
    mass = scene.reduced_mass
    if scene.start.velocity > 0 or fall == 0:
        most = math.sqrt(max(2.0 * most_energy / mass - fall, 0.0))
        raise FieldProblem("initial.velocity", outside(scene.start.velocity, Domain(0.0, most, "m/s"), why))
    most = most_energy / (mass * scene.effects.gravity.g)
    raise FieldProblem("initial.gap", outside(scene.start.gap, Domain(0.0, most, "m"), why))
