"""Quasi-static indentation with adhesion of finite range: Maugis–Dugdale (§3.8) and
Greenwood–Johnson's double Hertz (§3.9), under force control (ξ = 3) and displacement control
(ξ = 1), against the closed forms.

The march follows the equilibrium curve s ↦ (d, F, a) of each law (the one the impacts ride):
its pull-off is a located turning point of F(s) (force control) or d(s) (displacement control),
found to round-off. The Maugis–Dugdale reference (`theory.maugis_critical_state`) minimizes
(3.171) with its zone without contact (3.176) by bounded Brent, exact in the minimum itself and
to about 1e-8 in the position of the minimum; the double-Hertz one is closed-form. One
compilation per law and profile: every Tabor parameter, k, control and program reuses it.
"""

import math

import numpy as np
import pytest

import impact
from impact import theory as th
from impact._io.indentation import read_indentation, write_indentation
from impact._plots.indentation import dmt_limit, save_indentation_figures
from impact._run.indentation import IndentationResult
from impact._scene.scene import SceneError, load_scene
from tests.scenes import A_JKR, CONTROLS, D_JKR, E_STAR, F_JKR, WORK, R

TABORS = [0.05, 0.3, 1.0, 3.0, 10.0]


def scene(adhesion, control, peak, profile=None, **program):
    return dict(
        name="test",
        kind="indentation",
        control=control,
        program=dict(peak=peak, **program),
        body=dict(profile=profile or dict(shape="paraboloid", R=R)),
        material=dict(E_star=E_STAR),
        effects=dict(adhesion=adhesion),
    )


def maugis(tabor, control, peak=None, **program) -> IndentationResult:
    stress = float(th.maugis_adhesive_stress(tabor, R, WORK, E_STAR))
    peak = peak or (4 * F_JKR if control == "force" else 4 * D_JKR)
    adhesion = dict(model="maugis_dugdale", work_of_adhesion=WORK, stress=stress)
    result = impact.simulate(scene(adhesion, control, peak, **program))
    assert isinstance(result, IndentationResult)
    return result


def double_hertz(k, control, peak, **program) -> IndentationResult:
    adhesion = dict(model="greenwood_johnson", work_of_adhesion=WORK, k=k)
    result = impact.simulate(scene(adhesion, control, peak, **program))
    assert isinstance(result, IndentationResult)
    return result


def normalized_pull_off(result):
    """(ã, d̃, F̃) of the pull-off in the JKR units (3.170)."""
    assert result.status == "separated", result.status
    p = result.pull_off
    return np.array([p.contact_radius / A_JKR, p.indentation / D_JKR, p.force / F_JKR])


# ---------------------------------------------------------------- Maugis–Dugdale


@pytest.mark.parametrize("control, xi", CONTROLS)
def test_maugis_pull_off_is_the_critical_state_of_3_171(control, xi):
    """Λ ∈ {0.05, …, 10}: the pull-off force to 1e-6 (measured: round-off under force control,
    ≤ 3e-8 under displacement control, where the reference's position limits it), d̃ and ã too.
    Under force control it is the exact minimum of F̃ (`maugis_pull_off`)."""
    for tabor in TABORS:
        found = normalized_pull_off(maugis(tabor, control))
        expected = np.array(th.maugis_critical_state(tabor, xi))
        np.testing.assert_allclose(found[2], expected[2], rtol=1e-6)
        np.testing.assert_allclose(found, expected, rtol=1e-6, atol=1e-12)
        if xi == 3:
            assert found[2] == pytest.approx(-float(th.maugis_pull_off(tabor)), rel=1e-12, abs=0.0)


def test_maugis_displacement_control_lets_go_of_the_zone_for_small_tabor():
    """Λ = 0.05: the contact opens smoothly into a zone without contact, which lets go at its
    lowest d, b̃ = 8Λ/(3π) (3.176): F̃ = −32Λ³/(9π), d̃ = −(32/(3π²))Λ² − 4/(πΛ)."""
    tabor = 0.05
    result = maugis(tabor, "displacement")
    found = normalized_pull_off(result)
    expected = [0.0, -32 / (3 * math.pi**2) * tabor**2 - 4 / (math.pi * tabor), -32 * tabor**3 / (9 * math.pi)]
    np.testing.assert_allclose(found, expected, rtol=1e-12)
    assert [kind for _, kind in result.events] == ["touch", "snap_in", "reversal", "pull_off"]


