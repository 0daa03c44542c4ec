"""`impact bench --quick` through the `impact` typer app: its outputs, errors that fall as the
tolerance tightens, the spring array's order in N, the baseline, and the Markdown fragment for
the docs."""

import subprocess
import sys

import h5py
import numpy as np
import pytest
from typer.testing import CliRunner

from impact._bench.comparison import cheapest
from impact._bench.plans import OUTPUTS
from impact._bench.springs import fitted_order
from impact.cli import app

pytestmark = pytest.mark.slow  # a benchmark run of its own


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    folder = tmp_path_factory.mktemp("bench") / "quick"
    markdown = folder.parent / "work-precision.md"
    result = CliRunner().invoke(app, ["bench", "--quick", "-o", str(folder), "--markdown", str(markdown)])
    return folder, result


@pytest.mark.slow
def test_quick_bench_writes_its_outputs(quick):
    folder, result = quick
    assert result.exit_code == 0, result.output
    for name in OUTPUTS:
        assert (folder / name).is_file() and (folder / name).stat().st_size > 0, name
    assert (folder / "work_precision.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    table = (folder / "table.md").read_text()
    for heading in ("What a digit costs", "Continuum law", "exact event-driven", "velocity Verlet", "scipy"):
        assert heading in table, heading
    assert "benchmark written to" in result.output


@pytest.mark.slow
def test_markdown_fragment_holds_the_runs_tables(quick):
    """--markdown FILE writes the two tables the docs include, from the run's own numbers: the
    cheapest setting of each target error (its targets in order), then one row per solver × rtol
    with the error, the steps and the times of bench.h5 (to the digits shown)."""
    folder, result = quick
    assert result.exit_code == 0, result.output
    text = (folder.parent / "work-precision.md").read_text()
    assert text.startswith("Measured ") and "by `impact bench --quick` on " in text.splitlines()[0]
    rows = [[cell.strip() for cell in line.strip("|").split("|")] for line in text.splitlines() if line[:1] == "|"]
    cheapest_rows = [row for row in rows if row[0].startswith("1e-")]
    continuum_rows = [row for row in rows if row[0] == "tsit5"]
    with h5py.File(folder / "bench.h5") as file:
        targets = file["equal_error/targets"][()]
        rtols = file["continuum/rtol"][()]
        errors = file["continuum/tsit5/error_max"][()]
        single = file["continuum/tsit5/time_single_mean"][()]
        accepted = file["continuum/tsit5/accepted"][()]
    assert [float(row[0]) for row in cheapest_rows] == pytest.approx(list(targets), rel=1e-6, abs=0.0)
    assert len(continuum_rows) == len(rtols)
    for row, rtol, error, times, steps in zip(continuum_rows, rtols, errors, single, accepted, strict=True):
        assert float(row[1]) == pytest.approx(rtol, rel=0.051, abs=0.0)
        assert float(row[2]) == pytest.approx(error, rel=0.051, abs=0.0), row
        assert int(row[3].split(" / ")[0]) == round(float(np.mean(steps))), row
        value, unit = row[4].split()
        assert float(value) * {"µs": 1e-6, "ms": 1e-3, "s": 1.0}[unit] == pytest.approx(times, rel=5e-3, abs=0.0)


def test_error_falls_as_the_tolerance_tightens(quick):
    """Each tighter rtol gives a smaller max error, up to noise near the round-off floor; over
    the sweep the error falls by at least six decades."""
    folder, _ = quick
    with h5py.File(folder / "bench.h5") as file:
        rtols = file["continuum/rtol"][()]
        assert np.all(np.diff(rtols) < 0)
        for solver in file["continuum"]:
            if not isinstance(file["continuum"][solver], h5py.Group):
                continue
            errors = file[f"continuum/{solver}/error_max"][()]
            assert np.all(np.isfinite(errors)), (solver, errors)
            assert np.all(errors[1:] <= np.maximum(1.5 * errors[:-1], 1e-12)), (solver, errors)
            assert errors[-1] <= 1e-6 * errors[0], (solver, errors)
            assert np.all(file[f"continuum/{solver}/time_single"][()] > 0)
            assert np.all(file[f"continuum/{solver}/time_batch"][()] > 0)


def test_spring_array_order_in_n(quick):
    folder, _ = quick
    with h5py.File(folder / "bench.h5") as file:
        order = float(file["springs/exact/order"][()])
        errors = np.abs(file["springs/exact/error"][()])
        assert order >= 1.8, order
        assert errors[-1] < 1e-3 * errors[0]
        for name in file["springs/verlet"]:
            row = file[f"springs/verlet/{name}"]
            total = row["total_error"][()]
            assert np.allclose(total, row["time_error"][()] + row["spatial_error"][()], rtol=0, atol=1e-14)


def test_spring_cost_is_reported_for_ten_and_a_million_springs(quick):
    """Time per spring event and the compiled program's buffers at N = 10 and 10⁶: the same
    buffers (nothing of size N is kept)."""
    folder, result = quick
    with h5py.File(folder / "bench.h5") as file:
        cost = file["springs/cost"]
        assert list(cost["N"][()]) == [10, 1_000_000]
        assert np.all(cost["time_per_event"][()] > 0)
        memory = cost["memory"][()]
        assert memory[0] == memory[1] > 0
    assert "µs per spring event" in result.output


def test_baseline_is_measured_beside(quick):
    """The scipy baseline ran on the same cases, and its error falls with its tolerance."""
    folder, _ = quick
    with h5py.File(folder / "bench.h5") as file:
        cases = file["continuum/cases"].shape[0]
        for method in ("RK45", "DOP853"):
            errors = file[f"scipy/{method}/error"][()]
            assert errors.shape[1] == cases
            assert file[f"scipy/{method}/error_max"][-1] < 1e-3 * file[f"scipy/{method}/error_max"][0]
        assert np.any(np.isfinite(file["equal_error/scipy_solve_ivp"][()]))


def test_bench_refuses_an_existing_folder(tmp_path):
    folder = tmp_path / "taken"
    folder.mkdir()
    result = CliRunner().invoke(app, ["bench", "--quick", "-o", str(folder)])
    assert result.exit_code == 2
    assert "--overwrite" in result.output
    assert list(folder.iterdir()) == []


def test_bench_has_one_line_help():
    result = CliRunner().invoke(app, ["--help"])
    assert result.exit_code == 0 and "bench" in result.output and "accuracy costs" in result.output


def test_importing_the_bench_leaves_float32_alone():
    """Only the entry point enables float64; importing the command or the benchmark does not."""
    code = "import jax, impact._bench.work_precision, impact.cli.bench; assert not jax.config.jax_enable_x64"
    subprocess.run([sys.executable, "-c", code], check=True)


def test_equal_error_picks_the_cheapest_reliable_setting():
    """A setting counts when it and every tighter one of its method reach the error."""
    errors = np.array([1e-3, 1e-6, 1e-9, 1e-12])
    times = np.array([1.0, 2.0, 5.0, 9.0])
    assert cheapest([(errors, times)], 1e-5) == 2.0
    assert cheapest([(errors, times)], 1e-2) == 1.0
    assert np.isnan(cheapest([(errors, times)], 1e-13))
    lucky = np.array([1e-3, 1e-9, 1e-6, 1e-7])  # the second point is a lucky zigzag
    assert np.isnan(cheapest([(lucky, times)], 1e-8))
    assert cheapest([(lucky, times)], 1e-5) == 2.0
    failed = np.array([1e-3, np.nan, 1e-9, 1e-10])  # a failed run is no setting to rely on
    assert cheapest([(failed, times)], 1e-4) == 5.0
    assert cheapest([(failed, times), (errors, 2 * times)], 1e-4) == 4.0
    assert fitted_order([10, 100, 1000], [1e-2, 1e-4, 1e-6]) == pytest.approx(2.0, rel=1e-6, abs=0.0)
