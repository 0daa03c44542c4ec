"""Maugis–Dugdale adhesion (§3.8): the MDR law against the chapter's closed forms, its limits
(JKR, DMT, Bradley), and impacts on its equilibrium curve (energy balance, Thornton–Ning as
Λ grows, the reversible DMT side)."""

import math

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
import pytest
from scipy.optimize import minimize_scalar
from typer.testing import CliRunner

import impact
from impact import load_scene, simulate, theory
from impact._io.run import read_run
from impact._law.dugdale import DugdaleLaw
from impact._law.dugdale import _state as dugdale_state
from impact._law.maugis_curves import normalized_curve
from impact._plots.maugis_curves import equilibrium_figure
from impact._run.parameters import integrator_for, options_for, physics_for
from impact._scene.errors import SweepError
from impact._scene.scene import SceneError
from impact.cli import app
from tests.scenes import A_JKR, CONFIGS, D_JKR, E_STAR, F_JKR, MASS, WORK, R, micro_sphere

TABORS = (0.1, 0.3, 1.0, 3.0, 10.0)


def md_scene(tabor=1.0, velocity=0.6, profile=None, E_star=E_STAR, stress=None, adhesion_range=None, **extra):
    adhesion = {"model": "maugis_dugdale", "work_of_adhesion": WORK}
    if adhesion_range is not None:
        adhesion["range"] = adhesion_range
    else:
        adhesion["stress"] = float(
            stress if stress is not None else theory.maugis_adhesive_stress(tabor, R, WORK, E_star)
        )
    scene = micro_sphere(velocity, {"adhesion": adhesion}, material={"E_star": E_star})
    if profile is not None:
        scene["body"]["profile"] = profile
    return load_scene({"name": "md", **scene, **extra})


_build = eqx.filter_jit(lambda integrator, physics, options: integrator.build(physics, options))


def problem_of(scene):
    return _build(integrator_for(scene), physics_for(scene), options_for(scene, trajectory=False))


def si_contact(problem, share):
    """(d [m], F [N], a [m], b [m]) of the contact with zone share p = (b − a)/b."""
    depth, force, radius, zone = problem.law.contact(jnp.asarray(share))
    scales = problem.scales
    return (
        np.asarray(depth) * float(scales.normal),
        np.asarray(force) * float(scales.force),
        np.asarray(radius) * float(scales.radial),
        np.asarray(zone) * float(scales.radial),
    )


def jkr_units():
    """a_c, |d_c|, F_A of (3.170)."""
    return A_JKR, D_JKR, F_JKR


def pull_off(problem):
    """−min F over the whole equilibrium curve (N): a scan in s, then a bounded minimization."""
    curve, law = problem.curve, problem.law
    grid = np.concatenate(
        [np.linspace(0.0, float(curve.junction), 400), float(curve.junction) + np.linspace(0.0, 40.0, 4001)[1:]]
    )
    forces = np.asarray(curve.force(law, jnp.asarray(grid)))
    best = int(np.argmin(forces))
    lo, hi = grid[max(best - 1, 0)], grid[min(best + 1, grid.size - 1)]
    found = minimize_scalar(
        lambda s: float(curve.force(law, jnp.asarray(s))), bounds=(lo, hi), method="bounded", options={"xatol": 1e-13}
    )
    return -min(found.fun, forces[best]) * float(problem.scales.force)


