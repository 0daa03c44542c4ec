"""The scene of an oblique impact: `initial.angle`/`spin`, `body.inertia`, `material.G_star`,
`effects.friction`; what friction cannot run, each refusal with its reason; `impact validate`."""

import math

import pytest
import yaml
from typer.testing import CliRunner

import impact
from impact.cli import app

KHARAZ = "configs/oblique_kharaz.yaml"


def kharaz():
    return yaml.safe_load(open(KHARAZ))


def refusal(data) -> dict[str, str]:
    with pytest.raises(impact.SceneError) as error:
        impact.load_scene(data)
    return dict(error.value.problems)


def test_the_example_resolves_its_moduli_and_motion():
    """G* from E and ν of both bodies (1/G* = (2 − ν)/(4G) + (2 − ν_b)/(4G_b)), the normal and
    tangential speeds V·cos θ and V·sin θ of 3.9 m/s at 30°."""
    scene = impact.load_scene(KHARAZ)
    shear = [70e9 / (2 * 1.25), 380e9 / (2 * 1.23)]
    expected = 1.0 / ((2 - 0.25) / (4 * shear[0]) + (2 - 0.23) / (4 * shear[1]))
    assert scene.material.tangential_modulus == pytest.approx(expected, rel=1e-14, abs=0.0)
    assert scene.approach_velocity == pytest.approx(3.9 * math.sqrt(3) / 2, rel=1e-15, abs=0.0)
    assert scene.start.tangential_velocity == pytest.approx(3.9 / 2, rel=1e-15, abs=0.0)


def change(path: str, value):
    data = kharaz()
    node = data
    *sections, last = path.split(".")
    for key in sections:
        node = node.setdefault(key, {})
    node[last] = value
    return data


@pytest.mark.parametrize(
    "data, field, message",
    [
        (change("contact.springs", "continuum"), "effects.friction", "runs on a spring array (contact.springs: N)"),
        (
            change("solver", {"method": "verlet", "dt": 1e-9}),
            "effects.friction",
            "rides the exact event stepper of the spring array, not 'verlet'",
        ),
        (
            change("effects.damping", {"model": "linear", "coefficient": 1.0}),
            "effects.friction",
            "not with effects.damping: the springs' normal forces would hold the viscous force",
        ),
        (
            change("effects.plasticity", {"yield_pressure": 1e9}),
            "effects.friction",
            "not with effects.plasticity: Thornton's plastic law runs on the continuum law, without springs",
        ),
        (
            change("effects.adhesion", {"model": "maugis_dugdale", "work_of_adhesion": 0.1, "stress": 1e8}),
            "effects.friction",
            "not with adhesion model 'maugis_dugdale'",
        ),
        (
            change("counterpart", {"mass": 1e-3}),
            "effects.friction",
            "not with a counterpart: the tangential motion of two free spinning bodies",
        ),
        (
            change("body", {"profile": {"shape": "cone", "theta": 0.1}, "mass": 1e-3}),
            "body.profile.shape",
            "friction needs the lever arm R from the centre to the contact of a sphere (paraboloid or sphere), "
            "not 'cone'",
        ),
        (
            change("material", {"E_star": 1e10}),
            "material.G_star",
            "missing: friction needs the tangential modulus G*",
        ),
        (change("material.G_star", 1e10), "material.G_star", "only beside E_star: with E and nu, G* follows from them"),
        (change("initial.angle", math.pi / 2), "initial.angle", "is outside the allowed range [0, 1.5708) rad"),
        (change("effects.friction.coefficient", -0.1), "effects.friction.coefficient", "is outside the allowed range"),
        (change("effects.friction.limit", "lammps"), "effects.friction.limit", "'per_spring' or 'thornton'"),
        (change("body.inertia", 0.0), "body.inertia", "is outside the allowed range"),
    ],
)
def test_what_friction_cannot_run_is_refused_with_its_reason(data, field, message):
    problems = refusal(data)
    assert field in problems, problems
    assert message in problems[field]


def test_e_star_with_g_star_and_an_inertia_are_taken():
    """E_star with G_star replaces E and ν; body.inertia replaces (2/5)mR²."""
    data = change("material", {"E_star": 6.3e10, "G_star": 5.4e10})
    data["body"]["inertia"] = 1e-9
    scene = impact.load_scene(data)
    assert scene.material.tangential_modulus == 5.4e10 and scene.body.inertia == 1e-9


def test_validate_describes_the_friction_and_the_incidence(tmp_path):
    outcome = CliRunner().invoke(app, ["validate", KHARAZ])
    assert outcome.exit_code == 0, outcome.output
    assert "friction (μ = 0.092, per spring)" in outcome.output
    assert "angle 0.523599 rad from the normal" in outcome.output
    bad = tmp_path / "bad.yaml"
    bad.write_text(yaml.safe_dump(change("contact.springs", "continuum")))
    refused = CliRunner().invoke(app, ["validate", str(bad)])
    assert refused.exit_code == 2 and "effects.friction" in refused.output and "Traceback" not in refused.output


@pytest.mark.parametrize(
    "data, message",
    [
        (change("contact.springs", 20000), "takes at most 16384 springs, not 20000"),
        (change("effects.friction.time_step", 1e-13), "time_step 1e-13 s would take 1.32e+08 steps"),
    ],
)
def test_what_would_not_end_is_refused(data, message):
    """An impact's cost grows as N² and as 1/Δt: more than 16384 springs or 10⁷ steps a Hertzian
    contact are refused."""
    assert message in refusal(data)["effects.friction"]


def test_a_shear_test_takes_at_most_a_million_springs():
    data = yaml.safe_load(open("configs/shear_paraboloid.yaml"))
    data["contact"]["springs"] = 2_000_000
    assert refusal(data)["shear"] == "takes at most 1000000 springs, not 2000000: each point costs O(N)"
