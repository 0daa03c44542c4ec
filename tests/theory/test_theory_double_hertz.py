"""Greenwood–Johnson double-Hertz closed forms of impact.theory (§3.9): the curve c(a), F(a), d(a)
against quadrature of the stress (3.198), (3.200) and of the separation energy (3.201) with the
gap (3.199); the critical states against root finds; the JKR and DMT limits."""

import jax
import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from impact import theory

R, E_STAR, DGAMMA = 1e-6, 1e9, 0.1  # m, Pa, J/m²
QUAD = dict(epsabs=0.0, epsrel=1e-13, limit=200)
FACTORS = (1e-3, 0.3, 1.0, 2.5, 30.0, 1e3)


def radii(k):
    """Contact radii from 1e-3 of the onset ring c₀ to 10·max(1, k)·c₀."""
    c0 = float(theory.double_hertz_onset(k, R, E_STAR, DGAMMA)[0])
    return c0 * np.array([1e-3, 0.1, 0.5, 1.0, 3.0, 10.0 * max(1.0, k)])


def hertz(radius, r):
    """Hertz stress shape (2E*/(πR))·√(radius² − r²) inside the radius, 0 outside."""
    return 2 * E_STAR / (np.pi * R) * np.sqrt(max(radius**2 - r**2, 0.0))


@pytest.mark.parametrize("k", FACTORS)
def test_outer_radius_gives_the_work_of_adhesion(k):
    """∫σ d(Δw) over the ring a < r < c, σ = k·Hertz(c) (3.200) and Δw of (3.199)
    differentiated by hand, dΔw/dr = 2(1+k)/(πR)·(r·arccos(a/r) + a√(r² − a²)/r), gives back Δγ at
    the module's c(a) to rtol 1e-10, plus the round-off of the ring width c − a taken from c
    (4·eps·c/(c − a): the work goes as (c − a)²)."""
    for a in radii(k):
        c = float(theory.double_hertz_outer_radius(a, k, R, E_STAR, DGAMMA))
        width = c - a
        assert width > 0

        def integrand(phi, a=a, c=c, width=width):
            # r = a + t, t = (c − a)(1 − cos φ)/2: the square roots leave both ends
            t = width * (1 - np.cos(phi)) / 2
            root = np.sqrt(t * (2 * a + t))
            slope = 2 * (1 + k) / (np.pi * R) * ((a + t) * np.arctan2(root, a) + a * root / (a + t))
            stress = k * 2 * E_STAR / (np.pi * R) * np.sqrt((width - t) * (c + a + t))
            return stress * slope * width / 2 * np.sin(phi)

        work, _ = quad(integrand, 0.0, np.pi, **QUAD)
        assert work == pytest.approx(DGAMMA, rel=1e-10 + 4 * np.finfo(float).eps * c / width, abs=0)


@pytest.mark.slow
@pytest.mark.parametrize("k", FACTORS)
def test_force_and_indentation_integrate_the_stress(k):
    """F = ∫p·2πr dr and d = w(0) = (2/E*)∫p dr (Boussinesq, the centre's displacement) with the
    pressure p = (1+k)·Hertz(a) − k·Hertz(c) of (3.198), (3.200): equal to the closed forms to
    1e-10 of the size of their two terms."""
    for a in radii(k):
        c = float(theory.double_hertz_outer_radius(a, k, R, E_STAR, DGAMMA))
        inner = quad(lambda r, a=a: hertz(a, r) * 2 * np.pi * r, 0, a, **QUAD)[0]
        outer = quad(lambda r, c=c: hertz(c, r) * 2 * np.pi * r, 0, c, **QUAD)[0]
        force = float(theory.double_hertz_force(a, k, R, E_STAR, DGAMMA))
        assert abs(force - ((1 + k) * inner - k * outer)) <= 1e-10 * ((1 + k) * inner + k * outer)
        inner = quad(lambda r, a=a: hertz(a, r), 0, a, **QUAD)[0]
        outer = quad(lambda r, c=c: hertz(c, r), 0, c, **QUAD)[0]
        depth = float(theory.double_hertz_indentation(a, k, R, E_STAR, DGAMMA))
        scale = 2 / E_STAR * ((1 + k) * inner + k * outer)
        assert abs(depth - 2 / E_STAR * ((1 + k) * inner - k * outer)) <= 1e-10 * scale


@pytest.mark.parametrize("k", FACTORS)
def test_pull_off_under_force_control_is_the_minimum_of_F(k):
    """The force-controlled pull-off (ξ = 3) is F at the root of dF/da (autodiff through c(a))
    found by Brent's method in the test: a and F to rtol 1e-8."""
    slope = jax.jit(jax.grad(lambda a: theory.double_hertz_force(a, k, R, E_STAR, DGAMMA)))
    c0 = float(theory.double_hertz_onset(k, R, E_STAR, DGAMMA)[0])
    root = brentq(lambda a: float(slope(a)), 1e-9 * c0, 10 * c0 * max(1.0, k), xtol=1e-16 * c0, rtol=1e-15)
    a, _, F = map(float, theory.double_hertz_pull_off(k, R, E_STAR, DGAMMA, 3))
    assert a == pytest.approx(root, rel=1e-8, abs=0.0)
    assert F == pytest.approx(float(theory.double_hertz_force(root, k, R, E_STAR, DGAMMA)), rel=1e-8, abs=0.0)


