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
- (3.87): the truncated cone's equation has roots for β ≥ 2.1219 (min of (φ + cot φ)/√cos φ), not
  2.125; (3.110): the capped cone's for β ≥ 1.7967, not 1.795; (3.123) β0 ≈ 2.2 + 3.2 R1/R* is a
  fit (β0 = 2 at R1/R* = 0): ``*_threshold`` compute the exact minima. Between β = 2 and β0 the
  capped paraboloid loses contact at the edge of its cap (a = b, where the flank's slope jumps),
  not at the JKR state of R1 (whose radius then lies beyond b).
- Where a profile has two critical states (a flat tip or cap and the flank: §3.5.8–3.5.12) the
  contact is lost at the deeper one, not always at the flank's second root: a displacement-
  controlled contact snaps from the flank's minimum of d(a) onto the inner branch and survives
  while that branch reaches lower d (ξ = 1), a force-controlled one while it reaches a lower
  force (ξ = 3). ``*_pull_off`` pick the state that ends the contact; ``*_critical`` give the
  chapter's roots.
- §3.8.4, large Tabor parameter: (3.183) prints the ε₁^(3/2) coefficient of F̃_N as 23/6 (it is
  11/6: κ² arccos(1/κ) + √(κ² − 1) = √2(2ε₁^(1/2) + (11/6)ε₁^(3/2) + …)), and its first line drops
  −(4/9)ãΛε₁², of the same order as the term it keeps (so (3.184) lacks +1/(12ã²Λ⁴)). With both,
  F̃_N = ã³ − 2ã^(3/2) + (ã² − (13/12)ã^(1/2))/Λ² (the printed d̃ of (3.185) is right), and the
  pull-off (3.189) is F̃_A = 1 + 1/(12Λ²), not 1 + 11/(12Λ²); in (3.190) 11/24 becomes 1/24.
  ``maugis_pull_off`` (the exact minimum of (3.171)) confirms 1/12, remainder ≈ −0.0515/Λ⁴.
  (3.186)–(3.187), built on 23/12, inherit the error; (3.188)'s derivative is garbled besides
  (its root follows from (3.187)).
(3.51) and (3.82) follow exactly from the energy balance (see ``power_law_energy_loss``), and
(3.82) reduces to (3.51) at n = 2, c = 1/(2R).

The Maugis–Dugdale functions (§3.6–3.8, from ``tabor_parameter`` on) use numpy/scipy (hypergeometric
function, scalar minimization) and compute in float64 whatever the jax setting.
"""

import functools

import jax
import jax.numpy as jnp
import numpy as np
from jax.scipy.special import gammaln
from scipy.optimize import minimize_scalar
from scipy.special import gamma, hyp2f1

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
    "truncated_cone_beta",
    "truncated_cone_threshold",
    "truncated_cone_critical",
    "truncated_cone_pull_off",
    "truncated_paraboloid_beta",
    "truncated_paraboloid_threshold",
    "truncated_paraboloid_critical",
    "truncated_paraboloid_pull_off",
    "capped_flat_punch_thresholds",
    "capped_flat_punch_critical",
    "capped_flat_punch_normalized_force",
    "capped_cone_beta",
    "capped_cone_threshold",
    "capped_cone_critical",
    "capped_cone_pull_off",
    "capped_paraboloid_beta",
    "capped_paraboloid_threshold",
    "capped_paraboloid_critical",
    "capped_paraboloid_pull_off",
    "rounded_flat_punch_beta",
    "rounded_flat_punch_critical",
    "wavy_paraboloid_indentation",
    "wavy_paraboloid_force",
    "wavy_paraboloid_normalized",
    "constant_stress_profile",
    "constant_stress_uniform_state",
    "constant_stress_pull_off",
    "kendall_to_optimal_ratio",
    "power_law_half_threshold",
    "tabor_parameter",
    "maugis_adhesive_stress",
    "maugis_range",
    "tabor_criterion",
    "bradley_pull_off",
    "dmt_pull_off",
    "dmt_zone_radius",
    "power_law_dmt_pull_off",
    "maugis_paraboloid_state",
    "maugis_power_law_state",
    "maugis_paraboloid",
    "maugis_junction_zone_radius",
    "maugis_paraboloid_noncontact",
    "maugis_pull_off",
    "maugis_pull_off_force",
    "maugis_pull_off_large_tabor",
    "maugis_pull_off_force_large_tabor",
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


@jax.jit  # one compilation for every β (its loop would recompile on each eager call)
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


# --- quasi-static indentation: the profiles of §3.5 with two regimes ---------------------------
#
# Each flank equation of §3.5.8–3.5.13 reads ψ(φ) = β with φ = arccos(b/a_c) and ψ a fixed function
# of the angle: g'(a) = ξ √(πΔγ/(2E*a)) (3.35) written with a = b/cos φ. ψ has one interior
# minimum (one root pair) or rises monotonically (one root).

_ANGLE_STEPS = 100
_ANGLE_EDGE = 1e-12


def _golden_minimum(psi, lo, hi, steps=_ANGLE_STEPS):
    """Location of the minimum of a unimodal ψ on [lo, hi] (golden-section search)."""
    ratio = (jnp.sqrt(5.0) - 1.0) / 2.0

    def step(_, bracket):
        a, b = bracket
        left, right = b - ratio * (b - a), a + ratio * (b - a)
        lower = psi(left) < psi(right)
        return jnp.where(lower, a, left), jnp.where(lower, right, b)

    a, b = jax.lax.fori_loop(0, steps, step, (lo, hi))
    return 0.5 * (a + b)


def _bisect(fun, lo, hi, steps=_ANGLE_STEPS):
    """Sign change of `fun` on [lo, hi] (the sign at lo is kept on the left)."""
    sign = jnp.sign(fun(lo))

    def step(_, bracket):
        a, b = bracket
        mid = 0.5 * (a + b)
        same = jnp.sign(fun(mid)) == sign
        return jnp.where(same, mid, a), jnp.where(same, b, mid)

    a, b = jax.lax.fori_loop(0, steps, step, (lo, hi))
    return 0.5 * (a + b)


@functools.partial(jax.jit, static_argnums=0)
def _angle_roots(psi, beta, parameter=0.0):
    """(φ1, φ2, ψ_min): the roots of ψ(φ, parameter) = β left and right of ψ's minimum (nan where
    none). Compiled once per ψ (a module-level function)."""
    beta, parameter = jnp.broadcast_arrays(_float(beta), _float(parameter))

    def shape(phi):
        return psi(phi, parameter)

    lo = jnp.full_like(beta, _ANGLE_EDGE)
    hi = jnp.full_like(beta, jnp.pi / 2 - _ANGLE_EDGE)
    middle = _golden_minimum(shape, lo, hi)
    least = shape(middle)
    left = _bisect(lambda p: shape(p) - beta, lo, middle)
    right = _bisect(lambda p: shape(p) - beta, middle, hi)
    has_left = (least <= beta) & (shape(lo) >= beta)
    has_right = least <= beta
    return jnp.where(has_left, left, jnp.nan), jnp.where(has_right, right, jnp.nan), least


def _deeper(xi, first, second):
    """Of two critical states (a, d, F), the one that ends the contact: the lower indentation
    under displacement control (ξ = 1), the lower force under force control (ξ = 3); a state
    with nan values does not exist."""
    displacement = _float(xi) < 2
    key1 = jnp.where(displacement, first[1], first[2])
    key2 = jnp.where(displacement, second[1], second[2])
    take_second = jnp.isnan(key1) | (key2 < key1)
    take_second = take_second & ~jnp.isnan(key2)
    return tuple(jnp.where(take_second, s, f) for f, s in zip(first, second))


def _flat_tip(b, E_star, work_of_adhesion):
    """The state where the contact sits on a flat tip of radius b, (3.90): the flat punch (3.37)."""
    return flat_punch_critical(b, E_star, work_of_adhesion)


def _truncated_cone_psi(phi, _=None):
    return (phi + 1 / jnp.tan(phi)) / jnp.sqrt(jnp.cos(phi))


def truncated_cone_beta(b, theta, E_star, work_of_adhesion, xi):
    """β = (ξ/tanθ) √(πΔγ/(2E* b)) of the truncated cone (3.88); b [m] flat-tip radius."""
    return xi / jnp.tan(theta) * jnp.sqrt(jnp.pi * work_of_adhesion / (2 * E_star * b))


def truncated_cone_threshold():
    """Smallest β for which (3.87) φ + cot φ = β √cos φ has roots: 2.1219 (printed 2.125)."""
    return _angle_roots(_truncated_cone_psi, 10.0)[2]


def truncated_cone_critical(b, theta, E_star, work_of_adhesion, xi, root=1):
    """Critical state on the flank of a truncated cone, (3.87)–(3.89): φ = arccos(b/a_c) solves
    φ + cot φ = β √cos φ; root 0 is the smaller angle, root 1 the larger. Then
    d_c = a_c tanθ [φ(1 − 2/ξ) − (2/ξ) cot φ],
    F_c = E* tanθ a_c² [φ(1 − 4/ξ) + cot φ (sin²φ − 4/ξ)]. nan where (3.87) has no root
    (β < 2.1219). Returns (a_c [m], d_c [m], F_c [N])."""
    beta = truncated_cone_beta(b, theta, E_star, work_of_adhesion, xi)
    phi = _angle_roots(_truncated_cone_psi, beta)[root]
    t = jnp.tan(theta)
    a = b / jnp.cos(phi)
    d = a * t * (phi * (1 - 2 / xi) - 2 / xi / jnp.tan(phi))
    F = E_star * t * a**2 * (phi * (1 - 4 / xi) + (jnp.sin(phi) ** 2 - 4 / xi) / jnp.tan(phi))
    return a, d, F


def truncated_cone_pull_off(b, theta, E_star, work_of_adhesion, xi):
    """Where a truncated cone loaded past its critical radii loses contact: the deeper of the flat
    tip (3.90) and the flank's larger root (3.89) (see the module notes). Returns (a, d, F)."""
    return _deeper(xi, _flat_tip(b, E_star, work_of_adhesion), truncated_cone_critical(b, theta, E_star, work_of_adhesion, xi, 1))


