"""Maugis–Dugdale approach hysteresis (Δγa < Δγ, `impact._law.dugdale_hysteresis`, this project's
derivation): the frozen zone against an independent evaluation of (3.152), (3.154), (3.156) with
b fixed, the path's continuity at both switches, and impacts on it (energy balance, the
reversible law at Δγa = Δγ, restitution against Δγa, the JKR hysteresis law as Λ grows,
gravity). The impacts share one compiled program (without trajectory samples, as
`configs/maugis_dugdale_hysteresis.yaml` runs in `test_configs`); the law's checks compile only
the curves' construction."""

import dataclasses
import math

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from impact import load_scene, simulate, theory
from impact._integrate.curve import CurveIntegrator
from impact._law.dugdale import DugdaleLaw
from impact._law.dugdale_hysteresis import _on_part as path_state
from impact._law.dugdale_hysteresis import frozen_state
from impact._run.impacts import solve_scene
from impact._run.parameters import integrator_for, options_for, physics_for
from impact._run.sweep.closed_forms import closed_form_name
from impact._run.sweep.plan import physics_with, static_choices
from impact._scene.scene import SceneError
from tests.scenes import A_JKR, D_JKR, E_STAR, F_JKR, MASS, WORK, R, micro_sphere


def scene(tabor=1.0, share=0.5, velocity=0.6, profile=None, stress=None, **extra):
    """A Maugis–Dugdale impact with Δγa = share·Δγ (σ0 for Λ on the paraboloid, or given)."""
    adhesion = {
        "model": "maugis_dugdale",
        "work_of_adhesion": WORK,
        "stress": stress or float(theory.maugis_adhesive_stress(tabor, R, WORK, E_STAR)),
    }
    if share is not None:
        adhesion["approach_work_of_adhesion"] = share * WORK
    spec = micro_sphere(velocity, {"adhesion": adhesion}, name="md_hysteresis", **extra)
    if profile is not None:
        spec["body"]["profile"] = profile
    return spec


_build = eqx.filter_jit(lambda integrator, physics, options: integrator.build(physics, options))
_path = eqx.filter_jit(lambda curve, law, zone: curve.at(law, zone))
_on_segment = eqx.filter_jit(lambda curve, law, s, segment: curve.on_segment(law, s, segment))


@eqx.filter_jit
def _zone_radii(path, law):
    """b along the search grids of the path's detach and approach curves, up to their tops (nan
    beyond)."""

    def radii(curve, part):
        grid = curve.grid(part)
        return jnp.where(grid <= curve.nodes[-1], curve.state(part, grid)[3], jnp.nan)

    return radii(path.detach, law.detach), radii(path.approach, law.approach)


def path_of(spec, fraction=0.6, junctions=None):
    """(scene, its law, the path anchored on the approach curve at `fraction` of the way from
    the onset to the top of the curve's first rising contact segment; or, given `junctions`,
    at that multiple of the approach curve's junction radius b_J)."""
    loaded = load_scene(spec)
    problem = _build(integrator_for(loaded), physics_for(loaded), options_for(loaded, trajectory=False))
    law, curve = problem.law, problem.curve
    approach = curve.approach
    if junctions is not None:
        return loaded, law, _path(curve, law, junctions * approach.junction)
    nodes, rising = np.asarray(approach.nodes), np.asarray(approach.increasing)
    first = np.flatnonzero(rising & (nodes[1:] > float(approach.junction)))[0]
    low, top = nodes[first], min(nodes[first + 1], float(approach.junction) + 12.0)
    zone = approach.state(law.approach, jnp.asarray(low + fraction * (top - low)))[3]
    return loaded, law, _path(curve, law, zone)


def si(law, states):
    """(d [m], F [N], a [m], b [m]) of scaled states."""
    scales = law.scales
    units = (scales.normal, scales.force, scales.radial, scales.radial)
    return tuple(np.asarray(value) * float(unit) for value, unit in zip(states, units, strict=True))


