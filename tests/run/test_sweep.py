"""Sweeps (issue: restitution sweeps and vmap parameter studies): equal to `simulate` point by
point, shapes, no recompilation, 2 devices, kill-and-resume, multi-process shards, the figure,
refusals of an existing output (bad sweep files: tests/scene/test_sweep_files.py).

Compilation dominates the cost here, so the in-process sweeps share one compiled batch of
CHUNK points of the Thornton–Ning scene; the subprocesses share a persistent compilation cache.
"""

import math
import os
import signal
import socket
import subprocess
import sys
import threading
import time
import types
from pathlib import Path

import h5py
import jax
import numpy as np
import pytest
import yaml

from impact import simulate, theory
from impact._core.defaults import ACCELERATOR_CHUNK, DEFAULT_CHUNK
from impact._io.sweep import create_sweep_file, read_sweep
from impact._io.sweep_journal import SweepWriter, journal_folder, journal_rows, npz_bytes
from impact._plots.sweep import restitution_figure
from impact._run.sweep import empty_results, plan_sweep, result_names, sticking_estimates, sweep
from impact._run.sweep.closed_forms import sticking_velocity
from impact._run.sweep.execute import chunks_of, default_chunk
from impact._scene import sweep_method
from impact._scene.paths import with_values
from impact._scene.scene import load_scene
from impact._scene.sweep import make_spec
from tests.command import invoke
from tests.scenes import CONFIGS, THORNTON_NING

CHUNK = 8
VELOCITIES = [0.25, 0.45, 0.9, 4.0]  # v_s = 0.303 m/s at Δγ = 0.05: captured, then separated
WORKS = [0.03, 0.05]
GRID = {"initial.velocity": VELOCITIES, "effects.adhesion.work_of_adhesion": WORKS}
EXACT = (
    "restitution",
    "stuck",
    "status",
    "contact_time",
    "bounces",
    "touch_velocity",
    "separation_velocity",
    "steps",
    "accepted_steps",
    "rejected_steps",
    "theory_restitution",
)
# Partitioned over devices, XLA orders a few sums differently: the force extremes move by an ulp
# and the loop work ∮F dd (a small difference of large works) by a few 1e-12.
CLOSE = ("max_force", "min_force", "max_indentation", "dissipated_energy")
PRELUDE = "from impact.cli import main; main()"


@pytest.fixture(scope="module")
def cache_env(tmp_path_factory):
    """Environment of the subprocesses: a shared persistent compilation cache."""
    env = dict(os.environ)
    env.update(IMPACT_CACHE_DIR=str(tmp_path_factory.mktemp("jax_cache")))
    env.pop("JAX_NUM_CPU_DEVICES", None)
    return env


def sweep_cli(*args) -> list[str]:
    return [sys.executable, "-c", PRELUDE, *map(str, args)]


@pytest.fixture(scope="module")
def grid(jobs):
    """The shared 4 × 2 sweep; asking for it starts the subprocesses first, to overlap them."""
    return sweep(THORNTON_NING, GRID, chunk=CHUNK)


def point_scene(base, values: dict):
    return with_values(load_scene(base), values)


def assert_same(a, b, names=EXACT, rtol=0.0):
    for name in names:
        x, y = np.asarray(a[name]), np.asarray(b[name])
        if rtol == 0.0:
            assert np.array_equal(x, y, equal_nan=True), name
        else:
            np.testing.assert_allclose(x, y, rtol=rtol, atol=0.0, equal_nan=True, err_msg=name)


# --- the API --------------------------------------------------------------------------------


@pytest.mark.slow
def test_sweep_equals_simulate_point_by_point(grid):
    assert grid.shape == (4, 2) and grid.stats["points"] == 8
    for i, velocity in enumerate(VELOCITIES):
        for j, work in enumerate(WORKS):
            scene = point_scene(
                THORNTON_NING, {"initial.velocity": velocity, "effects.adhesion.work_of_adhesion": work}
            )
            single = simulate(scene, trajectory=False)
            assert grid.status_names()[i, j] == single.status
            assert bool(grid.stuck[i, j]) == single.stuck
            assert grid.bounces[i, j] == single.bounces and grid.steps[i, j] == single.stats["steps"]
            for name in (
                "restitution",
                "contact_time",
                "max_indentation",
                "max_force",
                "min_force",
                "touch_velocity",
                "separation_velocity",
                "dissipated_energy",
                "adhesion_hysteresis",
            ):
                mine, theirs = float(getattr(grid, name)[i, j]), float(getattr(single, name))
                assert math.isclose(mine, theirs, rel_tol=1e-12, abs_tol=0.0) or mine == theirs, (name, mine, theirs)
            # The batch compiles the closed form whole, an eager call op by op: a few ulps apart.
            expected = theory.thornton_ning_restitution(velocity, scene.body.resolved_mass, 1e-6, 1e9, work)
            assert math.isclose(grid.theory_restitution[i, j], float(expected), rel_tol=1e-14, abs_tol=1e-300)
    assert grid.status_names()[0, 1] == "captured" and grid.restitution[0, 1] == 0.0
    assert grid.max_theory_error() < 1e-8


