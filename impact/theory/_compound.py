"""Quasi-static indentation of the profiles of §3.5.8–3.5.13 with two regimes: a flat tip (truncated
cone and paraboloid), a parabolic cap (on a flat punch, a cone, a paraboloid) or a rounded edge.

Each flank equation reads ψ(φ) = β with φ = arccos(b/a_c) and ψ a fixed function of the angle:
g'(a) = ξ √(πΔγ/(2E*a)) (3.35) written with a = b/cos φ. ψ has one interior minimum (one root
pair) or rises monotonically (one root).
"""

import functools

import jax
import jax.numpy as jnp

from .._core.runtime import float64
from .._core.search import golden_section, sign_change
from ..profiles import Scalars
from ..profiles._base import as_float
from ._critical import flat_punch_critical, paraboloid_critical
from ._jkr import detach_length

_ANGLE_STEPS = 100
_ANGLE_EDGE = 1e-12


@functools.partial(jax.jit, static_argnums=0)
def _angle_roots(psi, beta, parameter=0.0):
    """(φ1, φ2, ψ_min): the roots of ψ(φ, parameter) = β left and right of ψ's minimum (nan where
    none). Compiled once per ψ (a module-level function)."""
    beta, parameter = jnp.broadcast_arrays(as_float(beta), as_float(parameter))

    def shape(phi):
        return psi(phi, parameter)

    lo = jnp.full_like(beta, _ANGLE_EDGE)
    hi = jnp.full_like(beta, jnp.pi / 2 - _ANGLE_EDGE)
    low, high = golden_section(shape, lo, hi, _ANGLE_STEPS)
    middle = 0.5 * (low + high)
    least = shape(middle)
    left = sign_change(lambda p: shape(p) - beta, lo, middle, _ANGLE_STEPS)
    right = sign_change(lambda p: shape(p) - beta, middle, hi, _ANGLE_STEPS)
    has_left = (least <= beta) & (shape(lo) >= beta)
    has_right = least <= beta
    return jnp.where(has_left, left, jnp.nan), jnp.where(has_right, right, jnp.nan), least


def _deeper(xi, first, second):
    """Of two critical states (a, d, F), the one that ends the contact: the lower indentation
    under displacement control (ξ = 1), the lower force under force control (ξ = 3); a state
    with nan values does not exist."""
    displacement = as_float(xi) < 2
    key1 = jnp.where(displacement, first[1], first[2])
    key2 = jnp.where(displacement, second[1], second[2])
    take_second = jnp.isnan(key1) | (key2 < key1)
    take_second = take_second & ~jnp.isnan(key2)
    return tuple(jnp.where(take_second, s, f) for f, s in zip(first, second, strict=True))


def _flat_tip(b, E_star, work_of_adhesion):
    """The state where the contact sits on a flat tip of radius b, (3.90): the flat punch (3.37)."""
    return flat_punch_critical(b, E_star, work_of_adhesion)


def _truncated_cone_psi(phi, _=None):
    return (phi + 1 / jnp.tan(phi)) / jnp.sqrt(jnp.cos(phi))


@float64
def truncated_cone_beta(b: Scalars, theta: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars):
    """`β = (ξ/tanθ) √(πΔγ/(2E* b))` of the truncated cone (3.88); b [m] flat-tip radius."""
    return xi / jnp.tan(theta) * jnp.sqrt(jnp.pi * work_of_adhesion / (2 * E_star * b))


@float64
def truncated_cone_threshold():
    """Smallest β for which (3.87) φ + cot φ = β √cos φ has roots: 2.1219 (printed 2.125)."""
    return _angle_roots(_truncated_cone_psi, 10.0)[2]


