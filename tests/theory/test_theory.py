"""Closed forms of impact.theory against independent numerics (scipy quadrature, root finding,
ODE integration) built here from the profile f(r) alone, not from the rest of the package."""

import jax
import jax.numpy as jnp
import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq
from scipy.special import gamma

from impact import theory

E_STAR, DGAMMA = 1.0e6, 0.05  # Pa, J/m²: soft and sticky, so that a_c/R is not small
MAT = (E_STAR, DGAMMA)
QUAD = dict(epsabs=0.0, epsrel=1e-13, limit=200)
ROOT = dict(xtol=1e-300, rtol=1e-15)


def kap(n):
    return np.sqrt(np.pi) * gamma(n / 2 + 1) / gamma((n + 1) / 2)


def c_of(n):
    """Power-law prefactor with f(1 µm) = 0.1 µm, so that a_c, a₀ are of order micrometres."""
    return 0.1 * 1e-6 ** (1 - n)


def dl(a):
    """Rule of Heß (3.26)."""
    return np.sqrt(2 * np.pi * a * DGAMMA / E_STAR)


# --- independent MDR transform (3.24): g(x) = x ∫₀^{π/2} f'(x sinθ) dθ -------------------------


def mdr(df, d2f):
    """g, g', G = ∫₀ g from f' and f'' by quadrature (r = x sinθ removes the singularity)."""

    def g(x):
        return x * quad(lambda t: df(x * np.sin(t)), 0, np.pi / 2, **QUAD)[0]

    def dg(x):
        rest = quad(lambda t: d2f(x * np.sin(t)) * np.sin(t), 0, np.pi / 2, **QUAD)[0]
        return g(x) / x + x * rest

    def G(a):
        return quad(g, 0, a, **QUAD)[0]

    return g, dg, G


def power_law_profile(n, c):
    return mdr(lambda r: n * c * r ** (n - 1), lambda r: n * (n - 1) * c * r ** (n - 2))


def ellipsoid_profile(R, k):
    return mdr(
        lambda r: R * k**2 * r / np.sqrt(1 - (k * r) ** 2),
        lambda r: R * k**2 / (1 - (k * r) ** 2) ** 1.5,
    )


def test_mdr_profiles_closed_forms():
    """The test transform reproduces κ(n) c xⁿ and, for the ellipsoid, g = kR x artanh(kx)
    (the kR factor that (3.57) drops from d(a)); rtol 1e-11."""
    for n in (0.75, 1.5, 3.0):
        assert np.isclose(float(theory.kappa(n)), kap(n), rtol=1e-13, atol=0)
        assert np.isclose(power_law_profile(n, 2.0)[0](0.7), kap(n) * 2.0 * 0.7**n, rtol=1e-11, atol=0)
    R, k, x = 2e-6, 3e5, 2e-6
    assert np.isclose(ellipsoid_profile(R, k)[0](x), k * R * x * np.arctanh(k * x), rtol=1e-11, atol=0)


# --- critical values: stability (3.35), equilibrium (3.27), force (3.28) -----------------------

R_SPH, R_ELL, K_ELL = 1e-6, 2e-6, 3e5
CRITICAL_CASES = {
    "cone": (lambda xi: theory.cone_critical(0.3, *MAT, xi), power_law_profile(1.0, np.tan(0.3))),
    "paraboloid": (
        lambda xi: theory.paraboloid_critical(R_SPH, *MAT, xi),
        power_law_profile(2.0, 0.5 / R_SPH),
    ),
    "sphere": (
        lambda xi: theory.sphere_critical(R_SPH, *MAT, xi),
        mdr(lambda r: r / np.sqrt(R_SPH**2 - r**2), lambda r: R_SPH**2 / (R_SPH**2 - r**2) ** 1.5),
    ),
    "ellipsoid": (
        lambda xi: theory.ellipsoid_critical(R_ELL, K_ELL, *MAT, xi),
        ellipsoid_profile(R_ELL, K_ELL),
    ),
    **{
        f"power{n}": (
            lambda xi, n=n: theory.power_law_critical(n, c_of(n), *MAT, xi),
            power_law_profile(n, c_of(n)),
        )
        for n in (0.75, 1.5, 3.0, 4.0)
    },
}


