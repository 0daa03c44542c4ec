"""The work ∫F dd along a branch of a power-law body ĝ = Â·aⁿ in closed form (`branch_work`)
against an independent quadrature of F(a)·h'(a) (scipy's adaptive quad), with and without
adhesion, loading and unloading, from the tip and across a short stretch."""

import jax.numpy as jnp
import numpy as np
import pytest
from scipy.integrate import quad

from impact._integrate.work import branch_work
from impact._law.branches import Tabulation, build_branch
from impact._law.law import ContactLaw
from impact._law.scales import Scales
from impact.profiles import PowerLaw

ONE = jnp.ones(())
UNITS = Scales(radial=ONE, normal=ONE, force=ONE, time=ONE)  # SI = scaled: ĝ = κ(n)·c·aⁿ


def power_law_law(exponent: float, coefficient: float) -> ContactLaw:
    profile = PowerLaw(n=exponent, c=0.7)
    return ContactLaw(profile, UNITS, jnp.asarray(coefficient), jnp.asarray(coefficient), coefficient > 0.0)


def reference_work(law: ContactLaw, coefficient: float, start: float, end: float) -> float:
    """∫ F(a)·h'(a) da with F = 2(a·h − Ĝ), h = Â·aⁿ − λ√a, by adaptive quadrature."""
    scale, exponent = (float(x) for x in law.power_form())

    def integrand(a):
        h = scale * a**exponent - coefficient * np.sqrt(a)
        force = 2.0 * (a * h - scale * a ** (exponent + 1.0) / (exponent + 1.0))
        slope = exponent * scale * a ** (exponent - 1.0) - 0.5 * coefficient / np.sqrt(a)
        return force * slope

    value, _ = quad(integrand, start, end, epsabs=0.0, epsrel=1e-13, limit=200)
    return value


@pytest.mark.parametrize("exponent", [1.0, 1.5, 2.0, 3.0])
@pytest.mark.parametrize("coefficient", [0.0, 0.8])
def test_the_work_along_a_power_law_branch_is_the_integral_of_force_times_edge_slope(exponent, coefficient):
    law = power_law_law(exponent, coefficient)
    branch = build_branch(law, jnp.asarray(coefficient), jnp.asarray(50.0), Tabulation(), 0)
    for start, end in ((0.0, 2.5), (0.3, 4.0), (4.0, 0.3), (1.1, 1.1 + 1e-3)):
        expected = reference_work(law, coefficient, min(start, end), max(start, end)) * np.sign(end - start)
        work = float(branch_work(law, branch, jnp.asarray(start), jnp.asarray(end)))
        assert work == pytest.approx(expected, rel=1e-11, abs=1e-14 * abs(reference_work(law, coefficient, 0.0, 4.0)))
