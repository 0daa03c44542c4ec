"""The work along the Maugis–Dugdale paraboloid's equilibrium curve in closed form
(`_law.dugdale_energy`) against the integral it replaces, ∫F dd by Gauss–Legendre."""

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
import pytest

from impact import load_scene, theory
from impact._law.dugdale_energy import closed_energy, curve_energy
from impact._run.parameters import integrator_for, options_for, physics_for
from tests.scenes import E_STAR, WORK, R, micro_sphere

_build = eqx.filter_jit(lambda integrator, physics, options: integrator.build(physics, options))


def md_problem(tabor: float, profile: dict | None = None):
    stress = float(theory.maugis_adhesive_stress(tabor, R, WORK, E_STAR))
    scene = micro_sphere(0.6, {"adhesion": {"model": "maugis_dugdale", "work_of_adhesion": WORK, "stress": stress}})
    if profile is not None:
        scene["body"]["profile"] = profile
    scene = load_scene({"name": "md", **scene, "solver": {"method": "quadrature"}})
    return _build(integrator_for(scene), physics_for(scene), options_for(scene, trajectory=False))


def gauss_work(law, curve, start, end, pieces=64, nodes=48):
    """∫F dd from s = start to end: Gauss–Legendre on `pieces` equal pieces."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    edges = np.linspace(start, end, pieces + 1)
    middles, halves = 0.5 * (edges[1:] + edges[:-1]), 0.5 * (edges[1:] - edges[:-1])
    points = middles[:, None] + halves[:, None] * x
    _, force, slope = curve.riding(law, jnp.asarray(points))
    return float(np.sum(halves[:, None] * w * np.asarray(force) * np.asarray(slope)))


@pytest.mark.parametrize("tabor", (1e-2, 0.3, 1.0, 10.0, 1e3))
def test_energy_differences_are_the_work_along_the_curve(tabor):
    """U(s₁) − U(s₀) is ∫F dd by 64 × 48-node Gauss–Legendre within 1e-13 of the larger |U| at
    the stretch's ends (measured ≤ 4e-15), over the zone, across the junction and deep into
    contact (p down to e^-40)."""
    problem = md_problem(tabor)
    law, curve = problem.law, problem.curve
    junction, top = float(curve.junction), float(curve.nodes[-1])
    for start, end in [
        (0.01 * junction, junction),
        (0.5 * junction, junction + 1.0),
        (junction, top),
        (junction + 0.5 * (top - junction), junction + 40.0),
    ]:
        energies = np.asarray(curve_energy(law, curve, jnp.asarray([start, end])))
        expected = gauss_work(law, curve, start, junction) + gauss_work(law, curve, junction, end)
        if start >= junction:
            expected = gauss_work(law, curve, start, end)
        scale = np.max(np.abs(energies))
        assert energies[1] - energies[0] == pytest.approx(expected, rel=0.0, abs=1e-13 * scale), (start, end)


@pytest.mark.parametrize("tabor", (1e-2, 1.0, 1e3))
def test_energy_slope_is_the_force_times_the_depth_slope(tabor):
    """dU/ds = F·dd/ds at states in the zone and in contact, within 1e-13 of |F·dd/ds| + |U|
    (measured ≤ 2e-15); the zone's and the contact's U meet at the junction (within 1e-15 of |U|
    there, measured 3e-16)."""
    problem = md_problem(tabor)
    law, curve = problem.law, problem.curve
    junction = float(curve.junction)
    states = jnp.asarray(
        np.concatenate([junction * np.array([0.05, 0.5, 0.95]), junction + np.array([0.1, 2.0, 20.0])])
    )
    energy, slope = jax.jvp(lambda s: curve_energy(law, curve, s), (states,), (jnp.ones_like(states),))
    _, force, depth_slope = curve.riding(law, states)
    density = np.asarray(force * depth_slope)
    tolerance = 1e-13 * (np.abs(density) + np.abs(np.asarray(energy)))
    assert np.all(np.abs(np.asarray(slope) - density) <= tolerance)
    below, above = (
        float(curve_energy(law, curve, jnp.asarray(s))) for s in (junction, np.nextafter(junction, 2 * junction))
    )
    assert above == pytest.approx(below, rel=1e-15, abs=0.0)


def test_only_the_paraboloid_curve_has_a_closed_energy():
    paraboloid, cone = md_problem(1.0), md_problem(1.0, {"shape": "cone", "theta": 0.1})
    assert closed_energy(paraboloid.law, paraboloid.curve) is not None
    assert closed_energy(cone.law, cone.curve) is None
