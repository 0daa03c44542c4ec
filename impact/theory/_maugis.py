"""Maugis–Dugdale adhesion (§3.6–3.8), in numpy/scipy float64 whatever the jax setting.

Dugdale's law (3.147): the tensile stress σ0 [Pa] acts wherever the gap is below the range h [m],
and Δγ = σ0 h (3.4). The paraboloid f = r²/(2R) is normalized with its force-controlled JKR state
(3.169)–(3.170), ``paraboloid_critical(R, E*, Δγ, 3)``: ã = a/a_c, d̃ = d/|d_c| (|d_c| = a_c²/(3R)),
F̃ = F/F_A with F_A = (3/2)πRΔγ; κ = b/a > 1 is the adhesive zone radius b over the contact radius a.
"""

import jax
import numpy as np

from .._core.runtime import float64
from ..profiles import Scalars, kappa

_PULL_OFF_GRID = np.linspace(-50.0, 50.0, 4001)  # ln(κ − 1) scanned by ``maugis_pull_off``
_ARCTAN_SERIES = np.arange(1, 11)


@float64
def tabor_parameter(R: Scalars, adhesive_stress: Scalars, adhesion_range: Scalars, E_star: Scalars):
    """Tabor parameter `Λ = (3Rσ0²/(πhE*²))^(1/3)` (3.172); R, h [m], σ0, `E*` [Pa]. Equivalently
    `Λ = 3Rσ0/(2E* a_c)` with the JKR a_c (3.170), and `Λ = (3/8)^(1/3) λ` with Maugis's
    `λ = 2σ0 (R/(πΔγE*²))^(1/3)`."""
    return np.cbrt(3 * R * adhesive_stress**2 / (np.pi * adhesion_range * E_star**2))


@float64
def maugis_adhesive_stress(tabor: Scalars, R: Scalars, work_of_adhesion: Scalars, E_star: Scalars):
    """σ0 [Pa] giving the Tabor parameter Λ at fixed Δγ = σ0 h, (3.172) with (3.4):
    `σ0 = Λ (πE*²Δγ/(3R))^(1/3)`."""
    return tabor * np.cbrt(np.pi * E_star**2 * work_of_adhesion / (3 * R))


@float64
def maugis_range(tabor: Scalars, R: Scalars, work_of_adhesion: Scalars, E_star: Scalars):
    """Range h = Δγ/σ0 [m] (3.4) with σ0 of ``maugis_adhesive_stress``."""
    return work_of_adhesion / maugis_adhesive_stress(tabor, R, work_of_adhesion, E_star)


@float64
def tabor_criterion(R: Scalars, work_of_adhesion: Scalars, adhesion_range: Scalars, E_star: Scalars):
    """Left side of (3.181), `2RΔγ²(1 − 2/π)²/(E*²h³) = (2π/3)(1 − 2/π)² Λ³`: Tabor's μ (3.3) with
    z0 = h, times 2(1 − 2/π)². The DMT limit holds where it is ≪ 1."""
    return 2 * R * work_of_adhesion**2 * (1 - 2 / np.pi) ** 2 / (E_star**2 * adhesion_range**3)


@float64
def bradley_pull_off(R: Scalars, work_of_adhesion: Scalars):
    """Pull-off force [N] of a rigid paraboloid of radius R from a rigid plane under any law σ(s)
    with ∫σ ds = Δγ (3.141): F_A = 2πRΔγ."""
    return 2 * np.pi * R * work_of_adhesion


@float64
def dmt_pull_off(R: Scalars, work_of_adhesion: Scalars):
    """DMT pull-off force [N] of a paraboloid (3.142), (3.180): Bradley's 2πRΔγ, i.e. F̃_A = 4/3 in
    the units (3.170), the Λ → 0 limit of ``maugis_pull_off``."""
    return bradley_pull_off(R, work_of_adhesion)


@float64
def dmt_zone_radius(R: Scalars, adhesive_stress: Scalars, adhesion_range: Scalars, E_star: Scalars):
    """Adhesive zone radius b [m] of the paraboloid where contact begins (a = 0, the centre gap just
    closed): the positive root (3.178) of `b²/(2R) + (2σ0b/E*)(1 − 2/π) = h` (3.177);
    b ≈ √(2Rh) under (3.179)."""
    q = 2 * R * adhesive_stress / E_star * (1 - 2 / np.pi)
    return 2 * R * adhesion_range / (q + np.sqrt(q**2 + 2 * R * adhesion_range))


