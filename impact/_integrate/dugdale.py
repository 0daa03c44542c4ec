"""Impacts with Maugis–Dugdale adhesion (§3.8): the body rides the equilibrium curve of
`_law.dugdale` (`curve`). The tip comes within the range h of the surface at d = −h, where the
adhesive zone snaps to its first stable radius."""

import functools

import jax.numpy as jnp

from .._law.curve import top_of_reach
from .._law.dugdale import DugdaleLaw, build_curve
from .._law.scales import adhesive_scales
from .curve import AbstractCurveIntegrator, CurveProblem
from .problem import Options, Physics, scaled_time_limit, touch_velocity


class MaugisDugdale(AbstractCurveIntegrator):
    """Impacts with Maugis–Dugdale adhesion (§3.8) on power-law bodies: the body rides the
    equilibrium curve of the finite-range law, phase by phase with an adaptive diffrax solver."""

    def build(self, physics: Physics, options: Options) -> CurveProblem:
        """Scale (JKR units, or the impact energy's where it reaches further) and tabulate."""
        profile, adhesion = physics.profile, physics.adhesion
        speed = touch_velocity(physics, options)
        scales = adhesive_scales(profile, physics.E_star, adhesion.work_of_adhesion, physics.mass, speed)
        law = DugdaleLaw.scaled(profile, scales, physics.E_star, adhesion.adhesive_stress, adhesion.adhesion_range)
        touch_speed = speed / scales.velocity
        return CurveProblem(
            law=law,
            curve=build_curve(law, options.tabulation.max_turns, functools.partial(top_of_reach, speed=touch_speed)),
            gravity=physics.gravity.scaled(scales) if options.gravity else jnp.zeros(()),
            start_indentation=-(adhesion.adhesion_range + physics.gap) / scales.normal,
            start_velocity=physics.velocity / scales.velocity,
            touch_speed=touch_speed,
            bounded=jnp.asarray(True),
            time_limit=scaled_time_limit(physics, scales),
        )
