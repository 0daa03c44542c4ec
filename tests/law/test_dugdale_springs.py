"""Maugis–Dugdale spring arrays (§3.8 on N midpoint springs): a piece of the array through a
continuum state is that state with its contact summed by the midpoint rule, and the quasi-static
pull-off and the restitution converge to the continuum law's at second order in N.

One compilation each for the march and the impact: the counts share a compiled capacity (N is
traced)."""

import math

import equinox as eqx
import jax.numpy as jnp
import numpy as np
import pytest

from impact import SceneError, load_scene, simulate, theory
from impact._integrate.codes import RESULT_CODE
from impact._integrate.dugdale import DugdaleSpringIntegrator
from impact._integrate.quasistatic import QuasiStaticNumerics, march
from impact._law.dugdale import DugdaleLaw
from impact._law.dugdale_springs import LENGTH_MARGIN, contact_margin, piece_state
from impact._law.scales import Scales
from impact._run.impacts import solve_scene
from impact._run.indentation import indentation_loading, indentation_numerics
from impact._run.parameters import integrator_for, options_for, physics_for
from impact.profiles import Paraboloid
from tests.scenes import A_JKR, D_JKR, E_STAR, F_JKR, MASS, WORK, R, micro_sphere

COUNTS = (64, 128, 256)  # one compiled capacity: 256


def adhesion(tabor):
    return {
        "model": "maugis_dugdale",
        "work_of_adhesion": WORK,
        "stress": float(theory.maugis_adhesive_stress(tabor, R, WORK, E_STAR)),
    }


def impact_scene(tabor):
    """The benchmark paraboloid at v0 = 0.6 m/s with Maugis–Dugdale adhesion at Tabor parameter
    `tabor` (continuum law; add a `contact` section for an array)."""
    return micro_sphere(0.6, {"adhesion": adhesion(tabor)}, name="md-springs")


def order(counts, errors):
    """The slope of log |error| against log N, negated."""
    return -np.polyfit(np.log(counts), np.log(np.abs(errors)), 1)[0]


@pytest.mark.parametrize("tabor", [0.3, 3.0])
def test_a_piece_through_a_continuum_state_is_that_state(tabor):
    """With a = kΔx and the continuum's zone radius b, the range condition gives the continuum d
    (3.152, 3.154: the edge's contact force vanishes) and F differs by the midpoint rule's error
    on ∫₀ᵃ g alone: F_springs − F = E*·a·Δx²/(6R) for g = x²/R."""
    one = jnp.ones(())
    stress = float(theory.maugis_adhesive_stress(tabor, R, WORK, E_STAR))
    scales = Scales(radial=A_JKR * one, normal=A_JKR**2 / R * one, force=E_STAR * A_JKR**3 / R * one, time=one)
    law = DugdaleLaw.scaled(Paraboloid(R=R * one), scales, E_STAR, stress, WORK / stress)
    radius, springs = 0.8 * A_JKR, 40
    spacing = radius / springs
    zone = radius * 1.3
    # the continuum state at (a, b) with the range h that puts it on the curve
    residual, depth, force = theory.maugis_paraboloid_state(radius, zone, R, stress, WORK / stress, E_STAR)
    law = DugdaleLaw(law=law.law, degree=law.degree, stress=law.stress, range=law.range + residual / scales.normal)
    positions = (np.arange(springs + 1) + 0.5) * spacing / A_JKR
    prefix = jnp.concatenate([jnp.zeros(1), jnp.cumsum(law.law.g(jnp.asarray(positions)))])
    d, F, a = piece_state(law, spacing / A_JKR, prefix, springs, jnp.asarray(zone / A_JKR))
    np.testing.assert_allclose(float(d) * float(scales.normal), depth, rtol=1e-12)
    assert abs(float(contact_margin(law, d, zone / A_JKR, radius / A_JKR))) < 1e-12
    midpoint = E_STAR * radius * spacing**2 / (6 * R)
    np.testing.assert_allclose(float(F) * float(scales.force) - force, midpoint, rtol=1e-8)


@pytest.mark.slow
@pytest.mark.parametrize("control", ["force", "displacement"])
def test_quasi_static_pull_off_converges_at_second_order(control):
    """Λ = 1: the pull-off of N springs tends to the exact critical state of (3.171) as N⁻², its
    force under force control, its depth under displacement control (measured over the default
    length at N = 64 … 256: 2.4e-3 … 1.7e-4, slope 1.9; 2.2e-4 … 1.3e-5, slope 2.0). One
    compilation for both controls, and
    for Λ = 3 on 32 springs (under 2 across the zone): refused at the march's start."""
    scene = load_scene(
        {
            "name": "md-springs",
            "kind": "indentation",
            "control": control,
            "program": {"peak": F_JKR if control == "force" else D_JKR},
            "body": {"profile": {"shape": "paraboloid", "R": R}},
            "material": {"E_star": E_STAR},
            "effects": {"adhesion": adhesion(1.0)},
            "contact": {"springs": COUNTS[-1]},
        }
    )
    numerics: QuasiStaticNumerics = indentation_numerics(scene)
    loading = indentation_loading(scene)
    index, unit = (2, F_JKR) if control == "force" else (1, D_JKR)
    exact = float(theory.maugis_critical_state(1.0, 3 if control == "force" else 1)[index]) * unit
    errors = []
    for count in COUNTS:
        scales, outcome = march(eqx.tree_at(lambda x: x.spring_count, loading, jnp.asarray(count)), numerics)
        assert int(outcome.status) == 0
        scale = scales.force if control == "force" else scales.normal
        errors.append(float(outcome.pull_off[index]) * float(scale) / exact - 1.0)
    assert 1.7 < order(COUNTS, errors) < 2.8, errors
    assert abs(errors[-1]) < 5e-4
    # Λ = 3 (the same program): 32 springs put under 2 across the zone, a march refused at its start
    stress = theory.maugis_adhesive_stress(3.0, R, WORK, E_STAR)
    coarse = eqx.tree_at(lambda x: (x.spring_count, x.law.adhesive_stress), loading, (jnp.asarray(32), stress))
    _, outcome = march(coarse, numerics)
    assert int(outcome.status) == RESULT_CODE["unresolved_zone"]


