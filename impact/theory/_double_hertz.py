"""Greenwood–Johnson double-Hertz adhesion of a paraboloid f = r²/(2R) (§3.9, Greenwood and
Johnson 1998), in jax.numpy: jit, vmap and grad work through every function.

The stress is the Hertz distribution of the contact radius a plus k times the difference of two
Hertz distributions of radii c > a and a (3.196), (3.198), (3.200); k > 0 is the interface's
constant (k → ∞: JKR, k → 0: DMT). The outer radius c follows from the work of adhesion (3.201),

    Δγ = k(k+1)·2E*/(3πR²)·(c − a)²(c + 2a),   i.e.  u²(u + 3a) = K := 3πR²Δγ/(2E*k(k+1)),

with the ring width u = c − a ≥ 0; then (u written out, so the JKR limit k → ∞, u → 0 does not
cancel)

    F = (1+k)·4E*a³/(3R) − k·4E*c³/(3R) = (4E*/(3R))·(a³ − k·u·(3a² + 3au + u²)),
    d = (1+k)a²/R − k·c²/R = (a² − k·u·(2a + u))/R.

One curve parametrised by a ≥ 0: it starts at a = 0 with c₀ = K^(1/3), d₀ = −k·c₀²/R and
F₀ = −2πRΔγ/(1+k) (the interaction switches on there: a body further away feels no force).
Along it dc/da = 2a/(a + c), so dd/da = (2a/R)·(1 − k·u/(a + c)) and
dF/da = (4E*a/R)·((1+k)·a − 2k·c²/(a + c)). With ρ = a/c:

- displacement control (and a free body): d(a) rises from a = 0 when k ≤ 1 (the contact ends at
  a = 0, at d₀); for k > 1 it falls to its minimum at ρ = (k − 1)/(k + 1) and rises beyond, so
  the states below that minimum are unstable: loading jumps in at d₀ onto the rising branch,
  unloading jumps out from the minimum;
- force control: F(a) falls from F₀ to its minimum at (1+k)·ρ·(1 + ρ) = 2k,
  ρ = (√((9k + 1)/(k + 1)) − 1)/2, for every k > 0: the pull-off force.

At a critical ratio ρ the state is closed-form: c³ = K/((1 − ρ)²(1 + 2ρ)), and the limits are
Thornton's and Bradley's: F → −(3/2)πRΔγ (JKR, k → ∞) and F → −2πRΔγ (DMT, k → 0).

Equivalent Maugis–Dugdale parameters (a choice, stated): at the onset a = 0 the adhesive stress
is the Hertz distribution of radius c₀ scaled by k, its peak σ_max = k·2E*c₀/(πR) (3.200) at
the centre; a Dugdale law of the same work Δγ = σ₀h (3.4) and σ₀ = σ_max has the range
h = Δγ/σ_max and the Tabor parameter (3.172) Λ = (36k²/(π³(1 + k)))^(1/3), a function of k alone.
"""

import jax
import jax.numpy as jnp

from .._core.runtime import float64
from ..profiles import Scalars

_NEWTON_STEPS = 8


def ring_width(a, constant):
    """u ≥ 0 with u²(u + 3a) = K (`constant`): Newton on ln(u³ + 3a·u²) = ln K in ln u, a convex
    increasing function, from the smaller one-term root, which lies above the root (so the
    iteration falls monotonically; from at most ln(2)/3 off, 8 steps reach round-off). The steps
    run under stop_gradient and one more outside carries the derivatives."""
    a = jnp.asarray(a)
    log_constant = jnp.log(constant)
    log_three_a = jnp.log(3.0 * a)

    def residual(log_u):
        return jnp.logaddexp(3.0 * log_u, log_three_a + 2.0 * log_u) - log_constant

    def newton(log_u):
        value, slope = jax.jvp(residual, (log_u,), (jnp.ones_like(log_u),))
        return log_u - value / slope

    start = jnp.minimum(log_constant / 3.0, 0.5 * (log_constant - log_three_a))
    settled = jax.lax.stop_gradient(
        jax.lax.fori_loop(0, _NEWTON_STEPS, lambda _, x: newton(x), jax.lax.stop_gradient(start))
    )
    return jnp.exp(newton(settled))


def _ring_constant(k, R, E_star, work_of_adhesion):
    """K = 3πR²Δγ/(2E*k(k+1)) [m³] of (3.201)."""
    return 3.0 * jnp.pi * R**2 * work_of_adhesion / (2.0 * E_star * k * (k + 1.0))


