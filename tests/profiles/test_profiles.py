"""Profiles: closed-form g and G against quadrature and against the chapter's formulas.

Tolerances: g vs `mdr_transform` rtol 1e-9 (smooth θ-integrands, split at the kinks);
G vs a Gauss-Legendre quadrature of g rtol 1e-10; d_n.a. = g(a) and F_n.a. = 2E*(a g - G)
vs the chapter's formulas evaluated in 40-digit arithmetic rtol 1e-12.
"""

import functools
import itertools

import jax
import jax.numpy as jnp
import mpmath as mp
import numpy as np
import pytest
import scipy.special
from pydantic import TypeAdapter

from impact import profiles as pr
from impact._scene import profiles as ps

B = 1e-4  # radius of the flat tip / cap / punch in the b-shapes (m)
TABLE_R = np.array([0.0, 0.3, 0.5, 1.0, 1.7, 2.5]) * 1e-4
TABLE_F = np.array([0.0, 0.1, 0.15, 0.5, 1.3, 1.5]) * 1e-6

# name: (class, constructor kwargs, largest x tested (m), kink radii (m), Gauss-Legendre nodes)
CASES = {
    "paraboloid": (pr.Paraboloid, dict(R=1e-3), 3e-4, (), 64),
    "sphere": (pr.Sphere, dict(R=1e-3), 0.9e-3, (), 64),
    "ellipsoid": (pr.Ellipsoid, dict(R=2e-3, k=800.0), 0.9 / 800, (), 64),
    "cone": (pr.Cone, dict(theta=0.3), 1e-3, (), 64),
    "power_law_1": (pr.PowerLaw, dict(n=1.0, c=0.2), 1e-3, (), 64),
    "power_law_2.5": (pr.PowerLaw, dict(n=2.5, c=1e4), 1e-3, (), 256),  # sin^1.5 θ: algebraic convergence
    "power_law_3": (pr.PowerLaw, dict(n=3.0, c=1e6), 1e-3, (), 64),
    "flat_punch": (pr.FlatPunch, dict(radius=B), B, (), 64),
    "truncated_cone": (pr.TruncatedCone, dict(b=B, theta=0.4), 4 * B, (B,), 64),
    "truncated_paraboloid": (pr.TruncatedParaboloid, dict(b=B, R=1e-3), 4 * B, (B,), 64),
    "capped_flat_punch": (pr.CappedFlatPunch, dict(b=B, R=1e-3), B, (), 64),
    "capped_cone": (pr.CappedCone, dict(b=B, theta=0.3), 4 * B, (B,), 64),
    "capped_paraboloid": (pr.CappedParaboloid, dict(b=B, R1=2e-3, R2=1e-3), 4 * B, (B,), 64),
    "rounded_flat_punch": (pr.RoundedFlatPunch, dict(b=B, R=5e-5), 4 * B, (B,), 64),
    # 2πx/λ up to 94: both Struve branches (quadrature below 30, asymptotic above)
    "wavy_paraboloid": (pr.WavyParaboloid, dict(R=1e-3, amplitude=4e-8, wavelength=2e-5), 3e-4, (), 128),
    "tabulated": (pr.Tabulated, dict(r=TABLE_R, f=TABLE_F), 4e-4, tuple(TABLE_R[1:]), 64),
}
NAMES = list(CASES)


def make(name):
    cls, kw, *_ = CASES[name]
    return cls(**kw)


def sample(name):
    """x in (0, xmax]: a uniform grid plus points just around every kink (kinks themselves excluded)."""
    _, _, xmax, kinks, _ = CASES[name]
    x = np.linspace(0.02, 1.0, 40) * xmax
    near = [k * (1 + e) for k in kinks for e in (-1e-3, 1e-3, 1e-6)]
    x = np.concatenate([x, [v for v in near if v < xmax]])
    return np.array([v for v in x if all(abs(v - k) > 1e-9 * k for k in kinks)])


