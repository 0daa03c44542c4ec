"""Every example scene in configs/ runs, succeeds, and meets its closed form where one exists."""

import math

import numpy as np
import pytest

import impact
from impact import theory
from impact._run.impacts import Result
from tests.run.passive import assert_passive
from tests.scenes import CONFIGS


def thornton_ning(scene, velocity):
    """Thornton–Ning restitution (3.50) of a paraboloid scene at a touch velocity (m/s)."""
    return float(
        theory.thornton_ning_restitution(
            velocity,
            scene.reduced_mass,
            scene.contact_profile.R,
            scene.material.effective_modulus,
            scene.effects.adhesion.work_of_adhesion,
        )
    )


def power_law(scene, velocity):
    """Power-law restitution (3.81) of a cone (n = 1, c = tan θ) or power-law scene."""
    profile = scene.body.profile
    n, c = (1.0, math.tan(profile.theta)) if profile.shape == "cone" else (profile.n, profile.c)
    return float(
        theory.power_law_restitution(
            velocity,
            scene.body.resolved_mass,
            n,
            c,
            scene.material.effective_modulus,
            scene.effects.adhesion.work_of_adhesion,
        )
    )


def matches(closed_form, tolerance):
    def check(result):
        assert result.restitution == pytest.approx(closed_form(result.scene, result.touch_velocity), abs=tolerance)

    return check


def below_thornton_ning(result):
    assert 0 < result.restitution < thornton_ning(result.scene, result.touch_velocity)


def captured_after_bouncing(result):
    assert result.stuck and result.status == "captured"
    assert result.bounces >= 3  # at least two rebounds, then the capturing contact


def force_controlled_pull_off(result):
    """Force control: the paraboloid lets go at F_c = −(3/2)πΔγR (3.46)."""
    scene = result.scene
    a_c, d_c, F_c = (
        float(x)
        for x in theory.paraboloid_critical(
            scene.body.profile.R, scene.material.effective_modulus, scene.effects.adhesion.work_of_adhesion, 3.0
        )
    )
    assert result.pull_off.force == pytest.approx(F_c, rel=1e-10, abs=0.0)
    assert result.pull_off.contact_radius == pytest.approx(a_c, rel=1e-10, abs=0.0)


def displacement_controlled_wavy_pull_off(result):
    """Displacement control: the last state lies on (3.138)'s d(a), at a turn of d(a) (a local minimum)."""
    scene, pull_off = result.scene, result.pull_off
    profile = scene.body.profile
    args = (
        profile.R,
        profile.amplitude,
        profile.wavelength,
        scene.material.effective_modulus,
        scene.effects.adhesion.work_of_adhesion,
    )

    def depth(a):
        return float(theory.wavy_paraboloid_indentation(a, *args))

    a = pull_off.contact_radius
    assert pull_off.indentation == pytest.approx(depth(a), rel=1e-9, abs=0.0)
    step = 1e-4 * a
    assert depth(a - step) > depth(a) and depth(a + step) > depth(a)
    assert pull_off.indentation < 0.0


def maugis_dugdale_pull_off(result):
    """Λ = 1: e between Thornton–Ning and 1; the unloading passes the pull-off force of (3.171)."""
    scene = result.scene
    adhesion = scene.effects.adhesion
    R, E_star = scene.body.profile.R, scene.material.effective_modulus
    tabor = float(theory.tabor_parameter(R, adhesion.adhesive_stress, adhesion.adhesion_range, E_star))
    assert result.tabor_parameter == pytest.approx(tabor, rel=1e-12, abs=0.0)
    assert thornton_ning(scene, result.touch_velocity) < result.restitution < 1.0
    pull_off = float(theory.maugis_pull_off(tabor)) * 1.5 * math.pi * R * adhesion.work_of_adhesion
    assert -result.min_force == pytest.approx(pull_off, rel=1e-8, abs=0.0)


def maugis_dugdale_hysteresis(result):
    """Λ = 1, Δγa = Δγ/2: the kinetic energy lost is ∮F dd (1e-8), the unloading passes a frozen
    zone onto the detach curve, and the loop between the two ranges leaves e below Thornton–Ning's
    (which the reversible Λ = 1 particle exceeds)."""
    mass = result.scene.reduced_mass
    lost = 0.5 * mass * (result.touch_velocity**2 - result.separation_velocity**2)
    assert abs(lost - result.dissipated_energy) <= 1e-8 * 0.5 * mass * result.touch_velocity**2
    assert [kind for _, kind in result.events] == ["touch", "max_indentation", "detach_start", "separation"]
    below_thornton_ning(result)


