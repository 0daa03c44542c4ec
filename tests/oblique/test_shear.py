"""Quasi-static shear tests (an indentation scene with `shear`): the tangential MDR springs at a
held normal force against Cattaneo–Mindlin loading and the Mindlin–Deresiewicz (Masing)
branches (Johnson 1985, §7.2, §7.4), their convergence in the number of springs, Thornton's
whole-contact limit, the refusals and the run file."""

import numpy as np
import pytest
import yaml
from typer.testing import CliRunner

import impact
from impact import theory
from impact._io.shear import read_shear, write_shear
from impact.cli import app

CONFIG = "configs/shear_paraboloid.yaml"
R, FORCE, MU = 5e-3, 10.0, 0.3


def scene(springs=2000, control="displacement", path=None, **friction):
    data = yaml.safe_load(open(CONFIG))
    data["contact"]["springs"] = springs
    data["effects"]["friction"].update(friction)
    data["shear"] = {"control": control, "path": path or [0.8 * slip(), -0.8 * slip(), 0.8 * slip()], "samples": 41}
    return data


def moduli():
    loaded = impact.load_scene(CONFIG)
    return loaded.material.effective_modulus, loaded.material.tangential_modulus


def hertz_radius():
    return (3.0 * FORCE * R / (4.0 * moduli()[0])) ** (1.0 / 3.0)


def slip():
    """δ_s = 3μF_n/(4G*a): where the whole contact slides."""
    return float(theory.full_slip_displacement(FORCE, hertz_radius(), MU, moduli()[1]))


def masing(result):
    """Q of every point after Cattaneo–Mindlin (first leg) and Masing (each leg after a reversal)."""
    return theory.masing_program_force(result.displacement, result.leg, FORCE, hertz_radius(), MU, moduli()[1])


def test_the_example_follows_cattaneo_mindlin_and_masing_to_1e_8():
    """configs/shear_paraboloid.yaml (20 000 springs): load, unload, reload within 1e-8·μF_n of the
    closed forms (measured 2.6e-9); the normal force held is the program's 10 N (1e-14)."""
    result = impact.simulate(CONFIG)
    assert result.status == "completed"
    assert result.normal_force == pytest.approx(FORCE, rel=1e-14, abs=0.0)
    assert np.max(np.abs(result.force - masing(result))) <= 1e-8 * MU * FORCE


def test_converges_as_the_square_of_the_spring_spacing():
    """max |Q − Q_closed form| over a load–unload–reload program at 0.8·δ_s: ≤ 1e-6·μF_n from
    N = 1000 springs, fitted order 1.8–2.3 in N over 500–4000 (measured 1.9–2.1), and the stick
    radius of the first loading within half a spring spacing of c = a(1 − Q/μF_n)^(1/3)."""
    counts = np.array([500, 1000, 2000, 4000])
    errors = []
    for springs in counts:
        result = impact.simulate(scene(int(springs)))
        errors.append(np.max(np.abs(result.force - masing(result))) / (MU * FORCE))
        loading = result.leg == 0
        closed = theory.cattaneo_mindlin_stick_radius(result.force[loading], FORCE, hertz_radius(), MU)
        assert np.max(np.abs(result.stick_radius[loading] - closed)) <= 0.5 * result.stats["spacing"] * (1 + 1e-9)
    order = -np.polyfit(np.log(counts), np.log(errors), 1)[0]
    assert 1.8 <= order <= 2.3, (order, errors)
    assert errors[1] <= 1e-6, errors


def test_a_force_program_gives_the_displacements_of_cattaneo_mindlin_and_masing():
    """Under force control (to ±0.8μF_n) each point's δ is within 1e-6·δ_s of δ(Q) (Johnson
    (7.43)) on loading and of δ_t + 2δ_CM((Q − Q_t)/2) after each reversal; the forces are the
    program's to round-off."""
    top = 0.8 * MU * FORCE
    result = impact.simulate(scene(2000, "force", [top, -top, top]))
    common = (FORCE, hertz_radius(), MU, moduli()[1])
    expected, turning = np.empty_like(result.displacement), None
    for leg in range(3):
        points = result.leg == leg
        forces = result.force[points]
        if turning is None:
            expected[points] = theory.cattaneo_mindlin_displacement(forces, *common)
        else:
            expected[points] = turning[0] + 2.0 * theory.cattaneo_mindlin_displacement(
                0.5 * (forces - turning[1]), *common
            )
        turning = (expected[points][-1], forces[-1])
    assert np.max(np.abs(result.displacement - expected)) <= 1e-6 * slip()
    program = np.concatenate([np.linspace(0, top, 41), np.linspace(top, -top, 41), np.linspace(-top, top, 41)])
    assert np.max(np.abs(result.force - program)) <= 1e-12 * top


