"""Closed-form results of the JKR/MDR theory of adhesive normal contact and impact.

Plain functions of SI parameters written with ``jax.numpy``: they take scalars or arrays,
broadcast, and work under ``jit``/``vmap``/``grad`` (float64 when x64 is enabled). Equation
numbers refer to ``reference/adhesive-normal-contact.md``.

Conventions: indentation d > 0 pressed in, force F > 0 compressive, F < 0 adhesive;
``work_of_adhesion`` is the Dupré work Δγ [J/m²] (not a surface energy γ); ``E_star`` is the
effective modulus E* [Pa]; ``xi`` selects the stability criterion (3.35): 3 force control,
1 displacement control. A free body separates at the displacement-controlled point (ξ = 1).
Critical values are returned as a tuple ``(a_c [m], d_c [m], F_c [N])``.

MDR profiles used here (3.24): paraboloid f = r²/(2R) → g = x²/R; power law f = c rⁿ →
g = κ(n) c |x|ⁿ; cone → g = (π/2) tanθ |x|; sphere → g = x artanh(x/R); ellipsoid
f = R(1 − √(1 − k²r²)) → g = kR x artanh(kx) (a sphere of radius 1/k scaled by kR).

Misprints found in the chapter (the code uses the corrected forms):
- (3.57): d(a) must read kR·a·artanh(ka) − √(2πaΔγ/E*); the factor kR is missing (the F_N
  line and the critical values (3.54)–(3.56) with β = ξ√(πΔγ/(2E*kR²)) are correct).
- (3.56): √a must read √α. Its F_c also cancels to O(α³) for a_c ≪ R, losing about
  2 log₁₀(R/a_c) digits; ``ellipsoid_critical`` uses an equivalent cancellation-free form.
(3.51) and (3.82) follow exactly from the energy balance (see ``power_law_energy_loss``), and
(3.82) reduces to (3.51) at n = 2, c = 1/(2R).
"""

import jax
import jax.numpy as jnp
from jax.scipy.special import gammaln

__all__ = [
    "kappa",
    "power_law_indentation",
    "power_law_force",
    "power_law_normalized_indentation",
    "power_law_normalized_force",
    "jkr_indentation",
    "jkr_force",
    "jkr_normalized_indentation",
    "jkr_normalized_force",
    "flat_punch_critical",
    "cone_critical",
    "power_law_critical",
    "paraboloid_critical",
    "ellipsoid_critical",
    "sphere_critical",
    "power_law_jump_in",
    "paraboloid_jump_in",
    "power_law_energy_loss",
    "power_law_beta",
    "power_law_restitution",
    "power_law_sticking_velocity",
    "thornton_ning_energy_loss",
    "thornton_ning_beta",
    "thornton_ning_restitution",
    "thornton_ning_sticking_velocity",
    "attach_on_touch_energy_loss",
    "attach_on_touch_restitution",
    "power_law_hertz_max_indentation",
    "power_law_hertz_max_force",
    "power_law_hertz_contact_time",
    "hertz_max_indentation",
    "hertz_max_force",
    "hertz_contact_time",
]

_SPHERE_ITERATIONS = 64


def _float(x):
    return jnp.asarray(x, dtype=jnp.result_type(float))


def _detach_length(a, E_star, work_of_adhesion):
    """Rule of Heß (3.26): Δl(a) = √(2π a Δγ / E*) [m]."""
    return jnp.sqrt(2 * jnp.pi * a * work_of_adhesion / E_star)


def _restitution(beta):
    """e = √(1 − β) for β < 1, else 0; gradient-safe at and beyond the sticking point."""
    below = beta < 1
    return jnp.where(below, jnp.sqrt(jnp.where(below, 1 - beta, 1.0)), 0.0)


def kappa(n):
    """Power-law MDR factor κ(n) = √π Γ(n/2 + 1) / Γ((n + 1)/2) (3.72); g = κ(n) c xⁿ."""
    n = _float(n)
    return jnp.sqrt(jnp.pi) * jnp.exp(gammaln(n / 2 + 1) - gammaln((n + 1) / 2))


# --- JKR equilibrium curves ---------------------------------------------------------------


def power_law_indentation(a, n, c, E_star, work_of_adhesion):
    """JKR indentation [m] at contact radius a [m] for f = c rⁿ (3.71):
    d = κ(n) c aⁿ − √(2π a Δγ / E*). ``c`` is in m^(1−n)."""
    return kappa(n) * c * a**n - _detach_length(a, E_star, work_of_adhesion)


