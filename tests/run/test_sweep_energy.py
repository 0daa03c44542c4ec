"""Every named loss of a sweep (issue #17, item 5): per point, the kinetic energy the first
contact took, ½m(v₀² − v₁²), is the sum of the losses the scene's effects name, to the solver
tolerance; sweep.h5 holds those columns and no others, with units, and a resumed file is the
uninterrupted one bitwise.

Two small subsamples of the example sweeps, one compiled batch each."""

from pathlib import Path

import h5py
import jax
import numpy as np
import pytest
from rich.console import Console

from impact import theory
from impact._io.sweep import read_sweep
from impact._io.sweep_journal import SweepWriter, journal_folder, npz_bytes
from impact._plots.sweep_losses import losses_figure
from impact._run.sweep import plan_sweep, result_names, run_spec
from impact._scene.paths import with_values
from impact._scene.sweep import load_sweep, make_spec
from impact.cli.tables import sweep_table
from tests.scenes import SWEEPS

LOSSES = ("plastic_work", "viscous_work", "adhesion_hysteresis", "unrecovered_elastic_energy")
# Imbalance over the energy turned over, ½mv₀² + Σ|named losses| (a captured Wall particle's plastic
# work and adhesive energy are 30 times its ½mv₀²): measured ≤ 7.4e-11 on the whole damped example,
# 1.9e-10 on the whole plastic one (rtol 1e-10).
BALANCE = 1e-9


def subsampled(name: str, every: int):
    """The example sweep with every `every`-th velocity of its axis (the other axes whole)."""
    spec = load_sweep(SWEEPS / f"{name}.yaml")
    axes = {
        axis.path: (axis.values[::every] if axis.path == "initial.velocity" else axis.values).tolist()
        for axis in spec.axes
    }
    return make_spec(spec.scene, axes, spec.mode, spec.order)


@pytest.fixture(scope="module")
def damped():
    """The viscoelastic rubber ball: 6 velocities from 1 mm/s to 10 m/s × 2 constants A."""
    spec = subsampled("rubber_ball_restitution", 8)
    return spec, run_spec(spec, chunk=spec.size)


@pytest.fixture(scope="module")
def plastic():
    """The Wall et al. particle, with and without yield: 7 velocities from 0.3 to 100 m/s × 2 p_y."""
    spec = subsampled("wall_particle", 33)
    return spec, run_spec(spec, chunk=spec.size)


def energies(result):
    """(energy turned over, ½m(v₀² − v₁²), the sum of the named losses) per point, flat."""
    mass = with_values(result.scene, {path: values.reshape(-1) for path, values in result.params.items()}).reduced_mass
    touch, separation = result.touch_velocity.reshape(-1), result.separation_velocity.reshape(-1)
    named = np.array([getattr(result, name).reshape(-1) for name in LOSSES if getattr(result, name) is not None])
    impact_energy = 0.5 * mass * touch**2
    return impact_energy + np.sum(np.abs(named), axis=0), 0.5 * mass * (touch**2 - separation**2), np.sum(named, axis=0)


@pytest.mark.slow
def test_a_damped_sweep_splits_the_lost_energy_into_viscous_work_and_unrecovered_energy(damped):
    _, result = damped
    assert [name for name in LOSSES if name in result.results] == ["viscous_work", "unrecovered_elastic_energy"]
    assert np.all(result.status_names() == "separated")
    turnover, lost, named = energies(result)
    imbalance = np.max(np.abs(lost - named) / turnover)
    assert imbalance < BALANCE and result.energy_imbalance() == pytest.approx(imbalance, rel=1e-12, abs=0.0)
    # the damper takes most of it; the surface keeps a little, elastic, as the body lets go
    viscous, unrecovered = result.viscous_work.reshape(-1), result.unrecovered_elastic_energy.reshape(-1)
    assert np.all(unrecovered > 0) and np.all(viscous > 0.9 * lost)