@pytest.mark.parametrize("xi", [1.0, 3.0])
@pytest.mark.parametrize("name", sorted(CRITICAL_CASES))
def test_critical_values_satisfy_mdr_conditions(name, xi):
    """g'(a_c) = ξ√(πΔγ/(2E* a_c)), d_c = g − Δl, F_c = 2E*(a_c d_c − G): rtol 1e-10, scaled
    by the size of the terms (d_c = 0 for n = 1.5, ξ = 3)."""
    critical, (g, dg, G) = CRITICAL_CASES[name]
    a_c, d_c, F_c = map(float, critical(xi))
    assert np.isclose(dg(a_c), xi * np.sqrt(np.pi * DGAMMA / (2 * E_STAR * a_c)), rtol=1e-10, atol=0)
    assert abs(d_c - (g(a_c) - dl(a_c))) <= 1e-10 * (g(a_c) + dl(a_c))
    F_scale = 2 * E_STAR * (a_c * abs(d_c) + G(a_c))
    assert abs(F_c - 2 * E_STAR * (a_c * d_c - G(a_c))) <= 1e-10 * F_scale


def test_flat_punch_critical():
    """(3.37) is (3.27)-(3.28) with g = 0 inside the punch; rtol 1e-14."""
    a, d_c, F_c = map(float, theory.flat_punch_critical(3e-6, *MAT))
    assert a == 3e-6
    assert np.isclose(d_c, -dl(a), rtol=1e-14, atol=0)
    assert np.isclose(F_c, -np.sqrt(8 * np.pi * a**3 * E_STAR * DGAMMA), rtol=1e-14, atol=0)


@pytest.mark.parametrize("xi", [1.0, 3.0])
def test_special_cases_agree(xi):
    """n = 2, c = 1/(2R) is the paraboloid and n = 1, c = tanθ the cone (rtol 1e-13); the
    sphere tends to the paraboloid with the derived O((a_c/R)²) coefficients (to 10 (a_c/R)²,
    the next order; this also catches the O(α³) cancellation of (3.56) in F_c)."""
    R, theta = 1e-6, 0.4
    assert np.allclose(
        theory.power_law_critical(2, 0.5 / R, *MAT, xi), theory.paraboloid_critical(R, *MAT, xi), rtol=1e-13, atol=0
    )
    assert np.allclose(
        theory.power_law_critical(1, np.tan(theta), *MAT, xi), theory.cone_critical(theta, *MAT, xi), rtol=1e-13, atol=0
    )
    # g = x²/R + x⁴/(3R³) + … shifts (a_c, d_c, F_c) relatively by C·(a_c/R)², with
    # C_a = −4/9, C_d = (8/(9ξ) − 5/9)/(1 − 4/ξ), C_F = (8/15 − (16/9)(1 − 3/ξ))/(4/3 − 8/ξ)
    C = [-4 / 9, (8 / (9 * xi) - 5 / 9) / (1 - 4 / xi), (8 / 15 - 16 / 9 * (1 - 3 / xi)) / (4 / 3 - 8 / xi)]
    for R in (1e2, 1e4):
        sphere = np.array(theory.sphere_critical(R, *MAT, xi))
        parab = np.array(theory.paraboloid_critical(R, *MAT, xi))
        alpha2 = (parab[0] / R) ** 2
        assert np.allclose((sphere / parab - 1) / alpha2, C, rtol=0, atol=10 * alpha2)
    for v, m, R, E, w in [(1.0, 1e-3, 2e-6, 1e9, 0.1), (2.0, 1e-12, 5e-9, 7e10, 0.5)]:
        e_pl = theory.power_law_restitution(v, m, 2, 0.5 / R, E, w)
        assert np.isclose(e_pl, theory.thornton_ning_restitution(v, m, R, E, w), rtol=1e-13, atol=0.0)
        v_pl = theory.power_law_sticking_velocity(m, 2, 0.5 / R, E, w)
        assert np.isclose(v_pl, theory.thornton_ning_sticking_velocity(m, R, E, w), rtol=1e-13, atol=0.0)