def power_law_force(a, n, c, E_star, work_of_adhesion):
    """JKR normal force [N] at contact radius a [m] for f = c rⁿ (3.71):
    F = 2E* n/(n+1) κ(n) c a^(n+1) − √(8π a³ E* Δγ)."""
    return 2 * E_star * n / (n + 1) * kappa(n) * c * a ** (n + 1) - jnp.sqrt(
        8 * jnp.pi * a**3 * E_star * work_of_adhesion
    )


def power_law_normalized_indentation(a_hat, n, xi):
    """d/|d_c| against a/a_c, normalized with the critical values of criterion ξ (3.78):
    d̂ = ξ âⁿ/|ξ − 2n| − 2n √â/|ξ − 2n|. Undefined where d_c = 0 (ξ = 2n, e.g. n = 1.5, ξ = 3)."""
    return (xi * a_hat**n - 2 * n * jnp.sqrt(a_hat)) / jnp.abs(xi - 2 * n)


def power_law_normalized_force(a_hat, n, xi):
    """F/|F_c| against a/a_c, normalized with the critical values of criterion ξ (3.78):
    F̂ = (ξ â^(n+1) − (2n + 2) â^(3/2)) / |ξ − 2n − 2|."""
    return (xi * a_hat ** (n + 1) - (2 * n + 2) * a_hat**1.5) / jnp.abs(xi - 2 * n - 2)


def jkr_indentation(a, R, E_star, work_of_adhesion):
    """JKR indentation [m] of a paraboloid f = r²/(2R) at contact radius a [m] (3.44):
    d = a²/R − √(2π a Δγ / E*)."""
    return a**2 / R - _detach_length(a, E_star, work_of_adhesion)


def jkr_force(a, R, E_star, work_of_adhesion):
    """JKR normal force [N] of a paraboloid at contact radius a [m] (3.44):
    F = 4E* a³/(3R) − √(8π a³ E* Δγ)."""
    return 4 * E_star * a**3 / (3 * R) - jnp.sqrt(8 * jnp.pi * a**3 * E_star * work_of_adhesion)


def jkr_normalized_indentation(a_hat):
    """Universal JKR curve d̂ = 3â² − 4√â (3.49); â, d̂ normalized by force-control a_c, |d_c|."""
    return 3 * a_hat**2 - 4 * jnp.sqrt(a_hat)


def jkr_normalized_force(a_hat):
    """Universal JKR curve F̂ = â³ − 2â^(3/2) (3.49); F̂ = F/|F_c| with force-control F_c."""
    return a_hat**3 - 2 * a_hat**1.5


# --- critical (pull-off) values -------------------------------------------------------------


def flat_punch_critical(radius, E_star, work_of_adhesion):
    """Flat punch of radius ``radius`` [m] (3.37), same for both criteria:
    a_c = radius, d_c = −√(2π a Δγ/E*), F_c = −√(8π a³ E* Δγ)."""
    a_c = _float(radius)
    d_c = -_detach_length(a_c, E_star, work_of_adhesion)
    return a_c, d_c, 2 * E_star * a_c * d_c


def power_law_critical(n, c, E_star, work_of_adhesion, xi):
    """Critical values for f = c rⁿ, n > 1/2 (3.74)–(3.76). With s = √(πΔγ/(2E*)) and
    K = κ(n) c: a_c = (ξ s/(nK))^(2/(2n−1)), d_c = s √a_c (ξ/n − 2),
    F_c = E* s a_c^(3/2) (2ξ/(n+1) − 4)."""
    s = jnp.sqrt(jnp.pi * work_of_adhesion / (2 * E_star))
    a_c = (xi * s / (n * kappa(n) * c)) ** (2 / (2 * n - 1))
    d_c = s * jnp.sqrt(a_c) * (xi / n - 2)
    F_c = E_star * s * a_c**1.5 * (2 * xi / (n + 1) - 4)
    return a_c, d_c, F_c


def cone_critical(theta, E_star, work_of_adhesion, xi):
    """Cone of slope angle θ [rad] (3.40)–(3.41): a_c = 2ξ²Δγ/(πE* tan²θ),
    d_c = (ξ² − 2ξ)Δγ/(E* tanθ), F_c = 2Δγ²(ξ⁴ − 4ξ³)/(πE* tan³θ)."""
    t = jnp.tan(theta)
    a_c = 2 * xi**2 * work_of_adhesion / (jnp.pi * E_star * t**2)
    d_c = (xi**2 - 2 * xi) * work_of_adhesion / (E_star * t)
    F_c = 2 * work_of_adhesion**2 * (xi**4 - 4 * xi**3) / (jnp.pi * E_star * t**3)
    return a_c, d_c, F_c