@jax.jit
def evaluate(p, x):
    """(g, G) in one compiled call: eager dispatch would compile every primitive separately."""
    return p.g(x), p.G(x)


@jax.jit
def derivatives(p, x):
    """d/dx of f, g, G by grad and jacfwd, and d(g + G)/d(parameters)."""
    by_x = [jax.vmap(jax.grad(fun))(x) for fun in (p.f, p.g, p.G)]
    by_x += [jnp.diagonal(jax.jacfwd(fun)(x)) for fun in (p.g, p.G)]
    return by_x, jax.grad(lambda q: jnp.sum(q.g(x) + q.G(x)))(p)


@jax.jit
def values(p):
    """f, g, G at 0, radius scale, extent, and f, g, G at and just past the extent."""
    ext = p.extent()
    return p.f(0.0), p.g(0.0), p.G(0.0), p.radius_scale(), ext, p.f(ext), p.f(1.001 * ext), p.g(ext), p.G(ext)


@functools.partial(jax.jit, static_argnames="nodes")
def transform(p, x, kinks, nodes=64):
    return pr.mdr_transform(p.f, x, nodes=nodes, breakpoints=kinks)


def integral(fun, x, kinks, nodes=200):
    """∫_0^x fun for each x; pieces split at the kinks, s = lo + (hi - lo) t² absorbs sqrt-edges."""
    t, w = np.polynomial.legendre.leggauss(nodes)
    t, w = (t + 1) / 2, w / 2
    out = []
    for xi in x:
        edges = [0.0, *[k for k in kinks if k < xi], xi]
        pieces = itertools.pairwise(edges)
        out.append(sum(np.sum(w * 2 * (hi - lo) * t * np.asarray(fun(lo + (hi - lo) * t**2))) for lo, hi in pieces))
    return np.array(out)


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_g_matches_mdr_transform_of_f(name):
    p = make(name)
    x = sample(name)
    g_num = transform(p, x, jnp.asarray(CASES[name][3]), nodes=CASES[name][4])
    np.testing.assert_allclose(evaluate(p, x)[0], g_num, rtol=1e-9, atol=0)


@pytest.mark.parametrize("name", NAMES)
def test_G_is_integral_of_g(name):
    p = make(name)
    x = sample(name)
    quadrature = integral(lambda s: evaluate(p, s)[0], x, CASES[name][3])
    np.testing.assert_allclose(evaluate(p, x)[1], quadrature, rtol=1e-10, atol=0)


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_values_at_zero_and_wall(name):
    f0, g0, G0, scale, ext, f_ext, f_past, g_ext, G_ext = values(make(name))
    assert f0 == 0 and g0 == 0 and G0 == 0
    assert np.isfinite(scale) and scale > 0
    if np.isfinite(ext) and name not in ("sphere", "ellipsoid"):  # walls: f jumps to inf past the wall
        assert np.isfinite(f_ext) and f_past == np.inf and np.isfinite(g_ext) and np.isfinite(G_ext)