@float64
def truncated_cone_critical(
    b: Scalars, theta: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars, root: int = 1
):
    """Critical state on the flank of a truncated cone, (3.87)–(3.89): φ = arccos(b/a_c) solves
    `φ + cot φ = β √cos φ`; root 0 is the smaller angle, root 1 the larger. Then
    `d_c = a_c tanθ [φ(1 − 2/ξ) − (2/ξ) cot φ]`,
    `F_c = E* tanθ a_c² [φ(1 − 4/ξ) + cot φ (sin²φ − 4/ξ)]`. nan where (3.87) has no root
    (β < 2.1219). Returns (a_c [m], d_c [m], F_c [N])."""
    beta = truncated_cone_beta(b, theta, E_star, work_of_adhesion, xi)
    phi = _angle_roots(_truncated_cone_psi, beta)[root]
    t = jnp.tan(theta)
    a = b / jnp.cos(phi)
    d = a * t * (phi * (1 - 2 / xi) - 2 / xi / jnp.tan(phi))
    F = E_star * t * a**2 * (phi * (1 - 4 / xi) + (jnp.sin(phi) ** 2 - 4 / xi) / jnp.tan(phi))
    return a, d, F


@float64
def truncated_cone_pull_off(b: Scalars, theta: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars):
    """Where a truncated cone loaded past its critical radii loses contact: the deeper of the flat
    tip (3.90) and the flank's larger root (3.89) (see the misprints listed in ``impact.theory``).
    Returns (a, d, F)."""
    flank = truncated_cone_critical(b, theta, E_star, work_of_adhesion, xi, 1)
    return _deeper(xi, _flat_tip(b, E_star, work_of_adhesion), flank)


def _truncated_paraboloid_psi(phi, _=None):
    s, c = jnp.sin(phi), jnp.cos(phi)
    return (1 + s**2) / (s * c) / jnp.sqrt(c)


@float64
def truncated_paraboloid_beta(b: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars):
    """`β = (ξR/b) √(πΔγ/(2E* b))` of the truncated paraboloid (3.96)."""
    return xi * R / b * jnp.sqrt(jnp.pi * work_of_adhesion / (2 * E_star * b))


@float64
def truncated_paraboloid_threshold():
    """Smallest β for which (3.95) has roots: 3.0945 (printed 3.095)."""
    return _angle_roots(_truncated_paraboloid_psi, 10.0)[2]


@float64
def truncated_paraboloid_critical(
    b: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars, root: int = 1
):
    """Critical state on the flank of a truncated paraboloid, (3.95)–(3.97):
    `(1 + sin²φ)/(sin φ cos φ) = β √cos φ`, `a_c = b/cos φ`,
    `d_c = (a_c²/R) sin φ (1 − 2/ξ − 2/(ξ sin²φ))`,
    `F_c = (2E* a_c³/(3R)) sin φ [3 − sin²φ − (6/ξ)(1 + 1/sin²φ)]`. nan without a root."""
    beta = truncated_paraboloid_beta(b, R, E_star, work_of_adhesion, xi)
    phi = _angle_roots(_truncated_paraboloid_psi, beta)[root]
    s = jnp.sin(phi)
    a = b / jnp.cos(phi)
    d = a**2 / R * s * (1 - 2 / xi - 2 / (xi * s**2))
    F = 2 * E_star * a**3 / (3 * R) * s * (3 - s**2 - 6 / xi * (1 + 1 / s**2))
    return a, d, F


@float64
def truncated_paraboloid_pull_off(b: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars):
    """The deeper of the flat tip (flat punch, §3.5.9) and the flank's larger root (3.97)."""
    flank = truncated_paraboloid_critical(b, R, E_star, work_of_adhesion, xi, 1)
    return _deeper(xi, _flat_tip(b, E_star, work_of_adhesion), flank)


@float64
def capped_flat_punch_thresholds(b: Scalars, R: Scalars, E_star: Scalars):
    """(Δγ1, Δγ2) of the flat punch with parabolic cap (3.101): the works of adhesion at which
    the JKR critical radius of the cap reaches the punch radius b under force control (ξ = 3)
    and displacement control (ξ = 1): `Δγ2 = 9Δγ1 = 8E*b³/(πR²)`."""
    second = 8 * E_star * b**3 / (jnp.pi * R**2)
    return second / 9, second