def paraboloid_critical(R, E_star, work_of_adhesion, xi):
    """Paraboloid f = r²/(2R) (3.45): a_c = (πξ²R²Δγ/(8E*))^(1/3),
    d_c = (π²ξΔγ²R/E*²)^(1/3) (ξ/4 − 1), F_c = πξΔγR (ξ/6 − 1).
    ξ = 3: F_c = −(3/2)πΔγR (JKR pull-off); ξ = 1: F_c = −(5/6)πΔγR."""
    a_c = jnp.cbrt(jnp.pi * xi**2 * R**2 * work_of_adhesion / (8 * E_star))
    d_c = jnp.cbrt(jnp.pi**2 * xi * work_of_adhesion**2 * R / E_star**2) * (xi / 4 - 1)
    F_c = jnp.pi * xi * work_of_adhesion * R * (xi / 6 - 1)
    return a_c, d_c, F_c


def _sphere_alpha(beta):
    """Root α ∈ (0, 1) of √α (artanh α + α/(1 − α²)) = β, i.e. (3.54).

    The left side rises monotonically from 0 to ∞, so the root is bracketed by [0, 1];
    a fixed number of Newton steps, replaced by bisection whenever they leave the bracket,
    then one differentiable Newton step so that ``jax.grad`` sees the implicit derivative.
    """
    beta = _float(beta)

    def phi(a):
        return jnp.sqrt(a) * (jnp.arctanh(a) + a / (1 - a**2)) - beta

    def dphi(a):
        h = jnp.arctanh(a) + a / (1 - a**2)
        return h / (2 * jnp.sqrt(a)) + jnp.sqrt(a) * (2 / (1 - a**2) ** 2)

    def step(_, state):
        lo, hi, a = state
        f = phi(a)
        lo = jnp.where(f < 0, a, lo)
        hi = jnp.where(f > 0, a, hi)
        newton = a - f / dphi(a)
        inside = (newton > lo) & (newton < hi)
        return lo, hi, jnp.where(inside, newton, (lo + hi) / 2)

    guess = jnp.clip((beta / 2) ** (2 / 3), 1e-300, 0.5)  # small-α limit: 2α^(3/2) = β
    init = (jnp.zeros_like(beta), jnp.ones_like(beta), guess)
    a = jax.lax.stop_gradient(jax.lax.fori_loop(0, _SPHERE_ITERATIONS, step, init)[2])
    return a - phi(a) / dphi(a)


def _hertz_sphere_shape(alpha):
    """(1 + α²) artanh α − α = Σ_{k≥1} 4k/(4k² − 1) α^(2k+1): the non-adhesive sphere force
    over E*R² at α = a/R, by its series below α = 0.3 (the closed form cancels as 4α³/3)."""
    k = jnp.arange(1, 21)
    small = jnp.minimum(alpha, 0.3)[..., None]
    series = jnp.sum(4 * k / (4 * k**2 - 1) * small ** (2 * k + 1), axis=-1)
    return jnp.where(alpha < 0.3, series, (1 + alpha**2) * jnp.arctanh(alpha) - alpha)


def ellipsoid_critical(R, k, E_star, work_of_adhesion, xi):
    """Ellipsoid f = R(1 − √(1 − k²r²)), g = kR x artanh(kx) (§3.5.5; R [m], k [1/m]).

    α = k a_c solves (3.54) with β = ξ√(πΔγ/(2E* k R²)); then, equal to (3.56) with the force
    factor E*R/k but free of its O(α³) cancellation in F_c,
    d_c = R(α artanh α − 2β√α/ξ) = g(a_c) − Δl(a_c),
    F_c = (E*R/k)[(1 + α²) artanh α − α − 4α^(3/2) β/ξ].
    Valid while α = k a_c < 1 is well inside the profile (half-space hypothesis: α ≲ 0.3).
    """
    beta = xi * jnp.sqrt(jnp.pi * work_of_adhesion / (2 * E_star * k * R**2))
    alpha = _sphere_alpha(beta)
    adhesion = 2 * beta * jnp.sqrt(alpha) / xi
    d_c = R * (alpha * jnp.arctanh(alpha) - adhesion)
    F_c = E_star * R / k * (_hertz_sphere_shape(alpha) - 2 * alpha * adhesion)
    return alpha / k, d_c, F_c


