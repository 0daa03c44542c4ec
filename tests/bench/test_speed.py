"""`impact bench speed` through the command line, on a tiny plan
(two spring arrays, two point counts): the CSV's rows and columns, the split into parts that add up to
the staged run, the figure, the Markdown fragment for the docs, and the refusals of bad options."""

import csv

import jax
import numpy as np
import pytest
from typer.testing import CliRunner

from impact._bench import speed
from impact._bench.speed import COLUMNS, Reduction, speed_csv
from impact._bench.workloads import CLOSED_FORM, TIGHTER, speed_plan, workloads
from impact._core.defaults import SPEED_REPEATS
from impact._run.sweep import plan_sweep
from impact._run.sweep.batch import point_function
from impact._scene.sweep import make_spec
from impact.cli import app
from impact.cli.bench import speed_command

POINTS = (32, 64)
ONLY = ("springs256", "springs64")  # in the plan's order


def invoke(*args: str):
    return CliRunner().invoke(app, ["bench", "speed", *args])


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    folder = tmp_path_factory.mktemp("speed") / "tiny"
    options = [f"--points={n}" for n in POINTS] + [f"--only={key}" for key in ONLY]
    markdown = folder.parent / "speed.md"
    result = invoke(*options, "--repeats", "3", "--chunk", "64", "-o", str(folder), "--markdown", str(markdown))
    rows = list(csv.DictReader((folder / "speed.csv").open())) if result.exit_code == 0 else []
    return folder, result, rows