@pytest.mark.parametrize("k", FACTORS)
def test_pull_off_under_displacement_control(k):
    """ξ = 1: for k > 1 the minimum of d(a) (root of dd/da by Brent's method) to rtol 1e-8; for
    k ≤ 1 the onset a = 0, d₀ = −k·c₀²/R, F₀ = −2πRΔγ/(1 + k) (d rises from there: d(a) > d₀), its
    d and F to 2e-13 (two roundings of the same point: 1.1e-13 at k = 1e-3)."""
    a, d, F = map(float, theory.double_hertz_pull_off(k, R, E_STAR, DGAMMA, 1))
    c0, d0, F0 = map(float, theory.double_hertz_onset(k, R, E_STAR, DGAMMA))
    if k <= 1:
        assert (a, d, F) == (0.0, pytest.approx(d0, rel=2e-13, abs=0.0), pytest.approx(F0, rel=2e-13, abs=0.0))
        assert np.all(np.asarray(theory.double_hertz_indentation(radii(k), k, R, E_STAR, DGAMMA)) > d0)
        assert d0 == pytest.approx(-k * c0**2 / R, rel=1e-13, abs=0.0)
        return
    slope = jax.jit(jax.grad(lambda a: theory.double_hertz_indentation(a, k, R, E_STAR, DGAMMA)))
    root = brentq(lambda a: float(slope(a)), 1e-9 * c0, 10 * c0 * max(1.0, k), xtol=1e-16 * c0, rtol=1e-15)
    assert a == pytest.approx(root, rel=1e-8, abs=0.0)
    assert d == pytest.approx(float(theory.double_hertz_indentation(root, k, R, E_STAR, DGAMMA)), rel=1e-8, abs=0.0)
    assert F == pytest.approx(float(theory.double_hertz_force(root, k, R, E_STAR, DGAMMA)), rel=1e-8, abs=0.0)


def test_jkr_and_dmt_limits():
    """Force control: F → −(3/2)πRΔγ at k = 1e4 (JKR) and −2πRΔγ at k = 1e-4 (DMT, Bradley),
    both to 1e-3 relative; displacement control at k = 1e4: the JKR −(5/6)πRΔγ to 1e-3."""
    scale = np.pi * R * DGAMMA
    assert float(theory.double_hertz_pull_off(1e4, R, E_STAR, DGAMMA, 3)[2]) == pytest.approx(
        -1.5 * scale, rel=1e-3, abs=0.0
    )
    assert float(theory.double_hertz_pull_off(1e-4, R, E_STAR, DGAMMA, 3)[2]) == pytest.approx(
        -2 * scale, rel=1e-3, abs=0.0
    )
    displaced = float(theory.double_hertz_pull_off(1e4, R, E_STAR, DGAMMA, 1)[2])
    assert displaced == pytest.approx(-5 / 6 * scale, rel=1e-3, abs=0.0)


def test_equivalent_dugdale_parameters():
    """σ₀·h = Δγ (3.4); the Tabor parameter (3.172) of (σ₀, h) is double_hertz_tabor_parameter(k),
    whose inverse is double_hertz_factor; rtol 1e-12."""
    for k in FACTORS:
        stress = float(theory.double_hertz_adhesive_stress(k, R, E_STAR, DGAMMA))
        reach = float(theory.double_hertz_range(k, R, E_STAR, DGAMMA))
        tabor = float(theory.double_hertz_tabor_parameter(k))
        assert stress * reach == pytest.approx(DGAMMA, rel=1e-12, abs=0.0)
        assert float(theory.tabor_parameter(R, stress, reach, E_STAR)) == pytest.approx(tabor, rel=1e-12, abs=0.0)
        assert float(theory.double_hertz_factor(tabor)) == pytest.approx(k, rel=1e-12, abs=0.0)


def test_gradient_of_the_pull_off_force():
    """d F_pull-off/dk by autodiff equals a central difference (step 1e-4 k) to 1e-6."""
    k = 2.0
    exact = float(jax.grad(lambda k: theory.double_hertz_pull_off(k, R, E_STAR, DGAMMA, 3)[2])(k))
    step = 1e-4 * k
    upper = float(theory.double_hertz_pull_off(k + step, R, E_STAR, DGAMMA, 3)[2])
    lower = float(theory.double_hertz_pull_off(k - step, R, E_STAR, DGAMMA, 3)[2])
    assert exact == pytest.approx((upper - lower) / (2 * step), rel=1e-6, abs=0.0)


def test_transition_figure_compares_both_models_within_one_and_a_half_percent():
    """At the equivalent Λ(k), Greenwood–Johnson's force-controlled pull-off is within 1.5 % of
    Maugis–Dugdale's (3.171) for 1e-3 ≤ Λ ≤ 1e3; the figure draws both models and the limits."""
    from impact._plots.transition import pull_off_figure

    tabors = np.geomspace(1e-3, 1e3, 61)
    maugis = 1.5 * theory.maugis_pull_off(tabors)
    factors = np.asarray(theory.double_hertz_factor(tabors))
    greenwood = -np.asarray(theory.double_hertz_pull_off(factors, R, E_STAR, DGAMMA, 3)[2]) / (np.pi * R * DGAMMA)
    assert np.max(np.abs(greenwood / maugis - 1)) < 0.015
    gids = [line.get_gid() for line in pull_off_figure(tabors).axes[0].get_lines()]
    assert gids == ["maugis", "greenwood_johnson", "greenwood_johnson", "limit", "limit", "limit"]
