"""The wavy paraboloid (§3.5.14, in complete contact) and the profile of constant adhesive stress
(§3.5.6), with Kendall's flat punch against the optimal profile (3.69)."""

import jax.numpy as jnp

from .._core.runtime import float64
from ..profiles import Scalars, ellipe
from ..profiles._base import as_float
from ..profiles._functions import struve_h, struve_h0_h1
from ._jkr import detach_length


@float64
def wavy_paraboloid_indentation(
    a: Scalars, R: Scalars, amplitude: Scalars, wavelength: Scalars, E_star: Scalars, work_of_adhesion: Scalars
):
    """JKR indentation [m] of the wavy paraboloid f = r²/(2R) + h(1 − cos(2πr/λ)) (3.134):
    `d = a²/R + (π²ha/λ) H0(2πa/λ) − √(2πaΔγ/E*)`, H0 the Struve function."""
    h0 = struve_h(2 * jnp.pi * a / wavelength, 0)
    return a**2 / R + jnp.pi**2 * amplitude * a / wavelength * h0 - detach_length(a, E_star, work_of_adhesion)


@float64
def wavy_paraboloid_force(
    a: Scalars, R: Scalars, amplitude: Scalars, wavelength: Scalars, E_star: Scalars, work_of_adhesion: Scalars
):
    """JKR force [N] of the wavy paraboloid (3.134):
    `F = 4E*a³/(3R) + E*πah[(2πa/λ)H0(2πa/λ) − H1(2πa/λ)] − √(8πa³E*Δγ)`."""
    z = 2 * jnp.pi * a / wavelength
    h0, h1 = struve_h0_h1(z)
    return (
        4 * E_star * a**3 / (3 * R)
        + E_star * jnp.pi * a * amplitude * (z * h0 - h1)
        - jnp.sqrt(8 * jnp.pi * a**3 * E_star * work_of_adhesion)
    )


@float64
def wavy_paraboloid_normalized(a_hat: Scalars, h_hat: Scalars, gamma_bar: Scalars):
    """The wavy paraboloid's curves in the units of (3.137), â = a/λ, d̂ = dR/λ², ĥ = hR/λ²,
    F̂ = 2F/(3πRΔγ), `Δγ̄ = 2πΔγR²/(E*λ³)`, (3.138):
    `d̂ = â² + π²ĥâ H0(2πâ) − √(Δγ̄ â)`,
    `F̂ = 16â³/(9Δγ̄) + (4π/3)(ĥâ/Δγ̄)[2πâ H0(2πâ) − H1(2πâ)] − (8/3)√(â³/Δγ̄)`.
    Returns (d̂, F̂). (Δγ̄ = 100, ĥ = 0.5 puts the lowest force at F̂ = −1.32, Fig. 3.27.)"""
    z = 2 * jnp.pi * a_hat
    h0, h1 = struve_h0_h1(z)
    d_hat = a_hat**2 + jnp.pi**2 * h_hat * a_hat * h0 - jnp.sqrt(gamma_bar * a_hat)
    F_hat = (
        16 * a_hat**3 / (9 * gamma_bar)
        + 4 * jnp.pi / 3 * h_hat * a_hat / gamma_bar * (z * h0 - h1)
        - 8 / 3 * jnp.sqrt(a_hat**3 / gamma_bar)
    )
    return d_hat, F_hat


@float64
def constant_stress_profile(r: Scalars, radius: Scalars, stress: Scalars, E_star: Scalars):
    """The profile that carries a uniform tensile stress σ0 over the whole contact of radius a
    (3.61): `f = (σ0 a/E*)[(4/π) E(r/a) − 2]` for r ≤ a, E the complete elliptic integral (3.62)."""
    return stress * radius / E_star * (4 / jnp.pi * ellipe(r / radius) - 2)


@float64
def constant_stress_uniform_state(radius: Scalars, stress: Scalars, E_star: Scalars):
    """(d [m], F [N]) where the profile (3.61) in full contact carries σ0 everywhere:
    `d = −2σ0 a/E*` (3.60 at r = 0) and `F = −πσ0a²` (3.63; tensile, hence negative here)."""
    return -2 * stress * radius / E_star, -jnp.pi * stress * radius**2


@float64
def constant_stress_pull_off(radius: Scalars, stress: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Pull-off of the profile (3.61) under the rule of Heß (ours, not in the chapter): its MDR
    transform `g = (2σ0/E*)(√(a² − x²) − a)` leaves only the wall as a critical radius, so under
    either control `a_c = a`, `d_c = g(a) − Δl(a) = −2σ0a/E* − √(2πaΔγ/E*)` and
    `F_c = −(πσ0a² + √(8πa³E*Δγ))`: the uniform stress (3.63) plus Kendall's punch (3.66).
    Returns (a_c, d_c, F_c)."""
    radius = as_float(radius)
    d_c = -2 * stress * radius / E_star - detach_length(radius, E_star, work_of_adhesion)
    F_c = -jnp.pi * stress * radius**2 - jnp.sqrt(8 * jnp.pi * radius**3 * E_star * work_of_adhesion)
    return radius, d_c, F_c


@float64
def kendall_to_optimal_ratio(radius: Scalars, stress: Scalars, E_star: Scalars, range_: Scalars):
    """`F_Kendall/F_opt = √(8E*h/(πσ0 a))` (3.69) with Δγ = σ0 h (3.68): Kendall's flat punch (3.66)
    against the optimal profile (3.67) of the same radius a; `range_` is h [m]."""
    return jnp.sqrt(8 * E_star * range_ / (jnp.pi * stress * radius))
