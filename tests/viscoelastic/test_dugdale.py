"""Maugis–Dugdale adhesion on a viscoelastic half-space (`_law.viscoelastic_dugdale`): the step of
a spring under a force linear in time, the elastic limits τ → 0 and τ → ∞ against the elastic
Maugis–Dugdale spring array, the energy balance with the zone's interface energy, the order of
the time step.

One compiled program serves every impact here: the step dt is traced (given as an array)."""

import equinox as eqx
import jax.numpy as jnp
import numpy as np
import pytest
from scipy.integrate import solve_ivp

import impact
from impact import theory
from impact._law.prony import PronyElement
from impact._run.impacts import solve_scene
from impact._run.parameters import integrator_for, options_for
from tests.scenes import MASS, WORK, R

SPEED = 0.6  # m/s
RELAXED, ARM = 1e9, 1e9  # E∞*, E₁ (Pa): E₀* = 2e9 Pa
STRESS = float(theory.maugis_adhesive_stress(1.0, R, WORK, RELAXED))  # Tabor parameter 1 at E∞*
SPRINGS, LENGTH = 200, 2.5e-7  # 1.9 times the largest contact radius
STEPS = 2000  # steps per contact time where the limits are checked
# The elastic limits against the elastic array (measured for τ → 0 and τ → ∞: restitution 9e-7
# and 1.0e-5, largest force 3.5e-4 and 3.5e-4, contact time 3.8e-5 and 9.3e-6; against the
# continuum law the restitution is 1.4e-5 and 8e-6 off, the elastic array's 1.5e-5 and 1.8e-5).
LIMIT_RESTITUTION, LIMIT_FORCE, LIMIT_TIME = 5e-5, 5e-4, 1e-4
# The energy balance at De ≈ 1 and dt = t_c/1000 (measured 2.2e-6; 4.2e-6, 1.1e-6, 2.2e-6, 1.2e-6
# at t_c/250 … t_c/2000: the small folds of the discrete zone near the pull-off that a sub-step
# of Δx/4 does not see as snaps).
BALANCE = 1e-5


def contact_time(modulus: float) -> float:
    return float(theory.hertz_contact_time(SPEED, MASS, R, modulus))


def adhesion() -> dict:
    return {"model": "maugis_dugdale", "work_of_adhesion": WORK, "stress": STRESS}


def scene(time: float) -> dict:
    return {
        "name": "viscoelastic_dugdale",
        "body": {"profile": {"shape": "paraboloid", "R": R}, "mass": MASS},
        "material": {"E_star": RELAXED},
        "initial": {"velocity": SPEED},
        "contact": {"springs": SPRINGS, "length": LENGTH},
        "solver": {"method": "midpoint", "dt": 1e-11},
        "effects": {"viscoelasticity": {"prony": [{"modulus": ARM, "time": time}]}, "adhesion": adhesion()},
    }


def run(data: dict, dt: float) -> impact.Result:
    """The scene stepped at dt (s), traced: one program for every dt."""
    loaded = impact.load_scene(data)
    integrator = eqx.tree_at(lambda solver: solver.dt, integrator_for(loaded), jnp.asarray(dt))
    return solve_scene(loaded, integrator, options_for(loaded, trajectory=False))


def test_spring_under_a_force_linear_in_time():
    """`PronyElement.forced` (two terms) against DOP853 (rtol 1e-13): stretches, displacement and
    the dashpots' dissipation to 1e-12; `forced_surface` meets its displacement."""
    moduli, times = np.array([3.0, 0.5]), np.array([0.7, 4.0])
    element = PronyElement(jnp.asarray(moduli), jnp.asarray(times))
    start, force, rate, duration = np.array([0.3, -0.2]), -0.4, 0.9, 1.3

    def slope(time, state):  # f = u + Σe·q, q̇ = u̇ − q/τ with u̇ = ḟ − Σe·q̇
        stretches = state[:2]
        arms = np.linalg.solve(np.eye(2) + np.outer(np.ones(2), moduli), rate - stretches / times)
        return np.concatenate([arms, [np.sum(moduli / times * stretches**2)]])

    exact = solve_ivp(slope, (0.0, duration), np.concatenate([start, [0.0]]), method="DOP853", rtol=1e-13, atol=1e-15)
    stretches, dissipation = exact.y[:2, -1], exact.y[2, -1]
    arguments = (jnp.asarray(start), jnp.asarray(force), jnp.asarray(rate), jnp.asarray(duration))
    step = element.forced(*arguments)
    assert np.allclose(step.stretches, stretches, rtol=0, atol=1e-12)
    assert float(step.dissipation) == pytest.approx(dissipation, abs=1e-12)
    displacement = force + rate * duration - moduli @ stretches
    assert float(step.displacement) == pytest.approx(displacement, abs=1e-12)
    surface, _ = element.forced_surface(*arguments)
    assert float(surface) == pytest.approx(float(step.displacement), abs=1e-14)


