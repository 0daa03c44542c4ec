"""Maugis–Dugdale adhesion (§3.8): a constant adhesive stress σ0 up to the range h = Δγ/σ0
(3.4), with approach hysteresis Δγa ≤ Δγ (the stress attaches over ha = Δγa/σ0). Its states lie
on the equilibrium curve of `dugdale` (with hysteresis, the path of `dugdale_hysteresis`)."""

import jax.numpy as jnp

from .._core.types import Parameter
from ..profiles import Profile
from .base import AbstractCurveLaw
from .curve import AbstractCurve, Reach
from .dugdale import DugdaleLaw, build_curve
from .dugdale_hysteresis import HystereticLaw, hysteresis_curve
from .scales import Scales


class MaugisDugdale(AbstractCurveLaw[DugdaleLaw | HystereticLaw]):
    """Maugis–Dugdale adhesion on power-law bodies (paraboloid, cone, power law n ≥ 1)."""

    work_of_adhesion: Parameter  # Δγ (J/m²)
    approach_work_of_adhesion: Parameter  # Δγa ≤ Δγ (J/m²)
    adhesive_stress: Parameter  # σ0 (Pa)

    @property
    def adhesion_range(self) -> Parameter:
        """h = Δγ/σ0 (m) of the stress (3.4)."""
        return self.work_of_adhesion / self.adhesive_stress

    @property
    def approach_range(self) -> Parameter:
        """ha = Δγa/σ0 (m): the range over which the stress attaches on approach."""
        return self.approach_work_of_adhesion / self.adhesive_stress

    def scaled(self, profile: Profile, E_star, scales: Scales, hysteresis: bool) -> DugdaleLaw | HystereticLaw:
        dugdale = DugdaleLaw.scaled(profile, scales, E_star, self.adhesive_stress, self.adhesion_range)
        if not hysteresis:
            return dugdale
        return HystereticLaw(dugdale, jnp.asarray(self.approach_range / scales.normal))

    def start_indentation(self, law: DugdaleLaw | HystereticLaw, gap, scales: Scales) -> Parameter:
        """`gap` (m) before the tip comes within the range (with hysteresis, the approach range)."""
        onset_range = self.approach_range if isinstance(law, HystereticLaw) else self.adhesion_range
        return -(onset_range + gap) / scales.normal

    def curve(self, law: DugdaleLaw | HystereticLaw, reach: Reach, max_turns: int) -> AbstractCurve:
        """The curve of range h, or with hysteresis the path apart over the approach curve (ha)
        and the detach curve (h)."""
        if isinstance(law, DugdaleLaw):
            return build_curve(law, max_turns, reach)
        approach, detach = (build_curve(part, max_turns, reach) for part in (law.approach, law.detach))
        return hysteresis_curve(law, approach, detach, 0.0)
