"""Impacts on the continuum JKR law (and without adhesion, Hertz's) against the chapter's closed
forms and our own references: Thornton–Ning, power laws and cones, capture, the spring array,
attach on touch, gravity."""

import dataclasses
from typing import NamedTuple

import numpy as np
import pytest

from impact import simulate, theory
from impact._run.impacts import solve_scene
from impact._run.parameters import integrator_for, options_for
from impact._scene.scene import load_scene
from tests.scenes import CONFIGS, E_STAR, MASS, WORK, R

MATERIALS = {
    # micro-particle on a stiff polymer, and a softer, stickier pair
    "micro": dict(R=R, E_star=E_STAR, work_of_adhesion=WORK, mass=MASS),
    "soft": dict(R=5e-5, E_star=2e7, work_of_adhesion=0.2, mass=2.0e-9),
}
TIGHT = dict(method="tsit5", rtol=1e-11, atol=1e-13)


def paraboloid_scene(material, velocity, adhesion=True, approach=None, solver=None, **extra):
    m = MATERIALS[material]
    effects = {}
    if adhesion:
        effects["adhesion"] = {"work_of_adhesion": m["work_of_adhesion"]}
        if approach is not None:
            effects["adhesion"]["approach_work_of_adhesion"] = approach
    scene = dict(
        name="test",
        body=dict(profile=dict(shape="paraboloid", R=m["R"]), mass=m["mass"]),
        material=dict(E_star=m["E_star"]),
        initial=dict(velocity=velocity),
        effects=effects,
    )
    if solver:
        scene["solver"] = solver
    scene.update(extra)
    return scene


def sticking_velocity(material):
    m = MATERIALS[material]
    return float(theory.thornton_ning_sticking_velocity(m["mass"], m["R"], m["E_star"], m["work_of_adhesion"]))


def tn_restitution(material, velocity):
    m = MATERIALS[material]
    return float(theory.thornton_ning_restitution(velocity, m["mass"], m["R"], m["E_star"], m["work_of_adhesion"]))


VELOCITY_FACTORS = np.geomspace(1.001, 50.0, 24)


@pytest.mark.slow
@pytest.mark.parametrize("material", sorted(MATERIALS))
@pytest.mark.parametrize("solver, tolerance", [(None, 1e-6), (TIGHT, 1e-9)], ids=["default", "tight"])
def test_thornton_ning_restitution(material, solver, tolerance):
    """(3.50–51) over 24 velocities in [1.001, 50]·v_s; the largest force against the energy
    balance along the JKR branch (`theory.thornton_ning_max_force`), relative."""
    v_s = sticking_velocity(material)
    m = MATERIALS[material]
    errors, force_errors = [], []
    for factor in VELOCITY_FACTORS:
        result = simulate(paraboloid_scene(material, factor * v_s, solver=solver))
        assert result.status == "separated"
        errors.append(abs(result.restitution - tn_restitution(material, factor * v_s)))
        expected = theory.thornton_ning_max_force(factor * v_s, m["mass"], m["R"], m["E_star"], m["work_of_adhesion"])
        force_errors.append(abs(result.max_force / float(expected) - 1))
    assert max(errors) <= tolerance, max(errors)
    assert max(force_errors) <= tolerance, max(force_errors)


def test_without_trajectory_the_same_impact_keeps_no_time_series():
    """`trajectory=False` leaves the samples out of the program: the same outcome to the bit."""
    scene = paraboloid_scene("micro", 2 * sticking_velocity("micro"))
    full, bare = simulate(scene), simulate(scene, trajectory=False)
    assert len(full.t) > 100 and len(full.force) == len(full.t)
    assert len(bare.t) == len(bare.indentation) == len(bare.force) == 0
    assert bare.restitution == full.restitution and bare.stats["steps"] == full.stats["steps"]
    assert bare.events == full.events


class Agreement(NamedTuple):
    """How closely the general program runs a scene that never loads in time (relative)."""

    events: float  # event times
    restitution: float
    samples: bool  # the same trajectory samples, compared to 1e-13 of each series' largest value