def sphere_critical(R, E_star, work_of_adhesion, xi):
    """Sphere of radius R [m], g = x artanh(x/R) (3.54)–(3.56): α = a_c/R solves
    artanh α + α/(1 − α²) = β/√α with β = ξ√(πΔγ/(2E*R)); d_c, F_c from (3.56).
    Tends to the paraboloid (3.45) as a_c/R → 0."""
    return ellipsoid_critical(R, 1 / R, E_star, work_of_adhesion, xi)


# --- jump-in at first touch (reversible JKR loading) ---------------------------------------


def power_law_jump_in(n, c, E_star, work_of_adhesion):
    """Contact radius and force when a power-law body first touches (d = 0) under the
    reversible JKR law: g(a₀) = Δl(a₀), i.e. a₀ = (2πΔγ/(E* κ² c²))^(1/(2n−1)), and
    F₀ = −2E* κ c a₀^(n+1)/(n+1) (< 0, adhesive). Returns (a₀ [m], F₀ [N])."""
    K = kappa(n) * c
    a0 = (2 * jnp.pi * work_of_adhesion / (E_star * K**2)) ** (1 / (2 * n - 1))
    return a0, -2 * E_star * K * a0 ** (n + 1) / (n + 1)


def paraboloid_jump_in(R, E_star, work_of_adhesion):
    """Jump-in of a paraboloid at first touch: a₀³ = 2πΔγR²/E*, F₀ = −(4/3)πΔγR, which is
    −(8/9)|F_c| with the force-control F_c. Returns (a₀ [m], F₀ [N])."""
    a0 = jnp.cbrt(2 * jnp.pi * work_of_adhesion * R**2 / E_star)
    return a0, -2 * E_star * a0**3 / (3 * R)


# --- adhesive impact: restitution (reversible JKR law, separation at ξ = 1) ---------------


def power_law_energy_loss(n, c, E_star, work_of_adhesion):
    """Kinetic energy [J] lost in one adhesive impact of f = c rⁿ, n > 1/2 (from (3.82)):
    W = ½ [(πΔγ/2)^(2n+1) (E* n² c² κ²)^(−2)]^(1/(2n−1)) (8n − 4)/(2n² + 3n + 1)
        · [n + (n + 1)(2n)^(4/(2n−1))].
    W = −∫ F dd along d(a) = g(a) − Δl(a) from the jump-in (d = 0, a₀) down to the
    displacement-controlled critical point; independent of the impact velocity."""
    p = 1 / (2 * n - 1)
    stiffness = E_star * (n * c * kappa(n)) ** 2
    scale = ((jnp.pi * work_of_adhesion / 2) ** (2 * n + 1) / stiffness**2) ** p
    shape = (8 * n - 4) / (2 * n**2 + 3 * n + 1) * (n + (n + 1) * (2 * n) ** (4 * p))
    return scale * shape / 2


def power_law_beta(velocity, mass, n, c, E_star, work_of_adhesion):
    """β = W / (½ m v₀²) of (3.82) for f = c rⁿ (velocity [m/s], mass [kg])."""
    return 2 * power_law_energy_loss(n, c, E_star, work_of_adhesion) / (mass * velocity**2)


def power_law_restitution(velocity, mass, n, c, E_star, work_of_adhesion):
    """Coefficient of restitution (3.81): e = √(1 − β) for β ≤ 1, 0 (capture) otherwise."""
    return _restitution(power_law_beta(velocity, mass, n, c, E_star, work_of_adhesion))


def power_law_sticking_velocity(mass, n, c, E_star, work_of_adhesion):
    """Impact velocity [m/s] with β = 1: v_s = √(2W/m); slower bodies stick."""
    return jnp.sqrt(2 * power_law_energy_loss(n, c, E_star, work_of_adhesion) / mass)


def thornton_ning_energy_loss(R, E_star, work_of_adhesion):
    """Kinetic energy [J] lost in the JKR impact of a paraboloid of radius R (from (3.51)):
    W = (1/10) [R⁴ (πΔγ)⁵ / E*²]^(1/3) (1 + 864^(1/3))."""
    return jnp.cbrt(R**4 * (jnp.pi * work_of_adhesion) ** 5 / E_star**2) * (1 + jnp.cbrt(864.0)) / 10


def thornton_ning_beta(velocity, mass, R, E_star, work_of_adhesion):
    """Thornton–Ning β (3.51) = W / (½ m v₀²)."""
    return 2 * thornton_ning_energy_loss(R, E_star, work_of_adhesion) / (mass * velocity**2)


