"""Rigid axisymmetric body profiles and their MDR equivalents (SI units).

A profile is the height f(r) (m) of the body surface above its tip at radius r (m). The method
of dimensionality reduction replaces it by the 1-D profile (3.24)

    g(x) = x ∫_0^x f'(r) / sqrt(x² - r²) dr = x ∫_0^{π/2} f'(x sin θ) dθ,

and the normal force at contact radius a and indentation d is F = 2E*(a d - G(a)) with
G(x) = ∫_0^x g(s) ds (3.28). Every class below gives f, g and G in closed form (the wavy
paraboloid through Struve functions evaluated to ~1e-14), elementwise on float64 arrays, safe
under `jax.jit`, `jax.vmap` and `jax.grad` (unused `jnp.where` branches are fed harmless
arguments, so gradients are finite for 0 < x < extent except at genuine kinks).

Shapes with a vertical wall (flat punch, capped flat punch) have f = inf beyond the wall and an
`extent` equal to the wall radius; the sphere and the ellipsoid end at their equator.
`mdr_transform` computes g numerically for any differentiable f(r).
"""

import abc
import math

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
from jax.scipy.special import gammaln
from jaxtyping import Array, ArrayLike

__all__ = [
    "Profile",
    "Paraboloid",
    "Sphere",
    "Ellipsoid",
    "Cone",
    "PowerLaw",
    "FlatPunch",
    "TruncatedCone",
    "TruncatedParaboloid",
    "CappedFlatPunch",
    "CappedCone",
    "CappedParaboloid",
    "RoundedFlatPunch",
    "WavyParaboloid",
    "ConstantStress",
    "Tabulated",
    "kappa",
    "ellipe",
    "mdr_transform",
]


def _f64(v: ArrayLike) -> Array:
    return jnp.asarray(v, dtype=float)


def _param():
    return eqx.field(converter=_f64)


# ---------------------------------------------------------------- elementary helpers


def _odd_series(t: Array, coeffs: np.ndarray, first: int) -> Array:
    """Σ_k coeffs[k] t^(first + 2k), evaluated by Horner's rule in t²."""
    t2 = t * t
    acc = jnp.zeros_like(t)
    for c in coeffs[::-1]:
        acc = acc * t2 + c
    return acc * t**first


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


def _p(phi: Array) -> Array:
    """φ - sin φ cos φ, accurate for small φ."""
    closed = phi - 0.5 * jnp.sin(2 * phi)
    return jnp.where(phi < _SMALL, _odd_series(phi, _P_COEF, 3), closed)


def _q(phi: Array) -> Array:
    """sin φ - φ cos φ, accurate for small φ."""
    closed = jnp.sin(phi) - phi * jnp.cos(phi)
    return jnp.where(phi < _SMALL, _odd_series(phi, _Q_COEF, 3), closed)


def _m(phi: Array) -> Array:
    """sin³φ / 3 - cos φ (φ - sin φ cos φ) / 2, accurate for small φ."""
    closed = 3 / 8 * jnp.sin(phi) + jnp.sin(3 * phi) / 24 - 0.5 * phi * jnp.cos(phi)
    return jnp.where(phi < _SMALL, _odd_series(phi, _M_COEF, 5), closed)


def _artanh_rest(u: Array) -> Array:
    """u - (1 - u²) artanh u for 0 <= u <= 1 (equal to 1 at u = 1), accurate for small u."""
    v = 1 - u
    closed = u - 0.5 * (1 + u) * (v * jnp.log1p(u) - jax.scipy.special.xlogy(v, v))
    return jnp.where(u < _SMALL, _odd_series(u, _A_COEF, 3), closed)


def _past(x: Array, b: Array):
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
    a = [1.0]
    for k in range(1, n):
        a.append(a[-1] * (4 * nu * nu - (2 * k - 1) ** 2) / (8 * k))
    return np.array(a)


