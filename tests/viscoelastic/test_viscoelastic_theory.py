"""The closed forms of a paraboloid on a viscoelastic half-space (`impact.theory`): Lee & Radok's
and Ting's forces against the hereditary integral by quadrature, their elastic limits, Ting's
contact time against a bracketed root."""

import jax
import jax.numpy as jnp
import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from impact import theory

R, E_RELAXED = 1e-5, 1e6  # m, Pa
MODULI, TIMES = np.array([2e6, 5e5]), np.array([0.5, 0.05])  # Pa, s
RATE, RAMP, HOLD = 1e-6, 1.0, 0.3  # m/s, s, s


def relaxation(t):
    return E_RELAXED + np.sum(MODULI * np.exp(-t / TIMES))


def hereditary(t, upper):
    """(4√R/3)∫₀^upper E*(t − s)·d/ds[(r·s)^(3/2)] ds by quadrature."""
    integrand = lambda s: relaxation(t - s) * 1.5 * RATE**1.5 * np.sqrt(s)  # noqa: E731
    return 4 * np.sqrt(R) / 3 * quad(integrand, 0.0, upper, epsabs=0, epsrel=1e-13, limit=200)[0]


def released(time, t1):
    """Ting's condition ∫_{t₁}^{t} E*(t − s)·ḋ(s) ds / r: loaded from t₁ to RAMP, unloaded after the hold."""
    loading = quad(lambda s: relaxation(time - s), t1, RAMP, epsabs=0, epsrel=1e-13)[0]
    return loading - quad(lambda s: relaxation(time - s), RAMP + HOLD, time, epsabs=0, epsrel=1e-13)[0]


def test_relaxation_modulus_runs_from_instantaneous_to_relaxed():
    moduli, times = jnp.asarray(MODULI), jnp.asarray(TIMES)
    values = np.asarray(theory.prony_relaxation_modulus(np.array([0.0, 0.1, 1e3]), E_RELAXED, moduli, times))
    assert values == pytest.approx([E_RELAXED + MODULI.sum(), relaxation(0.1), E_RELAXED], rel=1e-15, abs=0.0)


@pytest.mark.parametrize("X", [1e-9, 1e-3, 0.2, np.nextafter(0.5, 0), 0.5, 3.0, 40.0, 1e4])
def test_kernel_is_the_hereditary_integral(X):
    """H(X) = e^(−X)∫₀^X e^u·√u du (series below ½, Dawson's integral above), to 1e-12."""
    expected = quad(lambda u: np.exp(u - X) * np.sqrt(u), 0.0, X, epsabs=0, epsrel=1e-13, limit=400)[0]
    assert float(theory.lee_radok_kernel(X)) == pytest.approx(expected, rel=1e-12, abs=0.0)


@pytest.mark.parametrize("time", [0.05, 0.4, 1.0, 1.2, 3.0])
def test_lee_radok_force_during_loading_and_hold(time):
    """A ramp to RAMP, then held: the closed form is the hereditary integral (to 1e-12)."""
    force = theory.lee_radok_force(time, RATE, R, E_RELAXED, jnp.asarray(MODULI), jnp.asarray(TIMES), RAMP)
    assert float(force) == pytest.approx(hereditary(time, min(time, RAMP)), rel=1e-12, abs=0.0)


@pytest.mark.parametrize(("times", "modulus"), [(np.array([1e-30]), E_RELAXED), (np.array([1e30]), E_RELAXED + 2e6)])
def test_lee_radok_limits_are_hertz(times, modulus):
    """τ → 0: Hertz with E∞*; τ → ∞: Hertz with E₀* = E∞* + E₁, (4/3)E*√R·d^(3/2) (to 1e-14)."""
    force = theory.lee_radok_force(0.7, RATE, R, E_RELAXED, jnp.asarray([2e6]), jnp.asarray(times))
    assert float(force) == pytest.approx(4 / 3 * modulus * np.sqrt(R) * (0.7 * RATE) ** 1.5, rel=1e-14, abs=0.0)


def ting_root(time):
    """t₁ of Ting's condition by brentq (0 once the contact is lost)."""
    return brentq(lambda t1: released(time, t1), 0.0, RAMP, xtol=1e-15) if released(time, 0.0) > 0 else 0.0


@pytest.mark.parametrize("time", [1.35, 1.5, 1.8, 2.1])
def test_ting_force_while_unloading(time):
    """After the hold the contact recedes: t₁ as brentq finds it (1e-12), the force the integral
    up to t₁ (1e-11)."""
    moduli, times = jnp.asarray(MODULI), jnp.asarray(TIMES)
    t1 = float(theory.ting_contact_time(time, E_RELAXED, moduli, times, RAMP, HOLD))
    expected = ting_root(time)
    assert t1 == pytest.approx(expected, rel=1e-12, abs=1e-15)
    force = float(theory.ting_force(time, RATE, R, E_RELAXED, moduli, times, RAMP, HOLD))
    assert force == pytest.approx(hereditary(time, expected), rel=1e-11, abs=1e-25)


def test_ting_contact_is_lost_before_the_indentation_returns():
    """The medium recovers late: the contact is lost (t₁ = 0, F = 0) while d > 0, at the root of
    Ting's condition with t₁ = 0."""
    moduli, times = jnp.asarray(MODULI), jnp.asarray(TIMES)
    lost = brentq(lambda t: released(t, 0.0), RAMP + HOLD + 0.01, 2 * RAMP + HOLD, xtol=1e-14)
    assert lost < 2 * RAMP + HOLD - 0.1
    before, after = (
        float(theory.ting_force(t, RATE, R, E_RELAXED, moduli, times, RAMP, HOLD)) for t in (lost - 1e-3, lost + 1e-3)
    )
    assert before > 0.0 and after == 0.0


def test_ting_elastic_limit_follows_the_indentation():
    """τ → ∞: an elastic medium of E₀*: the contact radius follows d (t₁ = 2T + hold − t) and the
    force is Hertz's at d (to 1e-12)."""
    moduli, times = jnp.asarray([2e6]), jnp.asarray([1e30])
    time = 1.9
    depth = RATE * (2 * RAMP + HOLD - time)
    t1 = float(theory.ting_contact_time(time, E_RELAXED, moduli, times, RAMP, HOLD))
    assert t1 == pytest.approx(2 * RAMP + HOLD - time, rel=1e-12, abs=0.0)
    force = float(theory.ting_force(time, RATE, R, E_RELAXED, moduli, times, RAMP, HOLD))
    assert force == pytest.approx(4 / 3 * 3e6 * np.sqrt(R) * depth**1.5, rel=1e-12, abs=0.0)


def test_closed_forms_differentiate_in_the_prony_terms():
    """jax.grad of Ting's force in E₁ and τ₁ against central differences (1e-7)."""

    def force(parameters):
        moduli = jnp.asarray([parameters[0], MODULI[1]])
        times = jnp.asarray([parameters[1], TIMES[1]])
        return theory.ting_force(1.6, RATE, R, E_RELAXED, moduli, times, RAMP, HOLD)

    point = jnp.asarray([MODULI[0], TIMES[0]])
    gradient = np.asarray(jax.grad(force)(point))
    for index, step in enumerate((1e2, 1e-5)):
        shift = np.zeros(2)
        shift[index] = step
        central = (float(force(point + shift)) - float(force(point - shift))) / (2 * step)
        assert gradient[index] == pytest.approx(central, rel=1e-7, abs=0.0)