def frozen_reference(g, a, b, sigma):
    """(d, F, gap at b) of the contact of radius a with the zone radius b fixed, from (3.154),
    (3.156) and the left side of (3.152) by adaptive quadrature (x = b·sin t in the gap)."""
    d = g(a) - 2.0 * sigma / E_STAR * math.sqrt(b * b - a * a)
    elastic = 2.0 * E_STAR * quad(lambda x: d - g(x), 0.0, a, epsabs=0.0, epsrel=1e-13)[0]
    force = elastic - sigma * (-2.0 * a * math.sqrt(b * b - a * a) + 2.0 * b * b * math.acos(a / b))
    # The integrand cancels to round-off near its lower end: an absolute floor of 1e-14·g(b).
    opening = quad(
        lambda t: g(b * math.sin(t)) - d, math.asin(a / b), 0.5 * math.pi, epsabs=1e-14 * g(b), epsrel=1e-13
    )[0]
    gap = 2.0 / math.pi * opening - 4.0 * sigma / (math.pi * E_STAR) * (b - a)
    return d, force, gap


@pytest.mark.slow
@pytest.mark.parametrize("tabor, share", [(1.0, 0.5), (10.0, 0.1)])
def test_frozen_zone_solves_3_152_3_154_3_156_with_b_fixed(tabor, share):
    """d(a), F(a) along the frozen zone of the paraboloid and its two switches, where the gap at
    b_f reaches h (onto the detach curve) and ha (the approach curve), against quadrature and
    Brent's method: ≤ 1e-10 in the JKR units (3.170) (measured ≤ 5e-13; ≤ 2e-13 for the power law
    n = 1.5, whose P(p) is a quadrature, not run here: it compiles a curve of its own)."""
    spec, g = {"shape": "paraboloid", "R": R}, lambda x: x * x / R
    stress = float(theory.maugis_adhesive_stress(tabor, R, WORK, E_STAR))
    _, law, path = path_of(scene(tabor, share, profile=spec, stress=stress))
    lower, upper = float(path.lower), float(path.upper)
    assert upper > lower
    points = jnp.asarray(lower + (upper - lower) * np.array([0.0, 0.2, 0.5, 0.8, 1.0]))
    segment = int(np.searchsorted(np.asarray(path.nodes), 0.5 * (lower + upper))) - 1
    depth, force, radius, zone = si(law, _on_segment(path, law, points, segment))
    b = float(zone[0])
    np.testing.assert_array_equal(zone, b)
    for i in range(points.shape[0]):
        d_ref, f_ref, _ = frozen_reference(g, float(radius[i]), b, stress)
        assert abs(depth[i] - d_ref) <= 1e-10 * D_JKR
        assert abs(force[i] - f_ref) <= 1e-10 * F_JKR
    h = WORK / stress
    for end, gap in ((radius[0], h), (radius[-1], share * h)):
        root = brentq(
            lambda a, gap=gap: frozen_reference(g, a, b, stress)[2] - gap, 1e-6 * b, b * (1 - 1e-12), xtol=1e-20
        )
        assert abs(end - root) <= 1e-10 * A_JKR


@pytest.mark.slow
def test_the_path_is_each_parts_own_formula_from_one_evaluation_of_the_contact(monkeypatch):
    """Along the detach curve, the frozen zone and the approach curve the path's state is the
    part's own formula bit for bit (`DugdaleCurve.state` of the detach or approach law at its
    own parameter, `frozen_state` at φ = φ_d + s − s1), though the path evaluates the contact's
    formulas once for all three parts (traced once per state, not twice; and once per shape of
    s: the path's formulas are one jitted function, whose trace later evaluations reuse)."""
    _, law, path = path_of(scene(1.0, 0.5), fraction=0.4)
    lower, upper = float(path.lower), float(path.upper)
    detach = jnp.asarray(lower * np.array([0.2, 0.6, 0.9]))
    frozen = jnp.asarray(lower + (upper - lower) * np.array([0.1, 0.5, 0.9]))
    approach = jnp.asarray(upper + np.array([0.1, 1.0, 3.0]))
    state = eqx.filter_jit(lambda path, law, s: path.state(law, s))
    along = path.start + approach - path.upper
    expected = (
        eqx.filter_jit(lambda curve, law, s: curve.state(law, s))(path.detach, law.detach, detach),
        eqx.filter_jit(frozen_state)(law.detach, path.zone, path.switches_at[0] + frozen - path.lower),
        eqx.filter_jit(lambda curve, law, s: curve.state(law, s))(path.approach, law.approach, along),
    )
    for points, reference in zip((detach, frozen, approach), expected, strict=True):
        for value, other in zip(state(path, law, points), reference, strict=True):
            np.testing.assert_array_equal(np.asarray(value), np.asarray(other))
    traced: list[int] = []
    contact = DugdaleLaw.contact
    monkeypatch.setattr(DugdaleLaw, "contact", lambda *args, **kwargs: traced.append(1) or contact(*args, **kwargs))
    path_state.clear_cache()  # the evaluations above
    jax.make_jaxpr(lambda s: path.state(law, s))(frozen)
    assert len(traced) == 1
    jax.make_jaxpr(lambda s: path.state(law, s) + path.state(law, 2.0 * s))(frozen)
    assert len(traced) == 1


