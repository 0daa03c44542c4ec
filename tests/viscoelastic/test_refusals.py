"""What a scene with a viscoelastic half-space refuses, and why: each refusal names its field
and says what to do (the messages exactly)."""

import copy

import pytest

import impact
from impact._scene.paths import resolve_field

IMPACT = {
    "body": {"profile": {"shape": "paraboloid", "R": 1e-6}, "mass": 1e-14},
    "material": {"E_star": 1e9},
    "initial": {"velocity": 0.6},
    "contact": {"springs": 1000},
    "solver": {"method": "midpoint", "dt": 1e-11},
    "effects": {"viscoelasticity": {"prony": [{"modulus": 1e9, "time": 1e-8}]}},
}
INDENTATION = {
    "kind": "indentation",
    "control": "displacement",
    "program": {"peak": 1e-6, "rate": 1e-6},
    "body": {"profile": {"shape": "paraboloid", "R": 1e-5}},
    "material": {"E_star": 1e6},
    "contact": {"springs": 1000},
    "effects": {"viscoelasticity": {"prony": [{"modulus": 1e6, "time": 0.5}]}},
}


def refusal(base: dict, **changes) -> tuple[str, str]:
    """The one problem of `base` with `changes` (dotted path → value, None deletes)."""
    data = copy.deepcopy(base)
    for path, value in changes.items():
        *parents, key = path.split("__")
        node = data
        for parent in parents:
            node = node.setdefault(parent, {})
        if value is None:
            node.pop(key)
        else:
            node[key] = value
    with pytest.raises(impact.SceneError) as error:
        impact.load_scene(data)
    (problem,) = error.value.problems
    return problem


@pytest.mark.parametrize(
    ("changes", "field", "message"),
    [
        (
            {"effects__damping": {"model": "linear", "coefficient": 1e-6}},
            "effects.damping",
            "not with effects.viscoelasticity: the medium's dashpots already dissipate on the springs in contact, "
            "and a damping force on the same springs would count that dissipation twice",
        ),
        (
            {"effects__plasticity": {"yield_pressure": 1e9}},
            "effects.plasticity",
            "not with effects.viscoelasticity: Thornton's limiting contact pressure is a law of an elastic half-space",
        ),
        (
            {"effects__gravity": {"g": 9.81}},
            "effects.gravity",
            "not with effects.viscoelasticity: between bounces the surface still creeps back, which the analytic "
            "flight between contacts does not follow",
        ),
        (
            {"effects__friction": {"coefficient": 0.3}},
            "effects.friction",
            "not with effects.viscoelasticity: the tangential springs of a viscoelastic medium (their own "
            "relaxation, slip against creep) are not implemented",
        ),
        (
            {"effects__adhesion": {"model": "greenwood_johnson", "work_of_adhesion": 0.05, "k": 2.0}},
            "effects.adhesion.model",
            "'greenwood_johnson' not with effects.viscoelasticity: its double-Hertz stress acts at every gap, so "
            "every free spring would carry a load set by its own gap; use model 'jkr' or 'maugis_dugdale'",
        ),
        (
            {
                "effects__adhesion": {
                    "model": "maugis_dugdale",
                    "work_of_adhesion": 0.05,
                    "approach_work_of_adhesion": 0.01,
                    "stress": 1e8,
                }
            },
            "effects.adhesion.approach_work_of_adhesion",
            "0.01 J/m² (below work_of_adhesion) not with effects.viscoelasticity: the Dugdale zone of a viscoelastic "
            "half-space attaches and detaches over the one range h = Δγ/σ0; leave approach_work_of_adhesion out",
        ),
        (
            {"contact__springs": "continuum"},
            "contact.springs",
            "a viscoelastic half-space runs on a spring array: give the number of springs N (each spring carries "
            "the medium's history; the continuum law keeps none). The paraboloid's closed forms of Lee & Radok and "
            "Ting are impact.theory.lee_radok_force and impact.theory.ting_force",
        ),
        (
            {"contact__springs": 200000},
            "contact.springs",
            "200000 is outside the allowed range [1, 1e5]: with effects.viscoelasticity every spring is updated "
            "every step",
        ),
        (
            {"solver": {"method": "verlet", "dt": 1e-11}},
            "solver.method",
            "a viscoelastic impact steps its springs with method 'midpoint' at a fixed solver.dt (s), not 'verlet'",
        ),
        ({"solver": {"method": "midpoint"}}, "solver.dt", "missing: method 'midpoint' needs its fixed time step (s)"),
    ],
)
def test_impact_refusals(changes, field, message):
    assert refusal(IMPACT, **changes) == (field, message)