def test_spheroids_at_their_equator():
    """g diverges at the extent, G stays finite: R²/2 for the sphere, R/(2k) for the ellipsoid."""
    for name, G_end in (("sphere", 1e-6 / 2), ("ellipsoid", 2e-3 / (2 * 800.0))):
        *_, ext, f_ext, _, g_ext, G_ext = values(make(name))
        assert np.isfinite(f_ext) and g_ext == np.inf
        np.testing.assert_allclose(G_ext, G_end, rtol=1e-15)


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_derivatives_finite(name):
    p = make(name)
    x = jnp.asarray(np.concatenate([sample(name), CASES[name][3]]))  # the kinks themselves too
    assert all(np.all(np.isfinite(leaf)) for leaf in jax.tree.leaves(derivatives(p, x)))


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_jit_and_vmap_over_parameters(name):
    """Profiles built inside jit / vmap from traced parameters agree with the plain evaluation."""
    cls, kw, *_ = CASES[name]
    x = jnp.asarray(sample(name))
    g_ref, G_ref = evaluate(make(name), x)

    @jax.jit
    def traced(kw, x):
        p = cls(**kw)
        return p.g(x), p.G(x), jax.vmap(p.g)(x)  # the last: scalar calls, vmapped over x

    g_jit, G_jit, g_scalar = traced(kw, x)
    for got, want in ((g_jit, g_ref), (G_jit, G_ref), (g_scalar, g_ref)):
        np.testing.assert_allclose(got, want, rtol=1e-13)
    scales = np.array([0.9, 1.0, 1.1])
    batch = {k: scales.reshape((3,) + (1,) * np.ndim(v)) * np.asarray(v) for k, v in kw.items()}
    g_b, G_b, ext_b = jax.jit(jax.vmap(lambda kw: (cls(**kw).g(x), cls(**kw).G(x), cls(**kw).extent())))(batch)
    for i in range(3):
        q = cls(**{k: v[i] for k, v in batch.items()})
        g_i, G_i = evaluate(q, x)
        np.testing.assert_allclose(g_b[i], g_i, rtol=1e-13)
        np.testing.assert_allclose(G_b[i], G_i, rtol=1e-13)
        assert ext_b[i] == q.extent()


# ---------------------------------------------------------------- the chapter's d_n.a.(a), F_n.a.(a)


def chapter(name, a):
    """(d_n.a., F_n.a./E*) at contact radius a from the chapter's formulas, in 40 digits."""
    mp.mp.dps = 40
    kw = {k: mp.mpf(float(v)) for k, v in CASES[name][1].items() if np.ndim(v) == 0}
    a = mp.mpf(float(a))

    def parab(R):
        return a**2 / R, 4 * a**3 / (3 * R)

    if name == "paraboloid":
        return parab(kw["R"])
    if name == "sphere":  # (3.52)
        R = kw["R"]
        return a * mp.atanh(a / R), R**2 * ((1 + a**2 / R**2) * mp.atanh(a / R) - a / R)
    if name == "ellipsoid":  # (3.57); its d lacks the factor kR
        R, k = kw["R"], kw["k"]
        return k * R * a * mp.atanh(k * a), R / k * ((1 + k**2 * a**2) * mp.atanh(k * a) - k * a)
    if name == "cone":  # (3.38)
        t = mp.tan(kw["theta"])
        return mp.pi / 2 * a * t, mp.pi * a**2 * t / 2
    if name.startswith("power_law"):  # (3.71)
        n, c = kw["n"], kw["c"]
        kap = mp.sqrt(mp.pi) * mp.gamma(n / 2 + 1) / mp.gamma((n + 1) / 2)
        return kap * c * a**n, 2 * n / (n + 1) * kap * c * a ** (n + 1)
    if name == "capped_flat_punch":  # (3.98)
        return parab(kw["R"])
    b = kw.get("b")
    if name == "capped_cone" and a <= b:  # (3.109): paraboloid R = b / tan θ
        return parab(b / mp.tan(kw["theta"]))
    if name == "capped_paraboloid" and a <= b:  # (3.118)
        return parab(kw["R1"])
    if a <= b:
        return mp.mpf(0), mp.mpf(0)
    phi = mp.acos(b / a)
    if name == "truncated_cone":  # (3.83)
        t = mp.tan(kw["theta"])
        return a * t * phi, t * a**2 * (phi + b / a * mp.sqrt(1 - b**2 / a**2))
    if name == "truncated_paraboloid":  # (3.91)
        R = kw["R"]
        return a / R * mp.sqrt(a**2 - b**2), 2 / (3 * R) * (2 * a**2 + b**2) * mp.sqrt(a**2 - b**2)
    if name == "capped_cone":  # (3.105), (3.108)
        t, s, c = mp.tan(kw["theta"]), mp.sin(phi), mp.cos(phi)
        return a * t * ((1 - s) / c + phi), a**2 * t * (phi + mp.mpf(4) / 3 * (1 - s) / c + s * c / 3)
    if name == "capped_paraboloid":  # (3.114), (3.115)
        R1, R2 = kw["R1"], kw["R2"]
        Rs = R1 * R2 / (R1 - R2)
        sq = mp.sqrt(a**2 - b**2)
        return a**2 / R1 + a / Rs * sq, mp.mpf(2) / 3 * (2 * a**3 / R1 + (2 * a**2 + b**2) * sq / Rs)
    if name == "rounded_flat_punch":  # (3.125), (3.127)
        R = kw["R"]
        sq = mp.sqrt(a**2 - b**2)
        return a / R * (sq - b * phi), (sq * (4 * a**2 - b**2) - 3 * b * a**2 * phi) / (3 * R)
    raise KeyError(name)


