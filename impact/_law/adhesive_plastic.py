"""The adhesive elastic–plastic contact of a paraboloid (Thornton & Ning 1998, in the MDR with
the rule of Heß; `theory.adhesive_plastic_restitution` states the model), in scaled units.

With ĝ = c·x̂² the virgin 1-D profile and Δl̂ = λ·√x̂ the Heß elongation, every branch is a
curve of the contact radius â:

- elastic, about the dent (ρ = R/R_p, d̂_p; virgin 1, 0): d̂ = d̂_p + ρcâ² − λ√â,
  F̂ = (4/3)ρcâ³ − 2λâ^(3/2), up to the largest radius so far (at least the yield radius â_y);
- plastic loading beyond it: d̂ = câ² − λ√â, F̂ = F̂_H − 2λâ^(3/2) with the Hertzian part
  F̂_H = (4/3)câ_y³ + P̂(â² − â_y²), P̂ = πp_yℓx/(E*ℓz);
- a turnaround past the largest radius â_m leaves the dent ρ = F̂_H(â_m)/((4/3)câ_m³),
  d̂_p = (1 − ρ)câ_m² (the branches meet there in d̂ and F̂).

Lengths in the units of `Scales`, forces in E*·ℓx·ℓz, energies in E*·ℓx·ℓz².
"""

import equinox as eqx
import jax
import jax.numpy as jnp


class DentState(eqx.Module):
    """The memory of the contact, carried between contacts (scaled)."""

    onset: jax.Array  # the radius beyond which loading flows: max(â_y, â_m)
    ratio: jax.Array  # ρ = R/R_p (1 while elastic)
    residual: jax.Array  # d̂_p: the depth of the dent, where a contact starts and ends

    @staticmethod
    def virgin(yield_radius) -> "DentState":
        """An undeformed contact: elastic (JKR) up to the yield radius."""
        return DentState(jnp.asarray(yield_radius), jnp.ones(()), jnp.zeros(()))


class AdhesivePlasticLaw(eqx.Module):
    """d̂(â), F̂(â) and the stored energy of each branch."""

    curvature: jax.Array  # c of ĝ = c·x̂²: ℓx²/(R·ℓz)
    hess: jax.Array  # λ of Δl̂ = λ·√x̂
    yield_radius: jax.Array  # â_y: where the JKR pressure at the centre reaches p_y
    flow_pressure: jax.Array  # P̂ = πp_y·ℓx/(E*·ℓz)

    def hertzian_force(self, a):
        """F̂_H on plastic loading at the radius â (beyond â_y)."""
        a_y = self.yield_radius
        return 4.0 / 3.0 * self.curvature * a_y**3 + self.flow_pressure * (a**2 - a_y**2)

    def depth(self, a, state: DentState, flowing):
        """d̂ on the dent's branch, or on plastic loading where `flowing`."""
        ratio, residual = jnp.where(flowing, 1.0, state.ratio), jnp.where(flowing, 0.0, state.residual)
        return residual + ratio * self.curvature * a**2 - self.hess * jnp.sqrt(a)

    def slope(self, a, state: DentState, flowing):
        """dd̂/dâ of the branch."""
        ratio = jnp.where(flowing, 1.0, state.ratio)
        return 2.0 * ratio * self.curvature * a - 0.5 * self.hess / jnp.sqrt(a)

    def force(self, a, state: DentState, flowing):
        """F̂ of the branch at the radius â."""
        elastic = 4.0 / 3.0 * state.ratio * self.curvature * a**3
        return jnp.where(flowing, self.hertzian_force(a), elastic) - 2.0 * self.hess * a**1.5

    def stored_energy(self, a, state: DentState):
        """Û on the dent's branch: ∫₀^â (d̂ − ĝ_p)² dx̂ − (λ²/2)â², the springs' energy less the
        surface energy πa²Δγ; dÛ = F̂ dd̂ along the branch."""
        stiff = state.ratio * self.curvature
        excess = stiff * a**2 - self.hess * jnp.sqrt(a)
        return excess**2 * a - 2.0 / 3.0 * excess * stiff * a**3 + stiff**2 * a**5 / 5.0 - 0.5 * self.hess**2 * a**2

    def flow_work(self, a):
        """An antiderivative of F̂·dd̂/dâ on plastic loading."""
        c, lam, P, a_y = self.curvature, self.hess, self.flow_pressure, self.yield_radius
        k = 4.0 / 3.0 * c * a_y**3 - P * a_y**2
        return (
            c * k * a**2
            - lam * k * jnp.sqrt(a)
            + 0.5 * c * P * a**4
            - 0.2 * lam * P * a**2.5
            - 8.0 / 7.0 * c * lam * a**3.5
            + 0.5 * lam**2 * a**2
        )

    def work(self, start, end, state: DentState, flowing):
        """∫F̂ dd̂ while the radius rides the branch from `start` to `end`."""
        elastic = self.stored_energy(end, state) - self.stored_energy(start, state)
        return jnp.where(flowing, self.flow_work(end) - self.flow_work(start), elastic)

    def jump_in(self, state: DentState):
        """Radius of the jump-in at the touch d̂ = d̂_p: ρcâ² = λ√â."""
        return (self.hess / (state.ratio * self.curvature)) ** (2.0 / 3.0)

    def snap_off(self, state: DentState):
        """Radius where the dent's branch turns (dd̂/dâ = 0): a free body separates there."""
        return (0.25 * self.hess / (state.ratio * self.curvature)) ** (2.0 / 3.0)

    def weakest(self, state: DentState, flowing):
        """Radius of the branch's least force (dF̂/dâ = 0)."""
        elastic = (0.75 * self.hess / (state.ratio * self.curvature)) ** (2.0 / 3.0)
        return jnp.where(flowing, (1.5 * self.hess / self.flow_pressure) ** 2, elastic)

    def after_turn(self, a, state: DentState) -> DentState:
        """The state once loading turned at â: the dent of â where it lies past the onset."""
        deeper = a > state.onset
        ratio = self.hertzian_force(a) / (4.0 / 3.0 * self.curvature * a**3)
        return DentState(
            onset=jnp.where(deeper, a, state.onset),
            ratio=jnp.where(deeper, ratio, state.ratio),
            residual=jnp.where(deeper, (1.0 - ratio) * self.curvature * a**2, state.residual),
        )