def maugis_dugdale_indentation_pull_off(result):
    """Displacement control, Λ = 1: the tip snaps off at the lowest indentation of (3.171)."""
    scene = result.scene
    adhesion = scene.effects.adhesion
    R, E_star, work = scene.body.profile.R, scene.material.effective_modulus, adhesion.work_of_adhesion
    tabor = float(theory.tabor_parameter(R, adhesion.adhesive_stress, adhesion.adhesion_range, E_star))
    a_c = (9 * math.pi * R**2 * work / (8 * E_star)) ** (1 / 3)  # the JKR units (3.170)
    units = (a_c, a_c**2 / (3 * R), 1.5 * math.pi * R * work)
    expected = [v * unit for v, unit in zip(theory.maugis_critical_state(tabor, 1), units, strict=True)]
    pull_off = result.pull_off
    found = [pull_off.contact_radius, pull_off.indentation, pull_off.force]
    assert found == pytest.approx(expected, rel=1e-6, abs=0.0)


def greenwood_johnson_pull_off(result):
    """k = 10: e between Thornton–Ning and 1; the unloading passes the force-controlled pull-off of
    the double-Hertz curve (theory.double_hertz_pull_off, ξ = 3)."""
    scene = result.scene
    adhesion = scene.effects.adhesion
    R, E_star = scene.body.profile.R, scene.material.effective_modulus
    assert result.tabor_parameter == pytest.approx(
        float(theory.double_hertz_tabor_parameter(adhesion.k)), rel=1e-12, abs=0.0
    )
    assert thornton_ning(scene, result.touch_velocity) < result.restitution < 1.0
    pull_off = float(theory.double_hertz_pull_off(adhesion.k, R, E_star, adhesion.work_of_adhesion, 3)[2])
    assert result.min_force == pytest.approx(pull_off, rel=1e-8, abs=0.0)


def thornton_plastic(result):
    """Thornton's (1997) closed form of the elastic–perfectly plastic paraboloid."""
    scene = result.scene
    R, E_star = scene.contact_profile.R, scene.material.effective_modulus
    yield_velocity = theory.thornton_yield_velocity(
        scene.reduced_mass, R, E_star, scene.effects.plasticity.yield_pressure
    )
    closed_form = float(theory.thornton_restitution(result.touch_velocity, yield_velocity))
    assert 0.4 < closed_form < 0.6  # well beyond the yield velocity
    assert result.restitution == pytest.approx(closed_form, abs=1e-8)


def thornton_ning_plastic(result):
    """The Wall et al. particle: Thornton & Ning's adhesive plastic closed form, far below the
    elastic adhesive restitution."""
    scene = result.scene
    closed_form = float(
        theory.adhesive_plastic_restitution(
            result.touch_velocity,
            scene.reduced_mass,
            scene.contact_profile.R,
            scene.material.effective_modulus,
            scene.effects.adhesion.work_of_adhesion,
            scene.effects.plasticity.yield_pressure,
        )
    )
    assert 0.1 < closed_form < 0.5 * thornton_ning(scene, result.touch_velocity)
    assert result.restitution == pytest.approx(closed_form, abs=1e-8)


def viscoelastic_first_order(result):
    """Brilliantov's viscoelastic paraboloid: within (C1·βv₀^(1/5))² of Schwager & Pöschel's first
    order 1 − C1·βv₀^(1/5) (the second-order coefficient is 0.8 < 1), and above it."""
    scene = result.scene
    beta = theory.viscoelastic_beta(
        scene.effects.damping.dissipative_constant,
        scene.reduced_mass,
        scene.contact_profile.R,
        scene.material.effective_modulus,
    )
    first_order = float(theory.viscoelastic_restitution_first_order(result.touch_velocity, beta))
    assert first_order < result.restitution < first_order + (1 - first_order) ** 2


def _first_contact_balance(result, closure: float):
    """The kinetic energy lost is the work on the springs (to 1e-8 of it), and that is the
    dashpots' dissipation + the energy left in the medium + the snaps' (to `closure` of it)."""
    mass, work = result.scene.reduced_mass, result.dissipated_energy
    relaxation = result.relaxation
    snaps = relaxation.released_energy - relaxation.gained_energy
    assert 0.5 * mass * (result.touch_velocity**2 - result.separation_velocity**2) == pytest.approx(
        work, rel=1e-8, abs=0.0
    )
    assert result.viscous_work + relaxation.stored_energy + snaps == pytest.approx(work, rel=closure, abs=0.0)


def viscoelastic_energy_balance(result):
    """The micro-sphere: the first contact's energy balance, each part to 1e-8 of the work; e
    lies below Thornton–Ning of the relaxed medium (the dashpots take a third of the energy)."""
    _first_contact_balance(result, 1e-8)
    assert result.restitution < thornton_ning(result.scene, result.touch_velocity)
    assert result.viscous_work > 0.25 * 0.5 * result.scene.reduced_mass * result.touch_velocity**2