@float64
def dugdale_zone_width(E_star: Scalars, work_of_adhesion: Scalars, adhesive_stress: Scalars):
    """Width s = b − a [m] of the Maugis–Dugdale adhesive zone at the edge of a JKR-like contact:
    the edge is a crack tip with `K² = 2E*Δγ` (Griffith's balance, the energy release rate
    `K²/(2E*)` equal to Δγ), and Dugdale's (1960) zone of constant stress σ0 ahead of a crack tip is
    `s = (π/8)(K/σ0)²`, so `s = (π/4)E*Δγ/σ0² = (π/4)E*h/σ0`, for any body. For the paraboloid it
    is the leading term of (3.184), κ − 1 ≈ 1/(2ãΛ²): s/a_c = 1/(2Λ²) (a_c, Λ of (3.170),
    (3.172)), with corrections of order ã^(1/2)/Λ⁴. Against the exact (3.171)
    at the force-controlled pull-off the zone is 0.62, 0.92, 0.99 of s at Λ = 1, 3, 10; deeper
    contacts narrow it slowly (0.82 of s at ã = 5, Λ = 3); on the DMT side (Λ ≲ 1) the zone
    spans the contact and s overstates it."""
    return np.pi / 4 * E_star * work_of_adhesion / adhesive_stress**2


@float64
def power_law_dmt_pull_off(n: Scalars, c: Scalars, work_of_adhesion: Scalars, adhesion_range: Scalars):
    """DMT pull-off force [N] of f = c rⁿ (3.195): πσ0b² with f(b) = h, F_A = πΔγ h^((2−n)/n)/c^(2/n)
    (c [m^(1−n)]); the paraboloid n = 2, c = 1/(2R) gives 2πRΔγ."""
    return np.pi * work_of_adhesion * adhesion_range ** ((2 - n) / n) / c ** (2 / n)


def _zone_terms(a, b):
    """(√(b² − a²), arccos(a/b)) for 0 ≤ a ≤ b, accurate as a → b."""
    root = np.sqrt((b - a) * (b + a))
    return root, np.arctan2(root, a)


@float64
def maugis_paraboloid_state(
    a: Scalars, b: Scalars, R: Scalars, adhesive_stress: Scalars, adhesion_range: Scalars, E_star: Scalars
):
    """(residual [m], d [m], F [N]) of the paraboloid f = r²/(2R) at contact radius a and zone radius
    b ≥ a [m] (3.168): `d = a²/R − (2σ0/E*)√(b² − a²)`,
    `F = 2E*(ad − a³/(3R)) − σ0[2b² arccos(a/b) − 2a√(b² − a²)]`, and the residual of the range
    condition, `(2/π)[(b²/(2R) − d) arccos(a/b) + (a/(2R))√(b² − a²) − (2σ0/E*)(b − a)] − h`,
    which vanishes on the equilibrium curve."""
    root, angle = _zone_terms(a, b)
    stress = adhesive_stress / E_star
    d = a**2 / R - 2 * stress * root
    residual = 2 / np.pi * ((b**2 / (2 * R) - d) * angle + a * root / (2 * R) - 2 * stress * (b - a)) - adhesion_range
    F = 2 * E_star * (a * d - a**3 / (3 * R)) - adhesive_stress * (2 * b**2 * angle - 2 * a * root)
    return residual, d, F


@float64
def maugis_power_law_state(
    a: Scalars, b: Scalars, n: Scalars, c: Scalars, adhesive_stress: Scalars, adhesion_range: Scalars, E_star: Scalars
):
    """(residual [m], d [m], F [N]) of f = c rⁿ at contact radius a and zone radius b ≥ a [m] (3.192),
    with κ(n) of (3.193) and z = a²/b²: `d = cκ aⁿ − (2σ0/E*)√(b² − a²)`,
    `F = 2E*(da − cκ a^(n+1)/(n+1)) − σ0[2b² arccos(a/b) − 2a√(b² − a²)]`, and the range residual
    `c bⁿ[1 − 2κ/(π(n+1)) (a/b)^(n+1) ₂F₁(½, (n+1)/2; (n+3)/2; z)] − (2d/π) arccos(a/b)
    − 4σ0(b − a)/(πE*) − h`. n = 2, c = 1/(2R) is ``maugis_paraboloid_state``."""
    from scipy.special import hyp2f1  # imported here: so that `impact run` does not import scipy

    root, angle = _zone_terms(a, b)
    with jax.enable_x64(True):  # κ in float64 whatever the jax setting
        k = np.asarray(kappa(n), dtype=np.float64)
    ratio = a / b
    d = c * k * a**n - 2 * adhesive_stress / E_star * root
    inner = 2 * k / (np.pi * (n + 1)) * ratio ** (n + 1) * hyp2f1(0.5, (n + 1) / 2, (n + 3) / 2, ratio**2)
    residual = (
        c * b**n * (1 - inner)
        - 2 * d / np.pi * angle
        - 4 * adhesive_stress / (np.pi * E_star) * (b - a)
        - adhesion_range
    )
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


