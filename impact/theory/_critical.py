"""Critical (pull-off) values of the flat punch, cone, paraboloid, sphere, ellipsoid and power law
(§3.5.1–3.5.7), the jump-in at first touch and the turn-over threshold of f = c√r (3.80)."""

import jax
import jax.numpy as jnp

from .._core.runtime import float64
from ..profiles import Scalars, kappa
from ..profiles._base import as_float
from ._jkr import detach_length

_SPHERE_ITERATIONS = 64


@float64
def flat_punch_critical(radius: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Flat punch of radius ``radius`` [m] (3.37), same for both criteria:
    `a_c = radius`, `d_c = −√(2π a Δγ/E*)`, `F_c = −√(8π a³ E* Δγ)`."""
    a_c = as_float(radius)
    d_c = -detach_length(a_c, E_star, work_of_adhesion)
    return a_c, d_c, 2 * E_star * a_c * d_c


@float64
def power_law_critical(n: Scalars, c: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars):
    """Critical values for f = c rⁿ, n > 1/2 (3.74)–(3.76). With `s = √(πΔγ/(2E*))` and
    `K = κ(n) c`: `a_c = (ξ s/(nK))^(2/(2n−1))`, `d_c = s √a_c (ξ/n − 2)`,
    `F_c = E* s a_c^(3/2) (2ξ/(n+1) − 4)`."""
    s = jnp.sqrt(jnp.pi * work_of_adhesion / (2 * E_star))
    a_c = (xi * s / (n * kappa(n) * c)) ** (2 / (2 * n - 1))
    d_c = s * jnp.sqrt(a_c) * (xi / n - 2)
    F_c = E_star * s * a_c**1.5 * (2 * xi / (n + 1) - 4)
    return a_c, d_c, F_c


@float64
def cone_critical(theta: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars):
    """Cone of slope angle θ [rad] (3.40)–(3.41): `a_c = 2ξ²Δγ/(πE* tan²θ)`,
    `d_c = (ξ² − 2ξ)Δγ/(E* tanθ)`, `F_c = 2Δγ²(ξ⁴ − 4ξ³)/(πE* tan³θ)`."""
    t = jnp.tan(theta)
    a_c = 2 * xi**2 * work_of_adhesion / (jnp.pi * E_star * t**2)
    d_c = (xi**2 - 2 * xi) * work_of_adhesion / (E_star * t)
    F_c = 2 * work_of_adhesion**2 * (xi**4 - 4 * xi**3) / (jnp.pi * E_star * t**3)
    return a_c, d_c, F_c


@float64
def paraboloid_critical(R: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars):
    """Paraboloid f = r²/(2R) (3.45): `a_c = (πξ²R²Δγ/(8E*))^(1/3)`,
    `d_c = (π²ξΔγ²R/E*²)^(1/3) (ξ/4 − 1)`, `F_c = πξΔγR (ξ/6 − 1)`.
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
    beta = as_float(beta)

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


@float64
def ellipsoid_critical(R: Scalars, k: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars):
    """Ellipsoid f = R(1 − √(1 − k²r²)), g = kR x artanh(kx) (§3.5.5; R [m], k [1/m]).

    α = k a_c solves (3.54) with `β = ξ√(πΔγ/(2E* k R²))`; then, equal to (3.56) with the force
    factor `E*R/k` but free of its O(α³) cancellation in F_c,
    `d_c = R(α artanh α − 2β√α/ξ) = g(a_c) − Δl(a_c)`,
    `F_c = (E*R/k)[(1 + α²) artanh α − α − 4α^(3/2) β/ξ]`.
    Valid while α = k a_c < 1 is well inside the profile (half-space hypothesis: α ≲ 0.3).
    """
    beta = xi * jnp.sqrt(jnp.pi * work_of_adhesion / (2 * E_star * k * R**2))
    alpha = _sphere_alpha(beta)
    adhesion = 2 * beta * jnp.sqrt(alpha) / xi
    d_c = R * (alpha * jnp.arctanh(alpha) - adhesion)
    F_c = E_star * R / k * (_hertz_sphere_shape(alpha) - 2 * alpha * adhesion)
    return alpha / k, d_c, F_c


@float64
def sphere_critical(R: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars):
    """Sphere of radius R [m], g = x artanh(x/R) (3.54)–(3.56): α = a_c/R solves
    `artanh α + α/(1 − α²) = β/√α` with `β = ξ√(πΔγ/(2E*R))`; d_c, F_c from (3.56).
    Tends to the paraboloid (3.45) as a_c/R → 0."""
    return ellipsoid_critical(R, 1 / R, E_star, work_of_adhesion, xi)


@float64
def power_law_jump_in(n: Scalars, c: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Contact radius and force when a power-law body first touches (d = 0) under the
    reversible JKR law: g(a₀) = Δl(a₀), i.e. `a₀ = (2πΔγ/(E* κ² c²))^(1/(2n−1))`, and
    `F₀ = −2E* κ c a₀^(n+1)/(n+1)` (< 0, adhesive). Returns (a₀ [m], F₀ [N])."""
    K = kappa(n) * c
    a0 = (2 * jnp.pi * work_of_adhesion / (E_star * K**2)) ** (1 / (2 * n - 1))
    return a0, -2 * E_star * K * a0 ** (n + 1) / (n + 1)


@float64
def paraboloid_jump_in(R: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Jump-in of a paraboloid at first touch: `a₀³ = 2πΔγR²/E*`, `F₀ = −(4/3)πΔγR`, which is
    −(8/9)|F_c| with the force-control F_c. Returns (a₀ [m], F₀ [N])."""
    a0 = jnp.cbrt(2 * jnp.pi * work_of_adhesion * R**2 / E_star)
    return a0, -2 * E_star * a0**3 / (3 * R)


@float64
def power_law_half_threshold(E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars = 1):
    """c at which f = c√r turns over (3.80): `g = κ(½)c√x` against `Δl = √(2πΔγ/E*)√x`, so the
    displacement-controlled contact (ξ = 1) shrinks to nothing on unloading for
    `c > √(2π)/κ(½) √(Δγ/E*) = 1.9120 √(Δγ/E*)` and closes completely at first touch below it.
    Under force control (ξ = 3: `F = 2(κc/3 − √(2πΔγ/E*)) a^(3/2)`) the threshold is three times
    larger. Returns c [m^(1/2)]."""
    return xi * jnp.sqrt(2 * jnp.pi * work_of_adhesion / E_star) / kappa(0.5)