def test_thorntons_limit_slides_the_whole_contact_at_once():
    """Under the whole-contact limit every spring sticks until Q = μF_n: Q = 2G*·kΔx·δ (the
    array's no-slip stiffness, 1e-12), then μF_n; the stick radius is the contact radius, then 0."""
    result = impact.simulate(scene(2000, path=[2.0 * slip()], limit="thornton"))
    stiffness = 2.0 * moduli()[1] * result.contact_radius
    expected = np.minimum(stiffness * result.displacement, MU * result.normal_force)
    assert np.max(np.abs(result.force - expected)) <= 1e-12 * MU * FORCE
    sliding = stiffness * result.displacement > MU * result.normal_force
    assert np.all(result.stick_radius[~sliding] == pytest.approx(result.contact_radius, rel=1e-12, abs=0.0))
    assert np.all(result.stick_radius[sliding] == 0.0) and sliding.any()


@pytest.mark.parametrize(
    "change, field, message",
    [
        (
            lambda d: d["effects"].pop("friction"),
            "shear",
            "needs effects.friction (the coefficient μ of the tangential springs)",
        ),
        (lambda d: d["contact"].update(springs="continuum"), "shear", "runs on a spring array (contact.springs: N)"),
        (lambda d: d["program"].update(cycles=2), "shear", "holds the normal load at program.peak: give one cycle"),
        (
            lambda d: d["effects"].update(adhesion={"work_of_adhesion": 0.1}),
            "shear",
            "holds a normal contact without adhesion",
        ),
        (
            lambda d: d["shear"].update(control="force", path=[3.0]),
            "shear.path",
            "|Q| = 3 N reaches μF_n = 3 N: the whole contact would slide",
        ),
        (
            lambda d: (
                d.update(control="displacement"),
                d["program"].update(peak=1e-6),
                d["shear"].update(control="force", path=[1.0]),
            ),
            "shear.control",
            "'force' needs the normal load held as a force (control: force)",
        ),
        (
            lambda d: d["shear"].update(path=[1e-7, 1e-7]),
            "shear.path",
            "turning point 1 (1e-07) repeats the point before it",
        ),
    ],
)
def test_refusals_name_the_field_and_why(change, field, message):
    data = scene(100)
    change(data)
    with pytest.raises(impact.SceneError) as error:
        impact.load_scene(data)
    problems = dict(error.value.problems)
    assert field in problems, problems
    assert message in problems[field]


def test_an_impact_takes_no_shear_program():
    data = yaml.safe_load(open("configs/oblique_kharaz.yaml"))
    data["shear"] = {"control": "displacement", "path": [1e-7]}
    with pytest.raises(impact.SceneError) as error:
        impact.load_scene(data)
    assert dict(error.value.problems)["shear"].startswith("only for kind 'indentation'")


def test_an_indentation_takes_friction_only_with_a_shear_program():
    data = scene(100)
    del data["shear"]
    with pytest.raises(impact.SceneError) as error:
        impact.load_scene(data)
    assert dict(error.value.problems)["effects.friction"] == (
        "an indentation takes friction with a shear program (shear)"
    )


def test_run_file_and_command_line(tmp_path):
    """`impact run` writes run.h5 and shear.png; the file reads back equal (write_shear /
    read_shear, open_run) and `impact show` prints it."""
    folder = tmp_path / "shear"
    outcome = CliRunner().invoke(app, ["run", CONFIG, "-o", str(folder)])
    assert outcome.exit_code == 0, outcome.output
    assert (folder / "shear.png").is_file()
    stored = impact.open_run(folder)
    again = read_shear(write_shear(stored, tmp_path / "again.h5"))
    for name in ("displacement", "force", "stick_radius", "leg"):
        np.testing.assert_array_equal(getattr(again, name), getattr(stored, name))
    assert (again.normal_force, again.status) == (stored.normal_force, "completed")
    shown = CliRunner().invoke(app, ["show", str(folder / "run.h5")])
    assert shown.exit_code == 0 and "shear_paraboloid (shear)" in shown.output