@float64
def maugis_paraboloid(kappa_ratio: Scalars, tabor: Scalars):
    """Normalized Maugis–Dugdale state of the paraboloid (3.171) at κ = b/a > 1 and Tabor parameter
    Λ (3.172): (ã, d̃, F̃) with ã the positive root of
    2/(3Λ) = ã²[(κ²/2 − 1) arccos(1/κ) + √(κ² − 1)/2] + (4/3)ãΛ[1 − κ + √(κ² − 1) arccos(1/κ)],
    d̃ = 3ã² − 4ãΛ√(κ² − 1), F̃ = ã³ − ã²Λ[κ² arccos(1/κ) + √(κ² − 1)]. κ → 1 is the compressed
    (Hertz/JKR) end, κ → ∞ the junction a → 0 (``maugis_junction_zone_radius``)."""
    return _maugis_curve(np.asarray(kappa_ratio, dtype=float) - 1, tabor)


@float64
def maugis_junction_zone_radius(tabor: Scalars):
    """b̃ = b/a_c where the paraboloid's contact begins (a = 0), (3.177) in the units (3.170):
    (3/2)b̃² + 4Λ(1 − 2/π)b̃ = 4/(πΛ), so b̃ = (8/(πΛ)) / (q + √(q² + 24/(πΛ))), q = 4Λ(1 − 2/π);
    ``dmt_zone_radius`` / a_c. There d̃ = −4Λb̃ and F̃ = −(π/2)Λb̃²."""
    q = 4 * tabor * (1 - 2 / np.pi)
    return 8 / (np.pi * tabor) / (q + np.sqrt(q**2 + 24 / (np.pi * tabor)))


@float64
def maugis_paraboloid_noncontact(zone_radius: Scalars, tabor: Scalars):
    """(d̃, F̃) of the paraboloid before contact (a = 0, centre gap open) at zone radius b̃ = b/a_c,
    (3.176) with d free: `d = b²/(2R) − 4σ0b/(πE*) − h` and `F = −πσ0b²` become
    d̃ = (3/2)b̃² − (8Λ/π)b̃ − 4/(πΛ), F̃ = −(π/2)Λb̃² (b̃ = 0: d = −h, the stress zone is born).
    nan beyond the junction b̃ > ``maugis_junction_zone_radius`` (the centre gap would be negative)."""
    b = np.asarray(zone_radius, dtype=float)
    d = 1.5 * b**2 - 8 * tabor / np.pi * b - 4 / (np.pi * tabor)
    F = -np.pi / 2 * tabor * b**2
    open_gap = b <= maugis_junction_zone_radius(tabor)
    return np.where(open_gap, d, np.nan), np.where(open_gap, F, np.nan)


def _pull_off(tabor):
    """−min F̃ over (3.171) and the non-contact branch for one Λ (see ``maugis_pull_off``)."""
    from scipy.optimize import minimize_scalar  # imported here: so that `impact run` does not import scipy

    def force(log_excess):
        return _maugis_curve(np.exp(log_excess), tabor)[2]

    values = force(_PULL_OFF_GRID)
    i = int(np.argmin(values))
    bracket = (_PULL_OFF_GRID[max(i - 1, 0)], _PULL_OFF_GRID[min(i + 1, _PULL_OFF_GRID.size - 1)])
    best = minimize_scalar(force, bounds=bracket, method="bounded", options={"xatol": 1e-10})
    junction = np.pi / 2 * tabor * maugis_junction_zone_radius(tabor) ** 2
    return max(-float(best.fun), -float(values[i]), junction)


