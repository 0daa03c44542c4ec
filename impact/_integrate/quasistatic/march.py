"""One quasi-static test: the continuum or the spring-array march of a loading, or the march
along the equilibrium curve of a finite-range law."""

import dataclasses
import functools

import equinox as eqx
import jax
import jax.numpy as jnp

from ..._law.curve import AbstractCurve, CurveLaw, Reach, top_of_peak
from ..._law.double_hertz import DoubleHertzLaw, build_double_hertz_curve
from ..._law.dugdale import DugdaleLaw, build_curve
from ..._law.dugdale_hysteresis import HystereticLaw, with_force_turns
from ..._law.dugdale_springs import build_spring_curve, default_length, spring_turns
from ..._law.scales import Scales
from .continuum import march_continuum
from .curve import march_curve
from .loading import Loading, QuasiStaticNumerics
from .setup import build, loading_scales
from .springs import march_springs


@eqx.filter_jit
def march(loading: Loading, numerics: QuasiStaticNumerics):
    """Build and march one quasi-static program; returns (scales, scaled outcome)."""
    if numerics.model != "jkr":
        return march_finite_range(loading, numerics)
    built = build(loading, numerics)
    if numerics.springs is None:
        return built.law.scales, march_continuum(built, numerics)
    return built.law.scales, march_springs(built, numerics, loading.spring_length, loading.spring_count)


def march_finite_range(loading: Loading, numerics: QuasiStaticNumerics):
    """Maugis–Dugdale or Greenwood–Johnson: the law in the units of the JKR jump-in, its curve up
    to beyond the program's peak, and the march along it."""
    if numerics.springs is not None:  # every piece of the spring curve may turn, and takes steps of its own
        turns = spring_turns(numerics.tabulation.max_turns, numerics.springs)
        numerics = dataclasses.replace(
            numerics,
            tabulation=dataclasses.replace(numerics.tabulation, max_turns=turns),
            steps_per_leg=numerics.steps_per_leg or 8 * numerics.springs + 64,
        )
    scales, unit, law, curve = finite_range_curve(loading, numerics)
    program = (loading.force_control, loading.directions, loading.targets / unit, loading.legs)
    return scales, march_curve(law, curve, program, numerics)


def finite_range_curve(
    loading: Loading, numerics: QuasiStaticNumerics
) -> tuple[Scales, jax.Array, CurveLaw, AbstractCurve]:
    """(scales, unit of the controlled value, law, curve) of a Maugis–Dugdale or Greenwood–Johnson
    test: the law in the units of the JKR jump-in and its equilibrium curve up to beyond the
    program's peak (the unit: of the force under force control, else of the indentation)."""
    scales = loading_scales(loading, adhesive=True)
    unit = jnp.where(loading.force_control, scales.force, scales.normal)
    reach = functools.partial(top_of_peak, peak=loading.peak / unit, force_control=loading.force_control)
    law = finite_range_law(loading, numerics, scales)
    curve: AbstractCurve
    if isinstance(law, HystereticLaw):
        approach = build_curve(law.approach, numerics.tabulation.max_turns, reach)
        detach = build_curve(law.detach, numerics.tabulation.max_turns, reach)
        curve = with_force_turns(law, approach, detach, numerics.tabulation.max_turns)
    elif isinstance(law, DugdaleLaw) and numerics.springs is not None:
        curve = spring_curve(law, reach, loading, numerics.springs, numerics.tabulation.max_turns)
    elif isinstance(law, DugdaleLaw):
        curve = build_curve(law, numerics.tabulation.max_turns, reach)
    else:
        curve = build_double_hertz_curve(law, reach)
    return scales, unit, law, curve


def spring_curve(law: DugdaleLaw, reach: Reach, loading: Loading, capacity: int, max_turns: int):
    """The curve of the loading's Maugis–Dugdale spring array (`capacity` its compiled size): over
    its `spring_length`, or by default `default_length` (just beyond the program's peak, `reach`)."""
    length = jnp.where(
        jnp.isnan(loading.spring_length), default_length(law, reach), loading.spring_length / law.scales.radial
    )
    return build_spring_curve(law, loading.spring_count, capacity, length, max_turns)


def finite_range_law(
    loading: Loading, numerics: QuasiStaticNumerics, scales: Scales
) -> DugdaleLaw | HystereticLaw | DoubleHertzLaw:
    """The Maugis–Dugdale (with `numerics.hysteresis`: its hysteretic law, Δγa ≤ Δγ) or
    Greenwood–Johnson law of the loading in the units `scales`."""
    adhesion = loading.adhesion
    if numerics.model == "maugis_dugdale":
        law = DugdaleLaw.scaled(
            loading.profile, scales, loading.E_star, adhesion.adhesive_stress, adhesion.adhesion_range
        )
        return HystereticLaw(law, jnp.asarray(adhesion.approach_range / scales.normal)) if numerics.hysteresis else law
    return DoubleHertzLaw.scaled(
        loading.profile, scales, loading.E_star, adhesion.work_of_adhesion, adhesion.double_hertz_factor
    )