@pytest.mark.slow
@pytest.mark.parametrize("tabor", TABORS)
def test_paraboloid_states_solve_the_normalized_relations_3_171(tabor):
    problem = problem_of(md_scene(tabor))
    a_c, d_c, force_unit = jkr_units()
    shares = np.array([0.9, 0.6, 0.3, 0.1, 1e-2, 1e-4])
    depth, force, radius, zone = si_contact(problem, shares)
    a_hat, d_hat, f_hat = theory.maugis_paraboloid(zone / radius, tabor)
    np.testing.assert_allclose(radius / a_c, a_hat, rtol=1e-9)
    np.testing.assert_allclose(depth / d_c, d_hat, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(force / force_unit, f_hat, rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("tabor", (1e-3, 1.0, 1e3))
def test_paraboloid_curve_turns_once_where_the_coarse_search_finds_it(tabor):
    """d(s) of the paraboloid falls to one minimum, then rises (the coarse search grid rests on
    it): a grid of 40 000 states sees one sign change of dd/ds, next to a node of the curve
    where dd/ds vanishes (≤ 1e-9)."""
    problem = problem_of(md_scene(tabor))
    curve, law = problem.curve, problem.law
    junction, top = float(curve.junction), float(curve.nodes[-1])
    grid = np.concatenate([junction * np.geomspace(1e-12, 1.0, 8000), np.linspace(junction, top, 32001)[1:]])
    slopes = np.asarray(curve.riding(law, jnp.asarray(grid))[2])
    changes = np.flatnonzero((slopes[1:] > 0.0) != (slopes[:-1] > 0.0))
    assert changes.size == 1
    turn = grid[changes[0]]
    nodes = np.asarray(curve.nodes)
    nearest = nodes[np.argmin(np.abs(nodes - turn))]
    assert abs(nearest - turn) <= max(grid[changes[0] + 1] - turn, 1e-9 * turn)
    assert float(curve.riding(law, jnp.asarray(nearest))[2]) == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize("tabor", (1e-2, 1.0, 1e2))
def test_paraboloid_nodes_equal_the_fine_search_of_the_same_body_as_a_power_law(tabor):
    """The paraboloid's curve is searched on 48 states; the same body as a power law (n = 2,
    c = 1/(2R)) on 832, its zone radius by Newton steps: the junction and the turning point of
    d(s) hold the same contact and zone radii and force (SI) to 1e-10."""
    paraboloid = problem_of(md_scene(tabor))
    power = problem_of(md_scene(tabor, profile={"shape": "power_law", "n": 2.0, "c": 1.0 / (2.0 * R)}))

    def inner_states(problem):  # (F [N], a [m], b [m]) at the nodes between 0 and the top
        curve, law, scales = problem.curve, problem.law, problem.scales
        nodes = np.unique(np.asarray(curve.nodes))[1:-1]
        _, force, radius, zone = (np.asarray(v) for v in curve.state(law, jnp.asarray(nodes)))
        return force * float(scales.force), radius * float(scales.radial), zone * float(scales.radial)

    found, fine = inner_states(paraboloid), inner_states(power)
    assert found[0].shape == fine[0].shape == (2,)
    for coarse_values, fine_values in zip(found, fine, strict=True):
        np.testing.assert_allclose(coarse_values, fine_values, rtol=1e-10, atol=1e-10 * np.max(np.abs(fine_values)))


def test_the_curve_states_are_traced_once_per_shape(monkeypatch):
    """A ride evaluates the curve in many places; its states are one jitted function, so the
    contact's formulas are traced once per shape of s, and a derivative or a batch of them reuses
    that trace."""
    problem = problem_of(md_scene(1.0))
    curve, law = problem.curve, problem.law
    traced: list[int] = []
    contact = DugdaleLaw.contact
    monkeypatch.setattr(DugdaleLaw, "contact", lambda *args, **kwargs: traced.append(1) or contact(*args, **kwargs))
    s = jnp.linspace(0.1, 2.0, 7)
    dugdale_state.clear_cache()  # traces of earlier tests in this process

    def places(s):
        riding = curve.riding(law, s)
        return (
            curve.state(law, s),
            curve.depth(law, 2.0 * s),
            riding,
            jax.vmap(lambda x: curve.force(law, x))(s[:, None]),
        )

    jax.make_jaxpr(places)(s)
    assert len(traced) == 2  # s of shape [7], and the batch's rows of shape [1]


@pytest.mark.parametrize("tabor", (0.1, 1.0, 10.0))
def test_zone_without_contact_and_its_junction(tabor):
    problem = problem_of(md_scene(tabor))
    a_c, d_c, force_unit = jkr_units()
    junction = float(problem.curve.junction) * float(problem.scales.radial)
    assert junction / a_c == pytest.approx(float(theory.maugis_junction_zone_radius(tabor)), rel=1e-12, abs=0.0)
    zones = junction * np.array([0.05, 0.3, 0.7, 1.0]) / float(problem.scales.radial)
    depth, force = (np.asarray(v) for v in problem.law.zone(jnp.asarray(zones)))
    d_hat, f_hat = theory.maugis_paraboloid_noncontact(zones * float(problem.scales.radial) / a_c, tabor)
    np.testing.assert_allclose(depth * float(problem.scales.normal) / d_c, d_hat, rtol=1e-11)
    np.testing.assert_allclose(force * float(problem.scales.force) / force_unit, f_hat, rtol=1e-11)
    # The contact branch starts where the zone ends (a = 0).
    contact = si_contact(problem, 1.0)
    assert contact[2] == 0.0 and contact[3] == pytest.approx(junction, rel=1e-12, abs=0.0)


@pytest.mark.slow
@pytest.mark.parametrize(
    "profile, n, c",
    [
        ({"shape": "power_law", "n": 1.5, "c": 2.0e2}, 1.5, 2.0e2),
        ({"shape": "power_law", "n": 3.0, "c": 1.0e12}, 3.0, 1.0e12),
        ({"shape": "cone", "theta": 0.1}, 1.0, math.tan(0.1)),
    ],
)
def test_power_law_states_satisfy_3_192(profile, n, c):
    stress, adhesion_range = 1.0e7, WORK / 1.0e7
    problem = problem_of(md_scene(profile=profile, stress=stress))
    depth, force, radius, zone = si_contact(problem, np.array([0.9, 0.5, 0.2, 1e-2, 1e-4]))
    residual, d_closed, f_closed = theory.maugis_power_law_state(radius, zone, n, c, stress, adhesion_range, E_STAR)
    # The closed form's range condition cancels terms of size c·bⁿ (its ₂F₁ near z = 1).
    np.testing.assert_allclose(residual / (c * zone**n), 0.0, atol=1e-12)
    np.testing.assert_allclose(depth, d_closed, rtol=1e-9)
    np.testing.assert_allclose(force, f_closed, rtol=1e-9)


@pytest.mark.parametrize("tabor", TABORS)
def test_pull_off_force_is_the_minimum_of_3_171(tabor):
    _, _, force_unit = jkr_units()
    assert pull_off(problem_of(md_scene(tabor))) / force_unit == pytest.approx(
        float(theory.maugis_pull_off(tabor)), rel=1e-9, abs=0.0
    )


def test_large_tabor_pull_off_approaches_jkr_with_the_corrected_3_189():
    """F_A/F_A^JKR − 1 − 1/(12Λ²) shrinks like Λ⁻⁴ (the chapter's 11/12 is corrected to 1/12)."""
    _, _, force_unit = jkr_units()
    tabors = np.array([20.0, 40.0, 80.0])
    remainders = np.array(
        [pull_off(problem_of(md_scene(t))) / force_unit - float(theory.maugis_pull_off_large_tabor(t)) for t in tabors]
    )
    assert np.all(np.abs(remainders) < 0.2 / tabors**4)
    order = np.polyfit(np.log(tabors), np.log(np.abs(remainders)), 1)[0]
    assert -4.5 < order < -3.5


def test_small_tabor_pull_off_approaches_dmt_3_180():
    """F_A → 2πRΔγ as Λ → 0 under (3.179); 1 − F_A/(2πRΔγ) shrinks like Λ^(3/2)."""
    tabors = np.array([1e-3, 1e-2])
    gaps = np.array([1.0 - pull_off(problem_of(md_scene(t))) / float(theory.dmt_pull_off(R, WORK)) for t in tabors])
    assert gaps[0] < 1e-4 and np.all(gaps > 0)
    order = np.log(gaps[1] / gaps[0]) / np.log(tabors[1] / tabors[0])
    assert order == pytest.approx(1.5, abs=0.05)


def test_rigid_limit_is_bradley_3_141():
    """At fixed σ0 and h a stiffer half-space pulls off at 2πRΔγ, whatever the range."""
    bradley = float(theory.bradley_pull_off(R, WORK))
    errors = [
        abs(pull_off(problem_of(md_scene(stress=1e6, E_star=modulus))) / bradley - 1.0) for modulus in (1e11, 1e13)
    ]
    assert errors[1] < 1e-4 and errors[1] < errors[0] / 10


@pytest.mark.slow
def test_power_law_dmt_pull_off_3_195():
    """A stiff half-space under a power-law body pulls off at πΔγ h^((2−n)/n)/c^(2/n)."""
    n, c = 1.5, 2.0e2
    profile = {"shape": "power_law", "n": n, "c": c}
    adhesion_range = 1e-8
    expected = float(theory.power_law_dmt_pull_off(n, c, WORK, adhesion_range))
    errors = [
        abs(
            pull_off(problem_of(md_scene(profile=profile, adhesion_range=adhesion_range, E_star=modulus))) / expected
            - 1.0
        )
        for modulus in (1e11, 1e13)
    ]
    assert errors[1] < 1e-3 and errors[1] < errors[0]


def kinetic_energy_balance(result):
    lost = 0.5 * MASS * (result.touch_velocity**2 - result.separation_velocity**2)
    return lost, result.dissipated_energy


@pytest.mark.slow
@pytest.mark.parametrize("tabor", TABORS)
def test_impact_energy_balance_and_reported_tabor(tabor):
    result = simulate(md_scene(tabor))
    assert result.status == "separated"
    lost, work = kinetic_energy_balance(result)
    assert abs(lost - work) <= 1e-7 * 0.5 * MASS * result.touch_velocity**2
    assert result.tabor_parameter == pytest.approx(tabor, rel=1e-12, abs=0.0)
    for series in (result.t, result.indentation, result.velocity, result.force, result.contact_radius):
        assert np.all(np.isfinite(series))


def test_restitution_converges_to_thornton_ning_as_tabor_grows():
    """e − e_TN shrinks like 1/Λ (fitted), and falls monotonically from the DMT side."""
    velocity = 0.6
    expected = float(theory.thornton_ning_restitution(velocity, MASS, R, E_STAR, WORK))
    tabors = np.array([0.1, 1.0, 10.0, 100.0, 1000.0])
    restitution = np.array([simulate(md_scene(t, velocity)).restitution for t in tabors])
    assert np.all(np.diff(restitution) < 0)
    excess = restitution - expected
    assert np.all(excess[2:] > 0)
    order = np.polyfit(np.log(tabors[2:]), np.log(excess[2:]), 1)[0]
    assert -1.15 < order < -0.85
    assert excess[-1] < 2e-4
    # DMT side: nearly reversible (no contact hysteresis left but the zone's snaps).
    assert 1.0 - restitution[0] < 1e-5


def test_slow_impacts_are_captured():
    result = simulate(md_scene(10.0, velocity=0.05))
    assert result.status == "captured" and result.stuck
    assert result.restitution == 0.0
    assert result.events[-1][1] == "capture"


def test_dmt_side_impact_events_show_the_zone_closing_and_opening():
    kinds = [kind for _, kind in simulate(md_scene(0.1, velocity=1.0)).events]
    assert kinds == ["touch", "contact_start", "max_indentation", "contact_end", "separation"]


@pytest.mark.parametrize(
    "adhesion, extra, field, phrase",
    [
        ({"stress": 1e7, "range": 1e-9}, {}, "effects.adhesion.stress", "exactly one of stress"),
        ({}, {}, "effects.adhesion.stress", "exactly one of stress"),
        (
            {"stress": 1e7, "approach_work_of_adhesion": 0.0},
            {},
            "effects.adhesion.approach_work_of_adhesion",
            "model 'maugis_dugdale' takes 1e-09·Δγ ≤ Δγa ≤ Δγ",
        ),
        ({"stress": 1e7}, {"contact": {"springs": 4096}}, "contact.springs", "at most 2048 springs, not 4096"),
        (
            {"stress": 1e7},
            {"contact": {"springs": 100}, "solver": {"method": "verlet", "dt": 1e-12}},
            "solver.method",
            "'verlet' steps the JKR spring array only",
        ),
        ({"stress": -1.0}, {}, "effects.adhesion.stress", "-1 Pa is outside the allowed range [1, 1e13] Pa"),
    ],
)
def test_bad_dugdale_scenes_name_the_field(adhesion, extra, field, phrase):
    scene = {
        "body": {"profile": {"shape": "paraboloid", "R": R}, "mass": MASS},
        "material": {"E_star": E_STAR},
        "initial": {"velocity": 0.6},
        "effects": {"adhesion": {"model": "maugis_dugdale", "work_of_adhesion": WORK, **adhesion}},
        **extra,
    }
    with pytest.raises(SceneError) as error:
        load_scene(scene)
    assert any(path == field and phrase in message for path, message in error.value.problems), error.value.problems


@pytest.mark.parametrize(
    "profile, field, phrase",
    [
        ({"shape": "flat_punch", "radius": 1e-6}, "effects.adhesion.model", "smooth unbounded profile"),
        ({"shape": "power_law", "n": 0.8, "c": 1.0}, "body.profile.n", "n >= 1"),
    ],
)
def test_dugdale_refuses_profiles_it_is_not_built_for(profile, field, phrase):
    scene = {
        "body": {"profile": profile, "mass": MASS},
        "material": {"E_star": E_STAR},
        "initial": {"velocity": 0.6},
        "effects": {"adhesion": {"model": "maugis_dugdale", "work_of_adhesion": WORK, "stress": 1e7}},
    }
    with pytest.raises(SceneError) as error:
        load_scene(scene)
    assert any(path == field and phrase in message for path, message in error.value.problems), error.value.problems


def test_jkr_refuses_dugdale_parameters():
    scene = {
        "body": {"profile": {"shape": "paraboloid", "R": R}, "mass": MASS},
        "material": {"E_star": E_STAR},
        "initial": {"velocity": 0.6},
        "effects": {"adhesion": {"work_of_adhesion": WORK, "range": 1e-9}},
    }
    with pytest.raises(SceneError) as error:
        load_scene(scene)
    assert error.value.problems == [("effects.adhesion.range", "only for model 'maugis_dugdale' (jkr has zero range)")]


@pytest.mark.slow
def test_sweeps_over_range_equal_simulate_and_refuse_both_parameters():
    """`impact.sweep` over h (one compiled group: σ0 and h are traced) gives simulate's values
    with the sweep's method named (the quadrature: the scene names none); sweeping σ0 over a scene
    that gives h makes invalid points, refused before anything runs."""
    base = md_scene(adhesion_range=WORK / float(theory.maugis_adhesive_stress(1.0, R, WORK, E_STAR)), velocity=0.5)
    ranges = [1e-9, 1e-10]
    result = impact.sweep(base, {"effects.adhesion.range": ranges}, chunk=2)
    assert result.spec.method == "quadrature"
    for i, adhesion_range in enumerate(ranges):
        single = simulate(md_scene(adhesion_range=adhesion_range, velocity=0.5, solver={"method": "quadrature"}))
        assert result.status_names()[i] == single.status
        for name in ("restitution", "max_force", "min_force", "dissipated_energy"):
            assert math.isclose(float(getattr(result, name)[i]), getattr(single, name), rel_tol=1e-12), name
        expected = theory.thornton_ning_restitution(0.5, MASS, R, E_STAR, WORK)
        assert math.isclose(float(result.theory_restitution[i]), float(expected), rel_tol=1e-14)
    with pytest.raises(SweepError) as error:
        impact.sweep(base, {"effects.adhesion.stress": [1e7, 1e8]})
    assert "exactly one of stress" in str(error.value)


def test_normalized_curves_follow_3_171_and_the_figure_draws_them_with_both_limits():
    for tabor in (0.3, 3.0):
        radii, depths, forces = normalized_curve(tabor, contact_points=50, zone_points=20)
        zone = radii == 0.0
        contact = ~zone
        junction = float(theory.maugis_junction_zone_radius(tabor))
        d_zone, f_zone = theory.maugis_paraboloid_noncontact(np.linspace(0.0, junction, 20), tabor)
        np.testing.assert_allclose(depths[:20], d_zone, rtol=1e-10, atol=1e-12)
        np.testing.assert_allclose(forces[:20], f_zone, rtol=1e-10, atol=1e-12)
        shares = np.logspace(0.0, -6.0, 50)[1:]  # p = 1 is the junction (a = 0) itself
        a_hat, d_hat, f_hat = theory.maugis_paraboloid(1.0 / (1.0 - shares), tabor)
        np.testing.assert_allclose(radii[contact], a_hat, rtol=1e-9)
        np.testing.assert_allclose(depths[contact], d_hat, rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(forces[contact], f_hat, rtol=1e-9, atol=1e-9)
    figure = equilibrium_figure((0.3, 3.0))
    for axes in figure.axes:
        assert [line.get_gid() for line in axes.get_lines() if line.get_gid()] == ["maugis", "maugis", "limit", "limit"]


@pytest.mark.slow
def test_gravity_drop_bounces_then_is_captured():
    """A bead dropped onto the Maugis–Dugdale surface (Λ = 3): the bounces lose energy in the
    jumps until an outward turnaround in range captures it, in finite time."""
    radius, modulus, work = 1.0e-3, 1.0e10, 0.1
    scene = load_scene(
        {
            "body": {"profile": {"shape": "paraboloid", "R": radius}, "density": 2500.0},
            "material": {"E_star": modulus},
            "initial": {"velocity": 0.0, "gap": 1.5e-7},
            "effects": {
                "adhesion": {
                    "model": "maugis_dugdale",
                    "work_of_adhesion": work,
                    "stress": float(theory.maugis_adhesive_stress(3.0, radius, work, modulus)),
                },
                "gravity": {"g": 9.81},
            },
        }
    )
    result = simulate(scene)
    assert result.status == "captured" and result.stuck
    assert 3 <= result.bounces < scene.limits.max_bounces
    kinds = [kind for _, kind in result.events]
    assert kinds.count("touch") == result.bounces and kinds[-1] == "capture"
    assert 0.0 < result.restitution < 1.0
    assert np.all(np.isfinite(result.t)) and result.t[-1] < 1e-2


def test_cli_runs_a_dugdale_scene_stores_tabor_and_refuses_bad_parameters(tmp_path):
    config = str(CONFIGS / "maugis_dugdale.yaml")
    facts = CliRunner().invoke(app, ["validate", config])
    assert facts.exit_code == 0
    assert "Maugis–Dugdale adhesion" in facts.output and "σ0 = 3.7411e+07 Pa" in facts.output
    run = CliRunner().invoke(app, ["run", config, "-o", str(tmp_path / "run")])
    assert run.exit_code == 0, run.output
    assert "Tabor parameter Λ" in run.output
    stored = read_run(tmp_path / "run" / "run.h5")
    assert stored.tabor_parameter == pytest.approx(1.0, rel=1e-6, abs=0.0)
    assert [kind for _, kind in stored.events] == ["touch", "max_indentation", "separation"]
    refused = CliRunner().invoke(
        app, ["run", config, "--set", "effects.adhesion.range=1e-9", "-o", str(tmp_path / "bad")]
    )
    assert refused.exit_code == 2
    assert "effects.adhesion.stress" in refused.output and "Traceback" not in refused.output
    assert not (tmp_path / "bad").exists()
