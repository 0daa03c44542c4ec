"""The classical bodies of §3.5.1–3.5.7: paraboloid, sphere, ellipsoid, cone, power law and flat punch."""

import jax.numpy as jnp
import numpy as np
from jaxtyping import Array

from ._base import FloatParameter, Profile, as_float, float_field, kappa
from ._functions import artanh_rest


def paraboloid_g(x, R) -> Array:
    """The MDR profile of a paraboloid of radius R (m), (3.44): g = x²/R."""
    return as_float(x) ** 2 / R


def paraboloid_G(x, R) -> Array:
    """∫₀ˣ g dx' of a paraboloid: x³/(3R)."""
    return as_float(x) ** 3 / (3 * R)


class Paraboloid(Profile):
    """f = r²/(2R), g = x²/R (3.44); R: radius of curvature at the tip (m)."""

    R: FloatParameter = float_field()

    def f(self, r):
        return as_float(r) ** 2 / (2 * self.R)

    def g(self, x):
        return paraboloid_g(x, self.R)

    def G(self, x):
        return paraboloid_G(x, self.R)

    def radius_scale(self):
        return self.R

    def power_form(self):
        return 1 / self.R, as_float(2.0)


def _spheroid_g(x: Array, k: Array) -> Array:
    """x artanh(kx): g of a sphere of radius 1/k (m)."""
    return x * jnp.arctanh(k * x)


def _spheroid_G(x: Array, k: Array) -> Array:
    """∫_0^x s artanh(ks) ds = [kx - (1 - k²x²) artanh(kx)] / (2k²) (m²)."""
    return artanh_rest(k * x) / (2 * k**2)


def _spheroid_f(r: Array, k: Array) -> Array:
    """(1 - sqrt(1 - k²r²))/k: f of a sphere of radius 1/k (m); inf beyond its equator."""
    inside = k * r <= 1
    u2 = jnp.where(inside, (k * r) ** 2, 0.0)
    return jnp.where(inside, u2 / (k * (1 + jnp.sqrt(1 - u2))), jnp.inf)


class Sphere(Profile):
    """Sphere f = R - sqrt(R² - r²), g = x artanh(x/R) (3.52); R: radius (m); extent R."""

    R: FloatParameter = float_field()

    def f(self, r):
        return _spheroid_f(as_float(r), 1 / self.R)

    def g(self, x):
        return _spheroid_g(as_float(x), 1 / self.R)

    def G(self, x):
        return _spheroid_G(as_float(x), 1 / self.R)

    def extent(self):
        return self.R

    def radius_scale(self):
        return self.R


class Ellipsoid(Profile):
    """Ellipsoid of revolution f = R(1 - sqrt(1 - k²r²)) (3.58): R (m), k (1/m); extent 1/k.

    f is kR times a sphere of radius 1/k, so g = kR x artanh(kx) (the d(a) of (3.57) lacks
    this factor kR; its force has it).
    """

    R: FloatParameter = float_field()
    k: FloatParameter = float_field()

    def f(self, r):
        return self.k * self.R * _spheroid_f(as_float(r), self.k)

    def g(self, x):
        return self.k * self.R * _spheroid_g(as_float(x), self.k)

    def G(self, x):
        return self.k * self.R * _spheroid_G(as_float(x), self.k)

    def extent(self):
        return 1 / self.k

    def radius_scale(self):
        return 1 / self.k


class Cone(Profile):
    """Cone f = r tan θ, g = (π/2) tan θ x (3.38); theta: slope angle against the plane (rad)."""

    theta: FloatParameter = float_field()

    def f(self, r):
        return as_float(r) * jnp.tan(self.theta)

    def g(self, x):
        return np.pi / 2 * jnp.tan(self.theta) * as_float(x)

    def G(self, x):
        return np.pi / 4 * jnp.tan(self.theta) * as_float(x) ** 2

    def radius_scale(self):
        return jnp.asarray(1.0)  # a cone has no length: 1 m

    def power_form(self):
        return np.pi / 2 * jnp.tan(self.theta), as_float(1.0)


class PowerLaw(Profile):
    """f = c rⁿ, g = κ(n) c xⁿ (3.70-3.72); n > 0, c (m^(1-n))."""

    n: FloatParameter = float_field()
    c: FloatParameter = float_field()

    def f(self, r):
        r = as_float(r)
        rs = jnp.where(r > 0, r, 1.0)
        return jnp.where(r > 0, self.c * rs**self.n, 0.0)

    def g(self, x):
        return kappa(self.n) * self.f(x)

    def G(self, x):
        return kappa(self.n) * as_float(x) * self.f(x) / (self.n + 1)

    def radius_scale(self):
        # the radius where f(r) = r; 1 m for near-conical exponents
        return jnp.where(jnp.abs(self.n - 1) < 0.25, 1.0, self.c ** (1 / (1 - self.n)))

    def power_form(self):
        return kappa(self.n) * self.c, self.n


class FlatPunch(Profile):
    """Cylindrical flat punch of radius `radius` (m): f = 0 up to the wall, g = 0 (3.36)."""

    radius: FloatParameter = float_field()

    def f(self, r):
        return jnp.where(as_float(r) <= self.radius, 0.0, jnp.inf)

    def g(self, x):
        return jnp.zeros_like(as_float(x))

    def G(self, x):
        return jnp.zeros_like(as_float(x))

    def extent(self):
        return self.radius

    def radius_scale(self):
        return self.radius
