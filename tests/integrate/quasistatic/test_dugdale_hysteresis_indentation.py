"""Quasi-static indentation with Maugis–Dugdale approach hysteresis (Δγa < Δγ, this project's
derivation, `impact._law.dugdale_hysteresis`), under force control (ξ = 3) and displacement
control (ξ = 1): the pull-off where unloading reaches the detach curve (the reversible law's)
and where the frozen zone opens first (−π·σ0·b_max²), cycles that reload along the frozen zone
onto the approach curve, Δγa = Δγ, and the JKR hysteresis law as Λ grows. One compiled march
serves both controls and every Λ and Δγa; the reversible and the JKR marches are those of
`test_finite_range_indentation` and `test_indentation`."""

import dataclasses
import math

import numpy as np
import pytest
from scipy.optimize import brentq

import impact
from impact import theory as th
from impact._integrate.quasistatic import march
from impact._run.indentation import IndentationResult, indentation_loading, indentation_numerics
from impact._scene.scene import load_scene
from tests.scenes import A_JKR, CONTROLS, D_JKR, E_STAR, F_JKR, WORK, R


def spec(tabor, control, share=None, model="maugis_dugdale", **program):
    """An indentation to 4 JKR units of the controlled value, Δγa = share·Δγ."""
    adhesion = dict(model=model, work_of_adhesion=WORK)
    if model == "maugis_dugdale":
        adhesion["stress"] = float(th.maugis_adhesive_stress(tabor, R, WORK, E_STAR))
    if share is not None:
        adhesion["approach_work_of_adhesion"] = share * WORK
    peak = 4 * F_JKR if control == "force" else 4 * D_JKR
    return dict(
        name="hysteresis",
        kind="indentation",
        control=control,
        program=dict(peak=peak, **program),
        body=dict(profile=dict(shape="paraboloid", R=R)),
        material=dict(E_star=E_STAR),
        effects=dict(adhesion=adhesion),
    )


def run(*args, **kwargs) -> IndentationResult:
    result = impact.simulate(spec(*args, **kwargs))
    assert isinstance(result, IndentationResult)
    assert result.status == "separated", result.status
    return result


def pull_off(result):
    p = result.pull_off
    return np.array([p.contact_radius, p.indentation, p.force])


@pytest.mark.slow
@pytest.mark.parametrize("control, xi", CONTROLS)
def test_pull_off_is_the_reversible_one_where_unloading_reaches_the_detach_curve(control, xi):
    """Λ ∈ {0.3, 1, 3, 10}, Δγa/Δγ ∈ {0.5, 0.1}: the frozen zone meets the detach curve before its
    critical state, so the pull-off is the reversible law's (the same march: measured bitwise)
    and (3.171)'s to 1e-6 (as `test_maugis_pull_off_is_the_critical_state_of_3_171`)."""
    for tabor in (0.3, 1.0, 3.0, 10.0):
        reversible = pull_off(run(tabor, control))
        units = np.array([A_JKR, D_JKR, F_JKR])
        np.testing.assert_allclose(reversible / units, th.maugis_critical_state(tabor, xi), rtol=1e-6, atol=1e-12)
        for share in (0.5, 0.1):
            result = run(tabor, control, share)
            np.testing.assert_allclose(pull_off(result), reversible, rtol=1e-12, atol=1e-12 * A_JKR)
            kinds = [kind for _, kind in result.events]
            assert kinds[:3] == ["touch", "snap_in", "reversal"] and kinds[-1] == "pull_off"


@pytest.mark.slow
@pytest.mark.parametrize("share", [0.5, 0.1])
def test_force_control_lets_go_where_the_frozen_zone_opens(share):
    """Λ = 0.05: the frozen contact opens (a → 0) before the gap at b_max reaches h; without
    contact the frozen zone pulls with F = −π·σ0·b_max² whatever d, more than any state of the
    detach curve left below it (b ≤ b_max), so the body lets go there: b_max is the approach
    curve's zone radius at the peak, (3.171) with Λa = Λ·(Δγ/Δγa)^(1/3) in the units of Δγa,
    solved independently by Brent's method (to 1e-9). Displacement control still lets go on the
    detach curve (the reversible pull-off)."""
    tabor = 0.05
    stress = float(th.maugis_adhesive_stress(tabor, R, WORK, E_STAR))
    approach_tabor = tabor * share ** (-1 / 3)
    a_unit, f_unit = A_JKR * share ** (1 / 3), F_JKR * share  # (3.170) with Δγa

    def force(kappa):
        return float(th.maugis_paraboloid(kappa, approach_tabor)[2]) * f_unit - 4 * F_JKR

    kappa = brentq(force, 1.0 + 1e-12, 50.0, xtol=1e-15)
    zone = kappa * float(th.maugis_paraboloid(kappa, approach_tabor)[0]) * a_unit
    result = run(tabor, "force", share)
    assert result.pull_off.force == pytest.approx(-math.pi * stress * zone**2, rel=1e-9, abs=0.0)
    assert result.pull_off.contact_radius <= 1e-12 * A_JKR
    assert -result.pull_off.force < -run(tabor, "force").pull_off.force
    np.testing.assert_allclose(
        pull_off(run(tabor, "displacement", share)), pull_off(run(tabor, "displacement")), rtol=1e-12
    )