@pytest.mark.parametrize(
    "tabor, share, junctions",
    [
        (1.0, 0.5, None),
        (10.0, 0.1, None),
        (0.1, 0.5, 0.9),  # both switches without contact: the zone never closed
        (0.1, 0.5, 1.02),  # the frozen zone opens (a → 0) before it meets the detach curve
    ],
)
def test_the_path_is_continuous_at_its_switches_and_the_zone_only_grows(tabor, share, junctions):
    """At s1 (frozen zone → detach curve), s2 (approach curve → frozen zone) and where the frozen
    contact opens both formulas give the same state (measured ≤ 7e-15 relative, Λ = 0.01…100; asserted
    1e-12), and the zone radius b never falls along either curve (a point beyond b_f was never
    within ha, one left behind is beyond h; also measured for the cone and n = 1.5, 3)."""
    stress = float(theory.maugis_adhesive_stress(tabor, R, WORK, E_STAR))
    _, law, path = path_of(scene(tabor, share, stress=stress), fraction=0.4, junctions=junctions)
    nodes = np.asarray(path.nodes)
    lower, upper = float(path.lower), float(path.upper)
    switches = [lower, upper]
    detach_phi, approach_phi = (float(phi) for phi in path.switches_at)
    if junctions == 0.9:
        assert approach_phi < 0.0  # no contact anywhere on the frozen zone
    if junctions == 1.02:
        assert detach_phi < 0.0 < approach_phi
        switches.append(lower - detach_phi)  # the frozen zone's own junction, φ = 0
    for switch in switches:
        below = int(np.searchsorted(nodes, switch, side="left")) - 1
        above = int(np.searchsorted(nodes, switch, side="right")) - 1
        assert nodes[below + 1] == switch == nodes[above]
        one, other = (np.asarray(_on_segment(path, law, jnp.asarray(switch), k)) for k in (below, above))
        np.testing.assert_allclose(one, other, rtol=1e-12, atol=1e-12 * np.max(np.abs(one)))
    for radii in _zone_radii(path, law):
        radii = np.asarray(radii)
        assert np.all(np.diff(radii[~np.isnan(radii)]) >= 0.0)


def hysteretic_of(reversible):
    """The integrator of a hysteretic scene for a reversible one (Δγa = Δγ): the program its
    scenes with Δγa < Δγ run."""
    integrator = integrator_for(reversible)
    assert isinstance(integrator, CurveIntegrator) and not integrator.hysteresis
    return dataclasses.replace(integrator, hysteresis=True)


def balance(result):
    """(kinetic energy lost, ∮F dd) of the first contact (J)."""
    return 0.5 * MASS * (result.touch_velocity**2 - result.separation_velocity**2), result.dissipated_energy


@pytest.mark.slow
def test_equal_works_reproduce_the_reversible_law():
    """Δγa = Δγ on the hysteretic path (its frozen zone empty) gives the reversible program's
    impact to round-off (measured: bit for bit, with and without trajectory samples): the same
    events, work and forces. (A scene with Δγa = Δγ runs the reversible program itself.)"""
    reversible = load_scene(scene(share=None))
    hysteretic = solve_scene(reversible, hysteretic_of(reversible), options_for(reversible, trajectory=False))
    plain = simulate(reversible)
    for name in ("restitution", "dissipated_energy", "max_force", "min_force", "max_indentation", "contact_time"):
        assert getattr(hysteretic, name) == pytest.approx(getattr(plain, name), rel=1e-12, abs=0.0), name
    assert [kind for _, kind in hysteretic.events] == [kind for _, kind in plain.events]
    np.testing.assert_allclose([t for t, _ in hysteretic.events], [t for t, _ in plain.events], rtol=1e-12)


