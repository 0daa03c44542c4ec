"""Thornton's (1997) elastic–perfectly plastic contact of a paraboloid, in scaled units.

Virgin loading is Hertzian, F = (4/3)E*√R d^(3/2), up to the yield depth d_y where the peak
pressure reaches p_y, then linear, F = F_y + πp_yR(d − d_y) (the slope is continuous there).
Below the deepest indentation reached, the contact is elastic with the enlarged radius R_p and
the residual indentation d_p: F = (4/3)E*√R_p (d − d_p)^(3/2), on unloading and on reloading;
beyond it loading continues on the virgin curve. At a turnaround deeper than before, the contact
radius a = √(R·d_max) is kept (Thornton's closure), so R_p = 4E*a³/(3F_max) and
d_max − d_p = a²/R_p: R_p/R is the Hertzian force at d_max over the virgin one.

Lengths in the units of `Scales` (d̂ = d/ℓz, â = a/ℓx), forces in its force unit.
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from .scales import Scales


class PlasticState(eqx.Module):
    """The memory of the contact, carried between contacts (scaled)."""

    deepest: jax.Array  # d_max: the deepest indentation so far
    radius_ratio: jax.Array  # R_p/R (1 while elastic)
    residual: jax.Array  # d_p: the permanent dent, where a contact starts and ends

    @staticmethod
    def virgin() -> "PlasticState":
        """An undeformed contact: elastic Hertz until the yield depth."""
        return PlasticState(jnp.zeros(()), jnp.ones(()), jnp.zeros(()))


class PlasticLaw(eqx.Module):
    """F(d) of Thornton's law given the state; the contact radius â = c·√(R_p/R·(d̂ − d̂_p))."""

    scales: Scales  # the units of its lengths and forces
    stiffness: jax.Array  # k of Hertz's F̂ = k·d̂^(3/2): (4/3)E*√R·ℓz^(3/2) over the force unit
    radius_unit: jax.Array  # c = √(R·ℓz)/ℓx
    yield_depth: jax.Array  # d̂_y = (πp_y/(2E*))²R/ℓz

    def virgin_force(self, d):
        """Force on first loading to d: Hertz, then linear beyond d_y."""
        d_y = self.yield_depth
        hertz = self.stiffness * jnp.maximum(d, 0.0) ** 1.5
        plastic = self.stiffness * d_y**1.5 * (1.0 + 1.5 * (d - d_y) / d_y)
        return jnp.where(d > d_y, plastic, hertz)

    def virgin_work(self, d):
        """∫₀^d F dd along the virgin curve."""
        d_y = self.yield_depth
        elastic = 0.4 * self.stiffness * jnp.maximum(jnp.minimum(d, d_y), 0.0) ** 2.5
        beyond = jnp.maximum(d - d_y, 0.0)
        force_at_yield = self.stiffness * d_y**1.5
        return elastic + force_at_yield * beyond + 0.75 * force_at_yield / d_y * beyond**2

    def elastic_force(self, d, state: PlasticState):
        """Hertz with R_p about the residual dent: (4/3)c√(R_p/R)(d − d_p)^(3/2)."""
        return self.stiffness * jnp.sqrt(state.radius_ratio) * jnp.maximum(d - state.residual, 0.0) ** 1.5

    def elastic_work(self, d, state: PlasticState):
        """∫_{d_p}^d of the elastic force."""
        return 0.4 * self.stiffness * jnp.sqrt(state.radius_ratio) * jnp.maximum(d - state.residual, 0.0) ** 2.5

    def force(self, d, state: PlasticState):
        """Elastic below the deepest indentation so far, virgin loading beyond it."""
        return jnp.where(d > state.deepest, self.virgin_force(d), self.elastic_force(d, state))

    def work(self, d, state: PlasticState):
        """∫F dd from the dent d_p to d along `force` with this state (a potential per phase)."""
        beyond = self.elastic_work(state.deepest, state) + self.virgin_work(d) - self.virgin_work(state.deepest)
        return jnp.where(d > state.deepest, beyond, self.elastic_work(d, state))

    def contact_radius(self, d, state: PlasticState):
        """â: √(R·d) on virgin loading, √(R_p(d − d_p)) below the deepest indentation."""
        virgin = self.radius_unit * jnp.sqrt(jnp.maximum(d, 0.0))
        elastic = self.radius_unit * jnp.sqrt(state.radius_ratio * jnp.maximum(d - state.residual, 0.0))
        return jnp.where(d > state.deepest, virgin, elastic)

    def after_turn(self, d, state: PlasticState) -> PlasticState:
        """The state once loading turned at d: unchanged unless d is deeper than before; elastic
        (R_p = R, d_p = 0 exactly) until d passes the yield depth."""
        deeper = d > state.deepest
        yielded = d > self.yield_depth
        ratio = jnp.where(yielded, self.stiffness * d**1.5 / self.virgin_force(d), 1.0)
        residual = jnp.where(yielded, d * (1.0 - 1.0 / ratio), 0.0)
        return PlasticState(
            deepest=jnp.where(deeper, d, state.deepest),
            radius_ratio=jnp.where(deeper, ratio, state.radius_ratio),
            residual=jnp.where(deeper, residual, state.residual),
        )
