"""Thornton & Ning's adhesive elastic–plastic paraboloid in impacts: the elastic adhesive impact to
the bit below yield, the closed forms above it, continuity at v_y, the energy split, the dent kept
between bounces, and refusals."""

import math

import pytest

import impact
from impact import simulate, theory
from impact._scene.scene import load_scene
from tests.scenes import E_STAR, MASS, WORK, R, micro_sphere

P_Y = 1e8  # Pa: the micro-sphere yields at v_y = 2.92 m/s
YIELD_VELOCITY = float(theory.adhesive_plastic_yield_velocity(MASS, R, E_STAR, WORK, P_Y))


def particle(velocity: float, plastic: bool = True, yield_pressure: float = P_Y, **effects) -> dict:
    plasticity = {"plasticity": {"yield_pressure": yield_pressure}} if plastic else {}
    # tsit5 at rtol 1e-10 (the default): the elastic program is shared with other tests
    return micro_sphere(velocity, {"adhesion": {"work_of_adhesion": WORK}, **plasticity, **effects})


def run(velocity: float, plastic: bool = True, yield_pressure: float = P_Y):
    return simulate(particle(velocity, plastic, yield_pressure))


def closed_form(velocity: float, yield_pressure: float = P_Y) -> float:
    return float(theory.adhesive_plastic_restitution(velocity, MASS, R, E_STAR, WORK, yield_pressure))


@pytest.mark.slow
@pytest.mark.parametrize("velocity", [0.6, 0.999 * YIELD_VELOCITY])
def test_below_the_yield_velocity_it_is_the_elastic_adhesive_impact_to_the_bit(velocity):
    plastic, elastic = run(velocity), run(velocity, plastic=False)
    for name in ("restitution", "contact_time", "max_indentation", "max_force", "min_force", "dissipated_energy"):
        assert getattr(plastic, name) == getattr(elastic, name), name
    assert plastic.events == elastic.events and plastic.plastic_work == 0.0


@pytest.mark.slow
@pytest.mark.parametrize("velocity", [3.0, 10.0, 100.0])
def test_above_it_the_restitution_meets_the_closed_form(velocity):
    result = run(velocity)
    assert result.status == "separated"
    assert result.restitution == pytest.approx(closed_form(velocity), abs=1e-8)
    deepest = theory.adhesive_plastic_max_indentation(velocity, MASS, R, E_STAR, WORK, P_Y)
    assert result.max_indentation == pytest.approx(float(deepest), rel=1e-9, abs=0.0)
    assert [kind for _, kind in result.events] == ["touch", "yield", "max_indentation", "separation"]
    # the kinetic energy lost splits into the plastic work and the adhesion hysteresis
    energy = 0.5 * MASS * velocity**2
    lost = energy * (1 - result.restitution**2)
    assert result.plastic_work > 0 and result.adhesion_hysteresis > 0
    assert abs(result.dissipated_energy - lost) < 1e-8 * energy
    hysteresis, plastic = theory.adhesive_plastic_losses(result.max_indentation, R, E_STAR, WORK, P_Y)
    assert abs(float(hysteresis + plastic) - lost) < 1e-8 * energy
    assert result.plastic_work == float(plastic)


@pytest.mark.slow
def test_the_restitution_is_continuous_at_the_yield_velocity():
    """One side runs the elastic integrator, the other the plastic one: they meet to solver tolerance
    (the closed form's slope adds ~1e-10 over this step)."""
    velocities = YIELD_VELOCITY * (1 - 1e-9), YIELD_VELOCITY * (1 + 1e-9)
    below, above = run(velocities[0]), run(velocities[1])
    assert [kind for _, kind in below.events] == ["touch", "max_indentation", "separation"]
    assert "yield" in [kind for _, kind in above.events]
    assert abs(below.restitution - above.restitution) < 5e-9
    for result, velocity in zip((below, above), velocities, strict=True):
        assert result.restitution == pytest.approx(closed_form(velocity), abs=5e-9)


def test_plasticity_raises_the_sticking_velocity():
    """With p_y = 25 MPa (the touch pressure is 21.6 MPa) the sticking velocity is 0.53 m/s, not
    the elastic 0.303 m/s: the body sticks just below it and leaves just above it."""
    yield_pressure = 2.5e7
    sticking = float(theory.adhesive_plastic_sticking_velocity(MASS, R, E_STAR, WORK, yield_pressure))
    elastic = float(theory.thornton_ning_sticking_velocity(MASS, R, E_STAR, WORK))
    assert sticking > 1.5 * elastic
    assert run(0.99 * sticking, yield_pressure=yield_pressure).status == "captured"
    leaving = run(1.01 * sticking, yield_pressure=yield_pressure)
    assert leaving.status == "separated"
    assert leaving.restitution == pytest.approx(closed_form(1.01 * sticking, yield_pressure), abs=1e-8)