def viscoelastic_dugdale_balance(result):
    """The micro-sphere with Maugis–Dugdale adhesion: the work on the springs to 1e-8 of it, its
    parts (dashpots, the energy left in the medium, the snaps) to 1e-5 (measured 3e-7: the zone's
    path near the pull-off); the dashpots take more than a quarter of the impact energy."""
    _first_contact_balance(result, 1e-5)
    assert result.viscous_work > 0.25 * 0.5 * result.scene.reduced_mass * result.touch_velocity**2


def lee_radok_and_ting(result):
    """The viscoelastic film: Lee & Radok while loading and held, Ting while unloading, where the
    force exceeds 5 % of its peak (to 1e-6)."""
    scene = result.scene
    program, prony = scene.program, scene.effects.viscoelasticity.prony
    moduli, times = ([getattr(term, name) for term in prony] for name in ("modulus", "time"))
    expected = np.asarray(
        theory.ting_force(
            result.time,
            program.rate,
            scene.body.profile.R,
            scene.material.effective_modulus,
            np.array(moduli),
            np.array(times),
            program.peak / program.rate,
            program.hold,
        )
    )
    checked = (result.time >= 0.2) & (expected > 0.05 * expected.max())
    assert np.max(np.abs(result.force[checked] / expected[checked] - 1)) < 1e-6


def oblique_balance(result):
    """Kharaz et al.'s alumina sphere at 30°: the Hertz array rebounds with e = 1 (1e-12); the
    kinetic energy in (translational and rotational) is the energy out plus the friction work
    (1e-12); it leaves sliding slower and spinning forward."""
    scene = result.scene
    mass, radius = scene.body.resolved_mass, scene.body.profile.R
    inertia = 0.4 * mass * radius**2
    before = 0.5 * mass * scene.start.velocity**2
    after = 0.5 * mass * (result.separation_velocity**2 + result.tangential_velocity_after**2)
    after += 0.5 * inertia * result.spin_after**2
    assert result.restitution == pytest.approx(1.0, abs=1e-12)
    assert abs(before - after - result.dissipated_energy - result.friction_work) <= 1e-12 * before
    assert 0.0 < result.tangential_restitution < 1.0 and result.spin_after > 0.0


def cattaneo_mindlin_and_masing(result):
    """The shear test: Q(δ) within 1e-8·μF_n of Cattaneo–Mindlin and Masing's branches."""
    from impact._plots.shear import closed_form

    most = result.scene.effects.friction.coefficient * result.normal_force
    assert max(abs(result.force - closed_form(result))) <= 1e-8 * most


CHECKS = {
    "thornton_ning": matches(thornton_ning, 1e-6),
    "cone": matches(power_law, 1e-6),
    "power_law": matches(power_law, 1e-6),
    "attach_on_touch": below_thornton_ning,
    "nanoparticle": matches(thornton_ning, 1e-6),
    "rubber_ball": matches(thornton_ning, 1e-6),
    "gravity_bounces": captured_after_bouncing,
    "spring_array": matches(thornton_ning, 1e-4),
    "indentation_paraboloid": force_controlled_pull_off,
    "indentation_wavy": displacement_controlled_wavy_pull_off,
    "maugis_dugdale": maugis_dugdale_pull_off,
    "maugis_dugdale_hysteresis": maugis_dugdale_hysteresis,
    "indentation_maugis_dugdale": maugis_dugdale_indentation_pull_off,
    "greenwood_johnson": greenwood_johnson_pull_off,
    "two_spheres": matches(thornton_ning, 1e-6),
    "plastic_steel": thornton_plastic,
    "wall_particle": thornton_ning_plastic,
    "rubber_ball_viscoelastic": viscoelastic_first_order,
    "viscoelastic_sphere": viscoelastic_energy_balance,
    "viscoelastic_sphere_dugdale": viscoelastic_dugdale_balance,
    "indentation_viscoelastic": lee_radok_and_ting,
    "oblique_kharaz": oblique_balance,
    "shear_paraboloid": cattaneo_mindlin_and_masing,
}


def test_every_config_is_checked():
    assert {path.stem for path in CONFIGS.glob("*.yaml")} == set(CHECKS)


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(CHECKS))
def test_config_runs_and_meets_its_reference(name):
    result = impact.simulate(CONFIGS / f"{name}.yaml")
    assert result.success, result.status
    assert result.scene.name == name
    if isinstance(result, Result):  # an impact, not an indentation test
        assert_passive(result)
    CHECKS[name](result)