@pytest.mark.slow
def test_grid_and_zip_shapes(grid, thornton_ning_scene):
    velocity = grid.params["initial.velocity"]
    work = grid.params["effects.adhesion.work_of_adhesion"]
    assert velocity.shape == work.shape == grid.restitution.shape == (4, 2)
    assert np.array_equal(velocity[:, 0], VELOCITIES) and np.array_equal(velocity[:, 1], VELOCITIES)
    assert np.array_equal(work[0], WORKS) and np.array_equal(work[3], WORKS)
    # The same 8 points zipped, in reverse: same values (a point's result does not depend on
    # its neighbours in the batch).
    pairs = [(v, w) for v in VELOCITIES for w in WORKS][::-1]
    zipped = sweep(
        THORNTON_NING,
        {"initial.velocity": [p[0] for p in pairs], "effects.adhesion.work_of_adhesion": [p[1] for p in pairs]},
        mode="zip",
        chunk=CHUNK,
    )
    assert zipped.shape == (8,) and zipped.restitution.shape == (8,)
    flat = {name: column.reshape(-1)[::-1] for name, column in grid.results.items()}
    assert zipped.results.keys() == flat.keys() == set(result_names(thornton_ning_scene))
    assert_same(zipped.results, flat, names=tuple(flat))


def test_new_values_do_not_recompile(grid):
    compiles = []

    def listener(event, duration, **kwargs):
        if event == "/jax/core/compile/backend_compile_duration":
            compiles.append(duration)

    jax.monitoring.register_event_duration_secs_listener(listener)
    try:
        other = sweep(
            THORNTON_NING,
            {"initial.velocity": [0.3, 0.5, 0.7, 9.0], "effects.adhesion.work_of_adhesion": [0.04, 0.06]},
            chunk=CHUNK,
        )
    finally:
        jax.monitoring.unregister_event_duration_listener(listener)
    assert compiles == [] and other.stats["compile_time"] == 0.0
    assert np.all(other.success) and other.max_theory_error() < 1e-8


def test_static_fields_form_groups_and_points_are_ordered_by_cost():
    spec = make_spec(
        THORNTON_NING, {"initial.velocity": [2.0, 0.4, 1.0], "effects.adhesion.approach_work_of_adhesion": [0.02, 0.05]}
    )
    plan = plan_sweep(spec)
    assert len(plan.choices) == 2  # a partial approach work searches its edge's turn below the grid
    assert {choices.options.tabulation.tip_search for choices in plan.choices} == {True, False}
    # attach on touch and Δγa = Δγ: the paraboloid's radius rides from the tip or the jump-in alike
    on_touch = make_spec(THORNTON_NING, {"effects.adhesion.approach_work_of_adhesion": [0.0, 0.05]})
    assert len(plan_sweep(on_touch).choices) == 1
    for group in range(2):
        velocities = plan.params["initial.velocity"][plan.order[plan.group[plan.order] == group]]
        assert np.array_equal(velocities, [0.4, 1.0, 2.0])
    given = plan_sweep(make_spec(THORNTON_NING, {"initial.velocity": [2.0, 0.4, 1.0]}, order="given"))
    assert np.array_equal(given.order, [0, 1, 2])
    # chunks: 9 points at chunk 4 → 3 calls of 3 (not 4, 4, 1); a resumed run skips whole chunks
    assert [len(p) for _, p in chunks_of([np.arange(9)], 4)] == [3, 3, 3]
    assert [list(p) for _, p in chunks_of([np.arange(9)], 4, skip=3)] == [[3, 4, 5], [6, 7, 8]]