@float64
def capped_flat_punch_critical(b: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars):
    """Flat punch of radius b with a parabolic cap of radius R (§3.5.10, (3.98)–(3.101)):
    the JKR critical state (3.45) where its radius lies on the cap, else the punch edge `a_c = b`
    with `d_c = b²/R − √(2πbΔγ/E*)` and `F_c = 2E*(d_c b − b³/(3R))` (3.99)."""
    a_jkr, d_jkr, F_jkr = paraboloid_critical(R, E_star, work_of_adhesion, xi)
    d_edge = b**2 / R - detach_length(b, E_star, work_of_adhesion)
    F_edge = 2 * E_star * (d_edge * b - b**3 / (3 * R))
    on_cap = a_jkr < b
    return jnp.where(on_cap, a_jkr, b), jnp.where(on_cap, d_jkr, d_edge), jnp.where(on_cap, F_jkr, F_edge)


@float64
def capped_flat_punch_normalized_force(d_hat: Scalars, b_hat: Scalars):
    """F̂ = (d̂ b̂ − b̂³)/2 at the punch edge â = b̂ (3.104), normalized as in (3.102)."""
    return 0.5 * (d_hat * b_hat - b_hat**3)


def _capped_cone_psi(phi, _=None):
    s, c = jnp.sin(phi), jnp.cos(phi)
    return (2 * (1 - s) / c + phi) / jnp.sqrt(c)


@float64
def capped_cone_beta(b: Scalars, theta: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars):
    """`β = (ξ/tanθ) √(πΔγ/(2E* b))` of the cone with parabolic cap (3.111)."""
    return truncated_cone_beta(b, theta, E_star, work_of_adhesion, xi)


@float64
def capped_cone_threshold():
    """Smallest β for which (3.110) has roots: 1.7967 (printed 1.795); the smaller root exists
    up to β = 2, where the cap's own JKR critical radius reaches b."""
    return _angle_roots(_capped_cone_psi, 10.0)[2]


@float64
def capped_cone_critical(
    b: Scalars, theta: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars, root: int = 1
):
    """Critical state on the conical flank of a cone with parabolic cap (cap radius b/tanθ),
    (3.110)–(3.113): `2(1 − sin φ)/cos φ + φ = β √cos φ`, `a_c = b/cos φ`,
    `d_c = a_c tanθ [(1 − sin φ)/cos φ (1 − 4/ξ) + φ(1 − 2/ξ)]`,
    `F_c = E* a_c² tanθ [φ(1 − 4/ξ) + (1 − sin φ)/cos φ (4/3 − 8/ξ) + sin φ cos φ/3]`.
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


@float64
def capped_cone_pull_off(b: Scalars, theta: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars):
    """Where a cone with parabolic cap loaded past b loses contact: the deeper of the cap's JKR
    state (R = b/tanθ, for β < 2) and the flank's larger root (β ≥ 1.7967)."""
    cap = _on_cap(b / jnp.tan(theta), b, E_star, work_of_adhesion, xi)
    return _deeper(xi, cap, capped_cone_critical(b, theta, E_star, work_of_adhesion, xi, 1))


def _capped_paraboloid_psi(phi, ratio):
    s, c = jnp.sin(phi), jnp.cos(phi)
    return (2 + ratio * (1 + s**2) / s) / c / jnp.sqrt(c)


@float64
def capped_paraboloid_beta(b: Scalars, R1: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars):
    """`β = (ξR1/b) √(πΔγ/(2E* b))` of the paraboloid with parabolic cap (3.121)."""
    return truncated_paraboloid_beta(b, R1, E_star, work_of_adhesion, xi)


@float64
def capped_paraboloid_threshold(R1: Scalars, R2: Scalars):
    """`β0(R1/R*)`, the smallest β with roots of (3.120), `R* = R1R2/(R1 − R2)` (3.115); the chapter's
    fit (3.123) is `2.2 + 3.2 R1/R*` (exact: 2 at `R1/R* = 0`, `3.0945 R1/R*` for `R1/R* → ∞`)."""
    ratio = R1 / R2 - 1.0
    return _angle_roots(_capped_paraboloid_psi, 1e300 * jnp.ones_like(as_float(ratio)), ratio)[2]


