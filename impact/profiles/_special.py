"""Bodies evaluated through a special function or a sum: the wavy paraboloid (§3.5.14, Struve
functions), the constant-stress punch (§3.5.6, elliptic integral) and a tabulated piecewise-linear
profile (a sum of truncated cones)."""

import jax.numpy as jnp
import numpy as np
from jaxtyping import Array, ArrayLike

from ._base import FloatParameter, Profile, as_float, float_field
from ._functions import angle_minus_sin_cos, beyond_radius, ellipe, struve_h


class WavyParaboloid(Profile):
    """Paraboloid with periodic roughness (3.132): f = r²/(2R) + h (1 - cos(2π r/λ)).

    R (m), amplitude h (m), wavelength λ (m). g = x²/R + (π² h x/λ) H0(2π x/λ) (3.136) and
    G = x³/(3R) + (π/2) h x H1(2π x/λ) with the Struve functions H0, H1.
    """

    R: FloatParameter = float_field()
    amplitude: FloatParameter = float_field()
    wavelength: FloatParameter = float_field()

    def f(self, r):
        r = as_float(r)
        return r**2 / (2 * self.R) + self.amplitude * (1 - jnp.cos(2 * np.pi * r / self.wavelength))

    def g(self, x):
        x = as_float(x)
        h0 = struve_h(2 * np.pi * x / self.wavelength, 0)
        return x**2 / self.R + np.pi**2 * self.amplitude * x / self.wavelength * h0

    def G(self, x):
        x = as_float(x)
        h1 = struve_h(2 * np.pi * x / self.wavelength, 1)
        return x**3 / (3 * self.R) + np.pi / 2 * self.amplitude * x * h1

    def radius_scale(self):
        return self.R


class ConstantStress(Profile):
    """The punch of radius a (m) whose whole face carries the uniform tensile stress σ0 (Pa)
    against a half-space of modulus `E*` (Pa) (§3.5.6, Gao and Yao):

    `f = (σ0 a/E*)[(4/π) E(r/a) − 2]` for r <= a (3.61), a concave face (f <= 0: the rim stands
    out); wall at a (extent a). Its MDR transform is the 1-D line load of a uniform stress,
    `g = (2σ0/E*)(√(a² − x²) − a)`, and `G = (2σ0/E*)[(x√(a² − x²) + a² arcsin(x/a))/2 − a x]`.
    At `d = −2σ0 a/E*` every spring carries `E*(d − g) ∝ √(a² − x²)`: the stress is σ0 everywhere
    and `F = −π σ0 a²` (3.63).
    """

    radius: FloatParameter = float_field()
    stress: FloatParameter = float_field()
    E_star: FloatParameter = float_field()

    def _depth(self):
        return 2 * self.stress / self.E_star

    def f(self, r):
        r = as_float(r)
        inside = r <= self.radius
        k = jnp.where(inside, r / self.radius, 0.0)
        face = self.stress * self.radius / self.E_star * (4 / np.pi * ellipe(k) - 2)
        return jnp.where(inside, face, jnp.inf)

    def g(self, x):
        x = as_float(x)
        rest = jnp.sqrt(jnp.maximum((self.radius - x) * (self.radius + x), 0.0))
        return self._depth() * (rest - self.radius)

    def G(self, x):
        x = as_float(x)
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
        self.r_table = as_float(r)
        self.f_table = as_float(f)

    def _knots(self):
        slope = jnp.diff(self.f_table, axis=-1) / jnp.diff(self.r_table, axis=-1)
        jumps = jnp.diff(slope, axis=-1, prepend=0.0)
        return self.r_table[..., :-1], jumps

    def f(self, r):
        knots, jumps = self._knots()
        return jnp.sum(jumps * jnp.maximum(as_float(r)[..., None] - knots, 0.0), axis=-1)

    def g(self, x):
        knots, jumps = self._knots()
        mask, xs, _, phi = beyond_radius(as_float(x)[..., None], knots)
        return jnp.sum(jnp.where(mask, jumps * xs * phi, 0.0), axis=-1)

    def G(self, x):
        knots, jumps = self._knots()
        mask, xs, _, phi = beyond_radius(as_float(x)[..., None], knots)
        return jnp.sum(jnp.where(mask, jumps * xs**2 / 2 * angle_minus_sin_cos(phi), 0.0), axis=-1)

    def radius_scale(self):
        return self.r_table[..., -1]