@pytest.mark.slow
def test_one_row_per_workload_and_points_count(tiny):
    folder, result, rows = tiny
    assert result.exit_code == 0, result.output
    with (folder / "speed.csv").open() as file:
        assert next(csv.reader(file)) == list(COLUMNS)
    assert [(row["workload"], int(row["points"])) for row in rows] == [(k, n) for k in ONLY for n in POINTS]
    for row in rows:
        assert 0 < float(row["us_min"]) <= float(row["us_per_impact_median"]) <= float(row["us_max"]), row
        assert row["error_reference"] == CLOSED_FORM
        assert float(row["steps_mean"]) == 0 and float(row["peak_rss_mb"]) > 0  # prefix sums take no step
        assert (row["chunk"], row["device"], row["device_peak_mb"]) == ("64", "cpu", "nan"), row
    assert (folder / "speed.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "What a point costs" in result.output and "springs256" in result.output


def _cells(line: str) -> list[str]:
    return [cell.strip() for cell in line.strip().strip("|").split("|")]


@pytest.mark.slow
def test_markdown_fragment_holds_the_runs_table(tiny):
    """--markdown FILE writes the table the docs include: the command that measured it, one row
    per workload × points count in the CSV's order, each with the run's own numbers (to the
    digits shown)."""
    folder, result, rows = tiny
    assert result.exit_code == 0, result.output
    lines = (folder.parent / "speed.md").read_text().splitlines()
    assert lines[0].startswith("Measured ") and "Sweeps on cpu." in lines[0], lines[0]
    options = "--only springs256 --only springs64 --points 32 --points 64 --repeats 3 --chunk 64"
    assert f"`impact bench speed {options}`" in lines[0], lines[0]
    table = [line for line in lines if line.startswith("|")]
    assert _cells(table[0]) == [
        "workload (`--only`)", "method", "points", "µs per impact, median (min–max)", "max error (against)", "steps",
        "compile", "build / integrate / post, µs", "peak RSS",
    ]  # fmt: skip
    assert len(table) == 2 + len(rows)
    for line, row in zip(table[2:], rows, strict=True):
        name, method, points, time, error, steps, compile_time, split, rss = _cells(line)
        assert name.endswith(f"(`{row['workload']}`)") and int(points) == int(row["points"]), (line, row)
        assert method == row["method"] == "prefix sums", (line, row)
        median, low, high = (float(x) for x in time.replace("(", " ").replace(")", " ").replace("–", " ").split())
        for shown, value in ((median, "us_per_impact_median"), (low, "us_min"), (high, "us_max")):
            assert shown == pytest.approx(float(row[value]), rel=5e-3, abs=0.051), (line, row)
        assert float(error.split()[0]) == pytest.approx(float(row["max_error"]), rel=0.051, abs=0.0), (line, row)
        assert error.endswith(f"({row['error_reference']})")
        assert int(steps) == round(float(row["steps_mean"])), (line, row)
        assert float(compile_time.removesuffix(" s")) == pytest.approx(float(row["compile_s"]), abs=0.051)
        for shown, value in zip(split.split(" / "), ("build_us", "integrate_us", "post_us"), strict=True):
            assert float(shown) == pytest.approx(float(row[value]), rel=5e-3, abs=0.051), (line, row)
        assert float(rss.removesuffix(" MB")) == pytest.approx(float(row["peak_rss_mb"]), abs=0.51)


def test_the_markdown_file_is_checked_before_any_work(tmp_path):
    """A folder in the fragment's place, or a missing folder above it: exit 2 naming --markdown,
    nothing written."""
    for target, says in ((tmp_path, "is a folder"), (tmp_path / "missing" / "speed.md", "does not exist")):
        result = invoke("--only", "tn", "-o", str(tmp_path / "out"), "--markdown", str(target))
        assert result.exit_code == 2, result.output
        assert "--markdown" in result.output and says in result.output, result.output
        assert not (tmp_path / "out").exists()


def test_the_fragment_names_only_the_options_that_change_the_measurement():
    assert speed_command(False, [], ["tn"], SPEED_REPEATS, None) == "impact bench speed --only tn"
    assert speed_command(True, [10], [], 2, 8) == "impact bench speed --quick --points 10 --repeats 2 --chunk 8"


def test_spring_array_error_falls_with_n(tiny):
    """The error against Thornton–Ning is the spatial error of N springs: about N⁻²."""
    _, _, rows = tiny
    error = {row["workload"]: float(row["max_error"]) for row in rows}
    assert 0 < error["springs256"] < error["springs64"] / 4, error


def test_compile_counted_once_per_call_size(tiny):
    """The spring workloads run prefix sums, compiled for a capacity of springs (N itself traced up
    to it: `spring_capacity`, the next power of two): N = 256 and N = 64 compile each their own
    batches, one per call size, and say so."""
    _, _, rows = tiny
    compile_time = [float(row["compile_s"]) for row in rows]
    assert all(seconds > 0 for seconds in compile_time), compile_time


def test_split_parts_add_up_to_the_staged_run(tiny):
    """The split is one run of the three stages in a row, each part the time between two clock
    readings: every part is positive and they add up to the staged total (to the CSV's six
    digits). Not compared with the sweep's time: wall-time ratios on a loaded machine are noise."""
    _, _, rows = tiny
    for row in rows:
        parts = [float(row[name]) for name in ("build_us", "integrate_us", "post_us")]
        assert all(part > 0 for part in parts), row
        assert sum(parts) == pytest.approx(float(row["staged_us"]), rel=1e-5, abs=0.0), row


@pytest.mark.slow
def test_the_stages_compute_what_the_point_function_does():
    """Build, integrate and post-process run in a row give the sweep's point results, bit for
    bit (the same operations, only compiled apart); the row names the method."""
    plan = plan_sweep(make_spec(speed.named_method(workloads()[0].scene), {"initial.velocity": np.array([0.02, 0.05])}))
    choices = plan.choices[0]
    build, integrate, post = speed.stages(choices)
    staged = post(plan.physics, integrate(build(plan.physics)))
    whole = jax.jit(jax.vmap(point_function(choices)))(plan.physics)
    for name in ("restitution", "contact_time", "max_force", "status"):
        np.testing.assert_array_equal(np.asarray(staged[name]), np.asarray(whole[name]), err_msg=name)
    assert speed.method_label(plan.spec.scene) == "tsit5 rtol 1e-10"


@pytest.mark.parametrize(
    "options, named",
    [
        (["--points", "0"], "--points"),
        (["--repeats", "0"], "--repeats"),
        (["--chunk", "0"], "--chunk"),
        (["--only", "nothing"], "--only"),
    ],
)
def test_bad_options_exit_2_naming_the_option(options, named, tmp_path):
    result = invoke(*options, "-o", str(tmp_path / "out"))
    assert result.exit_code == 2, result.output
    assert named in result.output
    assert not (tmp_path / "out").exists()


def test_an_existing_folder_is_refused(tmp_path):
    result = invoke("--only", "tn", "-o", str(tmp_path))
    assert result.exit_code == 2 and "--overwrite" in result.output


def test_an_interrupted_run_leaves_no_folder(tmp_path, monkeypatch):
    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(speed, "measure", interrupted)
    result = invoke("--only", "tn", "-o", str(tmp_path / "out"))
    assert result.exit_code != 0
    assert not (tmp_path / "out").exists()


def test_plans():
    """The full plan has every workload of issue #14, the rate-independent ones once more timed by
    quadrature, the plastic ones by quadrature, and the scan over N = 64…4096; the quick one leaves
    out the heavy ones; --points replaces every count."""
    full = speed_plan()
    keys = [workload.key for workload, _ in full.runs()]
    assert keys[:24] == [
        "tn", "power1.5", "power3", "cone", "springs256", "springs2048", "md", "attach", "gravity", "gj",
        "tn_energy", "power1.5_energy", "power3_energy", "cone_energy",
        "tn_quadrature", "power1.5_quadrature", "power3_quadrature", "cone_quadrature",
        "md_quadrature", "attach_quadrature", "gravity_quadrature", "gj_quadrature",
        "plastic_quadrature", "tn_plastic_quadrature",
    ]  # fmt: skip
    assert sorted(w.springs for w, _ in full.runs() if w.springs) == [64, 128, 256, 512, 1024, 2048, 4096]
    assert all(100 in counts for _, counts in full.runs())
    quick = [workload.key for workload, _ in speed_plan(quick=True).runs()]
    assert "md" not in quick and "gravity" not in quick and "tn" in quick
    assert {counts for _, counts in speed_plan(points=(10**6,), only=("tn",)).runs()} == {(10**6,)}
    assert {w.reference for w in workloads() if w.key in ("md", "gravity", "gj")} == {TIGHTER}


def test_the_device_peak_is_the_most_any_gpu_held(monkeypatch):
    """On GPUs the row reports the most memory a device's allocator has held (MB); a device
    that keeps no count (a CPU: memory_stats() is None) leaves it nan."""

    class Device:
        def __init__(self, stats):
            self.stats = stats

        def memory_stats(self):
            return self.stats

    gpus = [Device({"peak_bytes_in_use": 3 * 2**20}), Device({"peak_bytes_in_use": 5 * 2**20})]
    monkeypatch.setattr(speed, "local_devices", lambda: gpus)
    assert speed.device_peak_mb() == 5.0
    monkeypatch.setattr(speed, "local_devices", lambda: [*gpus, Device(None)])
    assert np.isnan(speed.device_peak_mb())


def test_reduction_counts_a_failed_point_as_infinite_error():
    reduce = Reduction(3, CLOSED_FORM)
    values = {"restitution": np.array([0.5, np.nan, 0.7]), "theory_restitution": np.full(3, 0.6), "steps": np.ones(3)}
    reduce.add(np.arange(3), values)
    assert reduce.error() == np.inf and reduce.steps == 3
    clean = Reduction(2, CLOSED_FORM)
    clean.add(np.arange(2), {**{k: v[[0, 2]] for k, v in values.items()}})
    assert clean.error() == pytest.approx(0.1, rel=1e-6, abs=0.0)
    text = speed_csv([dict.fromkeys(COLUMNS, 1.0)])
    assert text.splitlines()[0] == ",".join(COLUMNS)
