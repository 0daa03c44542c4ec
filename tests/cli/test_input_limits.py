"""Hostile input and long runs (issue: reliability, round 3). A key given twice, nesting
thousands deep, aliases that expand a small file into millions of values, files of megabytes,
sweeps of 10¹⁴ points and runs of 10²² steps are each refused within seconds with exit code 2,
the limit named and nothing written; `--allow-long` (or `limits.step_budget`) accepts a long run,
and Ctrl-C stops it at once with exit code 130; runs started in the same second get folders of
their own."""

import dataclasses
import math
import signal
import subprocess
import sys
import threading
import time
from datetime import datetime
from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

from impact import simulate
from impact._scene import reading
from impact._scene.errors import SceneError
from impact._scene.reading import MAX_DEPTH, MAX_VALUES, MAX_YAML_BYTES
from impact.cli import app, folders
from impact.cli.tables import impact_table

ROOT = Path(__file__).parents[2]
CONFIGS = ROOT / "configs"
THORNTON_NING = CONFIGS / "thornton_ning.yaml"
SPRING_ARRAY = CONFIGS / "spring_array.yaml"


def invoke(*args):
    return CliRunner().invoke(app, [str(arg) for arg in args])


def refused(result, *phrases) -> None:
    """Exit code 2, each phrase in the output (whitespace folded), no traceback."""
    assert result.exit_code == 2, result.output
    said = " ".join(result.output.split())
    for phrase in phrases:
        assert phrase in said, said
    assert "Traceback" not in result.output


# --- YAML: a key twice, nesting, aliases, size -------------------------------------------------


@pytest.mark.parametrize("command", ["run", "validate"])
def test_a_key_given_twice_is_refused_with_both_lines(command, tmp_path, monkeypatch):
    """Not run at the last value (60 m/s) silently."""
    monkeypatch.chdir(tmp_path)
    lines = THORNTON_NING.read_text().splitlines()
    first = next(number for number, line in enumerate(lines) if line.startswith("  velocity: 0.6"))
    lines.insert(first + 1, "  velocity: 60.0")
    (tmp_path / "scene.yaml").write_text("\n".join(lines) + "\n")
    result = invoke(command, tmp_path / "scene.yaml")
    refused(
        result, f"key 'velocity' appears twice in one mapping (lines {first + 1} and {first + 2}); give each key once"
    )
    assert sorted(entry.name for entry in tmp_path.iterdir()) == ["scene.yaml"]


def test_a_key_given_twice_in_a_sweep_or_fit_file_or_set_is_refused(tmp_path):
    sweep = tmp_path / "sweep.yaml"
    sweep.write_text(f"scene: {THORNTON_NING}\naxes:\n  initial.velocity: [0.5]\naxes: {{}}\n")
    refused(invoke("sweep", sweep, "-o", tmp_path / "out"), "key 'axes' appears twice in one mapping (lines 2 and 4)")
    fit = CONFIGS / "fits" / "drop_test.yaml"
    twice = tmp_path / "fit.yaml"
    twice.write_text(fit.read_text().replace("model: theory", "model: theory\nmodel: simulation"))
    refused(invoke("fit", twice, "-o", tmp_path / "out"), "key 'model' appears twice in one mapping")
    refused(invoke("validate", THORNTON_NING, "--set", "initial={velocity: 1, velocity: 2}"), "twice on line 1")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize(
    ("text", "phrase"),
    [
        ("body: " + "[" * 20_000 + "]" * 20_000 + "\n", f"mappings and lists nested deeper than {MAX_DEPTH} levels"),
        (
            "".join(f"a{k}: &a{k} [{', '.join([f'*a{k - 1}' if k else '1'] * 10)}]\n" for k in range(7)),
            f"more than {MAX_VALUES} values, counting those its aliases repeat",
        ),
        (
            "".join(f"a{k}: &a{k} [{f'*a{k - 1}' if k else '1'}]\n" for k in range(40)),
            f"mappings and lists nested deeper than {MAX_DEPTH} levels through aliases",
        ),
    ],
    ids=["20000 brackets", "alias bomb", "aliases nested 40 deep"],
)
def test_a_document_too_deep_or_too_large_is_refused_within_seconds(text, phrase, tmp_path):
    """Not a RecursionError, nor a build of 10⁷ values."""
    (tmp_path / "scene.yaml").write_text(text)
    started = time.monotonic()
    refused(invoke("validate", tmp_path / "scene.yaml"), phrase)
    assert time.monotonic() - started < 10