def chapter_wavy(a):
    """(3.136) and (3.134) for the wavy paraboloid (E* = 1)."""
    _, kw, *_ = CASES["wavy_paraboloid"]
    R, h, lam = (mp.mpf(kw[k]) for k in ("R", "amplitude", "wavelength"))
    a, z = mp.mpf(float(a)), 2 * mp.pi * mp.mpf(float(a)) / lam
    d = a**2 / R + mp.pi**2 * h * a / lam * mp.struveh(0, z)
    return d, 4 * a**3 / (3 * R) + mp.pi * a * h * (z * mp.struveh(0, z) - mp.struveh(1, z))


CHAPTER = [n for n in NAMES if n not in ("flat_punch", "tabulated")]


@pytest.mark.parametrize("name", CHAPTER)
def test_non_adhesive_d_and_force_match_chapter(name):
    p = make(name)
    a = sample(name)
    formula = chapter_wavy if name == "wavy_paraboloid" else lambda a: chapter(name, a)
    ref = np.array([formula(ai) for ai in a], float)
    g, G = evaluate(p, a)
    np.testing.assert_allclose(g, ref[:, 0], rtol=1e-12, atol=0)
    np.testing.assert_allclose(2 * (a * g - G), ref[:, 1], rtol=1e-12, atol=0)


def test_wall_forces():
    """(3.36) flat punch F = 2E* d a and (3.99) capped flat punch F = 2E*(d b - b³/(3R)) at a = b."""
    d = np.array([-1e-6, 0.0, 2e-6])
    fp, cfp = make("flat_punch"), make("capped_flat_punch")
    np.testing.assert_allclose(2 * (d * B - fp.G(fp.extent())), 2 * d * B, rtol=1e-15)
    R = CASES["capped_flat_punch"][1]["R"]
    np.testing.assert_allclose(2 * (d * B - cfp.G(cfp.extent())), 2 * (d * B - B**3 / (3 * R)), rtol=1e-14)


def test_ellipsoid_chapter_d_lacks_factor_kR():
    """(3.57) prints d_n.a. = a artanh(ka); the transform of (3.58) is kR times that."""
    kw = CASES["ellipsoid"][1]
    a = np.linspace(0.1, 1.0, 5) / kw["k"] * 0.9
    printed = a * np.arctanh(kw["k"] * a)
    np.testing.assert_allclose(transform(make("ellipsoid"), a, jnp.zeros(0)), kw["k"] * kw["R"] * printed, rtol=1e-12)


# ---------------------------------------------------------------- power-law factor, tabulated profile


def test_kappa():
    np.testing.assert_allclose(pr.kappa(jnp.array([1.0, 2.0, 3.0])), [np.pi / 2, 2.0, 3 * np.pi / 4], rtol=1e-14)
    k_half = np.pi**1.5 * np.sqrt(2) / (4 * scipy.special.gamma(0.75) ** 2)  # (3.79)
    np.testing.assert_allclose(pr.kappa(0.5), k_half, rtol=1e-14)
    n = np.linspace(0.1, 6.0, 25)  # κ(n) = n ∫_0^{π/2} sin^{n-1} = (n/2) B(n/2, 1/2)
    np.testing.assert_allclose(pr.kappa(n), n / 2 * scipy.special.beta(n / 2, 0.5), rtol=1e-13)


