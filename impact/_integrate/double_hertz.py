"""Impacts with Greenwood–Johnson double-Hertz adhesion (§3.9): the body rides the curve of
`_law.double_hertz` (`curve`). The interaction starts at d₀ = −k·c₀²/R, where the force jumps
from 0 to F₀ = −2πRΔγ/(1 + k) (at fixed d: no work); the contact ends there again for k ≤ 1,
at the minimum of d(a) for k > 1."""

import functools

import jax.numpy as jnp

from .._law.curve import top_of_reach
from .._law.double_hertz import DoubleHertzLaw, build_double_hertz_curve
from .._law.scales import adhesive_scales
from .curve import AbstractCurveIntegrator, CurveProblem
from .problem import Options, Physics, scaled_time_limit, touch_velocity


class GreenwoodJohnson(AbstractCurveIntegrator):
    """Impacts with Greenwood–Johnson adhesion (§3.9) on a paraboloid: the body rides the
    double-Hertz equilibrium curve, phase by phase with an adaptive diffrax solver."""

    def build(self, physics: Physics, options: Options) -> CurveProblem:
        """Scale (JKR units, or the impact energy's where it reaches further) and bound the curve."""
        profile, adhesion = physics.profile, physics.adhesion
        speed = touch_velocity(physics, options)
        scales = adhesive_scales(profile, physics.E_star, adhesion.work_of_adhesion, physics.mass, speed)
        law = DoubleHertzLaw.scaled(
            profile, scales, physics.E_star, adhesion.work_of_adhesion, adhesion.double_hertz_factor
        )
        touch_speed = speed / scales.velocity
        return CurveProblem(
            law=law,
            curve=build_double_hertz_curve(law, functools.partial(top_of_reach, speed=touch_speed)),
            gravity=physics.gravity.scaled(scales) if options.gravity else jnp.zeros(()),
            start_indentation=law.onset - physics.gap / scales.normal,
            start_velocity=physics.velocity / scales.velocity,
            touch_speed=touch_speed,
            bounded=jnp.asarray(True),
            time_limit=scaled_time_limit(physics, scales),
        )
