"""Functions the closed-form profiles are written in, accurate where their textbook forms cancel:
odd power series, the angle φ = arccos(b/x) beyond a radius b, the Struve functions H0, H1 (3.136)
and the complete elliptic integral E (3.62)."""

import math

import jax
import jax.numpy as jnp
import numpy as np
from jaxtyping import Array, ArrayLike

from ._base import as_float


def _odd_series(t: Array, coeffs: np.ndarray, first: int) -> Array:
    """Σ_k coeffs[k] t^(first + 2k), evaluated by Horner's rule in t²."""
    t2 = t * t
    acc = jnp.zeros_like(t)
    for c in coeffs[::-1]:
        acc = acc * t2 + c
    return acc * t**first


def _odd_series_rows(t: Array, table: np.ndarray, firsts: tuple[int, ...]) -> list[Array]:
    """`_odd_series(t, table[i], firsts[i])` for every row i of `table` ([rows, terms]; a row
    padded with zeros at its high-order end, which Horner's rule passes through exactly), in one
    Horner's rule over a last axis of the rows: the same operations on each row, traced once."""
    t2 = (t * t)[..., None]
    acc = jnp.zeros((*t.shape, table.shape[0]), t.dtype)
    for c in table.T[::-1]:
        acc = acc * t2 + c
    return [acc[..., row] * t**first for row, first in enumerate(firsts)]


_SMALL = 0.1  # below this angle the closed forms lose more than 2 digits: use the series
_K = range(10)  # 10 series terms: truncation error < _SMALL**20 relative
# φ - sin φ cos φ = Σ_{k≥1} (-1)^(k+1) 4^k φ^(2k+1) / (2k+1)!
_P_COEF = np.array([(-1) ** k * 4.0 ** (k + 1) / math.factorial(2 * k + 3) for k in _K])
# sin φ - φ cos φ = Σ_{k≥1} (-1)^(k+1) 2k φ^(2k+1) / (2k+1)!
_Q_COEF = np.array([(-1) ** k * (2.0 * k + 2) / math.factorial(2 * k + 3) for k in _K])
# sin³φ/3 - cos φ (φ - sin φ cos φ)/2 = 3/8 sin φ + 1/24 sin 3φ - φ cos φ / 2 (φ³ term vanishes)
_M_COEF = np.array(
    [(-1) ** k * (3 / 8 + 3.0 ** (2 * k + 5) / 24 - (2 * k + 5) / 2) / math.factorial(2 * k + 5) for k in _K]
)
# u - (1 - u²) artanh u = Σ_{k≥1} 2 u^(2k+1) / (4k² - 1)
_A_COEF = np.array([2.0 / (4.0 * (k + 1) ** 2 - 1) for k in _K])


def angle_minus_sin_cos(phi: Array) -> Array:
    """φ - sin φ cos φ, accurate for small φ."""
    closed = phi - 0.5 * jnp.sin(2 * phi)
    return jnp.where(phi < _SMALL, _odd_series(phi, _P_COEF, 3), closed)


def sin_minus_angle_cos(phi: Array) -> Array:
    """sin φ - φ cos φ, accurate for small φ."""
    closed = jnp.sin(phi) - phi * jnp.cos(phi)
    return jnp.where(phi < _SMALL, _odd_series(phi, _Q_COEF, 3), closed)


def rounded_edge_G(phi: Array) -> Array:
    """sin³φ / 3 - cos φ (φ - sin φ cos φ) / 2, accurate for small φ: the rounded flat punch's
    G over x³/R (3.127)."""
    closed = 3 / 8 * jnp.sin(phi) + jnp.sin(3 * phi) / 24 - 0.5 * phi * jnp.cos(phi)
    return jnp.where(phi < _SMALL, _odd_series(phi, _M_COEF, 5), closed)


def artanh_rest(u: Array) -> Array:
    """u - (1 - u²) artanh u for 0 <= u <= 1 (equal to 1 at u = 1), accurate for small u."""
    v = 1 - u
    closed = u - 0.5 * (1 + u) * (v * jnp.log1p(u) - jax.scipy.special.xlogy(v, v))
    return jnp.where(u < _SMALL, _odd_series(u, _A_COEF, 3), closed)


def beyond_radius(x: Array, b: Array):
    """Where x > b: (mask, x, s = sqrt(x² - b²), φ = arccos(b/x)); harmless values elsewhere."""
    mask = x > b
    xs = jnp.where(mask, x, 2 * b + 1.0)  # any value > b: this branch is discarded
    s = jnp.sqrt((xs - b) * (xs + b))
    return mask, xs, s, jnp.arctan2(s, b)