# Scenes that never load in time. The paraboloid that jumps in runs the same bits here (7.8e-16
# apart in e at configs/thornton_ning.yaml). Attaching on touch (Δγa = 0) or without adhesion,
# loading rides from the tip, whose slope ĝ' = 2Âa is finite: the same steps and events, but
# the programs differ otherwise (the general one computes the timed values it then discards), so
# XLA rounds them otherwise: without adhesion the receding phase's contact time moves by 1.4e-11
# (its error against Hertz is 2e-10 in both), and the loading phase's first sample, at the touch,
# holds a radius of 1.6e-315 instead of 0 and is kept beside the touch's own sample.
NEVER_TIMED = {
    "jump-in": (lambda: paraboloid_scene("micro", 2 * sticking_velocity("micro")), Agreement(1e-14, 1e-14, True)),
    "attach on touch": (lambda: CONFIGS / "attach_on_touch.yaml", Agreement(1e-14, 1e-14, False)),
    "no adhesion": (lambda: CONFIGS / "hard" / "01_no_adhesion.yaml", Agreement(1e-10, 1e-14, False)),
}


@pytest.mark.slow
@pytest.mark.parametrize("case", NEVER_TIMED)
def test_a_scene_that_never_loads_in_time_runs_as_the_general_program_does(case):
    """Where loading is never integrated in time (`Options.timed_loading` false: a body
    ĝ = Â·aⁿ with n ≥ 1 that jumps in, attaches on touch or has no adhesion), every phase
    integrated in time is a hold, and the program leaves out the branch tables and the
    radius solve; the general program, which keeps them, runs the same impact with the same
    events, to the integration's rounding."""
    source, agree = NEVER_TIMED[case]
    scene = load_scene(source())
    options = options_for(scene)
    assert not options.timed_loading
    general = solve_scene(scene, integrator_for(scene), dataclasses.replace(options, timed_loading=True))
    specialised = simulate(scene)
    assert general.stats["steps"] == specialised.stats["steps"]
    assert [kind for _, kind in general.events] == [kind for _, kind in specialised.events]
    np.testing.assert_allclose([t for t, _ in general.events], [t for t, _ in specialised.events], rtol=agree.events)
    assert general.restitution == pytest.approx(specialised.restitution, rel=agree.restitution, abs=0.0)
    for name in ("contact_time", "max_indentation", "max_force"):
        assert getattr(general, name) == pytest.approx(getattr(specialised, name), rel=agree.events, abs=0.0), name
    for name in ("t", "indentation", "velocity", "force", "contact_radius") if agree.samples else ():
        mine, theirs = getattr(general, name), getattr(specialised, name)
        assert mine.shape == theirs.shape and len(theirs) > 100
        assert np.max(np.abs(mine - theirs)) <= 1e-13 * np.max(np.abs(theirs)), name


def test_pull_off_force_is_reached_during_unloading():
    """Separating contacts pass the force-controlled critical point: min F = −(3/2)πΔγR (3.46)."""
    m = MATERIALS["micro"]
    result = simulate(paraboloid_scene("micro", 3 * sticking_velocity("micro")))
    pull_off = -1.5 * np.pi * m["work_of_adhesion"] * m["R"]
    assert result.min_force == pytest.approx(pull_off, rel=1e-10, abs=0.0)


def power_law_scene(n, c, velocity, approach=None):
    m = MATERIALS["micro"]
    adhesion = {"work_of_adhesion": m["work_of_adhesion"]}
    if approach is not None:
        adhesion["approach_work_of_adhesion"] = approach
    return dict(
        name="power",
        body=dict(profile=dict(shape="power_law", n=n, c=c), mass=m["mass"]),
        material=dict(E_star=m["E_star"]),
        initial=dict(velocity=velocity),
        effects=dict(adhesion=adhesion),
    )


def tip_constant(n):
    """c for f = c·rⁿ through the paraboloid's f at r = R (keeps the contact micro-sized)."""
    return R ** (1.0 - n) / 2.0


