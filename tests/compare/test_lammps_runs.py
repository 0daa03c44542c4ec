"""`impact compare lammps` with LAMMPS running (skipped where the `lammps` extra is not installed):
the Hertz impact agrees to LAMMPS's own time-step error, LAMMPS's jkr loses exactly the energy of
a JKR branch cut at the force-controlled pull-off and pulls with exactly (3/2)πRΔγ (so γ = Δγ/2
and E* are mapped right, on a wall and between two spheres), and the viscoelastic damping maps
onto LAMMPS's force law. Each LAMMPS run is a few particles for a few thousand steps."""

import csv
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from impact import theory
from impact._compare.comparison import STEP_ERROR_FACTOR, compare_lammps, hertz_time
from impact._compare.granular import NormalModel
from impact._compare.lammps_batch import run_batch
from impact._compare.lammps_model import lammps_model
from impact._scene.scene import load_scene
from impact.cli import app
from tests.scenes import CONFIGS

pytest.importorskip("lammps")

STEPS_PER_CONTACT = 200  # a coarse step: LAMMPS's error stands well above impact's (1e-9)


def within_step_error(ours, theirs, half):
    """|theirs − ours| ≤ 2|theirs − half| elementwise (the time-step error bound of order ≥ 1)."""
    return np.abs(theirs - ours) <= STEP_ERROR_FACTOR * np.abs(theirs - half)


@pytest.mark.slow
def test_hertz_agrees_to_the_time_step_error_and_writes_the_comparison(tmp_path):
    """configs/hard/01_no_adhesion.yaml at 3 speeds, dt = Hertz's contact time at 1 m/s / 200:
    restitution, contact time and largest force by LAMMPS's hertz/material within
    2|X(dt) − X(dt/2)| of impact's (the contact time within 2 steps), and the files written."""
    scene_file = CONFIGS / "hard" / "01_no_adhesion.yaml"
    scene = load_scene(scene_file)
    dt = hertz_time(scene, lammps_model(scene), 1.0) / STEPS_PER_CONTACT
    folder = tmp_path / "hertz"
    result = CliRunner().invoke(
        app, ["compare", "lammps", str(scene_file), "--velocities", "0.2:1:3", "--dt", repr(dt), "-o", str(folder)]
    )
    assert result.exit_code == 0, result.output
    assert {path.name for path in folder.iterdir()} == {
        "comparison.csv",
        "comparison.png",
        "summary.txt",
        "in.lammps",
        "config.yaml",
    }
    assert (folder / "comparison.png").read_bytes().startswith(b"\x89PNG")
    assert "fix wall all wall/gran granular hertz/material" in (folder / "in.lammps").read_text()
    rows = list(csv.DictReader((folder / "comparison.csv").open()))
    assert np.allclose([float(row["velocity"]) for row in rows], [0.2, 0.6, 1.0], rtol=1e-15, atol=0.0)
    for name in ("restitution", "max_force"):
        ours, theirs, half = (np.array([float(row[key]) for row in rows]) for key in _keys(name))
        assert np.all(within_step_error(ours, theirs, half)), name
        assert np.all(theirs != ours)  # a step error to compare with, not round-off
    ours, theirs = (np.array([float(row[key]) for row in rows]) for key in _keys("contact_time")[:2])
    assert np.all(np.abs(theirs - ours) <= STEP_ERROR_FACTOR * dt)
    summary = (folder / "summary.txt").read_text()
    for name in ("restitution", "contact_time (s)", "max_force (N)"):
        assert any(
            line.startswith(f"  {name}:") and line.endswith("agree to the step error") for line in summary.splitlines()
        )


def _keys(name):
    return f"impact_{name}", f"lammps_{name}", f"lammps_{name}_half_step"


@pytest.mark.parametrize("scene_name", ["thornton_ning.yaml", "two_spheres.yaml"])
def test_lammps_jkr_loses_the_energy_of_the_branch_cut_at_the_force_controlled_pull_off(scene_name):
    """LAMMPS's jkr (γ = Δγ/2, the scene's E*; on a wall, and between two spheres of different
    sizes and speeds) loses theory.force_release_energy_loss at every speed, within
    2|W(dt) − W(dt/2)|; its most adhesive force is JKR's pull-off −(3/2)πR*Δγ, sampled at the
    steps: never beyond it, within 1e-6 at the slowest speed (whose steps lie densest around the
    minimum), 1e-2 at all. Just above LAMMPS's own sticking velocity (0.7028 v_s) it lets go
    where Thornton–Ning capture."""
    scene = load_scene(CONFIGS / scene_name)
    model = lammps_model(scene, NormalModel.jkr)
    v_s = float(
        theory.thornton_ning_sticking_velocity(
            scene.reduced_mass, scene.contact_profile.R, model.E_star, scene.effects.adhesion.work_of_adhesion
        )
    )
    approach = np.array([0.75, 2.0, 4.0]) * v_s  # the relative speeds; the counterpart adds its own
    velocities = approach - model.particles.counterpart_velocity
    dt = hertz_time(scene, model, float(velocities.max())) / STEPS_PER_CONTACT
    duration = 20 * hertz_time(scene, model, float(velocities.min()))
    runs = [run_batch(model, velocities, step, duration) for step in (dt, dt / 2)]
    R, dgamma = scene.contact_profile.R, scene.effects.adhesion.work_of_adhesion
    expected = float(theory.force_release_energy_loss(R, model.E_star, dgamma))
    lost = [0.5 * scene.reduced_mass * approach**2 * (1 - run.restitution**2) for run in runs]
    assert not runs[0].captured.any()
    assert np.all(within_step_error(expected, *lost))
    assert np.all(STEP_ERROR_FACTOR * np.abs(lost[0] - lost[1]) < 0.1 * expected)  # a bound that tells
    pull_off = -1.5 * math.pi * R * dgamma
    sampled = runs[1].min_force / pull_off  # the force at the steps: at most the minimum, near it
    assert np.all(sampled <= 1 + 1e-12) and np.all(sampled > 1 - 1e-2) and sampled[0] > 1 - 1e-6
    assert runs[0].restitution[0] > 0
    assert float(theory.thornton_ning_restitution(approach[0], scene.reduced_mass, R, model.E_star, dgamma)) == 0


@pytest.mark.slow
def test_viscoelastic_damping_is_lammps_viscoelastic_force_law():
    """A micro-sphere without adhesion, damped viscoelastically (A = 2e-10 s): with η₀ = 2E*A/m
    LAMMPS's force η₀·a·m·v_n is the scene's 2E*·a·A·ḋ, so the largest force (reached before
    either code ends the contact) agrees to the time-step error, while LAMMPS, holding the
    contact until the overlap ends, loses more energy than impact."""
    data = load_scene(CONFIGS / "hard" / "01_no_adhesion.yaml").model_dump(exclude_none=True)
    data["effects"] = {"damping": {"model": "viscoelastic", "dissipative_constant": 2e-10}}
    scene = load_scene(data)
    dt = hertz_time(scene, lammps_model(scene), 1.0) / STEPS_PER_CONTACT
    comparison = compare_lammps(scene, velocities=np.array([0.3, 1.0]), dt=dt)
    ours, theirs, half = comparison.impact.max_force, comparison.lammps.max_force, comparison.half_step.max_force
    assert np.all(within_step_error(ours, theirs, half))
    assert np.all(comparison.columns()["energy_loss_ratio"] > 1)