def test_jump_in():
    """a₀ from g(a₀) = Δl(a₀) by brentq, F₀ = −(8/9)|F_c(ξ = 3)| for the paraboloid and
    F₀ = −2E* G(a₀) for a power law; rtol 1e-12."""
    R = 2e-6
    a0, F0 = map(float, theory.paraboloid_jump_in(R, *MAT))
    assert np.isclose(a0, brentq(lambda a: a**2 / R - dl(a), 1e-3 * R, R, **ROOT), rtol=1e-12, atol=0.0)
    assert np.isclose(F0, -8 / 9 * 1.5 * np.pi * DGAMMA * R, rtol=1e-12, atol=0.0)
    n, c = 3.0, c_of(3.0)
    g, _, G = power_law_profile(n, c)
    a0, F0 = map(float, theory.power_law_jump_in(n, c, *MAT))
    assert np.isclose(g(a0), dl(a0), rtol=1e-12, atol=0.0)
    assert np.isclose(F0, -2 * E_STAR * G(a0), rtol=1e-12, atol=0.0)


# --- restitution: energy balance of the reversible JKR impact -----------------------------------


def jkr_impact_loss(g, dg, G):
    """W = −∫ F dd from the jump-in (d = 0) down to the ξ = 1 critical point, along
    d(a) = g(a) − Δl(a), F(a) = 2E*(a d − G), as −∫_{a_c}^{a₀} F(a) d'(a) da."""

    def d(a):
        return g(a) - dl(a)

    a0 = brentq(d, 1e-12, 1e3, **ROOT)
    a_c = brentq(lambda a: dg(a) - np.sqrt(np.pi * DGAMMA / (2 * E_STAR * a)), 1e-12, a0, **ROOT)

    def force(a):
        return 2 * E_STAR * (a * d(a) - G(a))

    def slope(a):
        return dg(a) - 0.5 * dl(a) / a

    return -quad(lambda a: force(a) * slope(a), a_c, a0, **QUAD)[0]


@pytest.mark.parametrize("n", [0.75, 1.0, 1.5, 2.0, 3.0, 4.0])
def test_restitution_energy_balance(n):
    """½ m v₀² β = W for (3.82), and for (3.51) at n = 2; rtol 1e-10."""
    c, m, v = c_of(n), 2e-12, 0.3
    K = kap(n) * c
    W = jkr_impact_loss(lambda x: K * x**n, lambda x: n * K * x ** (n - 1), lambda x: K * x ** (n + 1) / (n + 1))
    kinetic = 0.5 * m * v**2
    assert np.isclose(kinetic * float(theory.power_law_beta(v, m, n, c, *MAT)), W, rtol=1e-10, atol=0)
    if n == 2.0:
        assert np.isclose(kinetic * float(theory.thornton_ning_beta(v, m, 1 / (2 * c), *MAT)), W, rtol=1e-10, atol=0)


def test_force_release_energy_loss_is_the_work_down_to_the_force_controlled_pull_off():
    """W = −∫ F dd from the jump-in (d = 0) down to the minimum of F(a) on the JKR branch of the
    paraboloid (quadrature, the minimum by brentq on dF/da), against the closed form; rtol 1e-10.
    It is below the Thornton–Ning loss, which goes on to the ξ = 1 point."""
    R = 2e-6
    c = 1 / (2 * R)
    K = kap(2.0) * c

    def d(a):
        return K * a**2 - dl(a)

    def force(a):
        return 2 * E_STAR * (a * d(a) - K * a**3 / 3)

    a0 = brentq(d, 1e-12, 1e3, **ROOT)
    a_f = brentq(lambda a: 2 * E_STAR * (2 * K * a**2 - 1.5 * dl(a)), 1e-3 * a0, a0, **ROOT)  # dF/da = 0
    W = -quad(lambda a: force(a) * (2 * K * a - 0.5 * dl(a) / a), a_f, a0, **QUAD)[0]
    assert np.isclose(float(theory.force_release_energy_loss(R, *MAT)), W, rtol=1e-10, atol=0)
    assert W < float(theory.thornton_ning_energy_loss(R, *MAT))


