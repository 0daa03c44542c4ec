"""Impacts with Maugis–Dugdale adhesion (§3.8): the body rides the equilibrium curve of
`_law.dugdale` (`curve`). The tip comes within the range h of the surface at d = −h, where the
adhesive zone snaps to its first stable radius. With approach hysteresis (Δγa < Δγ,
`_law.dugdale_hysteresis`) it loads on the curve of the range ha = Δγa/σ0 and unloads on the
frozen zone of its largest zone radius, then on the curve of h."""

import functools

import equinox as eqx
import jax.numpy as jnp

from .._law.curve import AbstractCurve, CurveLaw, Reach, top_of_reach
from .._law.dugdale import DugdaleLaw, build_curve
from .._law.dugdale_hysteresis import HystereticLaw, hysteresis_curve
from .._law.dugdale_springs import build_spring_curve, default_length, spring_turns
from .._law.scales import adhesive_scales
from .curve import AbstractCurveIntegrator, CurveProblem
from .problem import Options, Physics, scaled_time_limit, touch_velocity


class MaugisDugdale(AbstractCurveIntegrator):
    """Impacts with Maugis–Dugdale adhesion (§3.8) on power-law bodies: the body rides the
    equilibrium curve of the finite-range law, phase by phase with an adaptive diffrax solver;
    with `hysteresis` (static) the path of `_law.dugdale_hysteresis` (Δγa ≤ Δγ)."""

    hysteresis: bool = eqx.field(default=False, static=True)

    def build(self, physics: Physics, options: Options) -> CurveProblem:
        """Scale (JKR units, or the impact energy's where it reaches further) and tabulate."""
        profile, adhesion = physics.profile, physics.adhesion
        speed = touch_velocity(physics, options)
        scales = adhesive_scales(profile, physics.E_star, adhesion.work_of_adhesion, physics.mass, speed)
        dugdale = DugdaleLaw.scaled(profile, scales, physics.E_star, adhesion.adhesive_stress, adhesion.adhesion_range)
        touch_speed = speed / scales.velocity
        reach = functools.partial(top_of_reach, speed=touch_speed)
        law: CurveLaw
        curve: AbstractCurve
        if self.hysteresis:
            law = hysteretic = HystereticLaw(dugdale, jnp.asarray(adhesion.approach_range / scales.normal))
            turns = options.tabulation.max_turns
            approach, detach = (build_curve(part, turns, reach) for part in (hysteretic.approach, hysteretic.detach))
            curve = hysteresis_curve(hysteretic, approach, detach, 0.0)
        else:
            law, curve = dugdale, self.curve(dugdale, reach, physics, options)
        onset_range = adhesion.approach_range if self.hysteresis else adhesion.adhesion_range  # the tip within it
        return CurveProblem(
            law=law,
            curve=curve,
            gravity=physics.gravity.scaled(scales) if options.gravity else jnp.zeros(()),
            start_indentation=-(onset_range + physics.gap) / scales.normal,
            start_velocity=physics.velocity / scales.velocity,
            touch_speed=touch_speed,
            bounded=jnp.asarray(True),
            time_limit=scaled_time_limit(physics, scales),
        )

    def curve(self, law: DugdaleLaw, reach: Reach, physics: Physics, options: Options) -> AbstractCurve:
        """The curve the body rides, up to `reach`: the continuum's."""
        return build_curve(law, options.tabulation.max_turns, reach)


class MaugisDugdaleSprings(MaugisDugdale):
    """Impacts of a spring array with Maugis–Dugdale adhesion (`_law.dugdale_springs`): the body
    rides the array's equilibrium curve, every spring event a jump between its pieces. The
    array has N = `Physics.spring_count` ≤ `capacity` springs (N traced: one compilation serves
    every N up to the capacity) over `Physics.spring_length` (nan: `default_length`, just beyond
    the impact's reach)."""

    capacity: int = eqx.field(default=64, static=True)

    def __check_init__(self):
        if self.hysteresis:
            raise ValueError("Maugis–Dugdale spring arrays have no approach hysteresis (Δγa = Δγ)")

    def curve(self, law: DugdaleLaw, reach: Reach, physics: Physics, options: Options) -> AbstractCurve:
        length = jnp.where(
            jnp.isnan(physics.spring_length), default_length(law, reach), physics.spring_length / law.scales.radial
        )
        turns = spring_turns(options.tabulation.max_turns, self.capacity)
        return build_spring_curve(law, physics.spring_count.astype(int), self.capacity, length, turns)