def _truncated_paraboloid_psi(phi, _=None):
    s, c = jnp.sin(phi), jnp.cos(phi)
    return (1 + s**2) / (s * c) / jnp.sqrt(c)


def truncated_paraboloid_beta(b, R, E_star, work_of_adhesion, xi):
    """β = (ξR/b) √(πΔγ/(2E* b)) of the truncated paraboloid (3.96)."""
    return xi * R / b * jnp.sqrt(jnp.pi * work_of_adhesion / (2 * E_star * b))


def truncated_paraboloid_threshold():
    """Smallest β for which (3.95) has roots: 3.0945 (printed 3.095)."""
    return _angle_roots(_truncated_paraboloid_psi, 10.0)[2]


def truncated_paraboloid_critical(b, R, E_star, work_of_adhesion, xi, root=1):
    """Critical state on the flank of a truncated paraboloid, (3.95)–(3.97):
    (1 + sin²φ)/(sin φ cos φ) = β √cos φ, a_c = b/cos φ,
    d_c = (a_c²/R) sin φ (1 − 2/ξ − 2/(ξ sin²φ)),
    F_c = (2E* a_c³/(3R)) sin φ [3 − sin²φ − (6/ξ)(1 + 1/sin²φ)]. nan without a root."""
    beta = truncated_paraboloid_beta(b, R, E_star, work_of_adhesion, xi)
    phi = _angle_roots(_truncated_paraboloid_psi, beta)[root]
    s = jnp.sin(phi)
    a = b / jnp.cos(phi)
    d = a**2 / R * s * (1 - 2 / xi - 2 / (xi * s**2))
    F = 2 * E_star * a**3 / (3 * R) * s * (3 - s**2 - 6 / xi * (1 + 1 / s**2))
    return a, d, F