def test_restitution_limits():
    """e = 0 below v_s and ≤ 1e-7 at v_s (β = 1 up to rounding), 0 < e ≪ 1 just above,
    1 − e = β/2 + O(β²) far above (rtol 1e-5)."""
    m, R, E, w = 1e-15, 5e-7, 1e10, 0.2
    vs = float(theory.thornton_ning_sticking_velocity(m, R, E, w))

    def e(v):
        return float(theory.thornton_ning_restitution(v, m, R, E, w))

    assert np.isclose(float(theory.thornton_ning_beta(vs, m, R, E, w)), 1.0, rtol=1e-14, atol=0.0)
    assert e(0.5 * vs) == 0.0 and e(vs) < 1e-7
    assert 0 < e(1.0001 * vs) < 0.02
    assert np.isclose(1 - e(1e3 * vs), 0.5e-6, rtol=1e-5, atol=0.0)
    for n in (0.75, 3.0):
        vs = float(theory.power_law_sticking_velocity(m, n, 1e3, E, w))
        assert float(theory.power_law_restitution(0.99 * vs, m, n, 1e3, E, w)) == 0.0
        assert 0 < float(theory.power_law_restitution(1.0001 * vs, m, n, 1e3, E, w)) < 0.02


def test_restitution_jit_vmap_grad():
    """jit(vmap(e)) equals scalar calls (rtol 1e-14); the gradient is finite at capture."""
    v = jnp.geomspace(0.01, 10.0, 7)
    ns = jnp.array([0.75, 1.0, 2.0, 3.0, 4.0, 1.5, 2.5])
    m, R, c, E, w = 1e-15, 5e-7, 1e3, 1e10, 0.2
    tn = jax.jit(jax.vmap(theory.thornton_ning_restitution, (0, None, None, None, None)))(v, m, R, E, w)
    pl = jax.jit(jax.vmap(theory.power_law_restitution, (0, None, 0, None, None, None)))(v, m, ns, c, E, w)
    for i in range(len(v)):
        vi, ni = float(v[i]), float(ns[i])
        assert np.isclose(tn[i], theory.thornton_ning_restitution(vi, m, R, E, w), rtol=1e-14, atol=0)
        assert np.isclose(pl[i], theory.power_law_restitution(vi, m, ni, c, E, w), rtol=1e-14, atol=0)
    assert 0.0 < tn[-1] < 1.0 and tn[0] == 0.0
    grads = jax.vmap(jax.grad(theory.thornton_ning_restitution), (0, None, None, None, None))(v, m, R, E, w)
    assert np.all(np.isfinite(grads))


def test_sphere_critical_jit_vmap_grad():
    """The vectorized sphere solver equals scalar calls (rtol 1e-13); its R-derivative
    matches a central difference (rtol 1e-6)."""
    R = jnp.geomspace(1e-9, 1.0, 9)
    batch = jax.jit(jax.vmap(theory.sphere_critical, (0, None, None, None)))(R, *MAT, 3.0)
    for i in range(len(R)):
        scalar = theory.sphere_critical(float(R[i]), *MAT, 3.0)
        assert np.allclose([x[i] for x in batch], scalar, rtol=1e-13, atol=0)

    def f(r):
        return theory.sphere_critical(r, *MAT, 3.0)[2]

    h = 1e-11
    assert np.isclose(jax.grad(f)(1e-6), (f(1e-6 + h) - f(1e-6 - h)) / (2 * h), rtol=1e-6, atol=0.0)


# --- Hertz impact: exact contact time vs the equation of motion ----------------------------------


