"""Impacts: the kinetic energy an adhesive impact loses, its coefficient of restitution and sticking
velocity (reversible JKR law, separation at ξ = 1; (3.50)–(3.51), (3.81)–(3.82)), and the
non-adhesive (Hertz-type) impact of a power-law body."""

import jax
import jax.numpy as jnp
from jax.scipy.special import gammaln

from .._core.runtime import float64
from ..profiles import Scalars, kappa
from ..profiles._base import as_float


def _restitution(beta):
    """e = √(1 − β) for β < 1, else 0; gradient-safe at and beyond the sticking point."""
    below = beta < 1
    return jnp.where(below, jnp.sqrt(jnp.where(below, 1 - beta, 1.0)), 0.0)


@float64
def power_law_energy_loss(n: Scalars, c: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Kinetic energy [J] lost in one adhesive impact of f = c rⁿ, n > 1/2 (from (3.82)):
    `W = ½ [(πΔγ/2)^(2n+1) (E* n² c² κ²)^(−2)]^(1/(2n−1)) (8n − 4)/(2n² + 3n + 1)`
        · [n + (n + 1)(2n)^(4/(2n−1))].
    W = −∫ F dd along d(a) = g(a) − Δl(a) from the jump-in (d = 0, a₀) down to the
    displacement-controlled critical point; independent of the impact velocity."""
    p = 1 / (2 * n - 1)
    stiffness = E_star * (n * c * kappa(n)) ** 2
    scale = ((jnp.pi * work_of_adhesion / 2) ** (2 * n + 1) / stiffness**2) ** p
    shape = (8 * n - 4) / (2 * n**2 + 3 * n + 1) * (n + (n + 1) * (2 * n) ** (4 * p))
    return scale * shape / 2


@float64
def power_law_beta(
    velocity: Scalars, mass: Scalars, n: Scalars, c: Scalars, E_star: Scalars, work_of_adhesion: Scalars
):
    """β = W / (½ m v₀²) of (3.82) for f = c rⁿ (velocity [m/s], mass [kg])."""
    return 2 * power_law_energy_loss(n, c, E_star, work_of_adhesion) / (mass * velocity**2)


@float64
def power_law_restitution(
    velocity: Scalars, mass: Scalars, n: Scalars, c: Scalars, E_star: Scalars, work_of_adhesion: Scalars
):
    """Coefficient of restitution (3.81): e = √(1 − β) for β ≤ 1, 0 (capture) otherwise."""
    return _restitution(power_law_beta(velocity, mass, n, c, E_star, work_of_adhesion))


@float64
def power_law_sticking_velocity(mass: Scalars, n: Scalars, c: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Impact velocity [m/s] with β = 1: v_s = √(2W/m); slower bodies stick."""
    return jnp.sqrt(2 * power_law_energy_loss(n, c, E_star, work_of_adhesion) / mass)


@float64
def thornton_ning_energy_loss(R: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Kinetic energy [J] lost in the JKR impact of a paraboloid of radius R (from (3.51)):
    `W = (1/10) [R⁴ (πΔγ)⁵ / E*²]^(1/3) (1 + 864^(1/3))`."""
    return jnp.cbrt(R**4 * (jnp.pi * work_of_adhesion) ** 5 / E_star**2) * (1 + jnp.cbrt(864.0)) / 10


@float64
def thornton_ning_beta(velocity: Scalars, mass: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Thornton–Ning β (3.51) = W / (½ m v₀²)."""
    return 2 * thornton_ning_energy_loss(R, E_star, work_of_adhesion) / (mass * velocity**2)


@float64
def thornton_ning_restitution(velocity: Scalars, mass: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Thornton–Ning restitution (3.50): e = √(1 − β) for β ≤ 1, 0 otherwise."""
    return _restitution(thornton_ning_beta(velocity, mass, R, E_star, work_of_adhesion))


@float64
def thornton_ning_sticking_velocity(mass: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Impact velocity [m/s] with β = 1 for the paraboloid."""
    return jnp.sqrt(2 * thornton_ning_energy_loss(R, E_star, work_of_adhesion) / mass)


def _jkr_units(R, E_star, work_of_adhesion):
    """JKR units of the paraboloid at the jump-in: a0 = (2πΔγR²/E*)^(1/3) [m], a0²/R [m] and
    the energy E*·a0·(a0²/R)² [J]; in them d = a² − √a, F = (4/3)a³ − 2a^(3/2) (3.44)."""
    a0 = jnp.cbrt(2.0 * jnp.pi * work_of_adhesion * R**2 / E_star)
    depth = a0**2 / R
    return a0, depth, E_star * a0 * depth**2


def _jkr_work(a):
    """∫ F dd along the JKR branch up to contact radius a, in JKR units (an antiderivative of
    F(a)·d'(a) with F = (4/3)a³ − 2a^(3/2), d' = 2a − a^(−1/2)/2)."""
    return 8.0 / 15.0 * a**5 - 4.0 / 3.0 * a**3.5 + 0.5 * a**2


@float64
def thornton_ning_max_force(velocity: Scalars, mass: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Largest compressive force [N] of the Thornton–Ning impact (reversible JKR law, jump-in at
    first touch): the energy balance ½ m v₀² = ∫ F dd along the JKR branch (3.44) from the
    jump-in (a = a0, d = 0) to the turning point a_m, then F_max = F(a_m).

    In JKR units the balance reads `w(a_m) − w(1) = ½ m v₀²/(E* a0 (a0²/R)²)`, with w convex and
    increasing beyond F = 0; Newton's method from above converges monotonically. Its iterations
    run without gradient and one differentiable step follows (exact derivatives)."""
    a0, depth, energy = _jkr_units(R, E_star, work_of_adhesion)
    target = _jkr_work(1.0) + 0.5 * mass * velocity**2 / energy

    def newton(a):
        force = 4.0 / 3.0 * a**3 - 2.0 * a**1.5
        return a - (_jkr_work(a) - target) / (force * (2.0 * a - 0.5 / jnp.sqrt(a)))

    start = 2.0 + (15.0 / 8.0 * (target + 1.0)) ** 0.2
    a_m = newton(jax.lax.stop_gradient(jax.lax.fori_loop(0, 80, lambda _, a: newton(a), start)))
    return (4.0 / 3.0 * a_m**3 - 2.0 * a_m**1.5) * E_star * a0 * depth


@float64
def force_release_energy_loss(R: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Kinetic energy [J] a paraboloid loses in a reversible JKR impact (jump-in at the touch)
    whose contact is released at the force-controlled pull-off, F = −(3/2)πRΔγ at
    a = (3/4)^(2/3) a0, instead of following the JKR branch to its displacement-controlled end
    a = 4^(−2/3) a0 as a free body does: the JKR law of discrete-element codes that cut the branch
    there (LAMMPS's granular jkr). In JKR units (`_jkr_units`) W = w((3/4)^(2/3)) − w(1), with w
    the work along the branch (3.44); 0.4931 of `thornton_ning_energy_loss` at any speed."""
    _, _, energy = _jkr_units(R, E_star, work_of_adhesion)
    return (_jkr_work(0.75 ** (2.0 / 3.0)) - _jkr_work(1.0)) * energy


@float64
def attach_on_touch_energy_loss(
    velocity: Scalars, mass: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars
):
    """Energy lost [J] by a paraboloid that attaches on touch (Δγa = 0) and detaches by Heß.

    Our own reference (not in the chapter). In JKR units (lengths `a0 = (2πΔγR²/E*)^(1/3)`
    and `a0²/R`, energy `E*·a0·(a0²/R)²`) the loop is: Hertzian loading `d = a²` up to a_m with
    `(8/15)·a_m⁵ = ½mv0²`; a hold at a_m, `F = 2(a_m·d − a_m³/3)`, down to `d = a_m² − √a_m`; the
    JKR branch `d = a² − √a` down to `a* = 4^(−2/3)` (skipped when `a_m < a*`, which then
    separates at once). Each piece integrates in closed form.
    """
    a0 = (2.0 * jnp.pi * work_of_adhesion * R**2 / E_star) ** (1.0 / 3.0)
    depth = a0**2 / R
    energy_unit = E_star * a0 * depth**2
    kinetic = 0.5 * mass * velocity**2 / energy_unit
    a_m = (15.0 * kinetic / 8.0) ** 0.2
    d_m = a_m**2
    d_h = a_m**2 - jnp.sqrt(a_m)
    loading = 8.0 / 15.0 * a_m**5
    hold = a_m * (d_m**2 - d_h**2) - 2.0 / 3.0 * a_m**3 * (d_m - d_h)
    a_star = 4.0 ** (-2.0 / 3.0)

    def branch(a):  # ∫ F(a)·h'(a) da with F = (4/3)a³ − 2a^(3/2), h' = 2a − a^(−1/2)/2
        return 8.0 / 15.0 * a**5 - 4.0 / 3.0 * a**3.5 + 0.5 * a**2

    unloading = jnp.where(a_m > a_star, branch(a_m) - branch(a_star), 0.0)
    return (loading - hold - unloading) * energy_unit


@float64
def attach_on_touch_restitution(
    velocity: Scalars, mass: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars
):
    """Restitution of the paraboloid with attach on touch (Δγa = 0); 0 when captured."""
    kinetic = 0.5 * mass * velocity**2
    return _restitution(attach_on_touch_energy_loss(velocity, mass, R, E_star, work_of_adhesion) / kinetic)


def _power_law_stiffness(n, c, E_star):
    """k in F = k d^((n+1)/n): with a = (d/K)^(1/n), F = 2E* n/(n+1) K a^(n+1), K = κ c."""
    return 2 * E_star * n / (n + 1) * (kappa(n) * c) ** (-1 / n)


@float64
def power_law_hertz_max_indentation(velocity: Scalars, mass: Scalars, n: Scalars, c: Scalars, E_star: Scalars):
    """Maximum indentation [m] of a non-adhesive impact of f = c rⁿ:
    ½ m v₀² = k n/(2n+1) d_max^((2n+1)/n)."""
    k = _power_law_stiffness(n, c, E_star)
    return (mass * velocity**2 * (2 * n + 1) / (2 * n * k)) ** (n / (2 * n + 1))


@float64
def power_law_hertz_max_force(velocity: Scalars, mass: Scalars, n: Scalars, c: Scalars, E_star: Scalars):
    """Maximum force [N] of a non-adhesive impact of f = c rⁿ: k d_max^((n+1)/n)."""
    d_max = power_law_hertz_max_indentation(velocity, mass, n, c, E_star)
    return _power_law_stiffness(n, c, E_star) * d_max ** ((n + 1) / n)


@float64
def power_law_hertz_contact_time(velocity: Scalars, mass: Scalars, n: Scalars, c: Scalars, E_star: Scalars):
    """Contact time [s] of a non-adhesive impact of f = c rⁿ, exact:
    t_c = 2 d_max/v₀ ∫₀¹ dx/√(1 − x^p), p = (2n+1)/n, with
    ∫₀¹ dx/√(1 − x^p) = √π Γ(1 + 1/p) / Γ(1/p + 1/2)."""
    p = (2 * n + 1) / as_float(n)
    integral = jnp.sqrt(jnp.pi) * jnp.exp(gammaln(1 + 1 / p) - gammaln(1 / p + 0.5))
    return 2 * power_law_hertz_max_indentation(velocity, mass, n, c, E_star) / velocity * integral


@float64
def hertz_max_indentation(velocity: Scalars, mass: Scalars, R: Scalars, E_star: Scalars):
    """Hertz impact of a paraboloid: `d_max = (15 m v₀² / (16 E* √R))^(2/5)` [m]."""
    return power_law_hertz_max_indentation(velocity, mass, 2, 1 / (2 * R), E_star)


@float64
def hertz_max_force(velocity: Scalars, mass: Scalars, R: Scalars, E_star: Scalars):
    """Hertz impact of a paraboloid: `F_max = (4/3) E* √R d_max^(3/2)` [N]."""
    return power_law_hertz_max_force(velocity, mass, 2, 1 / (2 * R), E_star)


@float64
def hertz_contact_time(velocity: Scalars, mass: Scalars, R: Scalars, E_star: Scalars):
    """Hertz impact of a paraboloid, exact constant:
    `t_c = 2 (15/16)^(2/5) √π Γ(7/5)/Γ(9/10) (m²/(R E*² v₀))^(1/5) ≈ 2.8682 (…)^(1/5)` [s]."""
    return power_law_hertz_contact_time(velocity, mass, 2, 1 / (2 * R), E_star)