@pytest.mark.slow
def test_energy_balance_events_and_restitution_against_the_approach_work():
    """Δγa/Δγ = 0.9 … 0.3 at Λ = 1 (one compiled program): every impact loses ∮F dd of kinetic
    energy (≤ 1e-8 relative; measured ≤ 2e-10) over touch, max_indentation, detach_start,
    separation, and e falls with Δγa from the reversible value (measured 0.938, 0.873, 0.752,
    0.651, 0.584). Below about Δγa = 0.1Δγ it rises again towards the Δγa → 0 limit, as the
    JKR law's does (measured 0.578 at 0.1, 0.628 at 0.01, 0.659 at 1e-6)."""
    reversible = load_scene(scene(share=None))
    options = options_for(reversible, trajectory=False)
    restitutions = [solve_scene(reversible, hysteretic_of(reversible), options).restitution]
    for share in (0.9, 0.7, 0.5, 0.3):
        result = simulate(scene(share=share))
        assert result.status == "separated"
        lost, work = balance(result)
        assert abs(lost - work) <= 1e-8 * 0.5 * MASS * result.touch_velocity**2
        assert [kind for _, kind in result.events] == ["touch", "max_indentation", "detach_start", "separation"]
        restitutions.append(result.restitution)
    assert np.all(np.diff(restitutions) < 0.0), restitutions


@pytest.mark.slow
@pytest.mark.parametrize(
    "tabor, share, velocity, status, kinds",
    [
        (1.0, 1e-9, 0.6, "separated", ["touch", "max_indentation", "detach_start", "separation"]),
        (1000.0, 1e-9, 0.6, "separated", ["touch", "max_indentation", "detach_start", "separation"]),
        (0.01, 1e-9, 0.6, "separated", ["touch", "max_indentation", "contact_end", "detach_start", "separation"]),
        (1.0, 0.5, 20.0, "separated", ["touch", "max_indentation", "detach_start", "separation"]),
        # Captured on the frozen zone without contact: it pulls with −πσ0·b_max² over its whole depth.
        (0.01, 0.5, 0.6, "captured", ["touch", "contact_start", "max_indentation", "contact_end", "capture"]),
        (1.0, 0.5, 0.05, "captured", ["touch", "max_indentation", "detach_start", "capture"]),
        # Λa = Λ·(Δγ/Δγa)^(1/3) = 1e7: the approach zone is narrower than the curve's grid resolves.
        (1e4, 1e-9, 0.6, "radius_overflow", ["touch", "contact_start"]),
    ],
)
def test_hard_cases_at_the_edges_of_the_domain(tabor, share, velocity, status, kinds):
    """The least Δγa allowed (1e-9·Δγ) from the DMT to the JKR side, a fast and a slow impact, a
    capture on the frozen zone, and the corner where the approach curve is not resolved (a named
    status, not a number): each ends as stated, a separated one with ∮F dd = ΔKE (1e-8)."""
    result = simulate(scene(tabor=tabor, share=share, velocity=velocity))
    assert result.status == status
    assert [kind for _, kind in result.events] == kinds
    if status == "separated":
        lost, work = balance(result)
        assert abs(lost - work) <= 1e-8 * 0.5 * MASS * result.touch_velocity**2


@pytest.mark.slow
def test_large_tabor_tends_to_the_jkr_hysteresis_law():
    """Δγa = Δγ/2: e − e_JKR(Δγa) shrinks like 1/Λ (fitted over Λ = 30, 100, 300; measured slope
    −0.98, 8.4e-5 at Λ = 300), as the zone's width b − a → 0 pins the frozen contact at a_max."""
    jkr = simulate(
        {
            **scene(share=None),
            "effects": {"adhesion": {"work_of_adhesion": WORK, "approach_work_of_adhesion": 0.5 * WORK}},
        },
        trajectory=False,
    ).restitution
    tabors = np.array([30.0, 100.0, 300.0])
    excess = np.array([simulate(scene(tabor=t)).restitution - jkr for t in tabors])
    assert np.all(excess > 0.0) and excess[-1] < 1.5e-4
    order = np.polyfit(np.log(tabors), np.log(excess), 1)[0]
    assert -1.1 < order < -0.9