def _struve_asym_coef(nu: int, n: int) -> np.ndarray:
    # H_ν(z) - Y_ν(z) ~ (1/π) Σ_k Γ(k+½)/Γ(ν+½-k) (z/2)^(ν-2k-1)
    return np.array(
        [math.gamma(k + 0.5) / math.gamma(nu + 0.5 - k) * 2.0 ** (2 * k + 1 - nu) / math.pi for k in range(n)]
    )


_HANKEL = [_hankel_coef(nu, 24) for nu in (0, 1)]
_STRUVE_ASYM = [_struve_asym_coef(nu, 15) for nu in (0, 1)]


def _struve01(z: Array) -> tuple[Array, Array]:
    """Struve functions (H0(z), H1(z)) for z >= 0, relative accuracy ~1e-14."""
    sz = jnp.sin(z[..., None] * np.sin(_SL_TH))
    h0_q = (2 / np.pi) * (sz @ _SL_W)
    h1_q = (2 / np.pi) * z * (sz @ (_SL_W * np.cos(_SL_TH) ** 2))
    zl = jnp.where(z > _Z_ASYM, z, _Z_ASYM)
    w = 1 / zl
    out = []
    for nu, h_q in ((0, h0_q), (1, h1_q)):
        a = _HANKEL[nu] * (-1.0) ** (np.arange(24) // 2)
        p = _odd_series(w, a[0::2], 0)
        q = _odd_series(w, a[1::2], 1)
        chi = zl - (2 * nu + 1) * np.pi / 4
        y = jnp.sqrt(2 / (np.pi * zl)) * (p * jnp.sin(chi) + q * jnp.cos(chi))
        h_a = y + _odd_series(w, _STRUVE_ASYM[nu], 1 - nu)
        out.append(jnp.where(z > _Z_ASYM, h_a, h_q))
    return out[0], out[1]


# ---------------------------------------------------------------- public helpers


def kappa(n: ArrayLike) -> Array:
    """Power-law factor κ(n) = √π Γ(n/2 + 1) / Γ((n+1)/2) (3.72): g = κ(n) c xⁿ for f = c rⁿ."""
    n = _f64(n)
    return jnp.sqrt(jnp.pi) * jnp.exp(gammaln(n / 2 + 1) - gammaln((n + 1) / 2))


def mdr_transform(f, x: ArrayLike, nodes: int = 64, breakpoints=()) -> Array:
    """Numerical MDR transform g(x) = x ∫_0^{π/2} f'(x sin θ) dθ of a profile f (m -> m).

    `f` maps a scalar radius r (m) to the height f(r) (m) and must be differentiable by
    `jax.grad`; `x` (m) is an array of any shape. Each θ-interval is integrated with `nodes`
    Gauss-Legendre points; the integral is split at θ = arcsin(b/x) for every radius b (m) in
    `breakpoints` below x, so kinks of f at known radii cost no accuracy. Exact for polynomial
    integrands, spectrally accurate for smooth ones.
    """
    x = _f64(x)
    t, w = np.polynomial.legendre.leggauss(nodes)
    dfdr = jnp.vectorize(jax.grad(f))
    xs = jnp.where(x > 0, x, 1.0)[..., None]
    bps = jnp.sort(jnp.atleast_1d(_f64(breakpoints)).reshape(-1))
    # θ_b = arcsin(b/x) as atan2(b, sqrt(x² - b²)): well conditioned as b -> x; π/2 for b >= x
    cuts = jnp.arctan2(bps, jnp.sqrt(jnp.clip((xs - bps) * (xs + bps), 0.0)))
    edges = jnp.concatenate([jnp.zeros_like(xs), cuts, jnp.full_like(xs, np.pi / 2)], axis=-1)
    lo, hi = edges[..., :-1, None], edges[..., 1:, None]
    theta = lo + (hi - lo) * (t + 1) / 2
    integral = jnp.sum((hi - lo) / 2 * w * dfdr(xs[..., None] * jnp.sin(theta)), axis=(-2, -1))
    return jnp.where(x > 0, xs[..., 0] * integral, 0.0)


# ---------------------------------------------------------------- profiles


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
        """G(x) = ∫_0^x g(s) ds (m²); the normal force is F = 2E*(a d - G(a))."""

    def extent(self) -> Array:
        """Largest possible contact radius (m): inf unless the body ends at a wall or equator."""
        return jnp.asarray(jnp.inf)

    @abc.abstractmethod
    def radius_scale(self) -> Array:
        """A characteristic radius (m), only used to bracket root searches."""


class Paraboloid(Profile):
    """f = r²/(2R), g = x²/R (3.44); R: radius of curvature at the tip (m)."""

    R: Array = _param()

    def f(self, r):
        return _f64(r) ** 2 / (2 * self.R)

    def g(self, x):
        return _f64(x) ** 2 / self.R

    def G(self, x):
        return _f64(x) ** 3 / (3 * self.R)

    def radius_scale(self):
        return self.R


def _spheroid_g(x: Array, k: Array) -> Array:
    """x artanh(kx): g of a sphere of radius 1/k (m)."""
    return x * jnp.arctanh(k * x)


def _spheroid_G(x: Array, k: Array) -> Array:
    """∫_0^x s artanh(ks) ds = [kx - (1 - k²x²) artanh(kx)] / (2k²) (m²)."""
    return _artanh_rest(k * x) / (2 * k**2)


def _spheroid_f(r: Array, k: Array) -> Array:
    """(1 - sqrt(1 - k²r²))/k: f of a sphere of radius 1/k (m); inf beyond its equator."""
    inside = k * r <= 1
    u2 = jnp.where(inside, (k * r) ** 2, 0.0)
    return jnp.where(inside, u2 / (k * (1 + jnp.sqrt(1 - u2))), jnp.inf)


class Sphere(Profile):
    """Sphere f = R - sqrt(R² - r²), g = x artanh(x/R) (3.52); R: radius (m); extent R."""

    R: Array = _param()

    def f(self, r):
        return _spheroid_f(_f64(r), 1 / self.R)

    def g(self, x):
        return _spheroid_g(_f64(x), 1 / self.R)

    def G(self, x):
        return _spheroid_G(_f64(x), 1 / self.R)

    def extent(self):
        return self.R

    def radius_scale(self):
        return self.R


class Ellipsoid(Profile):
    """Ellipsoid of revolution f = R(1 - sqrt(1 - k²r²)) (3.58): R (m), k (1/m); extent 1/k.

    f is kR times a sphere of radius 1/k, so g = kR x artanh(kx) (the d(a) of (3.57) lacks
    this factor kR; its force has it).
    """

    R: Array = _param()
    k: Array = _param()

    def f(self, r):
        return self.k * self.R * _spheroid_f(_f64(r), self.k)

    def g(self, x):
        return self.k * self.R * _spheroid_g(_f64(x), self.k)

    def G(self, x):
        return self.k * self.R * _spheroid_G(_f64(x), self.k)

    def extent(self):
        return 1 / self.k

    def radius_scale(self):
        return 1 / self.k


class Cone(Profile):
    """Cone f = r tan θ, g = (π/2) tan θ x (3.38); theta: slope angle against the plane (rad)."""

    theta: Array = _param()

    def f(self, r):
        return _f64(r) * jnp.tan(self.theta)

    def g(self, x):
        return np.pi / 2 * jnp.tan(self.theta) * _f64(x)

    def G(self, x):
        return np.pi / 4 * jnp.tan(self.theta) * _f64(x) ** 2

    def radius_scale(self):
        return jnp.asarray(1.0)  # a cone has no length: 1 m


class PowerLaw(Profile):
    """f = c rⁿ, g = κ(n) c xⁿ (3.70-3.72); n > 0, c (m^(1-n))."""

    n: Array = _param()
    c: Array = _param()

    def f(self, r):
        r = _f64(r)
        rs = jnp.where(r > 0, r, 1.0)
        return jnp.where(r > 0, self.c * rs**self.n, 0.0)

    def g(self, x):
        return kappa(self.n) * self.f(x)

    def G(self, x):
        return kappa(self.n) * _f64(x) * self.f(x) / (self.n + 1)

    def radius_scale(self):
        # the radius where f(r) = r; 1 m for near-conical exponents
        return jnp.where(jnp.abs(self.n - 1) < 0.25, 1.0, self.c ** (1 / (1 - self.n)))


class FlatPunch(Profile):
    """Cylindrical flat punch of radius `radius` (m): f = 0 up to the wall, g = 0 (3.36)."""

    radius: Array = _param()

    def f(self, r):
        return jnp.where(_f64(r) <= self.radius, 0.0, jnp.inf)

    def g(self, x):
        return jnp.zeros_like(_f64(x))

    def G(self, x):
        return jnp.zeros_like(_f64(x))

    def extent(self):
        return self.radius

    def radius_scale(self):
        return self.radius


class TruncatedCone(Profile):
    """Cone of slope theta (rad) with a flat tip of radius b (m) (3.83-3.86).

    f = (r - b) tan θ for r > b, g = x tan θ arccos(b/x) for x > b, both 0 below b.
    """

    b: Array = _param()
    theta: Array = _param()

    def f(self, r):
        return jnp.tan(self.theta) * jnp.maximum(_f64(r) - self.b, 0.0)

    def g(self, x):
        mask, xs, _, phi = _past(_f64(x), self.b)
        return jnp.where(mask, jnp.tan(self.theta) * xs * phi, 0.0)

    def G(self, x):
        mask, xs, _, phi = _past(_f64(x), self.b)
        return jnp.where(mask, jnp.tan(self.theta) / 2 * xs**2 * _p(phi), 0.0)

    def radius_scale(self):
        return self.b


class TruncatedParaboloid(Profile):
    """Paraboloid of radius R (m) cut flat at radius b (m) (3.91-3.93).

    f = (r² - b²)/(2R) for r > b, g = x sqrt(x² - b²)/R for x > b, both 0 below b.
    """

    b: Array = _param()
    R: Array = _param()

    def f(self, r):
        return jnp.maximum(_f64(r) ** 2 - self.b**2, 0.0) / (2 * self.R)

    def g(self, x):
        mask, xs, s, _ = _past(_f64(x), self.b)
        return jnp.where(mask, xs * s / self.R, 0.0)

    def G(self, x):
        mask, _, s, _ = _past(_f64(x), self.b)
        return jnp.where(mask, s**3 / (3 * self.R), 0.0)

    def radius_scale(self):
        return self.b


class CappedFlatPunch(Profile):
    """Flat punch of radius b (m) with a parabolic cap of radius R (m) (§3.5.10).

    f = r²/(2R) and g = x²/R for r, x <= b; vertical wall at b (extent b).
    """

    b: Array = _param()
    R: Array = _param()

    def f(self, r):
        r = _f64(r)
        return jnp.where(r <= self.b, r**2 / (2 * self.R), jnp.inf)

    def g(self, x):
        return _f64(x) ** 2 / self.R

    def G(self, x):
        return _f64(x) ** 3 / (3 * self.R)

    def extent(self):
        return self.b

    def radius_scale(self):
        return self.b


class CappedCone(Profile):
    """Cone of slope theta (rad) with a tangent parabolic cap up to radius b (m) (§3.5.11).

    Cap radius R = b / tan θ: f = r²/(2R) for r <= b, (r - b/2) tan θ beyond;
    g = x²/R for x <= b, x tan θ [(1 - sin φ)/cos φ + φ] with φ = arccos(b/x) beyond (3.109).
    """

    b: Array = _param()
    theta: Array = _param()

    def f(self, r):
        r = _f64(r)
        t = jnp.tan(self.theta)
        return jnp.where(r <= self.b, t * r**2 / (2 * self.b), t * (r - self.b / 2))

    def g(self, x):
        x = _f64(x)
        t = jnp.tan(self.theta)
        mask, xs, s, phi = _past(x, self.b)
        # (1 - sin φ)/cos φ = (x - s)/b = b/(x + s)
        return jnp.where(mask, t * xs * (self.b / (xs + s) + phi), t * x**2 / self.b)

    def G(self, x):
        x = _f64(x)
        t = jnp.tan(self.theta)
        mask, xs, s, phi = _past(x, self.b)
        cubes = self.b * (xs**2 + xs * s + s**2) / (xs + s)  # (x³ - s³)/b
        return jnp.where(mask, t * (cubes / 3 + xs**2 / 2 * _p(phi)), t * x**3 / (3 * self.b))

    def radius_scale(self):
        return self.b


class CappedParaboloid(Profile):
    """Paraboloid of radius R2 (m) with a tangent-continuous cap of larger radius R1 (m) up to b (m).

    f = r²/(2R1) + (r² - b²)₊/(2R*) with 1/R* = 1/R2 - 1/R1 (3.115);
    g = x²/R1 + x sqrt(x² - b²)/R* for x > b (3.118).
    """

    b: Array = _param()
    R1: Array = _param()
    R2: Array = _param()

    def _inv_rstar(self):
        return 1 / self.R2 - 1 / self.R1

    def f(self, r):
        r = _f64(r)
        return r**2 / (2 * self.R1) + jnp.maximum(r**2 - self.b**2, 0.0) * self._inv_rstar() / 2

    def g(self, x):
        x = _f64(x)
        mask, xs, s, _ = _past(x, self.b)
        return x**2 / self.R1 + jnp.where(mask, xs * s * self._inv_rstar(), 0.0)

    def G(self, x):
        x = _f64(x)
        mask, _, s, _ = _past(x, self.b)
        return x**3 / (3 * self.R1) + jnp.where(mask, s**3 * self._inv_rstar() / 3, 0.0)

    def radius_scale(self):
        return self.b


class RoundedFlatPunch(Profile):
    """Flat punch with a flat base of radius b (m) and edges rounded with radius R (m) (§3.5.13).

    f = (r - b)₊²/(2R); g = x²/R (sin φ - φ cos φ) with φ = arccos(b/x) for x > b (3.127).
    """

    b: Array = _param()
    R: Array = _param()

    def f(self, r):
        return jnp.maximum(_f64(r) - self.b, 0.0) ** 2 / (2 * self.R)

    def g(self, x):
        mask, xs, _, phi = _past(_f64(x), self.b)
        return jnp.where(mask, xs**2 / self.R * _q(phi), 0.0)

    def G(self, x):
        mask, xs, _, phi = _past(_f64(x), self.b)
        return jnp.where(mask, xs**3 / self.R * _m(phi), 0.0)

    def radius_scale(self):
        return self.b


class WavyParaboloid(Profile):
    """Paraboloid with periodic roughness (3.132): f = r²/(2R) + h (1 - cos(2π r/λ)).

    R (m), amplitude h (m), wavelength λ (m). g = x²/R + (π² h x/λ) H0(2π x/λ) (3.136) and
    G = x³/(3R) + (π/2) h x H1(2π x/λ) with the Struve functions H0, H1.
    """

    R: Array = _param()
    amplitude: Array = _param()
    wavelength: Array = _param()

    def f(self, r):
        r = _f64(r)
        return r**2 / (2 * self.R) + self.amplitude * (1 - jnp.cos(2 * np.pi * r / self.wavelength))

    def g(self, x):
        x = _f64(x)
        h0, _ = _struve01(2 * np.pi * x / self.wavelength)
        return x**2 / self.R + np.pi**2 * self.amplitude * x / self.wavelength * h0

    def G(self, x):
        x = _f64(x)
        _, h1 = _struve01(2 * np.pi * x / self.wavelength)
        return x**3 / (3 * self.R) + np.pi / 2 * self.amplitude * x * h1

    def radius_scale(self):
        return self.R


_AGM_STEPS = 12  # the arithmetic-geometric mean converges quadratically: ~1e-16 at k' ~ 1e-16


def ellipe(k: ArrayLike) -> Array:
    """Complete elliptic integral of the second kind E(k) = ∫_0^{π/2} √(1 − k² sin²φ) dφ (3.62),
    modulus k in [0, 1], by the arithmetic-geometric mean; differentiable for k < 1."""
    k = _f64(k)
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


class ConstantStress(Profile):
    """The punch of radius a (m) whose whole face carries the uniform tensile stress σ0 (Pa)
    against a half-space of modulus E* (Pa) (§3.5.6, Gao and Yao):

    f = (σ0 a/E*)[(4/π) E(r/a) − 2] for r <= a (3.61), a concave face (f <= 0: the rim stands
    out); wall at a (extent a). Its MDR transform is the 1-D line load of a uniform stress,
    g = (2σ0/E*)(√(a² − x²) − a), and G = (2σ0/E*)[(x√(a² − x²) + a² arcsin(x/a))/2 − a x].
    At d = −2σ0 a/E* every spring carries E*(d − g) ∝ √(a² − x²): the stress is σ0 everywhere
    and F = −π σ0 a² (3.63).
    """

    radius: Array = _param()
    stress: Array = _param()
    E_star: Array = _param()

    def _depth(self):
        return 2 * self.stress / self.E_star

    def f(self, r):
        r = _f64(r)
        inside = r <= self.radius
        k = jnp.where(inside, r / self.radius, 0.0)
        face = self.stress * self.radius / self.E_star * (4 / np.pi * ellipe(k) - 2)
        return jnp.where(inside, face, jnp.inf)

    def g(self, x):
        x = _f64(x)
        rest = jnp.sqrt(jnp.maximum((self.radius - x) * (self.radius + x), 0.0))
        return self._depth() * (rest - self.radius)

    def G(self, x):
        x = _f64(x)
        rest = jnp.sqrt(jnp.maximum((self.radius - x) * (self.radius + x), 0.0))
        angle = jnp.arcsin(jnp.clip(x / self.radius, -1.0, 1.0))
        return self._depth() * (0.5 * (x * rest + self.radius**2 * angle) - self.radius * x)

    def extent(self):
        return self.radius

    def radius_scale(self):
        return self.radius


class Tabulated(Profile):
    """Piecewise-linear f through the points (r_i, f_i) (m), r_0 = 0, f_0 = 0, r increasing.

    Beyond the last point f continues with the last slope. g and G are exact for this f: with
    the slope jumps Δs_j at r_j, g = Σ_j Δs_j x arccos(r_j/x) and
    G = Σ_j Δs_j x²/2 (φ_j - sin φ_j cos φ_j), φ_j = arccos(r_j/x), over r_j < x
    (a sum of truncated cones). Cost O(len(r)) per evaluation.
    """

    r_table: Array
    f_table: Array

    def __init__(self, r: ArrayLike, f: ArrayLike):
        self.r_table = _f64(r)
        self.f_table = _f64(f)

    def _knots(self):
        slope = jnp.diff(self.f_table, axis=-1) / jnp.diff(self.r_table, axis=-1)
        jumps = jnp.diff(slope, axis=-1, prepend=0.0)
        return self.r_table[..., :-1], jumps

    def f(self, r):
        knots, jumps = self._knots()
        return jnp.sum(jumps * jnp.maximum(_f64(r)[..., None] - knots, 0.0), axis=-1)

    def g(self, x):
        knots, jumps = self._knots()
        mask, xs, _, phi = _past(_f64(x)[..., None], knots)
        return jnp.sum(jnp.where(mask, jumps * xs * phi, 0.0), axis=-1)

    def G(self, x):
        knots, jumps = self._knots()
        mask, xs, _, phi = _past(_f64(x)[..., None], knots)
        return jnp.sum(jnp.where(mask, jumps * xs**2 / 2 * _p(phi), 0.0), axis=-1)

    def radius_scale(self):
        return self.r_table[..., -1]