@pytest.mark.parametrize("tabor", [0.3, 3.0])
def test_the_default_array_reaches_just_beyond_the_largest_contact(tabor):
    """Without `contact.length` the array spans LENGTH_MARGIN / TOP_MARGIN times the contact
    radius where the continuum curve's reach lies on its search grid: beyond the continuum
    impact's largest contact radius by at least LENGTH_MARGIN, and within 2.5 times it (measured
    2.15 and 1.70; the reach read on the curve's own coarser grid gives 2.7 and 8.9)."""
    continuum = impact_scene(tabor)
    largest = float(np.max(simulate(continuum).contact_radius))
    scene = load_scene({**continuum, "contact": {"springs": 64}})
    problem = eqx.filter_jit(lambda integrator, physics, options: integrator.build(physics, options))(
        integrator_for(scene), physics_for(scene), options_for(scene, trajectory=False)
    )
    curve = problem.curve
    length = float(curve.spacing * curve.count * problem.scales.radial)
    assert LENGTH_MARGIN * largest <= length <= 2.5 * largest


@pytest.mark.slow
def test_impact_restitution_converges_at_second_order_with_energy_balance():
    """Λ = 1, v0 = 0.6 m/s: e of N springs tends to the continuum's as N⁻² (measured: 1.3e-4 …
    8.7e-6 at N = 64 … 256, slope 1.95); the loop's work is the kinetic energy lost (to 1e-7 of
    it at rtol 1e-10; measured 1e-8); the Richardson limit of the last two counts meets the
    continuum to 1e-5. Λ = 3 at N = 64 puts 1.0 spring across the adhesive zone over the default
    length (3.6 a_c): flagged `unresolved_zone` (the same program)."""

    continuum = impact_scene(1.0)
    # e of the continuum Maugis–Dugdale law (its energy balance holds to 1e-9: test_maugis_dugdale)
    continuum_restitution = simulate(continuum).restitution

    def scene(count):
        return load_scene({**continuum, "contact": {"springs": count}})

    largest = scene(COUNTS[-1])
    integrator = DugdaleSpringIntegrator(rtol=1e-10, atol=1e-12, capacity=COUNTS[-1])
    options = options_for(largest, trajectory=False)
    values = []
    for count in COUNTS:
        result = solve_scene(scene(count), integrator, options)
        assert result.status == "separated"
        lost = 0.5 * MASS * (result.touch_velocity**2 - result.separation_velocity**2)
        assert abs(result.dissipated_energy - lost) < 1e-7 * 0.5 * MASS * result.touch_velocity**2
        values.append(result.restitution)
    errors = np.array(values) - continuum_restitution
    assert 1.7 < order(COUNTS, errors) < 2.6, errors
    limit = values[-1] + (values[-1] - values[-2]) / 3
    assert abs(limit - continuum_restitution) < 1e-5
    # the scene check passes (N ≥ 55 over the least default length), the default reaches further
    coarse = load_scene({**impact_scene(3.0), "contact": {"springs": 64}})
    result = solve_scene(coarse, integrator, options)
    assert result.status == "unresolved_zone" and math.isnan(result.restitution)


@pytest.mark.parametrize(
    ("length", "advice"),
    [
        (2e-7, "give at least 1426 springs, or 'continuum'"),
        (
            1e-6,
            "that needs 7129 springs, more than the 2048 allowed: give a shorter contact.length (just beyond the "
            "largest contact radius), or 'continuum'",
        ),
    ],
)
def test_an_array_that_cannot_resolve_the_zone_is_refused(length, advice):
    """Λ = 10: the zone is (π/4)E*Δγ/σ0² = a_c/(2Λ²) = 0.28 nm wide; 2 springs across it over
    contact.length L need N ≥ 2L/s (no solve)."""
    data = {**impact_scene(10.0), "contact": {"springs": 256, "length": length}}
    with pytest.raises(SceneError) as error:
        load_scene(data)
    assert error.value.problems == [
        (
            "contact.springs",
            f"256 springs over contact.length {length:.3g} m do not resolve the Maugis–Dugdale adhesive zone "
            "(Tabor parameter Λ = 10): its width (π/4)E*Δγ/σ0² = 2.81e-10 m needs 2 springs across it (else the "
            f"array dissipates like an attach-on-touch JKR contact); {advice}",
        )
    ]