@pytest.mark.parametrize("n", [0.75, 1.0, 1.5, 3.0, 4.0])
def test_power_law_restitution(n):
    """(3.81–82) at several velocities, default settings, within 1e-6."""
    m = MATERIALS["micro"]
    c = tip_constant(n)
    v_s = float(theory.power_law_sticking_velocity(m["mass"], n, c, m["E_star"], m["work_of_adhesion"]))
    for factor in (1.01, 1.5, 3.0, 10.0, 40.0):
        result = simulate(power_law_scene(n, c, factor * v_s))
        expected = float(
            theory.power_law_restitution(factor * v_s, m["mass"], n, c, m["E_star"], m["work_of_adhesion"])
        )
        assert abs(result.restitution - expected) <= 1e-6, (factor, result.restitution, expected)


def test_cone_restitution_is_the_power_law_n_1():
    """A cone of half-angle θ is the power law n = 1, c = tanθ."""
    m = MATERIALS["micro"]
    theta = 0.3
    c = np.tan(theta)
    v_s = float(theory.power_law_sticking_velocity(m["mass"], 1.0, c, m["E_star"], m["work_of_adhesion"]))
    scene = power_law_scene(1.0, c, 2.0 * v_s)
    scene["body"]["profile"] = dict(shape="cone", theta=theta)
    expected = float(theory.power_law_restitution(2.0 * v_s, m["mass"], 1.0, c, m["E_star"], m["work_of_adhesion"]))
    assert abs(simulate(scene).restitution - expected) <= 1e-6


@pytest.mark.parametrize("factor", [0.5, 0.999])
def test_below_sticking_velocity_the_body_is_captured(factor):
    v_s = sticking_velocity("micro")
    result = simulate(paraboloid_scene("micro", factor * v_s))
    assert result.status == "captured" and result.stuck
    assert result.restitution == 0.0
    assert result.contact_time == np.inf
    assert [kind for _, kind in result.events][-1] == "capture"
    assert np.isfinite(result.events[-1][0]) and result.stats["steps"] < 1000


@pytest.mark.slow
@pytest.mark.parametrize("adhesion", [None, 0.0], ids=["not named", "zero"])
def test_no_adhesion_is_elastic_hertz(adhesion):
    """Δγ = 0: e = 1 within 1e-9, contact time 2.868…(m²/(R E*² v0))^(1/5) within 1e-6."""
    m = MATERIALS["micro"]
    scene = paraboloid_scene("micro", 0.5, adhesion=False)
    if adhesion is not None:
        scene["effects"] = {"adhesion": {"work_of_adhesion": adhesion}}
    assert not options_for(load_scene(scene)).adhesive
    result = simulate(scene)
    assert abs(result.restitution - 1.0) <= 1e-9
    contact_time = float(theory.hertz_contact_time(0.5, m["mass"], m["R"], m["E_star"]))
    assert result.contact_time == pytest.approx(contact_time, rel=1e-6, abs=0.0)
    assert result.max_indentation == pytest.approx(
        float(theory.hertz_max_indentation(0.5, m["mass"], m["R"], m["E_star"])), rel=1e-8, abs=0.0
    )
    assert result.min_force >= 0.0


def test_spring_array_converges_to_the_continuum_at_second_order():
    """Midpoint springs, contact from d = 0: e(N) → e_TN with a fitted order ≥ 1.8."""
    v_s = sticking_velocity("micro")
    counts = np.unique(np.round(250 * 2 ** (np.arange(17) / 4)).astype(int))
    errors = []
    for count in counts:
        scene = paraboloid_scene("micro", 2 * v_s, contact={"springs": int(count)})
        result = simulate(scene)
        assert result.status == "separated"
        errors.append(abs(result.restitution - tn_restitution("micro", 2 * v_s)))
    order = -np.polyfit(np.log(counts), np.log(errors), 1)[0]
    assert order >= 1.8, order
    assert errors[-1] < 1e-7


