"""One MDR spring of a viscoelastic half-space, integrated exactly over a step.

The medium relaxes as a Prony series (generalized Maxwell model), E*(t) = E∞ + Σ E_i·e^(−t/τ_i)
(V. L. Popov, E. Willert, M. Heß, "Method of dimensionality reduction in contact mechanics and
friction: a user's handbook. III. Viscoelastic contacts", Facta Universitatis, Mech. Eng. 16
(2018) 99: each spring of the MDR foundation is the medium's rheological element). A spring of
width Δx is a spring E∞·Δx in parallel with Maxwell arms, E_i·Δx in series with a dashpot of
time τ_i. Per unit width and in the units of `Scales` (displacements in ℓz, moduli relative to
E∞, times in t*), its state is the displacement u (pressed in > 0) and the stretches q_i of the
arms' springs; its force is f = u + Σ e_i·q_i, e_i = E_i/E∞, and its elastic energy
½u² + ½Σ e_i·q_i².

- Attached, u follows the indenter, u = d − g(x). Over a step in which u changes linearly at the
  rate r, q̇_i = r − q_i/τ_i has the exact solution q_i(s) = q_i·e^(−s/τ_i) + r·s·φ₁(s/τ_i),
  φ₁(z) = (1 − e^(−z))/z; the work r·∫f ds and the dissipation Σ(e_i/τ_i)∫q_i² ds of the step
  follow in closed form (`_PHI`: series where z is small, so that τ → ∞ loses no digit).
- Free (force zero), u = −Σ e_i·q_i and q̇ = A·q with A = 1·cᵀ/e₀ − diag(1/τ_i), c_i = e_i/τ_i,
  e₀ = 1 + Σ e_i the instantaneous modulus: the surface creeps back with the retardation times
  −1/λ_k, the eigenvalues λ_k of A (of the symmetric diag(√c)·A·diag(1/√c), `eigh`); exact for
  any step.
- Free under a force per width linear in time, f(s) = f + ḟ·s (the Dugdale zone's load), the
  stretches obey q̇ = A·q + (ḟ/e₀)·1 (from f = u + Σ e_i·q_i and q̇_i = u̇ − q_i/τ_i): in the
  modes y = V·q of A, ẏ_k = λ_k·y_k + (ḟ/e₀)·b_k (b = V·1), the attached spring's equation with
  1/τ_i → −λ_k and the rate ḟ·b_k/e₀, so the same closed forms give the step (`forced`).
- A snap (a spring letting go, or attaching) is instantaneous: the dashpots do not move, so u and
  every q_i jump by the same Δu, at the instantaneous stiffness e₀.
"""

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np

from .._core.types import Parameter

# Below this z the φ-functions of `_PHI` are their Taylor series (terms to z^13: the remainder is
# below 1e-17 of the value); above, their closed forms lose at most 1.5 digits (J₂ at z = ¼: its
# numerator z²/3 out of terms of 1).
_SERIES_BELOW = 0.25
_SERIES_TERMS = 14


def _series(numerator, offset: int) -> np.ndarray:
    """Coefficients (ascending) of Σ_j (−z)^j·numerator(j)/(j + offset)!."""
    return np.array(
        [(-1.0) ** j * numerator(j) / float(np.prod(np.arange(1, j + offset + 1))) for j in range(_SERIES_TERMS)]
    )


# φ₁(z) = (1 − e^(−z))/z, K(z) = (1 − φ₁(z))/z, J₁(z) = (φ₁(z) − φ₁(2z))/z,
# J₂(z) = (1 − 2φ₁(z) + φ₁(2z))/z²: the integrals over a step of length h = z·τ of e^(−s/τ),
# s·φ₁(s/τ), e^(−s/τ)·s·φ₁(s/τ) and (s·φ₁(s/τ))², divided by h, h², h² and h³.
_PHI = {
    "phi1": _series(lambda j: 1.0, 1),
    "K": _series(lambda j: 1.0, 2),
    "J1": _series(lambda j: 2.0 ** (j + 1) - 1.0, 2),
    "J2": _series(lambda j: 2.0 ** (j + 2) - 2.0, 3),
}


def _horner(coefficients: np.ndarray, z):
    value = jnp.zeros_like(z)
    for coefficient in coefficients[::-1]:
        value = value * z + coefficient
    return value


def phi1(z):
    """φ₁(z) = (1 − e^(−z))/z for z ≥ 0 (expm1 keeps every digit as z → 0), 1 at z = 0."""
    positive = z > 0.0
    safe = jnp.where(positive, z, 1.0)
    return jnp.where(positive, -jnp.expm1(-safe) / safe, 1.0)


def _phi_family(z):
    """(φ₁(z), K(z), J₁(z), J₂(z)) of `_PHI`."""
    small = z < _SERIES_BELOW
    safe = jnp.where(small, 1.0, z)
    one = -jnp.expm1(-safe) / safe
    two = -jnp.expm1(-2.0 * safe) / (2.0 * safe)
    closed = (one, (1.0 - one) / safe, (one - two) / safe, (1.0 - 2.0 * one + two) / safe**2)
    return tuple(jnp.where(small, _horner(_PHI[name], z), value) for name, value in zip(_PHI, closed, strict=True))


class Loaded(eqx.Module):
    """An attached spring after a step of length h at the rate r (per unit width, scaled)."""

    stretches: jax.Array  # q_i at the end [..., M]
    force_integral: jax.Array  # ∫f ds over the step
    dissipation: jax.Array  # Σ (e_i/τ_i)·∫q_i² ds over the step


class Forced(eqx.Module):
    """A free spring after a step of length h under a force per width linear in time (scaled)."""

    stretches: jax.Array  # q_i at the end [..., M]
    displacement: jax.Array  # u at the end
    dissipation: jax.Array  # Σ (e_i/τ_i)·∫q_i² ds over the step