def truncated_paraboloid_pull_off(b, R, E_star, work_of_adhesion, xi):
    """The deeper of the flat tip (flat punch, §3.5.9) and the flank's larger root (3.97)."""
    return _deeper(xi, _flat_tip(b, E_star, work_of_adhesion), truncated_paraboloid_critical(b, R, E_star, work_of_adhesion, xi, 1))


def capped_flat_punch_thresholds(b, R, E_star):
    """(Δγ1, Δγ2) of the flat punch with parabolic cap (3.101): the works of adhesion at which
    the JKR critical radius of the cap reaches the punch radius b under force control (ξ = 3)
    and displacement control (ξ = 1): Δγ2 = 9Δγ1 = 8E*b³/(πR²)."""
    second = 8 * E_star * b**3 / (jnp.pi * R**2)
    return second / 9, second


def capped_flat_punch_critical(b, R, E_star, work_of_adhesion, xi):
    """Flat punch of radius b with a parabolic cap of radius R (§3.5.10, (3.98)–(3.101)):
    the JKR critical state (3.45) where its radius lies on the cap, else the punch edge a_c = b
    with d_c = b²/R − √(2πbΔγ/E*) and F_c = 2E*(d_c b − b³/(3R)) (3.99)."""
    a_jkr, d_jkr, F_jkr = paraboloid_critical(R, E_star, work_of_adhesion, xi)
    d_edge = b**2 / R - _detach_length(b, E_star, work_of_adhesion)
    F_edge = 2 * E_star * (d_edge * b - b**3 / (3 * R))
    on_cap = a_jkr < b
    return jnp.where(on_cap, a_jkr, b), jnp.where(on_cap, d_jkr, d_edge), jnp.where(on_cap, F_jkr, F_edge)


def capped_flat_punch_normalized_force(d_hat, b_hat):
    """F̂ = (d̂ b̂ − b̂³)/2 at the punch edge â = b̂ (3.104), normalized as in (3.102)."""
    return 0.5 * (d_hat * b_hat - b_hat**3)


def _capped_cone_psi(phi, _=None):
    s, c = jnp.sin(phi), jnp.cos(phi)
    return (2 * (1 - s) / c + phi) / jnp.sqrt(c)


def capped_cone_beta(b, theta, E_star, work_of_adhesion, xi):
    """β = (ξ/tanθ) √(πΔγ/(2E* b)) of the cone with parabolic cap (3.111)."""
    return truncated_cone_beta(b, theta, E_star, work_of_adhesion, xi)


def capped_cone_threshold():
    """Smallest β for which (3.110) has roots: 1.7967 (printed 1.795); the smaller root exists
    up to β = 2, where the cap's own JKR critical radius reaches b."""
    return _angle_roots(_capped_cone_psi, 10.0)[2]


def capped_cone_critical(b, theta, E_star, work_of_adhesion, xi, root=1):
    """Critical state on the conical flank of a cone with parabolic cap (cap radius b/tanθ),
    (3.110)–(3.113): 2(1 − sin φ)/cos φ + φ = β √cos φ, a_c = b/cos φ,
    d_c = a_c tanθ [(1 − sin φ)/cos φ (1 − 4/ξ) + φ(1 − 2/ξ)],
    F_c = E* a_c² tanθ [φ(1 − 4/ξ) + (1 − sin φ)/cos φ (4/3 − 8/ξ) + sin φ cos φ/3].
    Root 0 (1.7967 ≤ β < 2) or 1 (β ≥ 1.7967); nan where it does not exist."""
    beta = capped_cone_beta(b, theta, E_star, work_of_adhesion, xi)
    phi = _angle_roots(_capped_cone_psi, beta)[root]
    t = jnp.tan(theta)
    s, c = jnp.sin(phi), jnp.cos(phi)
    a = b / c
    d = a * t * ((1 - s) / c * (1 - 4 / xi) + phi * (1 - 2 / xi))
    F = E_star * a**2 * t * (phi * (1 - 4 / xi) + (1 - s) / c * (4 / 3 - 8 / xi) + s * c / 3)
    return a, d, F


