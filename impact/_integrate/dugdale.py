"""Impacts of a Maugis–Dugdale spring array (`_law.dugdale_springs`): the body rides the
array's equilibrium curve, every spring event a jump between its pieces (`curve`)."""

import equinox as eqx
import jax.numpy as jnp

from .._law.base import AbstractCurveLaw
from .._law.curve import AbstractCurve, CurveLaw, Reach
from .._law.dugdale import DugdaleLaw
from .._law.dugdale_springs import build_spring_curve, default_length, spring_turns
from .._law.maugis_dugdale import MaugisDugdale
from .._law.scales import Scales
from .curve import AbstractCurveIntegrator
from .problem import Options, Physics


class DugdaleSpringIntegrator(AbstractCurveIntegrator):
    """A Maugis–Dugdale spring array of N = `Physics.spring_count` ≤ `capacity` springs (N
    traced: one compilation serves every N up to the capacity) over `Physics.spring_length` (nan:
    `default_length`, just beyond the impact's reach); no approach hysteresis (Δγa = Δγ)."""

    capacity: int = eqx.field(default=64, static=True)

    def scaled_curve(
        self, law: AbstractCurveLaw, physics: Physics, options: Options, scales: Scales, reach: Reach
    ) -> tuple[CurveLaw, AbstractCurve]:
        assert isinstance(law, MaugisDugdale), f"a spring array's curve is Maugis–Dugdale's, not {type(law).__name__}"
        scaled = law.scaled(physics.profile, physics.E_star, scales, hysteresis=False)
        assert isinstance(scaled, DugdaleLaw)
        length = jnp.where(
            jnp.isnan(physics.spring_length), default_length(scaled, reach), physics.spring_length / scales.radial
        )
        turns = spring_turns(options.tabulation.max_turns, self.capacity)
        return scaled, build_spring_curve(scaled, physics.spring_count.astype(int), self.capacity, length, turns)