class PronyElement(eqx.Module):
    """The rheological element of every spring (scaled: moduli relative to E∞, times in t*)."""

    moduli: Parameter  # e_i = E_i/E∞ [M]
    times: Parameter  # τ_i [M]
    rates: jax.Array  # λ_k < 0, the free spring's relaxation rates [M]
    to_modes: jax.Array  # y = to_modes·q: the free spring's modes [M, M]
    from_modes: jax.Array  # q = from_modes·y [M, M]

    def __init__(self, moduli, times):
        self.moduli = moduli
        self.times = times
        weights = jnp.sqrt(moduli / times)  # √c_i
        instantaneous = 1.0 + jnp.sum(moduli)
        symmetric = jnp.outer(weights, weights) / instantaneous - jnp.diag(1.0 / times)
        self.rates, vectors = jnp.linalg.eigh(symmetric)
        self.to_modes = vectors.T * weights
        self.from_modes = vectors / weights[:, None]

    @property
    def instantaneous(self):
        """e₀ = E₀*/E∞ = 1 + Σ e_i: the stiffness of a snap (no dashpot moves)."""
        return 1.0 + jnp.sum(self.moduli)

    def force(self, displacement, stretches):
        """f = u + Σ e_i·q_i."""
        return displacement + stretches @ self.moduli

    def stored(self, displacement, stretches):
        """Elastic energy ½u² + ½Σ e_i·q_i²."""
        return 0.5 * displacement**2 + 0.5 * (stretches**2) @ self.moduli

    def free_displacement(self, stretches):
        """u of a free spring (f = 0): −Σ e_i·q_i."""
        return -(stretches @ self.moduli)

    def loaded(self, displacement, stretches, rate, duration) -> Loaded:
        """An attached spring whose displacement changes at `rate` for `duration` (both [...])
        from `displacement` and the arm stretches `stretches` [..., M]."""
        z = duration[..., None] / self.times
        one, k, j1, j2 = _phi_family(z)
        decay = jnp.exp(-z)
        travel = (rate * duration)[..., None]  # r·h
        q = stretches
        arms_integral = duration[..., None] * (q * one + travel * k)
        squares = q**2 * phi1(2.0 * z) + 2.0 * q * travel * j1 + travel**2 * j2
        return Loaded(
            stretches=q * decay + travel * one,
            force_integral=duration * (displacement + 0.5 * rate * duration) + arms_integral @ self.moduli,
            dissipation=(z * squares) @ self.moduli,
        )

    def free(self, stretches, duration):
        """A free spring after `duration` [...]: (stretches [..., M], dissipation [...])."""
        modes = stretches @ self.to_modes.T
        decay = jnp.exp(self.rates * duration[..., None])
        dissipation = jnp.sum(modes**2 * duration[..., None] * phi1(-2.0 * self.rates * duration[..., None]), axis=-1)
        return (modes * decay) @ self.from_modes.T, dissipation

    def forced(self, stretches, force, force_rate, duration) -> Forced:
        """A free spring under the force per width `force` + `force_rate`·s for `duration` (all
        [...]) from the arm stretches `stretches` [..., M]: its modes advanced as `loaded`
        advances the arms (z_k = −λ_k·h, travel (ḟ·h/e₀)·b_k); the dissipation Σ c_i·∫q_i² ds is
        ∫|y|² ds (the modes are scaled by √c_i). With `force_rate` 0 and `force` 0, `free`."""
        modes = stretches @ self.to_modes.T
        z = -self.rates * duration[..., None]
        one, _, j1, j2 = _phi_family(z)
        travel = (force_rate * duration / self.instantaneous)[..., None] * self._drive
        end = modes * jnp.exp(-z) + travel * one
        squares = modes**2 * phi1(2.0 * z) + 2.0 * modes * travel * j1 + travel**2 * j2
        end_stretches = end @ self.from_modes.T
        return Forced(
            stretches=end_stretches,
            displacement=force + force_rate * duration - end_stretches @ self.moduli,
            dissipation=duration * jnp.sum(squares, axis=-1),
        )

    def forced_surface(self, stretches, force, force_rate, time):
        """(u, du/ds) of a free spring `time` into a step under the force `force` + `force_rate`·s."""
        modes = stretches @ self.to_modes.T
        z = -self.rates * time[..., None]
        drive = (force_rate / self.instantaneous)[..., None] * self._drive
        y = modes * jnp.exp(-z) + time[..., None] * drive * phi1(z)
        weights = -(self.moduli @ self.from_modes)  # u = f + weights·y
        return force + force_rate * time + y @ weights, force_rate + (self.rates * y + drive) @ weights

    @property
    def _drive(self):
        """b = V·1: the modes' share of a unit force rate (times 1/e₀)."""
        return jnp.sum(self.to_modes, axis=-1)

    def loaded_force(self, displacement, stretches, rate, time):
        """(f, df/ds) of an attached spring `time` into a step at `rate` (for the root search)."""
        z = time[..., None] / self.times
        decay = jnp.exp(-z)
        arms = stretches * decay + (rate * time)[..., None] * phi1(z)
        slope_arms = (rate[..., None] - stretches / self.times) * decay
        return (
            displacement + rate * time + arms @ self.moduli,
            rate + slope_arms @ self.moduli,
        )

    def free_surface(self, stretches, time):
        """(u, du/ds) of a free spring `time` after its state `stretches`."""
        modes = stretches @ self.to_modes.T
        decay = jnp.exp(self.rates * time[..., None]) * modes
        weights = -(self.moduli @ self.from_modes)  # u = weights·y
        return decay @ weights, (decay * self.rates) @ weights