def test_spring_array_events_are_exact():
    """The array is integrated in closed form: its loop work equals the kinetic energy lost."""
    v_s = sticking_velocity("micro")
    result = simulate(paraboloid_scene("micro", 2 * v_s, contact={"springs": 300}))
    lost = 0.5 * MATERIALS["micro"]["mass"] * (result.touch_velocity**2 - result.separation_velocity**2)
    assert lost == pytest.approx(result.dissipated_energy, rel=1e-10, abs=0.0)


ATTACH_FACTORS = [1.3, 2.0, 5.0, 20.0]


@pytest.mark.parametrize("factor", ATTACH_FACTORS)
def test_attach_on_touch_matches_its_reference(factor):
    """Δγa = 0: Hertzian loading, hold at a_max, JKR unloading; e(v0) against the closed form
    of theory.attach_on_touch_restitution, and always below Thornton–Ning."""
    m = MATERIALS["micro"]
    velocity = factor * sticking_velocity("micro")
    result = simulate(paraboloid_scene("micro", velocity, approach=0.0))
    expected = float(
        theory.attach_on_touch_restitution(velocity, m["mass"], m["R"], m["E_star"], m["work_of_adhesion"])
    )
    assert abs(result.restitution - expected) <= 1e-6
    assert result.restitution < tn_restitution("micro", velocity)
    assert [kind for _, kind in result.events] == ["touch", "max_indentation", "detach_start", "separation"]


@pytest.mark.parametrize("factor", ATTACH_FACTORS)
def test_attach_on_touch_energy_balance(factor):
    """Kinetic energy lost = loop area ∮F dd within 1e-8 relative (tight tolerances)."""
    m = MATERIALS["micro"]
    velocity = factor * sticking_velocity("micro")
    result = simulate(paraboloid_scene("micro", velocity, approach=0.0, solver=TIGHT))
    lost = 0.5 * m["mass"] * (result.touch_velocity**2 - result.separation_velocity**2)
    assert lost == pytest.approx(result.dissipated_energy, rel=1e-8, abs=0.0)


def test_attach_on_touch_captures_below_its_own_threshold():
    """The attach-on-touch capture threshold is 1.2649·v_s (root of the reference's β = 1)."""
    v_s = sticking_velocity("micro")
    assert simulate(paraboloid_scene("micro", 1.2640 * v_s, approach=0.0)).stuck
    above = simulate(paraboloid_scene("micro", 1.2660 * v_s, approach=0.0))
    assert above.status == "separated" and 0.0 < above.restitution < 0.05


def test_gravity_touchdown_time():
    """Dropped from rest at height h, the body touches at √(2h/g)."""
    gap, g = 1e-6, 9.81
    scene = paraboloid_scene("micro", 0.0, initial={"velocity": 0.0, "gap": gap})
    scene["effects"]["gravity"] = {"g": g}
    result = simulate(scene)
    assert result.events[0][1] == "touch"
    assert result.events[0][0] == pytest.approx(np.sqrt(2 * gap / g), rel=1e-12, abs=0.0)
    assert result.touch_velocity == pytest.approx(np.sqrt(2 * g * gap), rel=1e-12, abs=0.0)


@pytest.mark.slow
def test_gravity_sticky_bounces_end_captured():
    """Dropped to touch at 2·v_s, the body bounces a few times and is captured, in bounded steps."""
    g = 9.81
    v_s = sticking_velocity("micro")
    gap = (2 * v_s) ** 2 / (2 * g)
    scene = paraboloid_scene("micro", 0.0, initial={"velocity": 0.0, "gap": gap})
    scene["effects"]["gravity"] = {"g": g}
    result = simulate(scene)
    assert result.status == "captured" and result.stuck
    assert result.bounces >= 3
    assert result.stats["steps"] < 64 * 4096
    kinds = [kind for _, kind in result.events]
    assert kinds.count("touch") == result.bounces and kinds[-1] == "capture"
    # The first bounce is the Thornton–Ning one: gravity is negligible during the contact.
    assert result.restitution == pytest.approx(tn_restitution("micro", result.touch_velocity), abs=1e-6)
