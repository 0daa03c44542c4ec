"""Sweeps over a Prony term's relaxation time and the impact speed (one compiled batch), and
derivatives of an impact's results with respect to E_i and τ_i (`impact.as_function`)."""

import jax
import jax.numpy as jnp
import numpy as np
import pytest

import impact
from impact import theory
from tests.scenes import MASS, R

SPEED, RELAXED, ARM = 0.6, 1e9, 1e9  # m/s; E∞*, E₁ (Pa)
CONTACT = float(theory.hertz_contact_time(SPEED, MASS, R, RELAXED + 0.5 * ARM))
TAU = "effects.viscoelasticity.prony.0.time"
MODULUS = "effects.viscoelasticity.prony.0.modulus"
SCENE = {
    "name": "viscoelastic_sweep",
    "body": {"profile": {"shape": "paraboloid", "R": R}, "mass": MASS},
    "material": {"E_star": RELAXED},
    "initial": {"velocity": SPEED},
    "contact": {"springs": 300},
    "solver": {"method": "midpoint", "dt": CONTACT / 400},
    "effects": {
        "viscoelasticity": {"prony": [{"modulus": ARM, "time": CONTACT}]},
        "adhesion": {"work_of_adhesion": 0.01},
    },
}


@pytest.mark.slow
def test_sweep_over_relaxation_time_and_speed():
    """A grid of τ and v0 in one batch: each point as `simulate` gives it (to 1e-12), the named
    losses (viscous work, the energy left in the medium, the snaps) summing to the loss, and no
    closed form."""
    times, speeds = [0.1 * CONTACT, CONTACT, 10 * CONTACT], [0.6, 1.2]
    result = impact.sweep(SCENE, {TAU: times, "initial.velocity": speeds})
    assert result.restitution.shape == (3, 2) and np.all(result.status == 0)
    for i, j in ((0, 0), (1, 1), (2, 0)):
        point = {**SCENE, "initial": {"velocity": speeds[j]}}
        point["effects"] = {**SCENE["effects"], "viscoelasticity": {"prony": [{"modulus": ARM, "time": times[i]}]}}
        single = impact.simulate(point, trajectory=False)
        assert result.restitution[i, j] == pytest.approx(single.restitution, rel=1e-12, abs=0.0)
        assert result.viscous_work[i, j] == pytest.approx(single.viscous_work, rel=1e-12, abs=0.0)
        assert result.unrecovered_elastic_energy[i, j] == pytest.approx(
            single.unrecovered_elastic_energy, rel=1e-12, abs=0.0
        )
    named = result.viscous_work + result.unrecovered_elastic_energy + result.adhesion_hysteresis
    assert named == pytest.approx(result.dissipated_energy, rel=1e-12, abs=0.0)
    assert np.all(np.isnan(result.theory_restitution))


@pytest.mark.slow
def test_derivatives_in_the_prony_term():
    """de/dE₁ and de/dτ₁ by forward mode through the steps (the springs' changes differentiated
    implicitly) against central differences of the same program (relative step 1e-5: to 1e-6)."""
    f = impact.as_function(SCENE, [MODULUS, TAU], "restitution")
    x = jnp.asarray([ARM, CONTACT])
    gradient = np.asarray(jax.grad(f)(x))
    assert gradient[0] < 0 < gradient[1]  # De ≈ 1: a stiffer arm dissipates more; a slower one less
    for index in range(2):
        step = np.zeros(2)
        step[index] = 1e-5 * float(x[index])
        central = (float(f(x + step)) - float(f(x - step))) / (2 * step[index])
        assert gradient[index] == pytest.approx(central, rel=1e-6, abs=0.0)
