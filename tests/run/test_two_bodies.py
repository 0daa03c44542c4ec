"""Two free bodies: the contact takes the effective radius, E* and the reduced mass; momentum is
conserved and the kinetic energy lost is the loop work; a sweep over the counterpart."""

import numpy as np
import pytest

import impact
from impact import simulate
from impact._scene.scene import load_scene
from tests.scenes import DENSITY, R_BODY, R_OTHER, V_BODY, V_OTHER, two_spheres


@pytest.fixture(scope="module")
def pair():
    return simulate(two_spheres())


@pytest.mark.slow
def test_same_restitution_as_the_wall_impact_with_effective_parameters(pair):
    scene = pair.scene
    m1, m2 = scene.body.resolved_mass, scene.counterpart.resolved_mass
    wall = simulate(
        {
            "body": {
                "profile": {"shape": "paraboloid", "R": R_BODY * R_OTHER / (R_BODY + R_OTHER)},
                "mass": m1 * m2 / (m1 + m2),
            },
            "material": {"E_star": 1.0 / ((1 - 0.2**2) / 63e9 + (1 - 0.22**2) / 70e9)},
            "initial": {"velocity": V_BODY + V_OTHER},
            "effects": {"adhesion": {"work_of_adhesion": 0.1}},
        },
        trajectory=False,
    )
    assert 0.5 < pair.restitution < 1.0
    assert pair.restitution == pytest.approx(wall.restitution, abs=1e-10)


def test_momentum_is_conserved(pair):
    scene = pair.scene
    m1, m2 = scene.body.resolved_mass, scene.counterpart.resolved_mass
    before = m1 * V_BODY - m2 * V_OTHER
    after = m1 * pair.body_velocity_after + m2 * pair.counterpart_velocity_after
    assert after == pytest.approx(before, rel=1e-12, abs=0.0)
    assert pair.centre_of_mass_velocity == pytest.approx(before / (m1 + m2), rel=1e-12, abs=0.0)
    # in the centre-of-mass frame the momenta cancel and the bodies part at the separation speed
    assert m1 * pair.body_velocity_after_cm == pytest.approx(
        -m2 * pair.counterpart_velocity_after_cm, rel=1e-12, abs=0.0
    )
    assert pair.counterpart_velocity_after - pair.body_velocity_after == pytest.approx(
        pair.restitution * (V_BODY + V_OTHER), rel=1e-12, abs=0.0
    )


def test_kinetic_energy_lost_is_the_loop_work(pair):
    scene = pair.scene
    m1, m2 = scene.body.resolved_mass, scene.counterpart.resolved_mass
    before = 0.5 * (m1 * V_BODY**2 + m2 * V_OTHER**2)
    after = 0.5 * (m1 * pair.body_velocity_after**2 + m2 * pair.counterpart_velocity_after**2)
    assert pair.dissipated_energy > 0
    assert before - after == pytest.approx(pair.dissipated_energy, rel=1e-7, abs=0.0)


def test_a_rigid_flat_at_rest_is_the_default():
    wall = simulate({**two_spheres(), "counterpart": None})
    assert wall.centre_of_mass_velocity == 0.0 and wall.counterpart_velocity_after == 0.0
    assert wall.body_velocity_after == -wall.separation_velocity


@pytest.mark.slow
def test_a_sweep_over_the_counterpart_meets_thornton_ning_with_effective_parameters():
    result = impact.sweep(two_spheres(), {"counterpart.velocity": [0.0, 0.2], "counterpart.profile.R": [1e-5, 4e-5]})
    assert result.restitution.shape == (2, 2)
    assert abs(result.restitution - result.theory_restitution).max() < 1e-8
    # both bodies' lab velocities: momentum conserved, separating at the relative rebound speed
    m1 = load_scene(two_spheres()).body.resolved_mass
    m2 = DENSITY * 4 / 3 * np.pi * result.params["counterpart.profile.R"] ** 3
    v2 = result.params["counterpart.velocity"]
    u1, u2 = result.body_velocity_after, result.counterpart_velocity_after
    np.testing.assert_allclose(m1 * u1 + m2 * u2, m1 * V_BODY - m2 * v2, rtol=1e-12, atol=1e-12 * m1 * V_BODY)
    np.testing.assert_allclose(u2 - u1, result.restitution * (V_BODY + v2), rtol=1e-12)
    assert result.viscous_work is None and result.adhesion_hysteresis is not None