def test_the_default_chunk_fills_a_gpu():
    """On CPU devices calls of about 1000 points run fastest; a GPU's loop iterations cost
    their launches whatever the batch, so each GPU takes ACCELERATOR_CHUNK points a call (on an
    H100 a Thornton–Ning point cost 4.8 µs in calls of 10⁴ and 0.86 µs in calls of 131 072)."""
    assert default_chunk(jax.local_devices()) == DEFAULT_CHUNK == 1000
    gpus = [types.SimpleNamespace(platform="gpu", id=i) for i in range(2)]
    assert default_chunk(gpus[:1]) == ACCELERATOR_CHUNK and default_chunk(gpus) == 2 * ACCELERATOR_CHUNK


def test_numpy_sticking_velocities_match_the_theory_module():
    for config, closed_form in [
        ("thornton_ning.yaml", lambda s: theory.thornton_ning_sticking_velocity(s.body.resolved_mass, 1e-6, 1e9, 0.05)),
        ("power_law.yaml", lambda s: theory.power_law_sticking_velocity(s.body.resolved_mass, 1.5, 300.0, 1e9, 0.05)),
        (
            "cone.yaml",
            lambda s: theory.power_law_sticking_velocity(s.body.resolved_mass, 1.0, math.tan(0.1), 1e9, 0.05),
        ),
    ]:
        spec = make_spec(CONFIGS / config, {"initial.velocity": [0.5, 1.0]})
        plan = plan_sweep(spec)
        values = sticking_velocity(spec.scene, plan.physics)
        np.testing.assert_allclose(values, float(closed_form(spec.scene)), rtol=1e-13)


def test_a_failing_point_gets_its_code_and_the_sweep_goes_on():
    # A 1 µm gap is crossed in 1.7 µs and the contact lasts 39 ns: shorter limits stop the run.
    result = sweep(THORNTON_NING, {"initial.gap": [0.0, 1e-6], "limits.duration": [1e-8, 1e-7, 1e-3, 1.0]}, chunk=CHUNK)
    names = result.status_names()
    assert list(names[0]) == ["time_limit", "separated", "separated", "separated"]
    assert list(names[1]) == ["time_limit", "time_limit", "separated", "separated"]
    assert np.all(np.isnan(result.restitution[names == "time_limit"]))
    assert np.allclose(result.restitution[names == "separated"], 0.862944882, atol=1e-8)


@pytest.mark.slow
def test_the_figure_draws_the_closed_form_beside_the_points(grid, thornton_ning_scene):
    figure = restitution_figure(grid)
    top = figure.axes[0]
    assert top.get_xscale() == "log"
    simulated = [line for line in top.get_lines() if line.get_gid() == "simulated"]
    curves = [line for line in top.get_lines() if line.get_gid() == "theory"]
    assert len(simulated) == len(curves) == len(WORKS)
    mass = thornton_ning_scene.body.resolved_mass
    for curve, work in zip(curves, WORKS, strict=True):
        v, e = curve.get_xdata(), curve.get_ydata()
        assert len(v) >= 500 and v.min() <= min(VELOCITIES) and v.max() >= max(VELOCITIES)
        # e = √(1 − β) (3.50), compiled as the sweep's batches, the eager call otherwise: β agrees
        # to a few ulps, which the square root amplifies to 1e-5 of e at e ≈ 1e-5.
        expected = theory.thornton_ning_restitution(v, mass, 1e-6, 1e9, work)
        np.testing.assert_allclose(1.0 - e**2, 1.0 - expected**2, rtol=1e-14, atol=1e-15)
    for points in simulated:
        assert len(points.get_xdata()) == len(VELOCITIES)
    rows = sticking_estimates(grid)
    assert [row["fixed"] for row in rows] == [{"effects.adhesion.work_of_adhesion": w} for w in WORKS]
    v_s = float(theory.thornton_ning_sticking_velocity(mass, 1e-6, 1e9, 0.05))
    assert rows[1]["low"] == 0.25 and rows[1]["high"] == 0.45
    assert math.isclose(rows[1]["estimate"], v_s, rel_tol=1e-6)
    assert math.isclose(rows[1]["theory"], v_s, rel_tol=1e-7)


# --- devices and processes ------------------------------------------------------------------
#
# The subprocesses (2 devices; a sweep killed and resumed; two processes of a multi-host run)
# start together when the module does and run beside the in-process tests: most of their time
# is compiling, one core each.


