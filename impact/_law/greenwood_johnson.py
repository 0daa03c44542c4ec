"""Greenwood–Johnson double-Hertz adhesion (§3.9) of a paraboloid: the factor k of the second
Hertz distribution (k → ∞: JKR, k → 0: DMT). Its states lie on the curve of `double_hertz`."""

from .._core.types import Parameter
from ..profiles import Profile
from .base import AbstractCurveLaw
from .curve import AbstractCurve, Reach
from .double_hertz import DoubleHertzLaw, build_double_hertz_curve
from .scales import Scales


class GreenwoodJohnson(AbstractCurveLaw[DoubleHertzLaw]):
    """Greenwood–Johnson adhesion on a paraboloid, without approach hysteresis."""

    work_of_adhesion: Parameter  # Δγ (J/m²)
    factor: Parameter  # k of the double-Hertz stress (3.198)

    def scaled(self, profile: Profile, E_star, scales: Scales, hysteresis: bool) -> DoubleHertzLaw:
        del hysteresis  # the stable branches load and unload alike
        return DoubleHertzLaw.scaled(profile, scales, E_star, self.work_of_adhesion, self.factor)

    def curve(self, law: DoubleHertzLaw, reach: Reach, max_turns: int) -> AbstractCurve:
        """The curve up to `reach` (it turns at most once)."""
        del max_turns
        return build_double_hertz_curve(law, reach)