@pytest.mark.slow
def test_a_plastic_sweep_splits_the_lost_energy_into_plastic_work_and_adhesion_hysteresis(plastic):
    spec, result = plastic
    assert [name for name in LOSSES if name in result.results] == ["plastic_work", "adhesion_hysteresis"]
    names = result.status_names().reshape(-1)
    assert set(names) == {"separated", "captured"}
    turnover, lost, named = energies(result)
    success = np.isin(names, ("separated", "captured"))  # captured: v₁ = 0, all of ½mv₀² held or lost
    imbalance = np.max(np.abs(lost - named)[success] / turnover[success])
    assert imbalance < BALANCE and result.energy_imbalance() == pytest.approx(imbalance, rel=1e-12, abs=0.0)
    # separated points: the split is Thornton & Ning's in closed form at the deepest indentation
    separated = names == "separated"
    scene = spec.scene
    yield_pressure = result.params["effects.plasticity.yield_pressure"].reshape(-1)[separated]
    hysteresis, plastic_work = jax.vmap(theory.adhesive_plastic_losses, in_axes=(0, None, None, None, 0))(
        result.max_indentation.reshape(-1)[separated],
        scene.body.profile.R,
        scene.material.effective_modulus,
        scene.effects.adhesion.work_of_adhesion,
        yield_pressure,
    )
    energy = turnover[separated]
    np.testing.assert_allclose(result.plastic_work.reshape(-1)[separated], plastic_work, rtol=1e-12, atol=0)
    assert np.max(np.abs(result.adhesion_hysteresis.reshape(-1)[separated] - hysteresis) / energy) < BALANCE
    assert np.all(result.plastic_work.reshape(-1)[separated][yield_pressure > 1e12] == 0.0)  # never yields
    assert np.all(result.plastic_work.reshape(-1)[separated][yield_pressure < 1e12] > 0.0)


def file_columns(path: Path) -> dict:
    """Every dataset along the rows of a sweep file: name → (values, attributes)."""
    with h5py.File(path, "r") as file:
        group = file["sweep"]
        datasets = {"index": group["index"], **group["params"], **group["results"]}
        return {name: (dataset[()], dict(dataset.attrs)) for name, dataset in datasets.items()}


@pytest.mark.slow
def test_the_sweep_file_holds_the_named_losses_and_a_resumed_one_is_the_same(damped, tmp_path):
    spec, result = damped
    plan = plan_sweep(spec)
    names = result_names(spec.scene)
    rows = {name: result.results[name].reshape(-1)[plan.order] for name in names}
    chunks = np.array_split(np.arange(spec.size), 3)

    def write(path: Path, kill: bool) -> None:
        writer = SweepWriter.start(path, spec, plan, expected=spec.size, chunk=4)
        for k, chunk in enumerate(chunks):
            if kill and k == 2:  # the journal got the last chunk, the file did not
                journal = journal_folder(path) / f"{writer.rows:012d}.npz"
                journal.write_bytes(npz_bytes(plan.order[chunk], {name: rows[name][chunk] for name in names}))
                writer = SweepWriter.resume(path, spec, plan, expected=spec.size, chunk=4)
                break
            writer.append(plan.order[chunk], {name: rows[name][chunk] for name in names})
        writer.finish()

    write(tmp_path / "whole.h5", kill=False)
    write(tmp_path / "resumed.h5", kill=True)
    whole, resumed = file_columns(tmp_path / "whole.h5"), file_columns(tmp_path / "resumed.h5")
    assert whole.keys() == resumed.keys()
    for name, (values, attributes) in whole.items():
        assert np.array_equal(values, resumed[name][0], equal_nan=True) and attributes == resumed[name][1], name
    assert whole["viscous_work"][1]["unit"] == whole["unrecovered_elastic_energy"][1]["unit"] == "J"
    assert "plastic_work" not in whole and "adhesion_hysteresis" not in whole and "body_velocity_after" not in whole
    stored = read_sweep(tmp_path / "resumed.h5")
    for name in names:
        assert np.array_equal(stored.results[name], result.results[name], equal_nan=True), name
    assert stored.plastic_work is None


def test_the_summary_and_the_losses_figure_show_the_named_losses_only(damped):
    _, result = damped
    table = Console(width=200, record=True)
    table.print(sweep_table(result, {}))
    text = table.export_text()
    assert "viscous work" in text and "unrecovered elastic energy" in text and "energy balance" in text
    assert "plastic work" not in text and "adhesion hysteresis" not in text and "lab" not in text
    axes = losses_figure(result).axes[0]
    lines = [line.get_gid() for line in axes.get_lines()]
    assert lines == ["viscous_work", "unrecovered_elastic_energy"] * 2  # two values of A
    share = axes.get_lines()[0].get_ydata()
    assert np.all((share > 0) & (share < 1)) and np.all(np.diff(share) > 0)  # grows with the speed
