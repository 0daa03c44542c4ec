"""Checks across fields: whether the scaled problem of an impact can represent the scene.

Every field may lie within its own domain (`domains`) while the scene as a whole cannot be
simulated: the adhesion too weak for float64 to resolve against the impact, the body pressed
in deeper than its own size, or the units of the scaled problem outside float64's range. The
units are those the integrators use (`_law.scales`), computed once per scene. Each refusal
names one field, its value and the range it may take with the other fields as they are.
"""

import math

import equinox as eqx
import jax
import jax.numpy as jnp

from .. import theory
from .._core.runtime import float64
from .._core.search import log_sign_change
from .._law.scales import Scales, adhesive_scales, energy_scales
from .domains import WORK_OF_ADHESION, Domain, outside
from .errors import FieldProblem

# Measured on configs/thornton_ning.yaml, lowering Δγ (and raising E*, lowering R): the run ends in
# solver_failure once the detachment length Δl(ℓx) = √(2πℓxΔγ/E*) falls below ~1e-16 of the
# indentation unit ℓz (4.1e-17 fails, 1.3e-16 runs): float64's resolution. Four decades of margin.
RESOLVABLE = 1e-12
# The units convert every result to SI; within 1e±150 their products stay finite (measured: an
# energy unit underflowing to 0 gave unbounded_contact and −inf m; 1e±127 still ran).
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


def _traced(tree):
    """Every number of `tree` as a float64 array: `eqx.filter_jit` keeps Python floats static, so a
    new value would compile anew (a sweep validates every point: thousands of programs)."""
    return jax.tree.map(lambda leaf: jnp.asarray(leaf, float) if isinstance(leaf, float) else leaf, tree)


@eqx.filter_jit
def _units(profile, E_star, approach, mass, speed, adhesive: bool) -> tuple[Scales, Scales]:
    """(units of the run, units of the impact energy alone)."""
    energetic = energy_scales(profile, E_star, mass, speed)
    units = adhesive_scales(profile, E_star, approach, mass, speed) if adhesive else energetic
    return units, energetic


@eqx.filter_jit
def _radius_at_height(profile, height):
    """The radius x where g(x) = height (m)."""
    reference = profile.radius_scale()
    lower, upper = reference * 1e-100, jnp.minimum(profile.extent(), reference * 1e100)
    radius, _ = log_sign_change(lambda x: profile.g(x) - height, lower, upper, _BISECTION_STEPS)
    return radius


@float64
def check_representable(scene) -> None:
    """Raise FieldProblem (dotted path from the scene) where the impact cannot be represented."""
    profile = scene.contact_profile.build()
    adhesion = scene.active_adhesion
    E_star, mass = scene.material.effective_modulus, scene.reduced_mass
    gravity = scene.effects.gravity
    fall = 2.0 * gravity.g * scene.start.gap if gravity is not None else 0.0
    speed = math.sqrt(scene.approach_velocity**2 + fall)
    approach = adhesion.approach if adhesion is not None and adhesion.model == "jkr" else 0.0
    if adhesion is not None and adhesion.model == "maugis_dugdale":
        approach = adhesion.work_of_adhesion
    body, modulus, attach, weight, impact_speed = _traced((profile, E_star, approach, mass, speed))
    units, energetic = _units(body, modulus, attach, weight, impact_speed, adhesion is not None)
    values = {name: float(getattr(units, name)) for name in ("radial", "normal", "force", "time")}
    _check_units(values, float(units.velocity), float(units.energy))
    if adhesion is not None and adhesion.model == "jkr":
        _check_adhesion_resolved(adhesion, E_star, values)
    if scene.effects.plasticity is not None:
        _check_plastic_depth(scene, speed, fall)
    elif scene.contact_profile.shape in SIZE_FIELD:
        _check_depth(scene, profile, float(energetic.normal), fall)


def _check_units(values: dict[str, float], velocity: float, energy: float) -> None:
    low, high = UNIT_RANGE
    for name, value in {**values, "velocity": velocity, "energy": energy}.items():
        if not (math.isfinite(value) and low <= value <= high):
            raise FieldProblem(
                "body",
                f"the scene's {name} unit {value:g} (SI) is outside the allowed range [1e-150, 1e150]: the "
                "scaled problem cannot represent this body, material and impact together",
            )


def _check_adhesion_resolved(adhesion, E_star: float, values: dict[str, float]) -> None:
    """The detachment length at the contact radius unit must reach RESOLVABLE of the indentation
    unit; it grows as √Δγ, so the least Δγ follows from the ratio."""
    ratio = math.sqrt(2.0 * math.pi * values["radial"] * adhesion.work_of_adhesion / E_star) / values["normal"]
    if ratio >= RESOLVABLE:
        return
    least = adhesion.work_of_adhesion * (RESOLVABLE / ratio) ** 2
    allowed = Domain(least, WORK_OF_ADHESION.high, WORK_OF_ADHESION.unit, zero=True)
    why = (
        f"the detachment length is {ratio:.2g} of the indentation, below what float64 resolves "
        f"({RESOLVABLE:g}); leave out effects.adhesion for a contact without adhesion"
    )
    raise FieldProblem("effects.adhesion.work_of_adhesion", outside(adhesion.work_of_adhesion, allowed, why))


def _check_depth(scene, profile, energetic_depth: float, fall: float) -> None:
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
    most_energy = scene.material.effective_modulus * float(_radius_at_height(*_traced((profile, size)))) * size**2
    _refuse_deeper(scene, most_energy, fall, why)


def _check_plastic_depth(scene, speed: float, fall: float) -> None:
    """A yielding paraboloid must not be pressed in deeper than its radius: the deepest
    indentation of Thornton's law (closed form) against R, the most energy its loading takes."""
    R, E_star = float(scene.contact_profile.build().radius_scale()), scene.material.effective_modulus
    yield_pressure = scene.effects.plasticity.yield_pressure
    depth = float(theory.thornton_max_indentation(speed, scene.reduced_mass, R, E_star, yield_pressure))
    if depth <= R:
        return
    why = (
        f"yielding at p_y = {yield_pressure:g} Pa, the body would be pressed in about {depth:.3g} m, deeper than "
        f"its radius {R:g} m"
    )
    _refuse_deeper(scene, float(theory.thornton_loading_work(R, R, E_star, yield_pressure)), fall, why)


def _refuse_deeper(scene, most_energy: float, fall: float, why: str) -> None:
    """Refuse the initial velocity (or, for a body dropped from rest, the gap) that brings more
    than `most_energy` (J) into the contact."""
    mass = scene.reduced_mass
    if scene.start.velocity > 0 or fall == 0:
        most = math.sqrt(max(2.0 * most_energy / mass - fall, 0.0))
        raise FieldProblem("initial.velocity", outside(scene.start.velocity, Domain(0.0, most, "m/s"), why))
    most = most_energy / (mass * scene.effects.gravity.g)
    raise FieldProblem("initial.gap", outside(scene.start.gap, Domain(0.0, most, "m"), why))