@float64
def double_hertz_outer_radius(a: Scalars, k: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Outer radius c [m] of the double-Hertz stress at contact radius a [m]: the root c ≥ a of
    (3.201), `Δγ = k(k+1)·2E*/(3πR²)·(c − a)²(c + 2a)`."""
    return a + ring_width(a, _ring_constant(k, R, E_star, work_of_adhesion))


@float64
def double_hertz_force(a: Scalars, k: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Normal force F [N] at contact radius a [m]: `(1+k)·4E*a³/(3R) − k·4E*c³/(3R)`, the integral
    of the stress (3.198), (3.200)."""
    u = ring_width(a, _ring_constant(k, R, E_star, work_of_adhesion))
    return 4.0 * E_star / (3.0 * R) * (a**3 - k * u * (3.0 * a**2 + 3.0 * a * u + u**2))


@float64
def double_hertz_indentation(a: Scalars, k: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Indentation d [m] at contact radius a [m]: (1+k)a²/R − k·c²/R, Hertz's a²/R plus k times
    the constant displacement (3.197)."""
    u = ring_width(a, _ring_constant(k, R, E_star, work_of_adhesion))
    return (a**2 - k * u * (2.0 * a + u)) / R


def _critical_ratio_gap(k, xi):
    """(ρ, 1 − ρ) of the state that ends the contact: force control (ξ = 3) the minimum of F,
    displacement control (ξ = 1) the minimum of d (ρ = 0 for k ≤ 1); 1 − ρ without cancellation."""
    root = jnp.sqrt((9.0 * k + 1.0) / (k + 1.0))
    force_gap = 4.0 / ((k + 1.0) * (3.0 + root))
    depth_gap = jnp.where(k > 1.0, 2.0 / (k + 1.0), 1.0)
    gap = jnp.where(xi == 3, force_gap, depth_gap)
    return 1.0 - gap, gap


@float64
def double_hertz_pull_off(k: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars = 3):
    """Critical state (a [m], d [m], F [N]) that ends the contact, under force control (ξ = 3:
    the minimum of F(a), the pull-off force) or displacement control and for a free body (ξ = 1:
    the minimum of d(a); the onset a = 0 when k ≤ 1). With ρ = a/c from `_critical_ratio_gap`,
    `c³ = K/((1 − ρ)²(1 + 2ρ))` (3.201), `F = (4E*c³/(3R))·(1 − (1+k)(1 − ρ)(1 + ρ + ρ²))` and
    `d = (c²/R)·(1 − (1+k)(1 − ρ)(1 + ρ))`."""
    ratio, gap = _critical_ratio_gap(jnp.asarray(k, float), xi)
    outer = jnp.cbrt(_ring_constant(k, R, E_star, work_of_adhesion) / (gap**2 * (1.0 + 2.0 * ratio)))
    force = 4.0 * E_star * outer**3 / (3.0 * R) * (1.0 - (1.0 + k) * gap * (1.0 + ratio + ratio**2))
    depth = outer**2 / R * (1.0 - (1.0 + k) * gap * (1.0 + ratio))
    return ratio * outer, depth, force


@float64
def double_hertz_onset(k: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Where the interaction starts, a = 0: (c₀ [m], d₀ [m], F₀ [N]) with c₀³ = K (3.201),
    `d₀ = −k·c₀²/R` and `F₀ = −k·4E*c₀³/(3R) = −2πRΔγ/(1 + k)`."""
    outer = jnp.cbrt(_ring_constant(k, R, E_star, work_of_adhesion))
    return outer, -k * outer**2 / R, -2.0 * jnp.pi * R * work_of_adhesion / (1.0 + k)


@float64
def double_hertz_adhesive_stress(k: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Equivalent Dugdale stress σ₀ [Pa]: the peak tensile stress at the onset, `k·2E*c₀/(πR)`
    (3.200) at r = 0, a = 0."""
    outer = jnp.cbrt(_ring_constant(k, R, E_star, work_of_adhesion))
    return k * 2.0 * E_star * outer / (jnp.pi * R)


@float64
def double_hertz_range(k: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Equivalent Dugdale range h = Δγ/σ₀ [m] (3.4) with σ₀ of `double_hertz_adhesive_stress`."""
    return work_of_adhesion / double_hertz_adhesive_stress(k, R, E_star, work_of_adhesion)


@float64
def double_hertz_tabor_parameter(k: Scalars):
    """Equivalent Tabor parameter Λ = (36k²/(π³(1 + k)))^(1/3): (3.172) with the equivalent σ₀
    and h; Λ ≈ (36k/π³)^(1/3) as k → ∞ (JKR), ≈ (36/π³)^(1/3)·k^(2/3) as k → 0 (DMT)."""
    return jnp.cbrt(36.0 * k**2 / (jnp.pi**3 * (1.0 + k)))


@float64
def double_hertz_factor(tabor: Scalars):
    """k of the equivalent Tabor parameter Λ (the inverse of `double_hertz_tabor_parameter`):
    the positive root of k² = q·(1 + k), q = π³Λ³/36."""
    q = jnp.pi**3 * tabor**3 / 36.0
    return 0.5 * (q + jnp.sqrt(q**2 + 4.0 * q))