def _on_cap(R, b, E_star, work_of_adhesion, xi):
    """The JKR critical state (3.45) of a cap of radius R, or nan where it lies beyond b."""
    a, d, F = paraboloid_critical(R, E_star, work_of_adhesion, xi)
    inside = a < b
    return tuple(jnp.where(inside, v, jnp.nan) for v in (a, d, F))


def capped_cone_pull_off(b, theta, E_star, work_of_adhesion, xi):
    """Where a cone with parabolic cap loaded past b loses contact: the deeper of the cap's JKR
    state (R = b/tanθ, for β < 2) and the flank's larger root (β ≥ 1.7967)."""
    cap = _on_cap(b / jnp.tan(theta), b, E_star, work_of_adhesion, xi)
    return _deeper(xi, cap, capped_cone_critical(b, theta, E_star, work_of_adhesion, xi, 1))


def _capped_paraboloid_psi(phi, ratio):
    s, c = jnp.sin(phi), jnp.cos(phi)
    return (2 + ratio * (1 + s**2) / s) / c / jnp.sqrt(c)


def capped_paraboloid_beta(b, R1, E_star, work_of_adhesion, xi):
    """β = (ξR1/b) √(πΔγ/(2E* b)) of the paraboloid with parabolic cap (3.121)."""
    return truncated_paraboloid_beta(b, R1, E_star, work_of_adhesion, xi)


def capped_paraboloid_threshold(R1, R2):
    """β0(R1/R*), the smallest β with roots of (3.120), R* = R1R2/(R1 − R2) (3.115); the chapter's
    fit (3.123) is 2.2 + 3.2 R1/R* (exact: 2 at R1/R* = 0, 3.0945 R1/R* for R1/R* → ∞)."""
    ratio = R1 / R2 - 1.0
    return _angle_roots(_capped_paraboloid_psi, 1e300 * jnp.ones_like(_float(ratio)), ratio)[2]


def capped_paraboloid_critical(b, R1, R2, E_star, work_of_adhesion, xi, root=1):
    """Critical state beyond the cap of a paraboloid R2 with a cap R1 ≥ R2 up to b, (3.120)–(3.122):
    (1/cos φ)(2 + (R1/R*)(1 + sin²φ)/sin φ) = β √cos φ, a_c = b/cos φ,
    d_c = (a_c²/R1)[1 − 4/ξ + (R1/R*) sin φ (1 − 2/ξ − 2/(ξ sin²φ))],
    F_c = (4E* a_c³/(3R1)){1 − 6/ξ + (R1/(2R*)) sin φ [3 − sin²φ − (6/ξ)(1 + 1/sin²φ)]}."""
    ratio = R1 / R2 - 1.0
    beta = capped_paraboloid_beta(b, R1, E_star, work_of_adhesion, xi)
    phi = _angle_roots(_capped_paraboloid_psi, beta, ratio)[root]
    s = jnp.sin(phi)
    a = b / jnp.cos(phi)
    d = a**2 / R1 * (1 - 4 / xi + ratio * s * (1 - 2 / xi - 2 / (xi * s**2)))
    F = 4 * E_star * a**3 / (3 * R1) * (1 - 6 / xi + ratio / 2 * s * (3 - s**2 - 6 / xi * (1 + 1 / s**2)))
    return a, d, F


def capped_paraboloid_pull_off(b, R1, R2, E_star, work_of_adhesion, xi):
    """The deepest of the cap's JKR state (radius R1, for β < 2), the cap's edge a = b (where the
    flank's slope jumps: d = b²/R1 − Δl(b), F = 4E*b³/(3R1) − √(8πb³E*Δγ)) and the larger root
    (3.122). For 2 < β < β0 neither root exists and the contact is lost at the edge, not at the
    JKR state of R1 as §3.5.12 states."""
    cap = _on_cap(R1, b, E_star, work_of_adhesion, xi)
    b = _float(b)
    edge = (b, b**2 / R1 - _detach_length(b, E_star, work_of_adhesion),
            4 * E_star * b**3 / (3 * R1) - jnp.sqrt(8 * jnp.pi * b**3 * E_star * work_of_adhesion))
    flank = capped_paraboloid_critical(b, R1, R2, E_star, work_of_adhesion, xi, 1)
    return _deeper(xi, _deeper(xi, cap, edge), flank)


@jax.jit
def _rounded_angle(beta):
    """The one root of (2 tan φ − φ)/√cos φ = β (rising from 0 to ∞ on (0, π/2))."""
    beta = _float(beta)
    lo = jnp.full_like(beta, _ANGLE_EDGE)
    hi = jnp.full_like(beta, jnp.pi / 2 - _ANGLE_EDGE)
    return _bisect(lambda p: (2 * jnp.tan(p) - p) / jnp.sqrt(jnp.cos(p)) - beta, lo, hi)


def rounded_flat_punch_beta(b, R, E_star, work_of_adhesion, xi):
    """β = (ξR/b) √(πΔγ/(2E* b)) of the flat punch with rounded edge (3.130)."""
    return truncated_paraboloid_beta(b, R, E_star, work_of_adhesion, xi)


