"""The solver section: what each method and `phase_ends` refuse, by field and in words (the
physics of each integrator is tested under tests/integrate)."""

import pytest
import yaml

import impact
from impact._integrate.verlet import Verlet
from impact._run.parameters import integrator_for
from impact._scene.scene import SceneError, load_scene
from tests.scenes import CONFIGS, MASS, WORK, R, micro_sphere


def scene(**extra) -> dict:
    """The micro-sphere at 0.6 m/s with JKR adhesion and the sections `extra`."""
    return micro_sphere(0.6, {"adhesion": {"work_of_adhesion": WORK}}, name="verlet", **extra)


@pytest.mark.parametrize(
    ("change", "why"),
    [
        (
            {"contact": {"springs": 64}},
            "for the continuum law only (contact.springs: continuum): a spring array's events advance exactly",
        ),
        (
            {"effects": {"adhesion": {"model": "maugis_dugdale", "work_of_adhesion": 0.05, "stress": 3.7e7}}},
            "not with adhesion model 'maugis_dugdale': its phases end where the solver locates them",
        ),
        (
            {"effects": {"adhesion": {"work_of_adhesion": 0.05}, "plasticity": {"yield_pressure": 3e8}}},
            "not with effects.plasticity: its phases end where the solver locates them",
        ),
        (
            {"effects": {"adhesion": {"work_of_adhesion": 0.05}, "damping": {"model": "linear", "coefficient": 1e-9}}},
            "not with effects.damping: a damped phase does not keep its energy",
        ),
    ],
)
def test_energy_ends_are_refused_where_they_do_not_apply(change, why):
    data = yaml.safe_load((CONFIGS / "thornton_ning.yaml").read_text())
    data.update(change)
    data["solver"] = {"phase_ends": "energy"}
    with pytest.raises(impact.SceneError) as error:
        impact.load_scene(data)
    assert dict(error.value.problems)["solver.phase_ends"] == why


@pytest.mark.parametrize(
    ("field", "value", "why"),
    [
        ("phase_ends", "exact", "unknown phase_ends 'exact'; expected one of: integrated, energy"),
        (
            "method",
            "rk4",
            "unknown method 'rk4'; expected one of: "
            "tsit5, dopri5, dopri8, bosh3, heun, kvaerno3, kvaerno5, verlet, midpoint, quadrature",
        ),
    ],
)
def test_an_unknown_solver_choice_is_refused(field, value, why):
    data = yaml.safe_load((CONFIGS / "thornton_ning.yaml").read_text())
    data["solver"] = {field: value}
    with pytest.raises(impact.SceneError) as error:
        impact.load_scene(data)
    assert dict(error.value.problems)[f"solver.{field}"] == why


@pytest.mark.parametrize(
    ("change", "why"),
    [
        (
            {"effects": {"adhesion": {"work_of_adhesion": 0.05}, "damping": {"model": "linear", "coefficient": 1e-9}}},
            "'quadrature' not with effects.damping: a damped phase does not keep its energy",
        ),
        (
            {"body": {"profile": {"shape": "sphere", "R": R}, "mass": MASS}},
            "'quadrature' needs a profile of the form g = A·xⁿ (paraboloid, cone, power_law), not 'sphere'",
        ),
        (
            {"body": {"profile": {"shape": "power_law", "n": 0.8, "c": 1e3}, "mass": MASS}},
            "'quadrature' needs a power law with n >= 1 (not 0.8) and, with adhesion, approach_work_of_adhesion "
            "equal to work_of_adhesion or 0: otherwise loading may start from a tip of infinite slope",
        ),
        ({"limits": {"duration": 1e-6}}, "'quadrature' does not stop a phase midway: leave limits.duration out"),
        (
            {"solver": {"method": "quadrature", "phase_ends": "integrated"}},
            "'quadrature' ends every phase from its energy balance: leave solver.phase_ends out (or set it to "
            "'energy')",
        ),
    ],
)
def test_quadrature_is_refused_where_it_does_not_apply(change, why):
    data = yaml.safe_load((CONFIGS / "thornton_ning.yaml").read_text())
    data.update(change)
    data.setdefault("solver", {})["method"] = "quadrature"
    with pytest.raises(impact.SceneError) as error:
        impact.load_scene(data)
    assert dict(error.value.problems)["solver.method"] == why


@pytest.mark.parametrize(
    "extra, path, words",
    [
        ({"solver": {"method": "verlet", "dt": 1e-11}}, "contact.springs", "number of springs"),
        ({"solver": {"method": "verlet"}, "contact": {"springs": 100}}, "solver.dt", "time step"),
        ({"solver": {"method": "tsit5", "dt": 1e-11}}, "solver.dt", "only for methods 'verlet' and 'midpoint'"),
        (
            {"solver": {"method": "verlet", "dt": -1.0}, "contact": {"springs": 100}},
            "solver.dt",
            "-1 s is outside the allowed range [1e-30, 1] s",
        ),
    ],
    ids=["continuum", "no step", "adaptive with a step", "negative step"],
)
def test_scene_refuses_verlet_misuse(extra, path, words):
    with pytest.raises(SceneError) as caught:
        load_scene(scene(**extra))
    assert any(p == path and words in message for p, message in caught.value.problems), caught.value.problems


def test_verlet_scene_accepts_a_yaml_string_step():
    loaded = load_scene(scene(solver={"method": "verlet", "dt": "1e-11"}, contact={"springs": 100}))
    assert loaded.solver.dt == 1e-11
    assert integrator_for(loaded) == Verlet(dt=1e-11)
