"""Bodies pieced together at a radius b (§3.5.8–3.5.13): a flat tip (truncated cone and paraboloid), a
parabolic cap (on a flat punch, a cone, a paraboloid) or a rounded edge (flat punch)."""

import jax.numpy as jnp

from ._base import FloatParameter, Profile, as_float, float_field
from ._classic import paraboloid_G, paraboloid_g
from ._functions import angle_minus_sin_cos, beyond_radius, rounded_edge_G, sin_minus_angle_cos


class TruncatedCone(Profile):
    """Cone of slope theta (rad) with a flat tip of radius b (m) (3.83-3.86).

    f = (r - b) tan θ for r > b, g = x tan θ arccos(b/x) for x > b, both 0 below b.
    """

    b: FloatParameter = float_field()
    theta: FloatParameter = float_field()

    def f(self, r):
        return jnp.tan(self.theta) * jnp.maximum(as_float(r) - self.b, 0.0)

    def g(self, x):
        mask, xs, _, phi = beyond_radius(as_float(x), self.b)
        return jnp.where(mask, jnp.tan(self.theta) * xs * phi, 0.0)

    def G(self, x):
        mask, xs, _, phi = beyond_radius(as_float(x), self.b)
        return jnp.where(mask, jnp.tan(self.theta) / 2 * xs**2 * angle_minus_sin_cos(phi), 0.0)

    def radius_scale(self):
        return self.b


class TruncatedParaboloid(Profile):
    """Paraboloid of radius R (m) cut flat at radius b (m) (3.91-3.93).

    f = (r² - b²)/(2R) for r > b, g = x sqrt(x² - b²)/R for x > b, both 0 below b.
    """

    b: FloatParameter = float_field()
    R: FloatParameter = float_field()

    def f(self, r):
        return jnp.maximum(as_float(r) ** 2 - self.b**2, 0.0) / (2 * self.R)

    def g(self, x):
        mask, xs, s, _ = beyond_radius(as_float(x), self.b)
        return jnp.where(mask, xs * s / self.R, 0.0)

    def G(self, x):
        mask, _, s, _ = beyond_radius(as_float(x), self.b)
        return jnp.where(mask, s**3 / (3 * self.R), 0.0)

    def radius_scale(self):
        return self.b


class CappedFlatPunch(Profile):
    """Flat punch of radius b (m) with a parabolic cap of radius R (m) (§3.5.10).

    f = r²/(2R) and g = x²/R for r, x <= b; vertical wall at b (extent b).
    """

    b: FloatParameter = float_field()
    R: FloatParameter = float_field()

    def f(self, r):
        r = as_float(r)
        return jnp.where(r <= self.b, r**2 / (2 * self.R), jnp.inf)

    def g(self, x):
        return paraboloid_g(x, self.R)

    def G(self, x):
        return paraboloid_G(x, self.R)

    def extent(self):
        return self.b

    def radius_scale(self):
        return self.b


class CappedCone(Profile):
    """Cone of slope theta (rad) with a tangent parabolic cap up to radius b (m) (§3.5.11).

    Cap radius R = b / tan θ: f = r²/(2R) for r <= b, (r - b/2) tan θ beyond;
    g = x²/R for x <= b, x tan θ [(1 - sin φ)/cos φ + φ] with φ = arccos(b/x) beyond (3.109).
    """

    b: FloatParameter = float_field()
    theta: FloatParameter = float_field()

    def f(self, r):
        r = as_float(r)
        t = jnp.tan(self.theta)
        return jnp.where(r <= self.b, t * r**2 / (2 * self.b), t * (r - self.b / 2))

    def g(self, x):
        x = as_float(x)
        t = jnp.tan(self.theta)
        mask, xs, s, phi = beyond_radius(x, self.b)
        # (1 - sin φ)/cos φ = (x - s)/b = b/(x + s)
        return jnp.where(mask, t * xs * (self.b / (xs + s) + phi), t * x**2 / self.b)

    def G(self, x):
        x = as_float(x)
        t = jnp.tan(self.theta)
        mask, xs, s, phi = beyond_radius(x, self.b)
        cubes = self.b * (xs**2 + xs * s + s**2) / (xs + s)  # (x³ - s³)/b
        return jnp.where(mask, t * (cubes / 3 + xs**2 / 2 * angle_minus_sin_cos(phi)), t * x**3 / (3 * self.b))

    def radius_scale(self):
        return self.b


class CappedParaboloid(Profile):
    """Paraboloid of radius R2 (m) with a tangent-continuous cap of larger radius R1 (m) up to b (m).

    `f = r²/(2R1) + (r² - b²)₊/(2R*)` with `1/R* = 1/R2 - 1/R1` (3.115);
    `g = x²/R1 + x sqrt(x² - b²)/R*` for x > b (3.118).
    """

    b: FloatParameter = float_field()
    R1: FloatParameter = float_field()
    R2: FloatParameter = float_field()

    def _inv_rstar(self):
        return 1 / self.R2 - 1 / self.R1

    def f(self, r):
        r = as_float(r)
        return r**2 / (2 * self.R1) + jnp.maximum(r**2 - self.b**2, 0.0) * self._inv_rstar() / 2

    def g(self, x):
        x = as_float(x)
        mask, xs, s, _ = beyond_radius(x, self.b)
        return x**2 / self.R1 + jnp.where(mask, xs * s * self._inv_rstar(), 0.0)

    def G(self, x):
        x = as_float(x)
        mask, _, s, _ = beyond_radius(x, self.b)
        return x**3 / (3 * self.R1) + jnp.where(mask, s**3 * self._inv_rstar() / 3, 0.0)

    def radius_scale(self):
        return self.b


class RoundedFlatPunch(Profile):
    """Flat punch with a flat base of radius b (m) and edges rounded with radius R (m) (§3.5.13).

    f = (r - b)₊²/(2R); g = x²/R (sin φ - φ cos φ) with φ = arccos(b/x) for x > b (3.127).
    """

    b: FloatParameter = float_field()
    R: FloatParameter = float_field()

    def f(self, r):
        return jnp.maximum(as_float(r) - self.b, 0.0) ** 2 / (2 * self.R)

    def g(self, x):
        mask, xs, _, phi = beyond_radius(as_float(x), self.b)
        return jnp.where(mask, xs**2 / self.R * sin_minus_angle_cos(phi), 0.0)

    def G(self, x):
        mask, xs, _, phi = beyond_radius(as_float(x), self.b)
        return jnp.where(mask, xs**3 / self.R * rounded_edge_G(phi), 0.0)

    def radius_scale(self):
        return self.b
