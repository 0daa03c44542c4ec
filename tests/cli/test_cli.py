"""The command line: one end-to-end run in a subprocess, then runs, overrides, stored runs and
refusals of bad input through typer's runner (exit code 2, dotted path, no traceback, no files)."""

import copy
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import h5py
import pytest
import yaml
from typer.testing import CliRunner

from impact import theory
from impact._io.run import read_run
from impact._scene.scene import load_scene, scene_yaml
from impact.cli import app

CONFIGS = Path(__file__).parents[2] / "configs"
THORNTON_NING = CONFIGS / "thornton_ning.yaml"
OUTPUTS = {"run.h5", "config.yaml", "time.png", "force_indentation.png"}
DELETE = object()


def invoke(*args):
    return CliRunner().invoke(app, [str(arg) for arg in args])


@pytest.fixture(scope="module")
def end_to_end(tmp_path_factory):
    """`impact run configs/thornton_ning.yaml -o DIR` through the console entry point."""
    folder = tmp_path_factory.mktemp("end_to_end") / "tn"
    command = shutil.which("impact")
    prefix = [command] if command else [sys.executable, "-c", "from impact.cli import main; main()"]
    process = subprocess.run([*prefix, "run", str(THORNTON_NING), "-o", str(folder)], capture_output=True, text=True)
    return folder, process


def test_help_lists_every_command():
    result = invoke("--help")
    assert result.exit_code == 0
    for command in ("run", "validate", "show"):
        assert command in result.output


def test_end_to_end_run_writes_the_run_its_config_and_plots(end_to_end):
    folder, process = end_to_end
    assert process.returncode == 0, process.stderr
    assert "Traceback" not in process.stderr
    for phrase in ("restitution e", "0.862944", "separated", "contact time", "wall time", f"run written to {folder}"):
        assert phrase in process.stdout
    assert {entry.name for entry in folder.iterdir()} == OUTPUTS
    for plot in ("time.png", "force_indentation.png"):
        assert (folder / plot).read_bytes().startswith(b"\x89PNG")
    scene = load_scene(THORNTON_NING)
    assert (folder / "config.yaml").read_text() == scene_yaml(scene)
    result = read_run(folder / "run.h5")
    assert result.scene == scene
    expected = theory.thornton_ning_restitution(0.6, scene.body.resolved_mass, 1e-6, 1e9, 0.05)
    assert math.isclose(result.restitution, float(expected), abs_tol=1e-6)
    with h5py.File(folder / "run.h5", "r") as file:
        assert bool(file["parameters/config.yaml"].attrs["x64"])  # main() enabled float64


def test_show_prints_the_stored_summary(end_to_end):
    folder, _ = end_to_end
    result = invoke("show", folder / "run.h5")
    assert result.exit_code == 0, result.output
    for phrase in ("thornton_ning", "restitution e", "0.862944", "separated", "written by impact"):
        assert phrase in result.output