def rounded_flat_punch_critical(b, R, E_star, work_of_adhesion, xi):
    """Flat punch with base radius b and edges rounded with radius R, (3.129)–(3.131): the one
    root of 2 tan φ − φ = β √cos φ, a_c = b/cos φ,
    d_c = (a_c²/R)[sin φ (1 − 4/ξ) − φ cos φ (1 − 2/ξ)],
    F_c = (4E* a_c³/(3R))[sin φ (1 − 6/ξ − cos²φ/4) − (3/4) φ cos φ (1 − 4/ξ)]."""
    phi = _rounded_angle(rounded_flat_punch_beta(b, R, E_star, work_of_adhesion, xi))
    s, c = jnp.sin(phi), jnp.cos(phi)
    a = b / c
    d = a**2 / R * (s * (1 - 4 / xi) - phi * c * (1 - 2 / xi))
    F = 4 * E_star * a**3 / (3 * R) * (s * (1 - 6 / xi - c**2 / 4) - 0.75 * phi * c * (1 - 4 / xi))
    return a, d, F


def _struve(z):
    from ..profiles import _struve01  # H0, H1 to ~1e-14 (quadrature and asymptotics)

    return _struve01(_float(z))


def wavy_paraboloid_indentation(a, R, amplitude, wavelength, E_star, work_of_adhesion):
    """JKR indentation [m] of the wavy paraboloid f = r²/(2R) + h(1 − cos(2πr/λ)) (3.134):
    d = a²/R + (π²ha/λ) H0(2πa/λ) − √(2πaΔγ/E*), H0 the Struve function."""
    h0, _ = _struve(2 * jnp.pi * a / wavelength)
    return a**2 / R + jnp.pi**2 * amplitude * a / wavelength * h0 - _detach_length(a, E_star, work_of_adhesion)


def wavy_paraboloid_force(a, R, amplitude, wavelength, E_star, work_of_adhesion):
    """JKR force [N] of the wavy paraboloid (3.134):
    F = 4E*a³/(3R) + E*πah[(2πa/λ)H0(2πa/λ) − H1(2πa/λ)] − √(8πa³E*Δγ)."""
    z = 2 * jnp.pi * a / wavelength
    h0, h1 = _struve(z)
    return (4 * E_star * a**3 / (3 * R) + E_star * jnp.pi * a * amplitude * (z * h0 - h1)
            - jnp.sqrt(8 * jnp.pi * a**3 * E_star * work_of_adhesion))


def wavy_paraboloid_normalized(a_hat, h_hat, gamma_bar):
    """The wavy paraboloid's curves in the units of (3.137), â = a/λ, d̂ = dR/λ², ĥ = hR/λ²,
    F̂ = 2F/(3πRΔγ), Δγ̄ = 2πΔγR²/(E*λ³), (3.138):
    d̂ = â² + π²ĥâ H0(2πâ) − √(Δγ̄ â),
    F̂ = 16â³/(9Δγ̄) + (4π/3)(ĥâ/Δγ̄)[2πâ H0(2πâ) − H1(2πâ)] − (8/3)√(â³/Δγ̄).
    Returns (d̂, F̂). (Δγ̄ = 100, ĥ = 0.5 puts the lowest force at F̂ = −1.32, Fig. 3.27.)"""
    z = 2 * jnp.pi * a_hat
    h0, h1 = _struve(z)
    d_hat = a_hat**2 + jnp.pi**2 * h_hat * a_hat * h0 - jnp.sqrt(gamma_bar * a_hat)
    F_hat = (16 * a_hat**3 / (9 * gamma_bar) + 4 * jnp.pi / 3 * h_hat * a_hat / gamma_bar * (z * h0 - h1)
             - 8 / 3 * jnp.sqrt(a_hat**3 / gamma_bar))
    return d_hat, F_hat


def constant_stress_profile(r, radius, stress, E_star):
    """The profile that carries a uniform tensile stress σ0 over the whole contact of radius a
    (3.61): f = (σ0 a/E*)[(4/π) E(r/a) − 2] for r ≤ a, E the complete elliptic integral (3.62)."""
    from ..profiles import ellipe

    return stress * radius / E_star * (4 / jnp.pi * ellipe(r / radius) - 2)


def constant_stress_uniform_state(radius, stress, E_star):
    """(d [m], F [N]) where the profile (3.61) in full contact carries σ0 everywhere:
    d = −2σ0 a/E* (3.60 at r = 0) and F = −πσ0a² (3.63; tensile, hence negative here)."""
    return -2 * stress * radius / E_star, -jnp.pi * stress * radius**2


def constant_stress_pull_off(radius, stress, E_star, work_of_adhesion):
    """Pull-off of the profile (3.61) under the rule of Heß (ours, not in the chapter): its MDR
    transform g = (2σ0/E*)(√(a² − x²) − a) leaves only the wall as a critical radius, so under
    either control a_c = a, d_c = g(a) − Δl(a) = −2σ0a/E* − √(2πaΔγ/E*) and
    F_c = −(πσ0a² + √(8πa³E*Δγ)): the uniform stress (3.63) plus Kendall's punch (3.66).
    Returns (a_c, d_c, F_c)."""
    radius = _float(radius)
    d_c = -2 * stress * radius / E_star - _detach_length(radius, E_star, work_of_adhesion)
    F_c = -jnp.pi * stress * radius**2 - jnp.sqrt(8 * jnp.pi * radius**3 * E_star * work_of_adhesion)
    return radius, d_c, F_c