def dent_rebound(touch_speed: float, first_velocity: float) -> float:
    """Speed leaving a JKR contact on the dent left by a first impact at `first_velocity`: the jump-in and the
    snap-off on the branch with R_p lose U(a_c) − U(a_j), U = E*∫₀^a(d − g_p)² dx − πa²Δγ."""
    hess = math.sqrt(2 * math.pi * WORK / E_STAR)  # Δl = hess·√a
    a_m = theory.adhesive_plastic_max_radius(first_velocity, MASS, R, E_STAR, WORK, P_Y)
    enlarged = float(theory.adhesive_plastic_dent(a_m, R, E_STAR, WORK, P_Y)[0])

    def stored(a):
        excess = a**2 / enlarged - hess * math.sqrt(a)
        elastic = excess**2 * a - 2 / 3 * excess * a**3 / enlarged + a**5 / (5 * enlarged**2)
        return E_STAR * elastic - math.pi * a**2 * WORK

    jump_in, snap_off = (enlarged * hess) ** (2 / 3), (enlarged * hess / 4) ** (2 / 3)
    return math.sqrt(touch_speed**2 - 2 * (stored(snap_off) - stored(jump_in)) / MASS)


def test_two_bodies_meet_the_closed_form_with_effective_parameters():
    """A sphere of twice the radius and seven times the mass coming the other way: the contact is the
    wall impact of the effective radius and the reduced mass at the closing speed."""
    other_mass, other_velocity, velocity = 7.0 * MASS, 2.0, 8.0
    scene = particle(velocity)
    counterpart = {"profile": {"shape": "paraboloid", "R": 2 * R}, "mass": other_mass, "velocity": other_velocity}
    scene["counterpart"] = counterpart
    result = simulate(scene)
    reduced = MASS * other_mass / (MASS + other_mass)
    closing = velocity + other_velocity
    expected = theory.adhesive_plastic_restitution(closing, reduced, 2 * R / 3, E_STAR, WORK, P_Y)
    assert result.plastic_work > 0
    assert result.restitution == pytest.approx(float(expected), abs=1e-8)
    before = MASS * velocity - other_mass * other_velocity
    after = MASS * result.body_velocity_after + other_mass * result.counterpart_velocity_after
    assert after == pytest.approx(before, rel=1e-12, abs=0.0)


@pytest.mark.slow
def test_bounces_under_gravity_keep_the_dent():
    """The second contact lands in the dent of the first, stays elastic (no yield) and loses only the
    jump-in and snap-off of the dent's JKR branch: its rebound speed (from the flight that follows)
    is that of R_p, far from a fresh paraboloid's."""
    scene = particle(10.0, gravity={})
    scene["limits"] = {"max_bounces": 3}
    result = simulate(scene)
    kinds = [kind for _, kind in result.events]
    assert kinds.count("yield") == 1 and kinds.count("touch") == 3
    assert result.max_indentation == pytest.approx(
        float(theory.adhesive_plastic_max_indentation(10.0, MASS, R, E_STAR, WORK, P_Y)), rel=1e-7, abs=0.0
    )
    touches = [time for time, kind in result.events if kind == "touch"]
    separations = [time for time, kind in result.events if kind == "separation"]
    g = 9.81
    first_out = result.separation_velocity
    second_in = first_out  # the flight returns to the dent (the levels differ by nanometres)
    assert (touches[1] - separations[0]) * g / 2 == pytest.approx(first_out, rel=1e-6, abs=0.0)
    second_out = (touches[2] - separations[1]) * g / 2
    assert second_out == pytest.approx(dent_rebound(second_in, 10.0), rel=1e-6, abs=0.0)
    fresh = float(theory.thornton_ning_restitution(second_in, MASS, R, E_STAR, WORK)) * second_in
    assert abs(second_out - fresh) > 1e-4 * second_in


TOUCH_PRESSURE = float(theory.adhesive_plastic_touch_pressure(R, E_STAR, WORK))
BAD = [
    (
        {"plasticity": {"yield_pressure": 2e7}},
        "effects.plasticity: yield_pressure 2e+07 Pa is at or below the pressure at the centre of the JKR "
        f"contact right after its jump-in, {TOUCH_PRESSURE:.6g} Pa: the contact would yield as it forms, where "
        "Thornton & Ning's law is undefined",
    ),
    (
        {"adhesion": {"work_of_adhesion": WORK, "approach_work_of_adhesion": 0.0}},
        "effects.plasticity: with adhesion the law of Thornton & Ning (1998) is the reversible JKR law: "
        "approach_work_of_adhesion must equal work_of_adhesion (0.05 J/m²), not 0",
    ),
]


@pytest.mark.parametrize(("effects", "message"), BAD)
def test_bad_adhesive_plasticity_is_refused(effects, message):
    scene = particle(1.0)
    scene["effects"] |= effects
    with pytest.raises(impact.SceneError) as error:
        load_scene(scene)
    assert str(error.value).startswith(message)


def test_a_cone_is_refused_with_adhesion_too():
    scene = particle(1.0)
    scene["body"]["profile"] = {"shape": "cone", "theta": 0.2}
    with pytest.raises(impact.SceneError) as error:
        load_scene(scene)
    assert "Thornton's limiting contact pressure is a law of the paraboloid" in str(error.value)