@pytest.mark.parametrize("control, xi", CONTROLS)
def test_maugis_limits_dmt_and_jkr(control, xi):
    """Λ = 1e-3: the force-controlled pull-off is DMT's 2πRΔγ (3.180) to 4e-5 (it tends to it as
    Λ → 0); under displacement control the zone lets go at F̃ = −32Λ³/(9π) → 0. Λ = 1000: the JKR
    critical state of the control (3.45) to 1e-6 (F̃ − F̃_JKR = 1/(12Λ²) under force control)."""
    dmt = normalized_pull_off(maugis(1e-3, control))[2]
    if xi == 3:
        assert dmt == pytest.approx(-4.0 / 3.0, rel=4e-5, abs=0.0)
    else:
        assert dmt == pytest.approx(-32e-9 / (9 * math.pi), rel=1e-9, abs=0.0)
    a_c, d_c, F_c = (float(v) for v in th.paraboloid_critical(R, E_STAR, WORK, xi))
    jkr = normalized_pull_off(maugis(1e3, control))
    np.testing.assert_allclose(jkr, [a_c / A_JKR, d_c / D_JKR, F_c / F_JKR], rtol=1e-6)


def test_maugis_cycles_partial_unloading_and_force_control_landing():
    """Two cycles, the first unloaded to F = 0 only: the same pull-off as one cycle; the curve
    passes the touch at d = −h (F = 0), the landing at F = 0 after the jump-in (force control),
    reversals at the peak and at F = 0 (unload_to), and the pull-off."""
    single = maugis(1.0, "force")
    cycled = maugis(1.0, "force", cycles=2, unload_to=0.0)
    assert cycled.pull_off == single.pull_off
    kinds = [kind for _, kind in cycled.events]
    assert kinds == ["touch", "snap_in", "reversal", "reversal", "reversal", "pull_off"]
    h = WORK / float(th.maugis_adhesive_stress(1.0, R, WORK, E_STAR))
    touch, landing = cycled.events[0][0], cycled.events[1][0]
    assert cycled.indentation[touch] == pytest.approx(-h, rel=1e-12, abs=0.0) and cycled.force[touch] == 0.0
    assert abs(cycled.force[landing]) < 1e-12 * F_JKR  # the jump-in lands at the applied F = 0
    reversals = [index for index, kind in cycled.events if kind == "reversal"]
    np.testing.assert_allclose(cycled.force[reversals], [4 * F_JKR, 0.0, 4 * F_JKR], atol=1e-12 * F_JKR)
    assert cycled.max_force == pytest.approx(4 * F_JKR, rel=1e-12, abs=0.0)


def test_maugis_displacement_loop_dissipates_the_area_of_its_jumps():
    """Displacement control, Λ = 3: the work ∮F dd done on the contact over the cycle is the
    area the unloading branch adds below the jump-in depth −h, ∫F dd along it from −h (its force
    there interpolated) to the pull-off (the jumps at fixed d do no work): to 1e-3, the trapezoid
    rule's error on the branch that loading and unloading share, sampled at other points
    (measured 3.2e-4); loading and unloading coincide on the branch they share."""
    result = maugis(3.0, "displacement")
    loop = np.sum(0.5 * (result.force[1:] + result.force[:-1]) * np.diff(result.indentation))
    h = WORK / float(th.maugis_adhesive_stress(3.0, R, WORK, E_STAR))
    unloading = result.leg == 1
    depth, force = result.indentation[unloading], result.force[unloading]
    k = np.flatnonzero((depth[:-1] > -h) & (depth[1:] <= -h))[0]
    force_at_h = force[k] + (force[k + 1] - force[k]) * (-h - depth[k]) / (depth[k + 1] - depth[k])
    tail = (depth <= -h) & (force < 0)
    d_tail, F_tail = np.concatenate([[-h], depth[tail]]), np.concatenate([[force_at_h], force[tail]])
    below = np.sum(0.5 * (F_tail[1:] + F_tail[:-1]) * np.diff(d_tail))
    assert loop > 0.1 * F_JKR * D_JKR and loop == pytest.approx(below, rel=1e-3, abs=0.0)
    assert result.events[1][1] == "snap_in" and result.events[-1][1] == "pull_off"
    # A point of the loading branch and the unloading branch at the same d: the same force.
    loading = result.leg == 0
    unloading = result.leg == 1
    d = 0.5 * D_JKR
    up = np.interp(d, result.indentation[loading][2:], result.force[loading][2:])
    down = np.interp(d, result.indentation[unloading][::-1], result.force[unloading][::-1])
    assert up == pytest.approx(down, rel=1e-3, abs=0.0)  # linear between the 33 samples of a piece