@pytest.mark.parametrize("n", [1.0, 2.0, 3.0])
def test_hertz_impact_vs_ode(n):
    """m d̈ = −F(d), F = 2E* n/(n+1) K a^(n+1), d = K aⁿ: contact time (rtol 1e-8), maximum
    indentation and force (rtol 1e-9) from DOP853 at rtol 1e-13 in units L, L/v₀."""
    m, v0, E, R = 3e-12, 0.7, 2e9, 5e-6
    c = 1 / (2 * R) if n == 2 else 0.1 * R ** (1 - n)
    K = kap(n) * c

    def force(d):
        return 2 * E * n / (n + 1) * K * (max(d, 0.0) / K) ** ((n + 1) / n)

    L = (m * v0**2 / (E * K ** (-1 / n))) ** (n / (2 * n + 1))  # from dimensional analysis only
    T = L / v0

    def exit_(t, y):
        return y[0]

    exit_.terminal, exit_.direction = True, -1

    def apex(t, y):
        return y[1]

    sol = solve_ivp(
        lambda t, y: [y[1], -(T**2) / (m * L) * force(L * y[0])],
        (0, 100),
        [0.0, 1.0],
        method="DOP853",
        rtol=1e-13,
        atol=1e-15,
        events=[exit_, apex],
    )
    t_c, d_max = sol.t_events[0][0] * T, sol.y_events[1][0][0] * L
    assert np.isclose(float(theory.power_law_hertz_contact_time(v0, m, n, c, E)), t_c, rtol=1e-8, atol=0)
    assert np.isclose(float(theory.power_law_hertz_max_indentation(v0, m, n, c, E)), d_max, rtol=1e-9, atol=0)
    assert np.isclose(float(theory.power_law_hertz_max_force(v0, m, n, c, E)), force(d_max), rtol=1e-9, atol=0)
    if n == 2:
        t_hertz = float(theory.hertz_contact_time(v0, m, R, E))
        assert np.isclose(t_hertz, t_c, rtol=1e-8, atol=0)
        assert np.isclose(float(theory.hertz_max_indentation(v0, m, R, E)), d_max, rtol=1e-9, atol=0)
        assert np.isclose(float(theory.hertz_max_force(v0, m, R, E)), force(d_max), rtol=1e-9, atol=0)
        assert np.isclose(t_hertz / (m**2 / (R * E**2 * v0)) ** 0.2, 2.868, rtol=0, atol=5e-4)


# --- normalized curves ---------------------------------------------------------------------------


def test_normalized_curves_match_dimensional():
    """(3.49) and (3.78) against the dimensional (3.44), (3.71) over 0 < â ≤ 4; rtol 1e-12."""
    a_hat = np.linspace(0.01, 4.0, 50)
    R = 3e-6
    a_c, d_c, F_c = theory.paraboloid_critical(R, *MAT, 3.0)
    a = a_hat * a_c

    def close(x, y):
        return np.allclose(x, y, rtol=1e-12, atol=1e-12)

    assert close(theory.jkr_normalized_indentation(a_hat), theory.jkr_indentation(a, R, *MAT) / abs(d_c))
    assert close(theory.jkr_normalized_force(a_hat), theory.jkr_force(a, R, *MAT) / abs(F_c))
    assert close(theory.jkr_indentation(a, R, *MAT) / R, theory.power_law_indentation(a, 2, 0.5 / R, *MAT) / R)
    assert close(theory.jkr_force(a, R, *MAT) / abs(F_c), theory.power_law_force(a, 2, 0.5 / R, *MAT) / abs(F_c))
    for n in (0.75, 1.0, 3.0):
        for xi in (1.0, 3.0):
            a_c, d_c, F_c = theory.power_law_critical(n, c_of(n), *MAT, xi)
            a = a_hat * a_c
            d_ref = theory.power_law_indentation(a, n, c_of(n), *MAT) / abs(d_c)
            F_ref = theory.power_law_force(a, n, c_of(n), *MAT) / abs(F_c)
            assert close(theory.power_law_normalized_indentation(a_hat, n, xi), d_ref)
            assert close(theory.power_law_normalized_force(a_hat, n, xi), F_ref)
    # the cone's (3.43) is (3.78) at n = 1, ξ = 3
    assert close(theory.power_law_normalized_indentation(a_hat, 1, 3.0), 3 * a_hat - 2 * np.sqrt(a_hat))
    assert close(theory.power_law_normalized_force(a_hat, 1, 3.0), 3 * a_hat**2 - 4 * a_hat**1.5)