@pytest.mark.parametrize(
    ("changes", "field", "message"),
    [
        (
            {"program__rate": None},
            "program.rate",
            "missing: a viscoelastic half-space answers the rate of loading (m/s under displacement control, N/s "
            "under force control)",
        ),
        (
            {"control": "force", "effects__adhesion": {"work_of_adhesion": 0.05}},
            "control",
            "'force' with adhesion on a viscoelastic half-space: its pull-off under force control is a dynamic "
            "instability that a rate-controlled test without inertia cannot follow; use 'displacement'",
        ),
        ({"program__rate": 0.0}, "program.rate", "0 m/s or N/s is outside the allowed range (0, 1e9] m/s or N/s"),
        (
            {"effects__adhesion": {"model": "maugis_dugdale", "work_of_adhesion": 0.05, "stress": 1e6}},
            "effects.adhesion.model",
            "'maugis_dugdale' with effects.viscoelasticity runs impacts only: the indentation test at a rate does "
            "not step the Dugdale zone's creep; use model 'jkr' for a viscoelastic indentation",
        ),
    ],
)
def test_indentation_refusals(changes, field, message):
    found = refusal(INDENTATION, **changes)
    assert found[0] == field and found[1].startswith(message)


@pytest.mark.parametrize("key", ["rate", "hold"])
def test_elastic_indentation_takes_no_rate_or_hold(key):
    elastic = copy.deepcopy(INDENTATION)
    del elastic["effects"]["viscoelasticity"]
    elastic["contact"] = {"springs": "continuum"}
    elastic["program"] = {"peak": 1e-6, key: 1.0}
    assert refusal(elastic) == (
        f"program.{key}",
        "only for a viscoelastic half-space (effects.viscoelasticity): an elastic indentation test is "
        "quasi-static, independent of rate and time",
    )


def test_midpoint_steps_only_a_viscoelastic_medium():
    elastic = copy.deepcopy(IMPACT)
    del elastic["effects"]["viscoelasticity"]
    assert refusal(elastic) == (
        "solver.method",
        "'midpoint' steps the springs of a viscoelastic half-space (effects.viscoelasticity); an elastic spring "
        "array takes 'verlet', or a diffrax method for its exact event stepping",
    )


@pytest.mark.parametrize(
    ("prony", "field", "start"),
    [
        ([], "effects.viscoelasticity.prony", "List should have at least 1 item"),
        ([{"modulus": 1e6, "time": 1.0}] * 17, "effects.viscoelasticity.prony", "at most 16 values, got 17"),
        ([{"modulus": 0.0, "time": 1.0}], "effects.viscoelasticity.prony.0.modulus", "0 Pa is outside"),
        ([{"modulus": 1e6, "time": 0.0}], "effects.viscoelasticity.prony.0.time", "0 s is outside"),
        ([{"modulus": 1e6}], "effects.viscoelasticity.prony.0.time", "missing (required)"),
    ],
)
def test_prony_terms_are_checked(prony, field, start):
    found = refusal(IMPACT, effects__viscoelasticity__prony=prony)
    assert found[0] == field and found[1].startswith(start), found


def test_terms_are_addressed_by_index():
    """Dotted paths index the list of terms (sweeps, fits, --set, as_function), and say how."""
    scene = impact.load_scene(IMPACT)
    owner, name = resolve_field(scene, "effects.viscoelasticity.prony.0.time")
    assert (owner.time, name) == (1e-8, "time")
    with pytest.raises(ValueError, match=r"effects.viscoelasticity.prony is a list of 1: index it by 0 … 0, not '1'"):
        resolve_field(scene, "effects.viscoelasticity.prony.1.time")