@pytest.mark.parametrize("libyaml", [True, False], ids=["libyaml's parser", "PyYAML's"])
def test_both_loaders_read_what_yaml_reads_and_refuse_alike(libyaml, monkeypatch):
    """With libyaml's parser (where PyYAML has it) or without, the same document, and the same
    refusals."""
    if not libyaml:
        monkeypatch.setattr(reading, "_FastLoader", None)
    elif reading._FastLoader is None:
        pytest.skip("PyYAML was built without libyaml")
    text = THORNTON_NING.read_text() + "anchored: &x [1, {a: 2.5e-3}]\nrepeated: *x\nmerged: {<<: {b: 1}, b: 2}\n"
    assert reading.parse_yaml(text, "scene.yaml") == yaml.safe_load(text)
    for hostile, phrase in [
        (
            "a: 1\nb: {c: 2, c: 3}\n",
            "scene.yaml: key 'c' appears twice in one mapping (twice on line 2); give each key once",
        ),
        ("a: " + "[" * 40 + "]" * 40, f"scene.yaml: mappings and lists nested deeper than {MAX_DEPTH} levels (line 1)"),
        (
            "a: " + "[" * 5000 + "]" * 5000,
            f"scene.yaml: mappings and lists nested deeper than {MAX_DEPTH} levels (line 1)",
        ),
    ]:
        with pytest.raises(SceneError) as caught:
            reading.parse_yaml(hostile, "scene.yaml")
        assert caught.value.problems == [("", phrase)]