@float64
def maugis_pull_off(tabor: Scalars):
    """Normalized Maugis–Dugdale pull-off of the paraboloid, F̃_A = F_A/((3/2)πRΔγ) = −min F̃ over
    the whole equilibrium curve (3.171) (force control), including its junction a = 0 with the
    non-contact branch (whose |F| is largest there). Minimized in ln(κ − 1) ∈ [−50, 50]: a scan
    of 4001 points, then bounded Brent around the lowest. Relative error against a 40-digit
    evaluation: 3e-16 for 1e-4 ≤ Λ ≤ 10, 1.5e-14 at Λ = 1e3, 5e-14 at 1e5 (the grid covers about
    1e-6 ≤ Λ ≤ 1e9).
    Tends to 4/3 (DMT) as Λ → 0 and 1 + 1/(12Λ²) (JKR) as Λ → ∞. Scalar or array Λ."""
    return np.vectorize(_pull_off, otypes=[float])(tabor)[()]


def _critical_state(tabor, xi):
    """(ã, d̃, F̃) of ``maugis_critical_state`` for one Λ."""
    from scipy.optimize import minimize_scalar  # imported here: so that `impact run` does not import scipy

    index = 2 if xi == 3 else 1  # force control: the lowest F̃; displacement control: the lowest d̃

    def value(log_excess):
        return _maugis_curve(np.exp(log_excess), tabor)[index]

    values = value(_PULL_OFF_GRID)
    i = int(np.argmin(values))
    bracket = (_PULL_OFF_GRID[max(i - 1, 0)], _PULL_OFF_GRID[min(i + 1, _PULL_OFF_GRID.size - 1)])
    best = minimize_scalar(value, bounds=bracket, method="bounded", options={"xatol": 1e-12})
    contact = np.array(_maugis_curve(np.exp(best.x if best.fun < values[i] else _PULL_OFF_GRID[i]), tabor))
    # Without contact: the junction, or (displacement control) the lowest d̃ of the zone,
    # at b̃ = 8Λ/(3π) where that lies before the junction.
    zone = min(maugis_junction_zone_radius(tabor), 8 * tabor / (3 * np.pi) if xi == 1 else np.inf)
    depth, force = maugis_paraboloid_noncontact(zone, tabor)
    zone_state = np.array([0.0, depth, force])
    return tuple(contact if contact[index] < zone_state[index] else zone_state)


@float64
def maugis_critical_state(tabor: Scalars, xi: int = 3):
    """Normalized state (ã, d̃, F̃) (3.169) that ends a quasi-static Maugis–Dugdale contact of the
    paraboloid: under force control (ξ = 3) the lowest F̃ of the whole equilibrium curve (3.171)
    with its zone without contact (3.176) (F̃ = −``maugis_pull_off``), under displacement control
    (ξ = 1) its lowest d̃. The zone's lowest d̃ (3.176) lies at b̃ = 8Λ/(3π), before the junction
    for Λ < 0.82: there the contact opens smoothly and the zone lets go at a tiny force
    F̃ = −32Λ³/(9π). Minimized as ``maugis_pull_off``; ã and d̃ at a minimum of F̃ (and ã, F̃
    at one of d̃) to about 1e-8 relative (the position of the extremum), the minimum itself to
    round-off. Scalar Λ."""
    return _critical_state(float(tabor), int(xi))


@float64
def maugis_pull_off_force(R: Scalars, adhesive_stress: Scalars, adhesion_range: Scalars, E_star: Scalars):
    """Maugis–Dugdale pull-off force [N] of a paraboloid: F̃_A(Λ) (3/2)πRσ0h."""
    tabor = tabor_parameter(R, adhesive_stress, adhesion_range, E_star)
    return maugis_pull_off(tabor) * 1.5 * np.pi * R * adhesive_stress * adhesion_range


@float64
def maugis_pull_off_large_tabor(tabor: Scalars):
    """Pull-off for Λ ≫ 1, (3.189) corrected: F̃_A = 1 + 1/(12Λ²) + O(Λ⁻⁴) (printed 11/(12Λ²);
    see the misprints listed in ``impact.theory``)."""
    return 1 + 1 / (12 * np.asarray(tabor, dtype=float) ** 2)


@float64
def maugis_pull_off_force_large_tabor(R: Scalars, adhesive_stress: Scalars, adhesion_range: Scalars, E_star: Scalars):
    """Dimensional (3.190) corrected [N]: `F_A = (3/2)πRσ0h + (1/24)(3π⁵E*⁴Rh⁵/σ0)^(1/3)`
    (printed 11/24), = (3/2)πRΔγ ``maugis_pull_off_large_tabor``(Λ)."""
    return (
        1.5 * np.pi * R * adhesive_stress * adhesion_range
        + np.cbrt(3 * np.pi**5 * E_star**4 * R * adhesion_range**5 / adhesive_stress) / 24
    )