def test_run_defaults_to_a_time_stamped_folder_and_applies_overrides(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    overrides = ["--set", "initial.velocity=0.8", "--set", "effects.adhesion.work_of_adhesion=4e-2"]
    result = invoke("run", THORNTON_NING, *overrides)
    assert result.exit_code == 0, result.output
    (folder,) = (tmp_path / "runs" / "thornton_ning").iterdir()
    assert {entry.name for entry in folder.iterdir()} == OUTPUTS
    config = yaml.safe_load((folder / "config.yaml").read_text())
    assert config["initial"]["velocity"] == 0.8
    assert config["effects"]["adhesion"]["work_of_adhesion"] == 0.04  # "4e-2" is a YAML string, coerced
    assert str(Path("runs") / "thornton_ning" / folder.name) in result.output


def test_existing_folder_is_refused_unless_overwrite(tmp_path):
    folder = tmp_path / "out"
    folder.mkdir()
    (folder / "notes.txt").write_text("keep")
    refused = invoke("run", THORNTON_NING, "-o", folder)
    assert refused.exit_code == 2
    assert "--output" in refused.output and "exists" in refused.output and "--overwrite" in refused.output
    assert {entry.name for entry in folder.iterdir()} == {"notes.txt"}
    accepted = invoke("run", THORNTON_NING, "-o", folder, "--overwrite")
    assert accepted.exit_code == 0, accepted.output
    assert {entry.name for entry in folder.iterdir()} == OUTPUTS | {"notes.txt"}


def test_unsuccessful_run_is_written_and_exits_1(tmp_path):
    # touch would come at 1.67 µs, after the time limit
    overrides = ["--set", "initial.gap=1e-6", "--set", "limits.duration=1e-7"]
    result = invoke("run", THORNTON_NING, "-o", tmp_path / "out", *overrides)
    assert result.exit_code == 1
    assert "time_limit" in result.output
    assert read_run(tmp_path / "out" / "run.h5").status == "time_limit"


def test_energy_drift_is_written_and_explained(tmp_path):
    """hard/08 with the located ends at rtol 1e-6: the solver's speed drifts from the energy
    balance; the run is written with that status, and the warning says what to do."""
    overrides = ["--set", "solver.phase_ends=integrated", "--set", "solver.rtol=1e-6", "--set", "solver.atol=1e-8"]
    result = invoke("run", CONFIGS / "hard" / "08_power_law_n06.yaml", "-o", tmp_path / "out", *overrides)
    assert result.exit_code == 1
    assert "warning: the run ended with status 'energy_drift'" in result.output
    assert "tighten solver.rtol/atol, or use solver.phase_ends: energy" in result.output
    assert read_run(tmp_path / "out" / "run.h5").status == "energy_drift"


def test_validate_prints_the_resolved_key_facts():
    result = invoke(
        "validate",
        CONFIGS / "gravity_bounces.yaml",
        "--set",
        "contact.springs=500",
        "--set",
        "body.profile.R=2e-3",
    )
    assert result.exit_code == 0, result.output
    for phrase in (
        "OK",
        "paraboloid",
        "R = 0.002",
        "8.37758e-05 kg",
        "density 2500",
        "1e+10 Pa",
        "Δγ = 0.1 J/m²",
        "gravity (g = 9.81",
        "500 springs",
    ):
        assert phrase in result.output


# --- refusals -------------------------------------------------------------------------------

TABULATED = {"shape": "tabulated", "r": [0.0, 1e-6, 2e-6], "f": [0.0, 1e-9, 4e-9]}

# (case, changes to configs/thornton_ning.yaml by dotted path, dotted path named, phrase)
BAD_SCENES = [
    ("unknown top-level key", {"colour": "red"}, "colour", "unknown key"),
    ("unknown nested key", {"initial.speed": 0.6}, "initial.speed", "unknown key"),
    ("unknown shape", {"body.profile.shape": "banana"}, "body.profile.shape", "unknown shape 'banana'"),
    ("missing shape parameter", {"body.profile.R": DELETE}, "body.profile.R", "missing"),
    ("string for a number", {"material.E_star": "stiff"}, "material.E_star", "expected a number"),
    ("not a number", {"initial.velocity": float("nan")}, "initial.velocity", "expected a finite number, got nan"),
    ("infinite", {"material.E_star": float("inf")}, "material.E_star", "expected a finite number, got inf"),
    ("zero mass", {"body.mass": 0}, "body.mass", "0 kg is outside the allowed range [1e-30, 1e6] kg"),
    ("negative mass", {"body.mass": -1e-14}, "body.mass", "-1e-14 kg is outside the allowed range"),
    (
        "negative density",
        {"body.mass": DELETE, "body.density": -2500},
        "body.density",
        "-2500 kg/m³ is outside the allowed range [0.001, 1e5] kg/m³",
    ),
    ("zero R", {"body.profile.R": 0}, "body.profile.R", "0 m is outside the allowed range [1e-12, 1000] m"),
    ("negative E_star", {"material.E_star": -1e9}, "material.E_star", "-1e+09 Pa is outside the allowed range"),
    (
        "negative velocity",
        {"initial.velocity": -0.6},
        "initial.velocity",
        "-0.6 m/s is outside the allowed range 0 or [1e-20, 1e4] m/s",
    ),
    ("zero velocity, no gravity", {"initial.velocity": 0}, "initial.velocity", "must be > 0"),
    ("nu = 0.5", {"material": {"E": 1e9, "nu": 0.5}}, "material.nu", "0.5 is outside the allowed range (-1, 0.5)"),
    ("nu = -1", {"material": {"E": 1e9, "nu": -1}}, "material.nu", "-1 is outside the allowed range (-1, 0.5)"),
    (
        "approach above work of adhesion",
        {"effects.adhesion.approach_work_of_adhesion": 0.1},
        "effects.adhesion.approach_work_of_adhesion",
        "0.1 J/m² is above work_of_adhesion (0.05 J/m²): 0 ≤ Δγa ≤ Δγ "
        "(attaching cannot gain more energy than detaching costs)",
    ),
    (
        "negative work of adhesion",
        {"effects.adhesion.work_of_adhesion": -0.05},
        "effects.adhesion.work_of_adhesion",
        "-0.05 J/m² is outside the allowed range [0, 1e4] J/m²",
    ),
    (
        "power law n = 0",
        {"body.profile": {"shape": "power_law", "n": 0, "c": 300.0}},
        "body.profile.n",
        "0 is outside the allowed range [0.001, 100]",
    ),
    ("cone theta = 0", {"body.profile": {"shape": "cone", "theta": 0}}, "body.profile.theta", "[1e-6, 1.5698] rad"),
    (
        "cone theta = pi/2",
        {"body.profile": {"shape": "cone", "theta": 1.5708}},
        "body.profile.theta",
        "1.5708 rad is outside the allowed range [1e-6, 1.5698] rad",
    ),
    (
        "tabulated r not increasing",
        {"body.profile": {**TABULATED, "r": [0.0, 2e-6, 1e-6]}},
        "body.profile.r",
        "strictly increasing",
    ),
    (
        "tabulated f not from 0",
        {"body.profile": {**TABULATED, "f": [1e-9, 2e-9, 4e-9]}},
        "body.profile.f",
        "start at 0",
    ),
    ("mass and density", {"body.density": 2500}, "body", "exactly one of mass"),
    ("springs < 1", {"contact.springs": 0}, "contact.springs", "0 is outside the allowed range [1, 1e9]"),
    ("rtol = 0", {"solver.rtol": 0}, "solver.rtol", "0 is outside the allowed range [1e-16, 0.5]"),
]


def changed(data: dict, changes: dict) -> dict:
    data = copy.deepcopy(data)
    for path, value in changes.items():
        *parents, key = path.split(".")
        node = data
        for parent in parents:
            node = node[parent]
        if value is DELETE:
            del node[key]
        else:
            node[key] = value
    return data


def assert_refused(result, folder: Path, files: set, *phrases):
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output
    for phrase in phrases:
        assert phrase in result.output
    assert {entry.name for entry in folder.iterdir()} == files  # no run folder, no partial file


@pytest.mark.parametrize("command", ["run", "validate"])
@pytest.mark.parametrize("case, changes, path, phrase", BAD_SCENES, ids=[case[0] for case in BAD_SCENES])
def test_bad_scene_is_refused(command, case, changes, path, phrase, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    scene_file = tmp_path / "scene.yaml"
    scene_file.write_text(yaml.safe_dump(changed(yaml.safe_load(THORNTON_NING.read_text()), changes)))
    assert_refused(invoke(command, scene_file), tmp_path, {"scene.yaml"}, path, phrase)


@pytest.mark.parametrize(
    "case, text, phrase",
    [
        ("missing file", None, "no such file"),
        ("invalid YAML", "body: [unclosed\n", "invalid YAML"),
        ("not a mapping", "- 1\n- 2\n", "must hold a mapping"),
    ],
)
def test_unreadable_scene_file_is_refused(case, text, phrase, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    if text is not None:
        (tmp_path / "scene.yaml").write_text(text)
    files = set() if text is None else {"scene.yaml"}
    assert_refused(invoke("run", tmp_path / "scene.yaml"), tmp_path, files, "scene.yaml", phrase)


@pytest.mark.parametrize("kind", ["binary", "directory", "fifo"])
def test_scene_that_is_no_text_file_is_refused(kind, tmp_path, monkeypatch):
    """Binary junk, a directory or a FIFO as the scene: exit 2 with the reason, nothing read
    from the FIFO (it would block), nothing written."""
    monkeypatch.chdir(tmp_path)
    target = tmp_path / "scene.yaml"
    if kind == "binary":
        target.write_bytes(b"\x89PNG\r\n\x1a\n\x00\xff")
    elif kind == "directory":
        target.mkdir()
    else:
        os.mkfifo(target)
    phrase = {
        "binary": "is not UTF-8 text (byte 0x89 at 0)",
        "directory": "is a directory, not a file",
        "fifo": "is not a regular file",
    }[kind]
    for command in ("run", "validate"):
        assert_refused(invoke(command, target), tmp_path, {"scene.yaml"}, phrase)


@pytest.mark.parametrize(
    "assignment, phrases",
    [
        (
            "initial.speed=0.8",
            ["--set", "no field 'initial.speed' in the scene", "initial takes: angle, gap, spin, velocity"],
        ),
        ("initial.velocity.x=1", ["--set", "no field 'initial.velocity.x'", "is a value"]),
        ("body.profile.theta=0.1", ["--set", "no field 'body.profile.theta'"]),  # a paraboloid has no theta
        ("initial.velocity=fast", ["initial.velocity", "expected a number", "'fast'"]),
        ("initial.velocity", ["--set", "expected dotted.path=value"]),
        ("name=[unclosed", ["--set name", "not valid YAML"]),
    ],
)
def test_bad_override_is_refused(assignment, phrases, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert_refused(invoke("run", THORNTON_NING, "--set", assignment), tmp_path, set(), *phrases)


def test_show_refuses_what_is_not_a_run(tmp_path):
    (tmp_path / "notes.h5").write_text("not HDF5")
    assert_refused(invoke("show", tmp_path / "absent.h5"), tmp_path, {"notes.h5"}, "no such file")
    assert_refused(invoke("show", tmp_path / "notes.h5"), tmp_path, {"notes.h5"}, "not an HDF5 file")


# A fresh interpreter that imports matplotlib ahead in a thread (as `impact run`, `sweep` and
# `fit` do before they compute), with matplotlib importable or not, and says what it imported.
AHEAD = """
import sys
if sys.argv[1] == "broken":
    sys.modules["matplotlib"] = None  # importing it raises ImportError
from impact._plots.figures import import_ahead
import_ahead().join()
print("matplotlib.figure" in sys.modules, "matplotlib.backends.backend_agg" in sys.modules)
"""


@pytest.mark.parametrize(("matplotlib", "imported"), [("present", ["True", "True"]), ("broken", ["False", "False"])])
def test_matplotlib_is_imported_ahead_by_a_thread_that_prints_nothing(matplotlib, imported):
    """The figure's modules are imported ahead; a failed import is left to the figure (which
    raises it) and prints nothing from the thread."""
    command = [sys.executable, "-c", AHEAD, matplotlib]
    process = subprocess.run(command, capture_output=True, text=True, cwd=CONFIGS.parent)
    assert process.returncode == 0 and process.stderr == ""
    assert process.stdout.split() == imported