def kendall_to_optimal_ratio(radius, stress, E_star, range_):
    """F_Kendall/F_opt = √(8E*h/(πσ0 a)) (3.69) with Δγ = σ0 h (3.68): Kendall's flat punch (3.66)
    against the optimal profile (3.67) of the same radius a; `range_` is h [m]."""
    return jnp.sqrt(8 * E_star * range_ / (jnp.pi * stress * radius))


def power_law_half_threshold(E_star, work_of_adhesion, xi=1):
    """c at which f = c√r turns over (3.80): g = κ(½)c√x against Δl = √(2πΔγ/E*)√x, so the
    displacement-controlled contact (ξ = 1) shrinks to nothing on unloading for
    c > √(2π)/κ(½) √(Δγ/E*) = 1.9120 √(Δγ/E*) and closes completely at first touch below it.
    Under force control (ξ = 3: F = 2(κc/3 − √(2πΔγ/E*)) a^(3/2)) the threshold is three times
    larger. Returns c [m^(1/2)]."""
    return xi * jnp.sqrt(2 * jnp.pi * work_of_adhesion / E_star) / kappa(0.5)


# --- Maugis–Dugdale adhesion (§3.6–3.8), numpy/scipy in float64 -------------------------------
#
# Dugdale's law (3.147): the tensile stress σ0 [Pa] acts wherever the gap is below the range h [m],
# and Δγ = σ0 h (3.4). The paraboloid f = r²/(2R) is normalized with its force-controlled JKR state
# (3.169)–(3.170), ``paraboloid_critical(R, E*, Δγ, 3)``: ã = a/a_c, d̃ = d/|d_c| (|d_c| = a_c²/(3R)),
# F̃ = F/F_A with F_A = (3/2)πRΔγ; κ = b/a > 1 is the adhesive zone radius b over the contact radius a.

_PULL_OFF_GRID = np.linspace(-50.0, 50.0, 4001)  # ln(κ − 1) scanned by ``maugis_pull_off``
_ARCTAN_SERIES = np.arange(1, 11)


def tabor_parameter(R, adhesive_stress, adhesion_range, E_star):
    """Tabor parameter Λ = (3Rσ0²/(πhE*²))^(1/3) (3.172); R, h [m], σ0, E* [Pa]. Equivalently
    Λ = 3Rσ0/(2E* a_c) with the JKR a_c (3.170), and Λ = (3/8)^(1/3) λ with Maugis's
    λ = 2σ0 (R/(πΔγE*²))^(1/3)."""
    return np.cbrt(3 * R * adhesive_stress**2 / (np.pi * adhesion_range * E_star**2))


def maugis_adhesive_stress(tabor, R, work_of_adhesion, E_star):
    """σ0 [Pa] giving the Tabor parameter Λ at fixed Δγ = σ0 h, (3.172) with (3.4):
    σ0 = Λ (πE*²Δγ/(3R))^(1/3)."""
    return tabor * np.cbrt(np.pi * E_star**2 * work_of_adhesion / (3 * R))


def maugis_range(tabor, R, work_of_adhesion, E_star):
    """Range h = Δγ/σ0 [m] (3.4) with σ0 of ``maugis_adhesive_stress``."""
    return work_of_adhesion / maugis_adhesive_stress(tabor, R, work_of_adhesion, E_star)


def tabor_criterion(R, work_of_adhesion, adhesion_range, E_star):
    """Left side of (3.181), 2RΔγ²(1 − 2/π)²/(E*²h³) = (2π/3)(1 − 2/π)² Λ³: Tabor's μ (3.3) with
    z0 = h, times 2(1 − 2/π)². The DMT limit holds where it is ≪ 1."""
    return 2 * R * work_of_adhesion**2 * (1 - 2 / np.pi) ** 2 / (E_star**2 * adhesion_range**3)


def bradley_pull_off(R, work_of_adhesion):
    """Pull-off force [N] of a rigid paraboloid of radius R from a rigid plane under any law σ(s)
    with ∫σ ds = Δγ (3.141): F_A = 2πRΔγ."""
    return 2 * np.pi * R * work_of_adhesion


def dmt_pull_off(R, work_of_adhesion):
    """DMT pull-off force [N] of a paraboloid (3.142), (3.180): Bradley's 2πRΔγ, i.e. F̃_A = 4/3 in
    the units (3.170), the Λ → 0 limit of ``maugis_pull_off``."""
    return bradley_pull_off(R, work_of_adhesion)


def dmt_zone_radius(R, adhesive_stress, adhesion_range, E_star):
    """Adhesive zone radius b [m] of the paraboloid where contact begins (a = 0, the centre gap just
    closed): the positive root (3.178) of b²/(2R) + (2σ0b/E*)(1 − 2/π) = h (3.177);
    b ≈ √(2Rh) under (3.179)."""
    q = 2 * R * adhesive_stress / E_star * (1 - 2 / np.pi)
    return 2 * R * adhesion_range / (q + np.sqrt(q**2 + 2 * R * adhesion_range))