def test_a_file_above_the_size_limit_is_refused_unread(tmp_path):
    big = tmp_path / "scene.yaml"
    big.write_text("# padding\n" * (MAX_YAML_BYTES // 10 + 1))
    refused(invoke("validate", big), f"holds 2 MB; impact reads files of at most {MAX_YAML_BYTES / 1e6:g} MB")


# --- budgets: sweeps, steps, memory ---------------------------------------------------------

HUGE_GRID = {
    "initial.velocity": {"geomspace": [0.2, 20.0, 10**7]},
    "material.E_star": {"geomspace": [1e8, 1e10, 10**7]},
}


def _sweep_file(tmp_path: Path, scene: Path, axes: dict) -> Path:
    path = tmp_path / "sweep.yaml"
    path.write_text(yaml.safe_dump({"scene": str(scene), "axes": axes}))
    return path


@pytest.mark.parametrize(
    ("axes", "field", "phrase"),
    [
        (HUGE_GRID, "axes", "the sweep has 1e+14 points, beyond the budget of 1e+07: run with --allow-long"),
        (
            {"initial.velocity": {"geomspace": [0.2, 20.0, 10**15]}},
            "axes",
            "the sweep has 1e+15 points, beyond the budget of 1e+07",
        ),
    ],
    ids=["grid of 10⁷ × 10⁷", "geomspace of 10¹⁵"],
)
def test_a_huge_sweep_is_refused_before_its_points_are_made(axes, field, phrase, tmp_path):
    """Not a MemoryError in meshgrid."""
    started = time.monotonic()
    refused(invoke("sweep", _sweep_file(tmp_path, THORNTON_NING, axes), "-o", tmp_path / "out"), f"{field}: {phrase}")
    assert time.monotonic() - started < 30 and not (tmp_path / "out").exists()


def test_a_sweep_beyond_the_machines_memory_is_refused_even_when_allowed(tmp_path):
    result = invoke("sweep", _sweep_file(tmp_path, THORNTON_NING, HUGE_GRID), "-o", tmp_path / "out", "--allow-long")
    refused(result, "axes: the sweep's 1e+14 points would need about 6e+07 GB, more than this machine's")


def test_a_springs_axis_beyond_the_step_budget_is_refused_point_by_point(tmp_path):
    axes = {"contact.springs": [1000, 10**9]}
    refused(
        invoke("sweep", _sweep_file(tmp_path, SPRING_ARRAY, axes), "-o", tmp_path / "out"),
        "axes.contact.springs: value 1000000000 makes the scene invalid: contact.springs: the run would take about "
        "1e+09 solver steps",
    )


@pytest.mark.parametrize(
    "lifted", [["--allow-long"], ["--set", "limits.step_budget=1e10"]], ids=["--allow-long", "limits.step_budget"]
)
def test_a_long_run_is_accepted_when_asked_for(lifted):
    assert invoke("validate", SPRING_ARRAY, "--set", "contact.springs=1000000000").exit_code == 2
    result = invoke("validate", SPRING_ARRAY, "--set", "contact.springs=1000000000", *lifted)
    assert result.exit_code == 0, result.output
    assert "1000000000 springs" in result.output


def test_an_indentation_beyond_the_machines_memory_is_refused_even_when_allowed():
    """Its march on springs keeps every event: 10⁹ springs would need terabytes."""
    changes = ["--set", "contact.springs=1000000000"]
    indentation = CONFIGS / "indentation_paraboloid.yaml"
    refused(
        invoke("validate", indentation, *changes),
        "contact.springs: the run would take about 2e+09 solver steps (1000000000 springs × 1 cycle(s))",
    )
    refused(
        invoke("validate", indentation, *changes, "--allow-long"),
        "contact.springs: the march on springs would need about 3e+03 GB, more than this machine's",
    )


# --- Ctrl-C ---------------------------------------------------------------------------------


# The command line with Ctrl-C raising KeyboardInterrupt, as in a terminal (a process started in
# the background of a shell, as the tests may be, inherits SIGINT ignored).
AS_FROM_A_TERMINAL = (
    "import signal; signal.signal(signal.SIGINT, signal.default_int_handler); from impact.cli import main; main()"
)


@pytest.mark.slow
def test_ctrl_c_stops_a_long_run_at_once_and_writes_nothing(tmp_path):
    """A Verlet run of 4e8 steps (minutes), Ctrl-C after 15 s (in its compile or its loop): exit
    code 130 within seconds (the loop runs in XLA, which does not return to Python before it
    ends), no folder."""
    command = [sys.executable, "-c", AS_FROM_A_TERMINAL, "run", str(SPRING_ARRAY), "--allow-long"]
    command += ["--set", "solver.method=verlet", "--set", "solver.dt=1e-16", "-o", str(tmp_path / "out")]
    process = subprocess.Popen(command, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        time.sleep(15)
        assert process.poll() is None, process.communicate()
        process.send_signal(signal.SIGINT)
        started = time.monotonic()
        _, err = process.communicate(timeout=60)
    finally:
        process.kill()  # no process left behind by a failure
    assert process.returncode == 130, err
    assert time.monotonic() - started < 5
    assert err.strip().endswith("interrupted") and "Traceback" not in err
    assert not (tmp_path / "out").exists()


# --- default folders, show, the table ---------------------------------------------------------


class _Noon(datetime):
    @classmethod
    def now(cls, tz=None):
        return datetime(2026, 1, 1, 12, 0, 0)


def test_runs_started_in_the_same_second_get_folders_of_their_own(tmp_path, monkeypatch):
    """The default runs/<name>/<time> is made where the run is written, atomically: one taken
    (by a run that finished first) gives -2, -3, …; eight threads making one at once get eight."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(folders, "datetime", _Noon)
    (tmp_path / "runs" / "thornton_ning" / "20260101-120000").mkdir(parents=True)
    result = invoke("run", THORNTON_NING)
    assert result.exit_code == 0, result.output
    assert f"run written to {Path('runs') / 'thornton_ning' / '20260101-120000-2'}" in result.output
    made: list[Path] = []
    threads = [threading.Thread(target=lambda: made.append(folders.fresh_folder(tmp_path / "many"))) for _ in range(8)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert sorted(path.name for path in made) == ["20260101-120000"] + [f"20260101-120000-{k}" for k in range(2, 9)]


def test_show_takes_a_run_folder(tmp_path):
    result = invoke("run", THORNTON_NING, "-o", tmp_path / "tn")
    assert result.exit_code == 0, result.output
    shown = invoke("show", tmp_path / "tn")
    assert shown.exit_code == 0 and "0.86294488" in shown.output, shown.output
    refused(invoke("show", tmp_path), f"{tmp_path} is a folder without a run.h5")


def _rows(table) -> dict[str, str]:
    names, values = ([str(cell) for cell in column._cells] for column in table.columns[:2])
    return dict(zip(names, values, strict=True))


def test_the_table_says_why_a_run_has_no_restitution_and_of_which_contact_it_is():
    """A run cut by limits.duration has neither e nor a contact time (not "nan" and "∞ (never
    let go)"); a body captured after bounces shows e of its first contact, said to be so."""
    result = simulate(THORNTON_NING)
    cut = dataclasses.replace(result, status="time_limit", restitution=math.nan, contact_time=math.inf)
    rows = _rows(impact_table(cut, None))
    assert rows["restitution e"] == "— (no physical outcome: time_limit)"
    assert rows["contact time"] == "— (ended in contact: time_limit)"
    captured = dataclasses.replace(result, status="captured", stuck=True, bounces=5)
    rows = _rows(impact_table(captured, None))
    assert rows["restitution e"] == f"{result.restitution:.8g} (of the first of 5 contacts)"
    assert rows["stuck"] == "yes"