@float64
def capped_paraboloid_critical(
    b: Scalars, R1: Scalars, R2: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars, root: int = 1
):
    """Critical state beyond the cap of a paraboloid R2 with a cap R1 ≥ R2 up to b, (3.120)–(3.122):
    `(1/cos φ)(2 + (R1/R*)(1 + sin²φ)/sin φ) = β √cos φ`, `a_c = b/cos φ`,
    `d_c = (a_c²/R1)[1 − 4/ξ + (R1/R*) sin φ (1 − 2/ξ − 2/(ξ sin²φ))]`,
    `F_c = (4E* a_c³/(3R1)){1 − 6/ξ + (R1/(2R*)) sin φ [3 − sin²φ − (6/ξ)(1 + 1/sin²φ)]}`."""
    ratio = R1 / R2 - 1.0
    beta = capped_paraboloid_beta(b, R1, E_star, work_of_adhesion, xi)
    phi = _angle_roots(_capped_paraboloid_psi, beta, ratio)[root]
    s = jnp.sin(phi)
    a = b / jnp.cos(phi)
    d = a**2 / R1 * (1 - 4 / xi + ratio * s * (1 - 2 / xi - 2 / (xi * s**2)))
    F = 4 * E_star * a**3 / (3 * R1) * (1 - 6 / xi + ratio / 2 * s * (3 - s**2 - 6 / xi * (1 + 1 / s**2)))
    return a, d, F


@float64
def capped_paraboloid_pull_off(
    b: Scalars, R1: Scalars, R2: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars
):
    """The deepest of the cap's JKR state (radius R1, for β < 2), the cap's edge a = b (where the
    flank's slope jumps: `d = b²/R1 − Δl(b)`, `F = 4E*b³/(3R1) − √(8πb³E*Δγ)`) and the larger root
    (3.122). For 2 < β < β0 neither root exists and the contact is lost at the edge, not at the
    JKR state of R1 as §3.5.12 states."""
    cap = _on_cap(R1, b, E_star, work_of_adhesion, xi)
    b = as_float(b)
    edge = (
        b,
        b**2 / R1 - detach_length(b, E_star, work_of_adhesion),
        4 * E_star * b**3 / (3 * R1) - jnp.sqrt(8 * jnp.pi * b**3 * E_star * work_of_adhesion),
    )
    flank = capped_paraboloid_critical(b, R1, R2, E_star, work_of_adhesion, xi, 1)
    return _deeper(xi, _deeper(xi, cap, edge), flank)


@jax.jit
def _rounded_angle(beta):
    """The one root of (2 tan φ − φ)/√cos φ = β (rising from 0 to ∞ on (0, π/2))."""
    beta = as_float(beta)
    lo = jnp.full_like(beta, _ANGLE_EDGE)
    hi = jnp.full_like(beta, jnp.pi / 2 - _ANGLE_EDGE)
    return sign_change(lambda p: (2 * jnp.tan(p) - p) / jnp.sqrt(jnp.cos(p)) - beta, lo, hi, _ANGLE_STEPS)


@float64
def rounded_flat_punch_beta(b: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars):
    """`β = (ξR/b) √(πΔγ/(2E* b))` of the flat punch with rounded edge (3.130)."""
    return truncated_paraboloid_beta(b, R, E_star, work_of_adhesion, xi)


@float64
def rounded_flat_punch_critical(b: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars, xi: Scalars):
    """Flat punch with base radius b and edges rounded with radius R, (3.129)–(3.131): the one
    root of `2 tan φ − φ = β √cos φ`, `a_c = b/cos φ`,
    `d_c = (a_c²/R)[sin φ (1 − 4/ξ) − φ cos φ (1 − 2/ξ)]`,
    `F_c = (4E* a_c³/(3R))[sin φ (1 − 6/ξ − cos²φ/4) − (3/4) φ cos φ (1 − 4/ξ)]`."""
    phi = _rounded_angle(rounded_flat_punch_beta(b, R, E_star, work_of_adhesion, xi))
    s, c = jnp.sin(phi), jnp.cos(phi)
    a = b / c
    d = a**2 / R * (s * (1 - 4 / xi) - phi * c * (1 - 2 / xi))
    F = 4 * E_star * a**3 / (3 * R) * (s * (1 - 6 / xi - c**2 / 4) - 0.75 * phi * c * (1 - 4 / xi))
    return a, d, F