@pytest.mark.slow
@pytest.mark.parametrize(("time", "modulus"), [(1e-20, RELAXED), (1e6, RELAXED + ARM)])
def test_elastic_limits_are_the_elastic_maugis_dugdale_array(time, modulus):
    """τ → 0: the elastic Maugis–Dugdale array of E∞*; τ → ∞: of E₀* (same springs, Δγ, σ0),
    dt = t_c/2000. They differ by the zone's discretisation (this array interpolates the zone's
    gaps between its springs, the elastic array takes the zone exactly)."""
    result = run(scene(time), contact_time(modulus) / STEPS)
    elastic = impact.simulate(
        {**scene(time), "material": {"E_star": modulus}, "effects": {"adhesion": adhesion()}, "solver": {}},
        trajectory=False,
    )
    assert result.status == elastic.status == "separated"
    assert result.restitution == pytest.approx(elastic.restitution, abs=LIMIT_RESTITUTION)
    assert result.max_force == pytest.approx(elastic.max_force, rel=LIMIT_FORCE, abs=0.0)
    assert result.contact_time == pytest.approx(elastic.contact_time, rel=LIMIT_TIME, abs=0.0)


def test_energy_balance_of_the_first_contact():
    """De ≈ 1: the kinetic energy lost is the work on the springs, ∮F dd (to 1e-10), and that is
    the dashpots' dissipation + the energy the medium still stores + the snaps (the zone's birth
    and collapse, the edge's) (the zone's interface energy is 0 once it collapsed)."""
    tau = contact_time(RELAXED + 0.5 * ARM)
    result = run(scene(tau), tau / 1000)
    relaxation = result.relaxation
    assert result.status == "separated" and relaxation is not None
    work = result.dissipated_energy
    lost = 0.5 * MASS * (result.touch_velocity**2 - result.separation_velocity**2)
    assert lost == pytest.approx(work, rel=1e-10, abs=0)
    snaps = relaxation.released_energy - relaxation.gained_energy
    assert result.viscous_work + relaxation.stored_energy + snaps == pytest.approx(work, rel=BALANCE, abs=0)
    assert result.viscous_work > 0.5 * work  # the dashpots take most of it at De ≈ 1


@pytest.mark.slow
def test_time_step_order_is_two():
    """De ≈ 1: restitution, contact time and largest force converge as dt² (fitted order within
    0.3 of 2 over t_c/250 … t_c/1000 against t_c/2000: measured 2.12, 2.19, 2.05)."""
    tau = contact_time(RELAXED + 0.5 * ARM)
    reference = run(scene(tau), tau / 2000)
    steps = np.array([250, 500, 1000])
    results = [run(scene(tau), tau / k) for k in steps]
    for name in ("restitution", "contact_time", "max_force"):
        errors = np.abs([getattr(result, name) - getattr(reference, name) for result in results])
        order = -np.polyfit(np.log(steps), np.log(errors), 1)[0]
        assert order == pytest.approx(2.0, abs=0.3), (name, errors)


def test_without_a_spring_array_it_is_refused():
    """Maugis–Dugdale on a viscoelastic half-space needs the springs (their history), as JKR does:
    the continuum is refused with the medium's message, before the adhesion's own checks."""
    data = scene(1e-8)
    data["contact"] = {"springs": "continuum"}
    with pytest.raises(impact.SceneError) as error:
        impact.load_scene(data)
    ((field, message),) = error.value.problems
    assert field == "contact.springs"
    assert message.startswith("a viscoelastic half-space runs on a spring array: give the number of springs N")