def test_tabulated_is_exact_for_piecewise_linear_shapes():
    """A 3-point table is a truncated cone, continued with the last slope."""
    theta = 0.4
    tab = pr.Tabulated(r=[0.0, B, 2 * B], f=[0.0, 0.0, B * np.tan(theta)])
    tc = pr.TruncatedCone(b=B, theta=theta)
    x = np.linspace(0.0, 10 * B, 41)
    values = jax.jit(lambda p, x: (p.f(x), p.g(x), p.G(x)))
    np.testing.assert_allclose(values(tab, x), values(tc, x), rtol=1e-13, atol=1e-30)
    np.testing.assert_allclose(values(make("tabulated"), x)[0][:10], np.interp(x[:10], TABLE_R, TABLE_F), rtol=1e-14)


def test_tabulated_converges_to_paraboloid():
    """Sampled paraboloid: G (hence the force) converges as h², g as h^1.5.

    g is a half-derivative of f, so the O(h²) interpolation error, oscillating on the scale h,
    gives O(h^1.5) in g; integrating back gives O(h²) in G.
    """
    R, L = 1e-3, 4e-4
    par = pr.Paraboloid(R=R)
    x = np.linspace(0.2, 0.9, 301) * L
    sizes, err_g, err_G = [], [], []
    for n in (100, 200, 400, 800, 1600):
        r = np.linspace(0.0, L, n + 1)
        g, G = evaluate(pr.Tabulated(r=r, f=r**2 / (2 * R)), x)
        sizes.append(L / n)
        err_g.append(np.max(np.abs(g / par.g(x) - 1)))
        err_G.append(np.max(np.abs(G / par.G(x) - 1)))
    order_g = np.polyfit(np.log(sizes), np.log(err_g), 1)[0]
    order_G = np.polyfit(np.log(sizes), np.log(err_G), 1)[0]
    assert 1.4 < order_g < 1.6, order_g
    assert 1.9 < order_G < 2.1, order_G
    assert err_g[-1] < 1e-4 and err_G[-1] < 1e-5


def test_mdr_transform_breakpoints_matter():
    """Without the split the kink of the truncated cone costs accuracy; with it g is exact."""
    p = make("truncated_cone")
    x = np.array([1.3 * B, 2.2 * B])
    exact = p.g(x)
    assert np.max(np.abs(transform(p, x, jnp.zeros(0)) / exact - 1)) > 1e-6
    np.testing.assert_allclose(transform(p, x, jnp.array([B])), exact, rtol=1e-14)


# ---------------------------------------------------------------- scene-file schema

SPEC = TypeAdapter(ps.ProfileSpec)
SCHEMA_CASES = {
    "paraboloid": pr.Paraboloid,
    "sphere": pr.Sphere,
    "ellipsoid": pr.Ellipsoid,
    "cone": pr.Cone,
    "power_law_3": pr.PowerLaw,
    "flat_punch": pr.FlatPunch,
    "truncated_cone": pr.TruncatedCone,
    "truncated_paraboloid": pr.TruncatedParaboloid,
    "capped_flat_punch": pr.CappedFlatPunch,
    "capped_cone": pr.CappedCone,
    "capped_paraboloid": pr.CappedParaboloid,
    "rounded_flat_punch": pr.RoundedFlatPunch,
    "wavy_paraboloid": pr.WavyParaboloid,
    "tabulated": pr.Tabulated,
}


def entry(name, **changes):
    kw = {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in CASES[name][1].items()}
    return {"shape": name.removesuffix("_3"), **kw, **changes}


@pytest.mark.parametrize("name", list(SCHEMA_CASES))
def test_schema_builds_right_profile(name):
    p = SPEC.validate_python(entry(name)).build()
    assert type(p) is SCHEMA_CASES[name]
    x = sample(name)
    np.testing.assert_allclose(evaluate(p, x)[1], evaluate(make(name), x)[1], rtol=1e-15)