@pytest.mark.slow
@pytest.mark.parametrize("n, c", [(1.0, math.tan(0.3)), (1.5, 1e3)])
def test_power_laws_tend_to_their_jkr_and_dmt_limits(n, c):
    """f = c·rⁿ, the cone (n = 1, c = tan θ) and n = 1.5, one compilation: at σ0 = 1e11 Pa the
    force-controlled pull-off force of JKR (3.74)–(3.76) to 1e-6 (the error falls as 1/σ0²: 100
    times per decade); at σ0 = 1e5 Pa the DMT pull-off πΔγ·h^((2−n)/n)/c^(2/n) (3.195) to 2e-3;
    two cycles, the first unloaded to F = 0."""
    power_law = dict(shape="power_law", n=n, c=c)
    a_c, d_c, F_c = (float(v) for v in th.power_law_critical(n, c, E_STAR, WORK, 3))

    def pull_off(stress):
        adhesion = dict(model="maugis_dugdale", work_of_adhesion=WORK, stress=stress)
        result = impact.simulate(scene(adhesion, "force", 4 * abs(F_c), profile=power_law, cycles=2, unload_to=0.0))
        assert [kind for _, kind in result.events][-1] == "pull_off"
        return result.pull_off.force

    errors = [abs(pull_off(stress) / F_c - 1.0) for stress in (1e10, 1e11)]
    assert errors[1] < 1e-6 and 80 < errors[0] / errors[1] < 120
    stress = 1e5
    dmt = float(th.power_law_dmt_pull_off(n, c, WORK, WORK / stress))
    assert -pull_off(stress) == pytest.approx(dmt, rel=2e-3, abs=0.0)


# ---------------------------------------------------------------- Greenwood–Johnson


@pytest.mark.slow
@pytest.mark.parametrize("control, xi", CONTROLS)
def test_double_hertz_pull_off_matches_the_closed_form(control, xi):
    """k ∈ {0.1, 1, 3, 30}: (a, d, F) of `double_hertz_pull_off` to 1e-8 (measured ≤ 2e-15);
    two cycles partially unloaded to F = 0 (force) or half the peak (displacement) first."""
    for k in (0.1, 1.0, 3.0, 30.0):
        a, d, F = (float(v) for v in th.double_hertz_pull_off(k, R, E_STAR, WORK, xi))
        peak = 4 * F_JKR if xi == 3 else 4 * D_JKR
        result = double_hertz(k, control, peak, cycles=2, unload_to=0.0 if xi == 3 else 0.5 * peak)
        p = result.pull_off
        assert result.status == "separated"
        np.testing.assert_allclose([p.indentation, p.force], [d, F], rtol=1e-8)
        assert p.contact_radius == pytest.approx(a, rel=1e-8, abs=1e-12 * A_JKR)


def test_double_hertz_limits_and_curve_points():
    """Force control: −2πRΔγ at k = 1e-4 (DMT) and −(3/2)πRΔγ at k = 1e4 (JKR) to 1e-3; every
    point in contact lies on F(a), d(a) of (3.198)–(3.201) to 1e-10."""
    dmt = double_hertz(1e-4, "force", 4 * F_JKR)
    jkr = double_hertz(1e4, "force", 4 * F_JKR)
    assert dmt.pull_off.force == pytest.approx(-2 * math.pi * R * WORK, rel=1e-3, abs=0.0)
    assert jkr.pull_off.force == pytest.approx(-1.5 * math.pi * R * WORK, rel=1e-3, abs=0.0)
    result = double_hertz(3.0, "displacement", 4 * D_JKR)
    contact = result.contact_radius > 0
    a = result.contact_radius[contact]
    np.testing.assert_allclose(
        result.force[contact], np.asarray(th.double_hertz_force(a, 3.0, R, E_STAR, WORK)), rtol=1e-10
    )
    np.testing.assert_allclose(
        result.indentation[contact], np.asarray(th.double_hertz_indentation(a, 3.0, R, E_STAR, WORK)), rtol=1e-10
    )