# Struve functions H0, H1: Gauss-Legendre quadrature of their integral representations for
# z <= _Z_ASYM, asymptotic expansions (Hankel for Y0, Y1 plus the Struve series) beyond.
_Z_ASYM = 30.0
_SL_T, _SL_W = np.polynomial.legendre.leggauss(48)
_SL_TH = (_SL_T + 1) * np.pi / 4
_SL_W = _SL_W * np.pi / 4


def _hankel_coef(nu: int, n: int) -> np.ndarray:
    """The first n coefficients a_k(ν) of Hankel's asymptotic expansion of Y_ν."""
    a = [1.0]
    for k in range(1, n):
        a.append(a[-1] * (4 * nu * nu - (2 * k - 1) ** 2) / (8 * k))
    return np.array(a)


def _struve_asym_coef(nu: int, n: int) -> np.ndarray:
    """The first n coefficients of H_ν(z) - Y_ν(z) ~ (1/π) Σ_k Γ(k+½)/Γ(ν+½-k) (z/2)^(ν-2k-1)."""
    return np.array(
        [math.gamma(k + 0.5) / math.gamma(nu + 0.5 - k) * 2.0 ** (2 * k + 1 - nu) / math.pi for k in range(n)]
    )


def _asymptotic_series(nu: int) -> np.ndarray:
    """The coefficients of the three series of `struve_h`'s asymptotic branch of order ν, one row
    each, zero-padded to one length: Hankel's P and Q of Y_ν (every other a_k(ν), signs
    alternating in pairs) and the Struve part H_ν − Y_ν."""
    hankel = _hankel_coef(nu, 24) * (-1.0) ** (np.arange(24) // 2)
    rows = [hankel[0::2], hankel[1::2], _struve_asym_coef(nu, 15)]
    terms = max(len(row) for row in rows)
    return np.array([np.concatenate([row, np.zeros(terms - len(row))]) for row in rows])


_ASYMPTOTIC = [_asymptotic_series(nu) for nu in (0, 1)]
_ASYMPTOTIC_FIRSTS = [(0, 1, 1), (0, 1, 0)]  # the lowest power of 1/z in each row (P, Q, H − Y), by ν


def struve_h(z: ArrayLike, nu: int) -> Array:
    """The Struve function H_ν(z) of order ν = 0 or 1 for z >= 0, relative accuracy ~1e-14."""
    z = as_float(z)
    sz = jnp.sin(z[..., None] * np.sin(_SL_TH))
    if nu == 0:
        h_q = (2 / np.pi) * (sz @ _SL_W)
    else:
        h_q = (2 / np.pi) * z * (sz @ (_SL_W * np.cos(_SL_TH) ** 2))
    zl = jnp.where(z > _Z_ASYM, z, _Z_ASYM)
    w = 1 / zl
    p, q, rest = _odd_series_rows(w, _ASYMPTOTIC[nu], _ASYMPTOTIC_FIRSTS[nu])
    chi = zl - (2 * nu + 1) * np.pi / 4
    y = jnp.sqrt(2 / (np.pi * zl)) * (p * jnp.sin(chi) + q * jnp.cos(chi))
    return jnp.where(z > _Z_ASYM, y + rest, h_q)


def struve_h0_h1(z: ArrayLike) -> tuple[Array, Array]:
    """Struve functions (H0(z), H1(z)) for z >= 0 (`struve_h`)."""
    return struve_h(z, 0), struve_h(z, 1)


_AGM_STEPS = 12  # the arithmetic-geometric mean converges quadratically: ~1e-16 at k' ~ 1e-16


def ellipe(k: ArrayLike) -> Array:
    """Complete elliptic integral of the second kind E(k) = ∫_0^{π/2} √(1 − k² sin²φ) dφ (3.62),
    modulus k in [0, 1], by the arithmetic-geometric mean; differentiable for k < 1."""
    k = as_float(k)
    edge = k >= 1
    ks = jnp.where(edge, 0.5, jnp.abs(k))
    a, b, c = jnp.ones_like(ks), jnp.sqrt((1 - ks) * (1 + ks)), ks
    total = 0.5 * c**2
    weight = 0.5
    for _ in range(_AGM_STEPS):
        a, b, c = 0.5 * (a + b), jnp.sqrt(a * b), 0.5 * (a - b)
        weight = 2 * weight
        total = total + weight * c**2
    return jnp.where(edge, 1.0, np.pi / (2 * a) * (1 - total))
