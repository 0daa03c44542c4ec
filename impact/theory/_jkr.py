"""JKR equilibrium curves d(a), F(a) of the power law and the paraboloid under the rule of Heß (3.26),
dimensional and normalized by the critical values (§3.5.3, §3.5.7)."""

import jax.numpy as jnp

from .._core.runtime import float64
from ..profiles import Scalars, kappa


@float64
def detach_length(a: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Rule of Heß (3.26): Δl(a) = √(2π a Δγ / E*) [m]."""
    return jnp.sqrt(2 * jnp.pi * a * work_of_adhesion / E_star)


@float64
def power_law_indentation(a: Scalars, n: Scalars, c: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """JKR indentation [m] at contact radius a [m] for f = c rⁿ (3.71):
    `d = κ(n) c aⁿ − √(2π a Δγ / E*)`. ``c`` is in m^(1−n)."""
    return kappa(n) * c * a**n - detach_length(a, E_star, work_of_adhesion)


@float64
def power_law_force(a: Scalars, n: Scalars, c: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """JKR normal force [N] at contact radius a [m] for f = c rⁿ (3.71):
    `F = 2E* n/(n+1) κ(n) c a^(n+1) − √(8π a³ E* Δγ)`."""
    return 2 * E_star * n / (n + 1) * kappa(n) * c * a ** (n + 1) - jnp.sqrt(
        8 * jnp.pi * a**3 * E_star * work_of_adhesion
    )


@float64
def power_law_normalized_indentation(a_hat: Scalars, n: Scalars, xi: Scalars):
    """d/|d_c| against a/a_c, normalized with the critical values of criterion ξ (3.78):
    d̂ = ξ âⁿ/|ξ − 2n| − 2n √â/|ξ − 2n|. Undefined where d_c = 0 (ξ = 2n, e.g. n = 1.5, ξ = 3)."""
    return (xi * a_hat**n - 2 * n * jnp.sqrt(a_hat)) / jnp.abs(xi - 2 * n)


@float64
def power_law_normalized_force(a_hat: Scalars, n: Scalars, xi: Scalars):
    """F/|F_c| against a/a_c, normalized with the critical values of criterion ξ (3.78):
    F̂ = (ξ â^(n+1) − (2n + 2) â^(3/2)) / |ξ − 2n − 2|."""
    return (xi * a_hat ** (n + 1) - (2 * n + 2) * a_hat**1.5) / jnp.abs(xi - 2 * n - 2)


@float64
def jkr_indentation(a: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """JKR indentation [m] of a paraboloid f = r²/(2R) at contact radius a [m] (3.44):
    `d = a²/R − √(2π a Δγ / E*)`."""
    return a**2 / R - detach_length(a, E_star, work_of_adhesion)


@float64
def jkr_force(a: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """JKR normal force [N] of a paraboloid at contact radius a [m] (3.44):
    `F = 4E* a³/(3R) − √(8π a³ E* Δγ)`."""
    return 4 * E_star * a**3 / (3 * R) - jnp.sqrt(8 * jnp.pi * a**3 * E_star * work_of_adhesion)


@float64
def jkr_normalized_indentation(a_hat: Scalars):
    """Universal JKR curve d̂ = 3â² − 4√â (3.49); â, d̂ normalized by force-control a_c, |d_c|."""
    return 3 * a_hat**2 - 4 * jnp.sqrt(a_hat)


@float64
def jkr_normalized_force(a_hat: Scalars):
    """Universal JKR curve F̂ = â³ − 2â^(3/2) (3.49); F̂ = F/|F_c| with force-control F_c."""
    return a_hat**3 - 2 * a_hat**1.5