def thornton_ning_restitution(velocity, mass, R, E_star, work_of_adhesion):
    """Thornton–Ning restitution (3.50): e = √(1 − β) for β ≤ 1, 0 otherwise."""
    return _restitution(thornton_ning_beta(velocity, mass, R, E_star, work_of_adhesion))


def thornton_ning_sticking_velocity(mass, R, E_star, work_of_adhesion):
    """Impact velocity [m/s] with β = 1 for the paraboloid."""
    return jnp.sqrt(2 * thornton_ning_energy_loss(R, E_star, work_of_adhesion) / mass)


# --- non-adhesive (Hertz-type) impact -------------------------------------------------------


def attach_on_touch_energy_loss(velocity, mass, R, E_star, work_of_adhesion):
    """Energy lost [J] by a paraboloid that attaches on touch (Δγa = 0) and detaches by Heß.

    Our own reference (not in the chapter). In JKR units (lengths a0 = (2πΔγR²/E*)^(1/3)
    and a0²/R, energy E*·a0·(a0²/R)²) the loop is: Hertzian loading d = a² up to a_m with
    (8/15)·a_m⁵ = ½mv0²; a hold at a_m, F = 2(a_m·d − a_m³/3), down to d = a_m² − √a_m; the
    JKR branch d = a² − √a down to a* = 4^(−2/3) (skipped when a_m < a*, which then
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


def attach_on_touch_restitution(velocity, mass, R, E_star, work_of_adhesion):
    """Restitution of the paraboloid with attach on touch (Δγa = 0); 0 when captured."""
    kinetic = 0.5 * mass * velocity**2
    return _restitution(attach_on_touch_energy_loss(velocity, mass, R, E_star, work_of_adhesion) / kinetic)


def _power_law_stiffness(n, c, E_star):
    """k in F = k d^((n+1)/n): with a = (d/K)^(1/n), F = 2E* n/(n+1) K a^(n+1), K = κ c."""
    return 2 * E_star * n / (n + 1) * (kappa(n) * c) ** (-1 / n)


def power_law_hertz_max_indentation(velocity, mass, n, c, E_star):
    """Maximum indentation [m] of a non-adhesive impact of f = c rⁿ:
    ½ m v₀² = k n/(2n+1) d_max^((2n+1)/n)."""
    k = _power_law_stiffness(n, c, E_star)
    return (mass * velocity**2 * (2 * n + 1) / (2 * n * k)) ** (n / (2 * n + 1))


def power_law_hertz_max_force(velocity, mass, n, c, E_star):
    """Maximum force [N] of a non-adhesive impact of f = c rⁿ: k d_max^((n+1)/n)."""
    d_max = power_law_hertz_max_indentation(velocity, mass, n, c, E_star)
    return _power_law_stiffness(n, c, E_star) * d_max ** ((n + 1) / n)


def power_law_hertz_contact_time(velocity, mass, n, c, E_star):
    """Contact time [s] of a non-adhesive impact of f = c rⁿ, exact:
    t_c = 2 d_max/v₀ ∫₀¹ dx/√(1 − x^p), p = (2n+1)/n, with
    ∫₀¹ dx/√(1 − x^p) = √π Γ(1 + 1/p) / Γ(1/p + 1/2)."""
    p = (2 * n + 1) / _float(n)
    integral = jnp.sqrt(jnp.pi) * jnp.exp(gammaln(1 + 1 / p) - gammaln(1 / p + 0.5))
    return 2 * power_law_hertz_max_indentation(velocity, mass, n, c, E_star) / velocity * integral


def hertz_max_indentation(velocity, mass, R, E_star):
    """Hertz impact of a paraboloid: d_max = (15 m v₀² / (16 E* √R))^(2/5) [m]."""
    return power_law_hertz_max_indentation(velocity, mass, 2, 1 / (2 * R), E_star)


def hertz_max_force(velocity, mass, R, E_star):
    """Hertz impact of a paraboloid: F_max = (4/3) E* √R d_max^(3/2) [N]."""
    return power_law_hertz_max_force(velocity, mass, 2, 1 / (2 * R), E_star)


def hertz_contact_time(velocity, mass, R, E_star):
    """Hertz impact of a paraboloid, exact constant:
    t_c = 2 (15/16)^(2/5) √π Γ(7/5)/Γ(9/10) (m²/(R E*² v₀))^(1/5) ≈ 2.8682 (…)^(1/5) [s]."""
    return power_law_hertz_contact_time(velocity, mass, 2, 1 / (2 * R), E_star)