def write_sweep(path: Path, axes: dict, **extra) -> Path:
    path.write_text(yaml.safe_dump({"scene": str(THORNTON_NING), "axes": axes, **extra}, sort_keys=False))
    return path


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


KILL_POINTS = 1024


def _journal_rows_now(path: Path) -> int:
    """Rows the journal holds now (0 while it cannot be read)."""
    try:
        return journal_rows(path)
    except (OSError, ValueError):
        return 0


class Jobs:
    """The module's subprocesses, started at once; each test waits for its own."""

    def __init__(self, folder: Path, env: dict):
        self.folder = folder
        self.env = env
        script = (
            "import jax, numpy as np; jax.config.update('jax_enable_x64', True)\n"
            "from impact._run.sweep import sweep\n"
            f"r = sweep({str(THORNTON_NING)!r}, {GRID!r}, chunk={CHUNK})\n"
            "assert r.stats['devices'] == 2, r.stats\n"
            f"np.savez({str(folder / 'two.npz')!r}, **r.results)\n"
        )
        self.two_devices = subprocess.Popen(
            [sys.executable, "-c", script],
            env=dict(env, JAX_NUM_CPU_DEVICES="2"),
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        self.grid_file = write_sweep(folder / "grid.yaml", GRID)
        port = free_port()
        self.shards = [
            subprocess.Popen(
                sweep_cli(
                    "sweep",
                    self.grid_file,
                    "-o",
                    folder / "shards",
                    "--chunk",
                    CHUNK,
                    "--coordinator",
                    f"127.0.0.1:{port}",
                    "--num-processes",
                    2,
                    "--process-id",
                    index,
                ),
                env=env,
                stdout=subprocess.PIPE,
                stderr=subprocess.PIPE,
                text=True,
            )
            for index in range(2)
        ]
        self.long_file = write_sweep(
            folder / "long.yaml", {"initial.velocity": {"geomspace": [0.25, 20.0, KILL_POINTS]}}
        )
        self.killed = folder / "killed"
        self.killed_process = subprocess.Popen(
            sweep_cli("sweep", self.long_file, "-o", self.killed, "--chunk", CHUNK),
            env=env,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        self.killer = threading.Thread(target=self._kill_midway, daemon=True)
        self.killer.start()

    def _kill_midway(self) -> None:
        """SIGKILL the sweep once its journal holds 4 chunks (of 128). The journal, not the HDF5
        file: a read of the file while the sweep appends to it may fail for as long as the sweep
        runs (measured once in CI: the sweep finished and deleted its journal first)."""
        process, deadline = self.killed_process, time.monotonic() + 400
        while (
            _journal_rows_now(self.killed / "sweep.h5") < 4 * CHUNK
            and process.poll() is None
            and time.monotonic() < deadline
        ):
            time.sleep(0.005)
        process.send_signal(signal.SIGKILL)
        process.wait()

    def kill_midway(self) -> None:
        self.killer.join(timeout=420)

    def close(self) -> None:
        for process in [self.two_devices, *self.shards, self.killed_process]:
            if process.poll() is None:
                process.kill()
                process.wait()


@pytest.fixture(scope="module")
def jobs(tmp_path_factory, cache_env):
    started = Jobs(tmp_path_factory.mktemp("jobs"), cache_env)
    yield started
    started.close()


@pytest.mark.slow
def test_two_devices_give_the_results_of_one(grid, jobs):
    _, err = jobs.two_devices.communicate(timeout=400)
    assert jobs.two_devices.returncode == 0, err
    two = np.load(jobs.folder / "two.npz")
    assert_same(two, grid.results)
    assert_same(two, grid.results, names=CLOSE, rtol=1e-11)


@pytest.mark.slow
def test_the_devices_option_shards_the_sweep_over_that_many_cpu_devices(tmp_path, cache_env):
    """`impact sweep --devices 2` starts two host devices (jax 0.10 refuses `jax.config.read`
    of a setting that has a context manager: it is read as an attribute of jax.config)."""
    sweep_file = write_sweep(tmp_path / "tiny.yaml", {"initial.velocity": [0.5, 1.0, 2.0, 4.0]})
    done = subprocess.run(
        sweep_cli("sweep", sweep_file, "-o", tmp_path / "out", "--devices", 2),
        env=cache_env,
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    with h5py.File(tmp_path / "out" / "sweep.h5", "r") as file:
        assert int(file["sweep"].attrs["last_devices"]) == 2


def h5_columns(path: Path) -> dict:
    with h5py.File(path, "r") as file:
        group = file["sweep"]
        columns = {"index": group["index"][()], "definition": file["parameters/sweep.yaml"].asstr()[()]}
        for kind in ("params", "results"):
            for name, dataset in group[kind].items():
                columns[f"{kind}/{name}"] = dataset[()]
        columns["rows"] = int(group.attrs["rows"])
        columns["complete"] = bool(group.attrs["complete"])
    return columns


def assert_same_files(mine: Path, theirs: Path) -> None:
    a, b = h5_columns(mine), h5_columns(theirs)
    assert a.keys() == b.keys()
    for key in a:
        if isinstance(a[key], np.ndarray):
            assert np.array_equal(a[key], b[key], equal_nan=True), key
        else:
            assert a[key] == b[key], key


@pytest.mark.slow
def test_a_killed_sweep_resumes_to_the_uninterrupted_result(tmp_path, jobs):
    jobs.kill_midway()
    # The journal holds every finished chunk; the HDF5 file as many or one fewer (the kill may
    # have cut its append short, or even left it unreadable: the restart rebuilds it).
    done = journal_rows(jobs.killed / "sweep.h5")
    assert 0 < done < KILL_POINTS and done % CHUNK == 0, done
    try:
        written = h5_columns(jobs.killed / "sweep.h5")["rows"]
    except OSError:
        written = None
    assert written is None or done - CHUNK <= written <= done
    assert not (jobs.killed / "restitution.png").exists()

    resumed = subprocess.run(
        sweep_cli("sweep", jobs.long_file, "-o", jobs.killed, "--chunk", 64),
        env=jobs.env,
        capture_output=True,
        text=True,
        timeout=400,
    )
    assert resumed.returncode == 0, resumed.stderr
    said = " ".join(resumed.stdout.split())
    assert f"resuming {jobs.killed / 'sweep.h5'}: {done} of {KILL_POINTS} points done" in said
    assert "stored chunk size 8" in said

    reference = tmp_path / "reference"
    finished = invoke("sweep", jobs.long_file, "-o", reference, "--chunk", CHUNK)
    assert finished.exit_code == 0, finished.output
    for phrase in ("separated", "captured", "max |e − e_theory|", "sticking velocity", "0.30317"):
        assert phrase in finished.output
    assert_same_files(jobs.killed / "sweep.h5", reference / "sweep.h5")
    assert h5_columns(reference / "sweep.h5")["complete"]
    assert (jobs.killed / "restitution.png").read_bytes().startswith(b"\x89PNG")

    again = invoke("sweep", jobs.long_file, "-o", jobs.killed)
    assert again.exit_code == 2 and "finished" in again.output and "--overwrite" in again.output


@pytest.mark.slow
def test_two_processes_write_shards_that_merge_into_the_single_process_file(grid, tmp_path, jobs):
    for process in jobs.shards:
        out, err = process.communicate(timeout=400)
        assert process.returncode == 0, err
        assert "impact merge" in out
    shards = sorted((jobs.folder / "shards").glob("shard-*.h5"))
    assert [shard.name for shard in shards] == ["shard-000-of-002.h5", "shard-001-of-002.h5"]
    assert [len(h5_columns(shard)["index"]) for shard in shards] == [4, 4]

    incomplete = invoke("merge", shards[0], "-o", tmp_path / "merged.h5")
    assert incomplete.exit_code == 2 and "missing process(es) [1]" in incomplete.output
    merged = invoke("merge", *shards, "-o", tmp_path / "merged.h5")
    assert merged.exit_code == 0, merged.output
    assert (tmp_path / "restitution.png").exists()

    single = tmp_path / "single"
    assert invoke("sweep", jobs.grid_file, "-o", single, "--chunk", CHUNK).exit_code == 0
    assert_same_files(tmp_path / "merged.h5", single / "sweep.h5")
    columns = h5_columns(tmp_path / "merged.h5")
    flat = {name: columns[f"results/{name}"][np.argsort(columns["index"])] for name in grid.results}
    assert_same(flat, {name: column.reshape(-1) for name, column in grid.results.items()}, names=tuple(flat))


def test_the_command_checks_its_points_once(grid, tmp_path, monkeypatch):
    """`impact sweep` validates its points once: reading back the file it has just written
    takes the spec it holds (checking 10⁶ points as scenes takes about 20 s). Read without
    it, the file is validated again and gives the same results."""
    checked = []
    check_points = sweep_method.check_points  # what `make_spec` checks the points with, its method chosen
    monkeypatch.setattr(sweep_method, "check_points", lambda spec: (checked.append(spec.size), check_points(spec))[1])
    sweep_file = tmp_path / "grid.yaml"
    sweep_file.write_text(yaml.safe_dump({"scene": str(THORNTON_NING), "axes": GRID}, sort_keys=False))
    result = invoke("sweep", sweep_file, "-o", tmp_path / "out", "--chunk", CHUNK)
    assert result.exit_code == 0, result.output
    assert checked == [8]
    stored = read_sweep(tmp_path / "out" / "sweep.h5")
    assert checked == [8, 8]
    assert_same(stored.results, grid.results)


def test_the_journal_recovers_what_a_kill_inside_a_write_breaks(tmp_path):
    spec = make_spec(THORNTON_NING, {"initial.velocity": np.linspace(0.4, 2.0, 12).tolist()})
    plan = plan_sweep(spec)
    path = tmp_path / "sweep.h5"
    writer = SweepWriter.start(path, spec, plan, expected=12, chunk=4)
    fake = [empty_results(4, result_names(spec.scene)) for _ in range(3)]
    for k, results in enumerate(fake):
        results["restitution"][:] = np.arange(4) + 10 * k
        results["status"][:] = 0
    writer.append(plan.order[:4], fake[0])
    writer.append(plan.order[4:8], fake[1])
    # killed after the journal got chunk 3, before the file did
    (journal_folder(path) / f"{writer.rows:012d}.npz").write_bytes(npz_bytes(plan.order[8:], fake[2]))
    assert SweepWriter.resume(path, spec, plan, expected=12, chunk=4).rows == 12
    # killed inside a write: the HDF5 file is unreadable; the journal rebuilds it
    path.write_bytes(path.read_bytes()[:2000])
    result = invoke(
        "sweep",
        write_sweep(tmp_path / "s.yaml", {"initial.velocity": np.linspace(0.4, 2.0, 12).tolist()}),
        "-o",
        tmp_path,
        "--chunk",
        4,
    )
    assert result.exit_code == 0, result.output  # rebuilt, complete: nothing left to solve
    assert "resuming" in result.output and "12 of 12 points done" in result.output
    columns = h5_columns(path)
    assert columns["complete"] and np.array_equal(columns["index"], plan.order)
    assert np.array_equal(columns["results/restitution"], np.concatenate([r["restitution"] for r in fake]))
    assert not journal_folder(path).exists()  # a finished sweep drops its journal


# --- refusals -------------------------------------------------------------------------------


@pytest.mark.parametrize("case", ["finished", "different", "not hdf5", "bad options"])
def test_existing_output_is_refused(case, tmp_path):
    sweep_file = write_sweep(tmp_path / "grid.yaml", GRID)
    folder = tmp_path / "out"
    folder.mkdir()
    spec = make_spec(THORNTON_NING, GRID)
    args = []
    if case == "finished":
        create_sweep_file(folder / "sweep.h5", spec, expected=0, chunk=CHUNK)
        phrases = ["finished", "--overwrite"]
    elif case == "different":
        other = make_spec(THORNTON_NING, {"initial.velocity": [0.5, 1.0]})
        create_sweep_file(folder / "sweep.h5", other, expected=2, chunk=CHUNK)
        phrases = ["different sweep", "parameters/sweep.yaml", "--overwrite"]
    elif case == "not hdf5":
        (folder / "sweep.h5").write_text("not HDF5")
        phrases = ["not a readable HDF5 file"]
    else:
        (folder / "sweep.h5").write_text("untouched")
        args = ["--coordinator", "127.0.0.1:1"]
        phrases = ["--coordinator", "needs --num-processes and --process-id"]
    before = (folder / "sweep.h5").read_bytes()
    result = invoke("sweep", sweep_file, "-o", folder, *args)
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output
    for phrase in phrases:
        assert phrase in " ".join(result.output.split())
    assert (folder / "sweep.h5").read_bytes() == before