@pytest.mark.parametrize("control, unload_to", [("force", 0.0), ("displacement", 0.0)])
@pytest.mark.slow
def test_cycles_reload_along_the_frozen_zone_onto_the_approach_curve(control, unload_to):
    """Λ = 1, Δγa = Δγ/2, two cycles, the first unloaded to F = 0 (on the frozen zone) or d = 0 (on
    the detach curve): the second loading returns to the first one's approach curve (its peak
    state to 1e-10; measured ≤ 2e-14) and the pull-off is the one-cycle one (bitwise)."""
    single = run(1.0, control, 0.5)
    cycled = run(1.0, control, 0.5, cycles=2, unload_to=unload_to)
    np.testing.assert_array_equal(pull_off(cycled), pull_off(single))
    reversals = [index for index, kind in cycled.events if kind == "reversal"]
    assert len(reversals) == 3
    first, second = reversals[0], reversals[2]
    states = np.stack([cycled.contact_radius, cycled.indentation, cycled.force], axis=1)
    units = np.array([A_JKR, D_JKR, F_JKR])
    np.testing.assert_allclose(states[second] / units, states[first] / units, rtol=0, atol=1e-10)
    # Reloading starts on a frozen zone: a stiffer path than the approach curve below the peak.
    reload = (cycled.leg == 2) & (cycled.contact_radius > 0)
    low = states[reversals[1]]
    assert np.all(cycled.contact_radius[reload] >= low[0] * (1 - 1e-12))


@pytest.mark.slow
def test_equal_works_reproduce_the_reversible_march():
    """Δγa = Δγ on the hysteretic path (its frozen zone empty): the reversible march's points to
    1e-10 of their largest value (measured 5e-15), its events and pull-off, under both controls."""
    for control in ("force", "displacement"):
        scene = load_scene(spec(1.0, control, cycles=2, unload_to=0.0))
        loading, numerics = indentation_loading(scene), indentation_numerics(scene)
        assert not numerics.hysteresis
        _, reversible = march(loading, numerics)
        _, hysteretic = march(loading, dataclasses.replace(numerics, hysteresis=True))
        np.testing.assert_array_equal(hysteretic.events, reversible.events)
        rows, expected = np.asarray(hysteretic.rows), np.asarray(reversible.rows)
        np.testing.assert_array_equal(np.isnan(rows), np.isnan(expected))
        used = ~np.isnan(expected)
        np.testing.assert_allclose(rows[used], expected[used], rtol=0, atol=1e-10 * np.max(np.abs(expected[used])))


def cycle_work(result):
    """∮F dd of a displacement-controlled cycle from the touch to the pull-off (the jumps at fixed
    d do no work), in the JKR units."""
    d, f = result.indentation / D_JKR, result.force / F_JKR
    return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(d)))


def test_large_tabor_loops_tend_to_the_jkr_hysteresis_law():
    """Displacement control, Δγa = Δγ/2: the work of a cycle tends to the JKR law's with the same
    Δγa (its hold at a_max, `continuum` march) like 1/Λ (fitted over Λ = 30, 100, 300; measured
    slope −0.98, 9.4e-4 of F_c·|d_c| at Λ = 300), and the pull-off to JKR's (3.45) like 1/Λ²
    (measured slope −2.00, 3.9e-7 at Λ = 300)."""
    jkr = run(None, "displacement", 0.5, model="jkr")
    tabors = np.array([30.0, 100.0, 300.0])
    results = [run(t, "displacement", 0.5) for t in tabors]
    deficit = np.array([cycle_work(jkr) - cycle_work(r) for r in results])
    assert np.all(deficit > 0.0) and deficit[-1] < 2e-3
    order = np.polyfit(np.log(tabors), np.log(deficit), 1)[0]
    assert -1.1 < order < -0.85
    pull_offs = np.array([r.pull_off.force for r in results])
    excess = np.abs(pull_offs / jkr.pull_off.force - 1.0)
    assert excess[-1] < 1e-5 and np.polyfit(np.log(tabors), np.log(excess), 1)[0] < -1.8
