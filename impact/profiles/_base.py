"""The profile interface, the power-law factor κ(n) and the numerical MDR transform (3.24)."""

import abc

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
from jax.scipy.special import gammaln
from jaxtyping import Array, ArrayLike, Float

from .._core.quadrature import gauss_legendre


def as_float(v: ArrayLike) -> Array:
    """`v` as a float array (float64 when JAX's x64 flag is on). A number goes through a NumPy
    array: converting a Python or NumPy scalar directly would compile a program of its own."""
    if isinstance(v, int | float | np.generic):
        v = np.asarray(v, dtype=np.float64)
    return jnp.asarray(v, dtype=float)


# Scalars of a closed form or a profile, broadcast against each other: numbers or arrays.
Scalars = Float[Array | np.ndarray | float, "*#batch"]

# A profile's parameter: given as a number or array (m, rad, Pa, ...), stored as a float array.
FloatParameter = Float[Array | np.ndarray | float, "*batch"]


def float_field():
    """A module field stored as a float array."""
    return eqx.field(converter=as_float)


def kappa(n: ArrayLike) -> Array:
    """Power-law factor κ(n) = √π Γ(n/2 + 1) / Γ((n+1)/2) (3.72): g = κ(n) c xⁿ for f = c rⁿ."""
    n = as_float(n)
    return jnp.sqrt(jnp.pi) * jnp.exp(gammaln(n / 2 + 1) - gammaln((n + 1) / 2))


def mdr_transform(f, x: ArrayLike, nodes: int = 64, breakpoints=()) -> Array:
    """Numerical MDR transform g(x) = x ∫_0^{π/2} f'(x sin θ) dθ of a profile f (m -> m).

    `f` maps a scalar radius r (m) to the height f(r) (m) and must be differentiable by
    `jax.grad`; `x` (m) is an array of any shape. Each θ-interval is integrated with `nodes`
    Gauss-Legendre points; the integral is split at θ = arcsin(b/x) for every radius b (m) in
    `breakpoints` below x, so kinks of f at known radii cost no accuracy. Exact for polynomial
    integrands, spectrally accurate for smooth ones.
    """
    x = as_float(x)
    fractions, weights = gauss_legendre(nodes)
    dfdr = jnp.vectorize(jax.grad(f))
    xs = jnp.where(x > 0, x, 1.0)[..., None]
    bps = jnp.sort(jnp.atleast_1d(as_float(breakpoints)).reshape(-1))
    # θ_b = arcsin(b/x) as atan2(b, sqrt(x² - b²)): well conditioned as b -> x; π/2 for b >= x
    cuts = jnp.arctan2(bps, jnp.sqrt(jnp.clip((xs - bps) * (xs + bps), 0.0)))
    edges = jnp.concatenate([jnp.zeros_like(xs), cuts, jnp.full_like(xs, jnp.pi / 2)], axis=-1)
    lo, hi = edges[..., :-1, None], edges[..., 1:, None]
    theta = lo + (hi - lo) * fractions
    integral = jnp.sum((hi - lo) * weights * dfdr(xs[..., None] * jnp.sin(theta)), axis=(-2, -1))
    return jnp.where(x > 0, xs[..., 0] * integral, 0.0)


class Profile(eqx.Module):
    """Rigid axisymmetric body: height f(r) above the tip, MDR profile g(x) and G = ∫_0^x g.

    All methods act elementwise on float64 arrays; lengths in m.
    """

    @abc.abstractmethod
    def f(self, r: ArrayLike) -> Array:
        """Height of the body surface above its tip at radius r >= 0 (m); inf beyond a wall."""

    @abc.abstractmethod
    def g(self, x: ArrayLike) -> Array:
        """MDR equivalent profile g(x) (3.24) for 0 <= x <= extent (m)."""

    @abc.abstractmethod
    def G(self, x: ArrayLike) -> Array:
        """`G(x) = ∫_0^x g(s) ds` (m²); the normal force is `F = 2E*(a d - G(a))`."""

    def extent(self) -> Array:
        """Largest possible contact radius (m): inf unless the body ends at a wall or equator."""
        return jnp.asarray(jnp.inf)

    @abc.abstractmethod
    def radius_scale(self) -> Array:
        """A characteristic radius (m), only used to bracket root searches."""

    def power_form(self) -> tuple[Array, Array] | None:
        """(A, n) where g(x) = A·xⁿ exactly (A in m^(1−n)): the contact law then states the
        turning points of its edge functions and ∫g² in closed form instead of searching and
        integrating. None (the default): g has no such form."""
        return None