@pytest.mark.slow
def test_gravity_drop_bounces_then_is_captured():
    """The bead of the reversible gravity test (Λ = 3) with Δγa = 0.9Δγ: every bounce lands on
    the approach curve again (the memory cleared in flight) and unloads over a frozen zone onto
    the detach curve, until an outward turnaround captures it (measured: 4 bounces, against 6
    without hysteresis)."""
    radius, modulus, work = 1.0e-3, 1.0e10, 0.1
    stress = float(theory.maugis_adhesive_stress(3.0, radius, work, modulus))
    adhesion = {"model": "maugis_dugdale", "work_of_adhesion": work, "stress": stress}
    result = simulate(
        {
            "body": {"profile": {"shape": "paraboloid", "R": radius}, "density": 2500.0},
            "material": {"E_star": modulus},
            "initial": {"velocity": 0.0, "gap": 1.5e-7},
            "effects": {"adhesion": {**adhesion, "approach_work_of_adhesion": 0.9 * work}, "gravity": {"g": 9.81}},
        },
        trajectory=False,
    )
    assert result.status == "captured" and result.stuck
    kinds = [kind for _, kind in result.events]
    assert 3 <= result.bounces < result.scene.limits.max_bounces
    assert kinds.count("touch") == kinds.count("max_indentation") == kinds.count("detach_start") == result.bounces
    assert kinds.count("separation") == result.bounces - 1 and kinds[-1] == "capture"
    assert 0.0 < result.restitution < 1.0 and result.events[-1][0] < 1e-2


def test_sweeps_pass_the_approach_work_and_run_the_hysteretic_program():
    """A sweep over Δγa hands each point its value (traced) and the hysteretic integrator (static,
    each Δγa < Δγ), and names no closed form; Δγa = Δγ keeps the reversible program."""
    base = load_scene(scene(share=0.5))
    values = np.array([0.9, 0.3, 1.0]) * WORK
    physics = physics_with(base, {"effects.adhesion.approach_work_of_adhesion": values})
    np.testing.assert_array_equal(physics.law.approach_work_of_adhesion, values)
    for value, hysteretic in zip(values, (True, True, False), strict=True):
        point = load_scene(scene(share=value / WORK))
        assert static_choices(point).integrator.hysteresis == hysteretic
    assert closed_form_name(base) == "no closed form (Maugis–Dugdale with approach hysteresis)"


@pytest.mark.parametrize(
    "adhesion, extra, field, message",
    [
        (
            {"model": "maugis_dugdale", "stress": 1e7, "approach_work_of_adhesion": 0.06},
            {},
            "effects.adhesion.approach_work_of_adhesion",
            "0.06 J/m² is above work_of_adhesion (0.05 J/m²): 0 ≤ Δγa ≤ Δγ "
            "(attaching cannot gain more energy than detaching costs)",
        ),
        (
            {"model": "maugis_dugdale", "stress": 1e7, "approach_work_of_adhesion": 0.0},
            {},
            "effects.adhesion.approach_work_of_adhesion",
            "0 J/m² is below 1e-09·work_of_adhesion (5e-11 J/m²): model 'maugis_dugdale' takes 1e-09·Δγ ≤ Δγa ≤ Δγ "
            "(its approach range Δγa/σ0 must be resolved; attach on touch, Δγa = 0, is model 'jkr')",
        ),
        (
            {"model": "maugis_dugdale", "stress": 1e7, "approach_work_of_adhesion": 0.02},
            {"contact": {"springs": 64}},
            "effects.adhesion.approach_work_of_adhesion",
            "0.02 J/m² is below work_of_adhesion (0.05 J/m²): a maugis_dugdale spring array has no approach "
            "hysteresis (its curve is built spring by spring for one range; the frozen zone is derived for the "
            "continuum law only): leave it out, or set it to work_of_adhesion, or use contact.springs: continuum",
        ),
        (
            {"model": "greenwood_johnson", "k": 10.0, "approach_work_of_adhesion": 0.02},
            {},
            "effects.adhesion.approach_work_of_adhesion",
            "0.02 J/m² is not taken by model 'greenwood_johnson', which loads and unloads on the stable "
            "branches of its equilibrium curve without approach hysteresis: leave it out (approach "
            "hysteresis: model 'jkr' or 'maugis_dugdale')",
        ),
    ],
)
def test_bad_approach_works_name_the_field_the_value_and_what_is_allowed(adhesion, extra, field, message):
    spec = {
        "body": {"profile": {"shape": "paraboloid", "R": R}, "mass": MASS},
        "material": {"E_star": E_STAR},
        "initial": {"velocity": 0.6},
        "effects": {"adhesion": {"work_of_adhesion": WORK, **adhesion}},
        **extra,
    }
    with pytest.raises(SceneError) as error:
        load_scene(spec)
    assert (field, message) in error.value.problems, error.value.problems
