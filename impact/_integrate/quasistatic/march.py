"""One quasi-static test: the continuum or the spring-array march of a loading, or the march
along the equilibrium curve of a finite-range law."""

import dataclasses
import functools

import equinox as eqx
import jax
import jax.numpy as jnp

from ..._law.base import AbstractCurveLaw
from ..._law.curve import AbstractCurve, CurveLaw, Reach, top_of_peak
from ..._law.dugdale import DugdaleLaw
from ..._law.dugdale_hysteresis import HysteresisCurve, HystereticLaw, with_force_turns
from ..._law.dugdale_springs import build_spring_curve, default_length, spring_turns
from ..._law.scales import Scales
from .continuum import march_continuum
from .curve import march_curve
from .loading import Loading, QuasiStaticNumerics
from .program import Program
from .setup import build, loading_scales
from .springs import march_springs


@eqx.filter_jit
def march(loading: Loading, numerics: QuasiStaticNumerics):
    """Build and march one quasi-static program; returns (scales, scaled outcome)."""
    if isinstance(loading.law, AbstractCurveLaw):
        return march_finite_range(loading, numerics)
    built = build(loading, numerics)
    if numerics.springs is None:
        return built.law.scales, march_continuum(built, numerics)
    return built.law.scales, march_springs(built, numerics, loading.spring_length, loading.spring_count)


def march_finite_range(loading: Loading, numerics: QuasiStaticNumerics):
    """A finite-range law (Maugis–Dugdale, Greenwood–Johnson): the law in the units of the JKR
    jump-in, its curve up to beyond the program's peak, and the march along it."""
    if numerics.springs is not None:  # every piece of the spring curve may turn, and takes steps of its own
        turns = spring_turns(numerics.tabulation.max_turns, numerics.springs)
        numerics = dataclasses.replace(
            numerics,
            tabulation=dataclasses.replace(numerics.tabulation, max_turns=turns),
            steps_per_leg=numerics.steps_per_leg or 8 * numerics.springs + 64,
        )
    scales, unit, scaled, curve = finite_range_curve(loading, numerics)
    program = Program(
        force_control=loading.force_control,
        directions=loading.directions,
        targets=loading.targets / unit,
        legs=loading.legs,
    )
    return scales, march_curve(scaled, curve, program, numerics)


def finite_range_curve(
    loading: Loading, numerics: QuasiStaticNumerics
) -> tuple[Scales, jax.Array, CurveLaw, AbstractCurve]:
    """(scales, unit of the controlled value, scaled law, curve) of a finite-range test: the law in
    the units of the JKR jump-in and its equilibrium curve up to beyond the program's peak (the
    unit: of the force under force control, else of the indentation); with `numerics.hysteresis`
    the path of Maugis–Dugdale's approach hysteresis, with the turning points of its force."""
    scales = loading_scales(loading, adhesive=True)
    unit = jnp.where(loading.force_control, scales.force, scales.normal)
    reach = functools.partial(top_of_peak, peak=loading.peak / unit, force_control=loading.force_control)
    law = loading.law
    assert isinstance(law, AbstractCurveLaw), f"a finite-range test rides a curve law, not {type(law).__name__}"
    scaled = finite_range_law(loading, numerics, scales)
    turns = numerics.tabulation.max_turns
    curve: AbstractCurve
    if numerics.springs is not None:
        assert isinstance(scaled, DugdaleLaw), "validated: spring arrays of finite range are Maugis–Dugdale's"
        curve = spring_curve(scaled, reach, loading, numerics.springs, turns)
    else:
        curve = law.curve(scaled, reach, turns)
        if isinstance(curve, HysteresisCurve):
            assert isinstance(scaled, HystereticLaw)
            curve = with_force_turns(scaled, curve.approach, curve.detach, turns)
    return scales, unit, scaled, curve


def spring_curve(law: DugdaleLaw, reach: Reach, loading: Loading, capacity: int, max_turns: int):
    """The curve of the loading's Maugis–Dugdale spring array (`capacity` its compiled size): over
    its `spring_length`, or by default `default_length` (just beyond the program's peak, `reach`)."""
    length = jnp.where(
        jnp.isnan(loading.spring_length), default_length(law, reach), loading.spring_length / law.scales.radial
    )
    return build_spring_curve(law, loading.spring_count, capacity, length, max_turns)


def finite_range_law(loading: Loading, numerics: QuasiStaticNumerics, scales: Scales) -> CurveLaw:
    """The finite-range law of the loading in the units `scales` (with `numerics.hysteresis`:
    Maugis–Dugdale's approach path)."""
    law = loading.law
    assert isinstance(law, AbstractCurveLaw), f"a finite-range test rides a curve law, not {type(law).__name__}"
    return law.scaled(loading.profile, loading.E_star, scales, numerics.hysteresis)