# ---------------------------------------------------------------- hard cases, bad input, files


@pytest.mark.parametrize("control", ["force", "displacement"])
def test_pulled_off_mid_program_then_touches_again(control):
    """The first cycle unloads beyond the pull-off (to −10 F_JKR, or 100 nm out of range): the
    body lets go, (displacement control) moves out at F = 0, then the second cycle touches again
    and the program ends with the same pull-off as the first."""
    beyond = -10 * F_JKR if control == "force" else -1e-7
    peak = 4 * F_JKR if control == "force" else 4 * D_JKR
    result = double_hertz(3.0, control, peak, cycles=2, unload_to=beyond)
    kinds = [kind for _, kind in result.events]
    assert kinds == ["touch", "snap_in", "reversal", "pull_off", "touch", "snap_in", "reversal", "pull_off"]
    pulls = [index for index, kind in result.events if kind == "pull_off"]
    np.testing.assert_array_equal(result.force[pulls[0]], result.force[pulls[1]])
    if control == "displacement":
        apart = result.indentation < -0.99e-7 * (1 - 1e-12)
        assert np.any(apart) and np.all(result.force[apart] == 0.0) and result.indentation.min() == -1e-7


def test_a_large_peak_rides_far_out_and_back():
    """A peak of 10⁴ JKR pull-off forces: still the same pull-off (the curve reaches beyond it)."""
    far = maugis(1.0, "force", peak=1e4 * F_JKR)
    assert far.max_force == pytest.approx(1e4 * F_JKR, rel=1e-12, abs=0.0)
    assert far.pull_off.force == pytest.approx(-float(th.maugis_pull_off(1.0)) * F_JKR, rel=1e-12, abs=0.0)


@pytest.mark.parametrize(
    "adhesion, profile, springs, field, phrase",
    [
        (
            dict(model="maugis_dugdale", stress=1e7),
            dict(shape="flat_punch", radius=1e-6),
            "continuum",
            "effects.adhesion.model",
            "smooth unbounded profile",
        ),
        (
            dict(model="maugis_dugdale", stress=1e7),
            dict(shape="power_law", n=0.8, c=1.0),
            "continuum",
            "body.profile.n",
            "n >= 1",
        ),
        (dict(model="maugis_dugdale", stress=1e7), None, 4096, "contact.springs", "at most 2048 springs"),
        (
            dict(model="greenwood_johnson", k=1.0),
            dict(shape="cone", theta=0.3),
            "continuum",
            "effects.adhesion.model",
            "needs a paraboloid",
        ),
        (dict(model="greenwood_johnson", k=1.0), None, 100, "contact.springs", "continuum law only"),
        (dict(model="greenwood_johnson"), None, "continuum", "effects.adhesion.k", "needs the double-Hertz factor"),
        (
            dict(model="maugis_dugdale", stress=1e7, approach_work_of_adhesion=0.01),
            None,
            64,
            "effects.adhesion.approach_work_of_adhesion",
            "a maugis_dugdale spring array has no approach hysteresis",
        ),
    ],
)
def test_bad_finite_range_indentations_name_the_field(adhesion, profile, springs, field, phrase):
    data = scene(dict(work_of_adhesion=WORK, **adhesion), "force", 1e-7, profile=profile)
    data["contact"] = dict(springs=springs)
    with pytest.raises(SceneError) as error:
        load_scene(data)
    assert any(path == field and phrase in message for path, message in error.value.problems), error.value.problems


def test_hdf5_round_trip_and_figures_draw_both_limits(tmp_path):
    result = maugis(1.0, "displacement")
    back = read_indentation(write_indentation(result, tmp_path / "run.h5"))
    assert back.scene == result.scene and back.pull_off == result.pull_off and back.events == result.events
    np.testing.assert_array_equal(back.force, result.force)
    a, d, F = dmt_limit(result)
    assert F[0] == pytest.approx(-2 * math.pi * R * WORK, rel=1e-9, abs=0.0)  # f(b) = h: b² = 2Rh, πσ0b² (3.180)
    assert d[-1] <= 1.02 * result.max_indentation
    paths = save_indentation_figures(result, tmp_path)
    assert all(path.read_bytes().startswith(b"\x89PNG") for path in paths)