def power_law_dmt_pull_off(n, c, work_of_adhesion, adhesion_range):
    """DMT pull-off force [N] of f = c rⁿ (3.195): πσ0b² with f(b) = h, F_A = πΔγ h^((2−n)/n)/c^(2/n)
    (c [m^(1−n)]); the paraboloid n = 2, c = 1/(2R) gives 2πRΔγ."""
    return np.pi * work_of_adhesion * adhesion_range ** ((2 - n) / n) / c ** (2 / n)


def _kappa_float64(n):
    """κ(n) of (3.193) in numpy float64 (``kappa`` follows the jax precision setting)."""
    return np.sqrt(np.pi) * gamma(n / 2 + 1) / gamma((n + 1) / 2)


def _zone_terms(a, b):
    """(√(b² − a²), arccos(a/b)) for 0 ≤ a ≤ b, accurate as a → b."""
    root = np.sqrt((b - a) * (b + a))
    return root, np.arctan2(root, a)


def maugis_paraboloid_state(a, b, R, adhesive_stress, adhesion_range, E_star):
    """(residual [m], d [m], F [N]) of the paraboloid f = r²/(2R) at contact radius a and zone radius
    b ≥ a [m] (3.168): d = a²/R − (2σ0/E*)√(b² − a²),
    F = 2E*(ad − a³/(3R)) − σ0[2b² arccos(a/b) − 2a√(b² − a²)], and the residual of the range
    condition, (2/π)[(b²/(2R) − d) arccos(a/b) + (a/(2R))√(b² − a²) − (2σ0/E*)(b − a)] − h,
    which vanishes on the equilibrium curve."""
    root, angle = _zone_terms(a, b)
    stress = adhesive_stress / E_star
    d = a**2 / R - 2 * stress * root
    residual = 2 / np.pi * ((b**2 / (2 * R) - d) * angle + a * root / (2 * R) - 2 * stress * (b - a)) - adhesion_range
    F = 2 * E_star * (a * d - a**3 / (3 * R)) - adhesive_stress * (2 * b**2 * angle - 2 * a * root)
    return residual, d, F


def maugis_power_law_state(a, b, n, c, adhesive_stress, adhesion_range, E_star):
    """(residual [m], d [m], F [N]) of f = c rⁿ at contact radius a and zone radius b ≥ a [m] (3.192),
    with κ(n) of (3.193) and z = a²/b²: d = cκ aⁿ − (2σ0/E*)√(b² − a²),
    F = 2E*(da − cκ a^(n+1)/(n+1)) − σ0[2b² arccos(a/b) − 2a√(b² − a²)], and the range residual
    c bⁿ[1 − 2κ/(π(n+1)) (a/b)^(n+1) ₂F₁(½, (n+1)/2; (n+3)/2; z)] − (2d/π) arccos(a/b)
    − 4σ0(b − a)/(πE*) − h. n = 2, c = 1/(2R) is ``maugis_paraboloid_state``."""
    root, angle = _zone_terms(a, b)
    k = _kappa_float64(n)
    ratio = a / b
    d = c * k * a**n - 2 * adhesive_stress / E_star * root
    inner = 2 * k / (np.pi * (n + 1)) * ratio ** (n + 1) * hyp2f1(0.5, (n + 1) / 2, (n + 3) / 2, ratio**2)
    residual = (c * b**n * (1 - inner) - 2 * d / np.pi * angle
                - 4 * adhesive_stress / (np.pi * E_star) * (b - a) - adhesion_range)
    F = 2 * E_star * (d * a - c * k * a ** (n + 1) / (n + 1)) - adhesive_stress * (2 * b**2 * angle - 2 * a * root)
    return residual, d, F


def _s_minus_arctan(s):
    """s − arctan s, by its series below s = 0.1 (where the difference cancels)."""
    s = np.asarray(s, dtype=float)
    small = np.minimum(s, 0.1)[..., None]
    k = _ARCTAN_SERIES
    series = np.sum((-1.0) ** (k + 1) * small ** (2 * k + 1) / (2 * k + 1), axis=-1)
    return np.where(s < 0.1, series, s - np.arctan(s))


def _maugis_curve(excess, tabor):
    """(ã, d̃, F̃) of (3.171) at κ = 1 + excess, excess = κ − 1 > 0 passed on its own so that
    κ → 1 keeps its digits. With s = √(κ² − 1), t = arccos(1/κ) = arctan s the range condition
    reads A ã² + B ã = 2/(3Λ), A = (κ²/2 − 1)t + s/2 = (s − t + s²t)/2 > 0,
    B = (4/3)Λ(1 − κ + st) > 0, whose one positive root is taken."""
    s = np.sqrt(excess * (2 + excess))
    t = np.arctan(s)
    quad = 0.5 * (_s_minus_arctan(s) + s**2 * t)
    lin = 4 / 3 * tabor * (s * t - excess)
    const = 2 / (3 * tabor)
    a = 2 * const / (lin + np.sqrt(lin**2 + 4 * quad * const))
    d = 3 * a**2 - 4 * a * tabor * s
    F = a**3 - a**2 * tabor * ((1 + excess) ** 2 * t + s)
    return a, d, F


