"""The contact-law interface: a law's traced SI parameters and the units an impact on it is
scaled to. Concrete laws are final (equinox's abstract/final pattern, as diffrax's solvers): a
scene picks one (`impact._scene`), an integrator rides it (`impact._integrate`).

The families, by what an integrator rides:
- `AbstractEdgeLaw`: the continuum MDR with the rule of Heß (zero range): the contact radius
  rides the edge functions h(x) = g(x) − λ·√x (`law.ContactLaw`, `branches`);
- `AbstractCurveLaw`: a finite-range law whose states lie on an equilibrium curve (`curve`);
- `AbstractPlasticLaw`: Thornton's limiting contact pressure of a paraboloid (`plastic`).
"""

import abc
from typing import Generic, TypeVar

import equinox as eqx
import jax

from .._core.types import Parameter
from ..profiles import Profile
from .curve import AbstractCurve, CurveLaw, Reach
from .scales import Scales, adhesive_scales


class AbstractContactLaw(eqx.Module):
    """A contact law: its traced SI parameters (new values do not recompile) and its units."""

    @abc.abstractmethod
    def scales(self, profile: Profile, E_star, mass, touch_velocity) -> Scales:
        """The units in which an impact of `mass` (kg) at `touch_velocity` (m/s) on this law is
        O(1), for the body `profile` on a half-space of modulus `E_star` (Pa)."""


class AbstractAdhesiveLaw(AbstractContactLaw):
    """A law with adhesion: the Dupré work of adhesion Δγ (J/m²) is one of its parameters."""

    work_of_adhesion: eqx.AbstractVar[Parameter]


class AbstractEdgeLaw(AbstractContactLaw):
    """The continuum MDR law, its springs attaching and detaching by the rule of Heß (3.26)."""

    @abc.abstractmethod
    def hess_coefficients(self, scales: Scales, E_star) -> tuple[jax.Array, jax.Array]:
        """(λ, λa) of the scaled Heß rule: the edge spring at x̂ detaches at the elongation λ·√x̂
        and the next one attaches at λa·√x̂ (both 0 without adhesion)."""


ScaledCurveLaw = TypeVar("ScaledCurveLaw", bound=CurveLaw)


class AbstractCurveLaw(AbstractAdhesiveLaw, Generic[ScaledCurveLaw]):
    """A finite-range law whose states lie on an equilibrium curve: impacts and quasi-static
    tests ride it (`curve.AbstractCurve`)."""

    def scales(self, profile: Profile, E_star, mass, touch_velocity) -> Scales:
        """The JKR units of Δγ, or the impact energy's where it reaches further."""
        return adhesive_scales(profile, E_star, self.work_of_adhesion, mass, touch_velocity)

    @abc.abstractmethod
    def scaled(self, profile: Profile, E_star, scales: Scales, hysteresis: bool) -> ScaledCurveLaw:
        """The law in the units of `scales`; with `hysteresis` (static) its approach path."""

    @abc.abstractmethod
    def curve(self, law: ScaledCurveLaw, reach: Reach, max_turns: int) -> AbstractCurve:
        """The curve of the scaled `law` up to `reach`, with at most `max_turns` turning points."""

    def start_indentation(self, law: ScaledCurveLaw, gap, scales: Scales) -> Parameter:
        """Where an impact starts (scaled): `gap` (m) before the interaction does."""
        return law.onset - gap / scales.normal


class AbstractPlasticLaw(AbstractContactLaw):
    """Thornton's (1997) limiting contact pressure p_y of a paraboloid (`plastic`)."""

    yield_pressure: eqx.AbstractVar[Parameter]