def maugis_paraboloid(kappa_ratio, tabor):
    """Normalized Maugis–Dugdale state of the paraboloid (3.171) at κ = b/a > 1 and Tabor parameter
    Λ (3.172): (ã, d̃, F̃) with ã the positive root of
    2/(3Λ) = ã²[(κ²/2 − 1) arccos(1/κ) + √(κ² − 1)/2] + (4/3)ãΛ[1 − κ + √(κ² − 1) arccos(1/κ)],
    d̃ = 3ã² − 4ãΛ√(κ² − 1), F̃ = ã³ − ã²Λ[κ² arccos(1/κ) + √(κ² − 1)]. κ → 1 is the compressed
    (Hertz/JKR) end, κ → ∞ the junction a → 0 (``maugis_junction_zone_radius``)."""
    return _maugis_curve(np.asarray(kappa_ratio, dtype=float) - 1, tabor)


def maugis_junction_zone_radius(tabor):
    """b̃ = b/a_c where the paraboloid's contact begins (a = 0), (3.177) in the units (3.170):
    (3/2)b̃² + 4Λ(1 − 2/π)b̃ = 4/(πΛ), so b̃ = (8/(πΛ)) / (q + √(q² + 24/(πΛ))), q = 4Λ(1 − 2/π);
    ``dmt_zone_radius`` / a_c. There d̃ = −4Λb̃ and F̃ = −(π/2)Λb̃²."""
    q = 4 * tabor * (1 - 2 / np.pi)
    return 8 / (np.pi * tabor) / (q + np.sqrt(q**2 + 24 / (np.pi * tabor)))


def maugis_paraboloid_noncontact(zone_radius, tabor):
    """(d̃, F̃) of the paraboloid before contact (a = 0, centre gap open) at zone radius b̃ = b/a_c,
    (3.176) with d free: d = b²/(2R) − 4σ0b/(πE*) − h and F = −πσ0b² become
    d̃ = (3/2)b̃² − (8Λ/π)b̃ − 4/(πΛ), F̃ = −(π/2)Λb̃² (b̃ = 0: d = −h, the stress zone is born).
    nan beyond the junction b̃ > ``maugis_junction_zone_radius`` (the centre gap would be negative)."""
    b = np.asarray(zone_radius, dtype=float)
    d = 1.5 * b**2 - 8 * tabor / np.pi * b - 4 / (np.pi * tabor)
    F = -np.pi / 2 * tabor * b**2
    open_gap = b <= maugis_junction_zone_radius(tabor)
    return np.where(open_gap, d, np.nan), np.where(open_gap, F, np.nan)


def _pull_off(tabor):
    """−min F̃ over (3.171) and the non-contact branch for one Λ (see ``maugis_pull_off``)."""

    def force(log_excess):
        return _maugis_curve(np.exp(log_excess), tabor)[2]

    values = force(_PULL_OFF_GRID)
    i = int(np.argmin(values))
    bracket = (_PULL_OFF_GRID[max(i - 1, 0)], _PULL_OFF_GRID[min(i + 1, _PULL_OFF_GRID.size - 1)])
    best = minimize_scalar(force, bounds=bracket, method="bounded", options={"xatol": 1e-10})
    junction = np.pi / 2 * tabor * maugis_junction_zone_radius(tabor) ** 2
    return max(-float(best.fun), -float(values[i]), junction)


def maugis_pull_off(tabor):
    """Normalized Maugis–Dugdale pull-off of the paraboloid, F̃_A = F_A/((3/2)πRΔγ) = −min F̃ over
    the whole equilibrium curve (3.171) (force control), including its junction a = 0 with the
    non-contact branch (whose |F| is largest there). Minimized in ln(κ − 1) ∈ [−50, 50]: a scan
    of 4001 points, then bounded Brent around the lowest. Relative error against a 40-digit
    evaluation: 3e-16 for 1e-4 ≤ Λ ≤ 10, 1.5e-14 at Λ = 1e3, 5e-14 at 1e5 (the grid covers about
    1e-6 ≤ Λ ≤ 1e9).
    Tends to 4/3 (DMT) as Λ → 0 and 1 + 1/(12Λ²) (JKR) as Λ → ∞. Scalar or array Λ."""
    return np.vectorize(_pull_off, otypes=[float])(tabor)[()]


def maugis_pull_off_force(R, adhesive_stress, adhesion_range, E_star):
    """Maugis–Dugdale pull-off force [N] of a paraboloid: F̃_A(Λ) (3/2)πRσ0h."""
    tabor = tabor_parameter(R, adhesive_stress, adhesion_range, E_star)
    return maugis_pull_off(tabor) * 1.5 * np.pi * R * adhesive_stress * adhesion_range


def maugis_pull_off_large_tabor(tabor):
    """Pull-off for Λ ≫ 1, (3.189) corrected: F̃_A = 1 + 1/(12Λ²) + O(Λ⁻⁴) (printed 11/(12Λ²);
    see the module notes)."""
    return 1 + 1 / (12 * np.asarray(tabor, dtype=float) ** 2)


def maugis_pull_off_force_large_tabor(R, adhesive_stress, adhesion_range, E_star):
    """Dimensional (3.190) corrected [N]: F_A = (3/2)πRσ0h + (1/24)(3π⁵E*⁴Rh⁵/σ0)^(1/3)
    (printed 11/24), = (3/2)πRΔγ ``maugis_pull_off_large_tabor``(Λ)."""
    return 1.5 * np.pi * R * adhesive_stress * adhesion_range + np.cbrt(
        3 * np.pi**5 * E_star**4 * R * adhesion_range**5 / adhesive_stress
    ) / 24
