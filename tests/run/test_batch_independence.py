"""A point's result does not depend on its batch (issue #18, item 3): for each law, a sweep run
point by point (chunk 1), in calls of 6 (chunk 7), all at once (chunk 64 and the default) and in
reverse order gives every result bitwise equal, and (continuum law, spring array, attach
hysteresis) equal to `impact.simulate` of the point.

XLA:CPU vectorises the lanes of a batch; with fused multiply–adds, lanes in SIMD registers and
lanes in the scalar remainder rounded differently (restitutions apart by a few ulps,
Maugis–Dugdale's step counts by up to 20). The tests' process runs without FMA
(`impact.configure()`, `impact._core.runtime.NO_FMA_FLAG`) and keeps the vectors; twelve points
make the batch wide enough to be vectorised with a remainder.

A Runge–Kutta step's sum of its stages is one matrix–vector product over every lane's state,
which XLA:CPU computes in tiles of 4 rows with fused multiply–adds and the rows left over
without: the last lane of a batch whose lanes hold 3 components in all not a multiple of 4 (a
batch of 3 or 7) rounded differently, by 3e-15 in the restitution of a power law n = 1.5. Rides
pad their state to 4 components (`impact._integrate.base`); the power law checks it with a
batch of 3.

XLA compiles a vmapped program of one lane as the unbatched one, with its multiply–adds fused
(rounded) otherwise than in any batch: a call of one point runs it in two lanes
(`impact._run.sweep.execute`). The Maugis–Dugdale and Greenwood–Johnson laws (whose curve rides
amplify an ulp most) check it with two points, each alone (beside its copy), together and
swapped. Sums over an axis are added in node order (`impact._core.quadrature.ordered_sum`):
XLA:CPU's reduce picked its order by the batch's shape from 100 points up; and it compiles a
loop whole or op by op by the bytes it touches, which grow with the batch, so that a curve law's
calls of 60 points rounded otherwise than calls of 16: curve laws run calls of at most 16 points on CPU devices
(both measured with more points than are affordable here: docs/src/sweeps.md; the call sizes are
checked below). `impact.simulate` (unbatched) gives those two laws' results to a few ulps, not
checked here.
"""

import os
import platform
import subprocess
import sys
import types
from pathlib import Path

import jax
import numpy as np
import pytest

from impact import simulate
from impact._core import runtime
from impact._core.defaults import DEFAULT_CHUNK
from impact._core.runtime import (
    ELEMENTAL_EMITTERS_FLAG,
    NO_FMA_FLAG,
    SCALAR_LANES,
    compiler_options,
    contracts_multiply_adds,
)
from impact._run.sweep import batch as batch_module
from impact._run.sweep import sweep
from impact._run.sweep.execute import _call_sizes
from impact._run.sweep.plan import plan_sweep
from impact._scene.paths import with_values
from impact._scene.scene import load_scene
from impact._scene.sweep import make_spec
from tests.run.bitwise import assert_bitwise, named_method
from tests.scenes import CONFIGS

# (scene, its changes, lowest and highest velocity in m/s, points): captured and separated points.
# Each scene names its method (a sweep of one that names none runs the quadrature). Each call size
# compiles once: chunk 1 runs calls of 2 (a point and its copy), chunk 7 calls of 6, chunks 64 and
# the default one call; a curve law's program takes ~10 s to compile, so its two points make one
# call size, 2, in every chunk; attach hysteresis's seven points make two (chunk 7 is one call of
# all seven).
LAWS = {
    "continuum JKR": ("thornton_ning.yaml", {}, 0.25, 5.0, 12),
    "spring array": ("spring_array.yaml", {}, 0.3, 3.0, 12),
    "attach hysteresis": (
        "attach_on_touch.yaml",
        {"effects.adhesion.approach_work_of_adhesion": 0.02, "solver.method": "tsit5"},
        0.2,
        3.0,
        7,
    ),
    "Maugis–Dugdale": ("maugis_dugdale.yaml", {}, 0.1, 2.0, 2),  # Λ = 1
    "Greenwood–Johnson": ("greenwood_johnson.yaml", {}, 0.1, 1.0, 2),
}
# Laws whose points `impact.simulate` (unbatched, its own compile) gives as the sweep does.
SIMULATED_LAWS = ("continuum JKR", "spring array", "attach hysteresis")
# Results `impact.simulate` gives bitwise on the continuum law; its program (with the event log)
# contracts a few multiply–adds of the force differently: the force extremes and ∮F dd agree to a
# few ulps, and on a spring array (whose events advance in closed form) these results too.
SIMULATED = ("restitution", "stuck", "contact_time", "bounces", "touch_velocity", "separation_velocity")
SIMULATED_CLOSE = {"spring array": 1e-14}
CLOSE = {
    "max_indentation": 1e-14,
    "max_force": 1e-14,
    "min_force": 1e-14,
    "dissipated_energy": 1e-12,  # ∮F dd cancels
    "adhesion_hysteresis": 1e-12,  # all of it here
}


@pytest.mark.slow
@pytest.mark.parametrize("law", LAWS)
def test_a_points_result_does_not_depend_on_its_batch(law):
    config, changes, low, high, points = LAWS[law]
    scene = named_method(with_values(load_scene(CONFIGS / config), changes))  # a single run's method
    velocities = np.geomspace(low, high, points)
    axes = {"initial.velocity": velocities.tolist()}
    alone = sweep(scene, axes, order="given", chunk=1)
    assert alone.stats["call_sizes"] == [2]  # the point and its copy
    assert 0 < np.count_nonzero(alone.stuck) < points  # both outcomes: lanes that finish early
    for chunk, size in ((7, 6 if points > 7 else max(points, 2)), (64, points), (DEFAULT_CHUNK, points)):
        batched = sweep(scene, axes, order="given", chunk=chunk)
        assert batched.stats["call_sizes"] == [size]
        assert_bitwise(batched.results, alone.results, f"chunk {chunk}")
    backwards = sweep(scene, {"initial.velocity": velocities[::-1].tolist()}, order="given", chunk=64)
    assert_bitwise({name: column[::-1] for name, column in backwards.results.items()}, alone.results, "reversed")
    if law in SIMULATED_LAWS:
        for point in (0, points // 2, points - 1):
            assert_simulated(law, with_values(scene, {"initial.velocity": float(velocities[point])}), alone, point)


def assert_simulated(law: str, scene, swept, point: int) -> None:
    """`impact.simulate` of the scene gives the sweep's results of the point (`SIMULATED`
    bitwise, `CLOSE` to their tolerances)."""
    single = simulate(scene, trajectory=False)
    assert single.status == swept.status_names()[point]
    assert single.stats["steps"] == swept.steps[point]
    for name in SIMULATED:
        mine, theirs = getattr(single, name), swept.results[name][point]
        if law in SIMULATED_CLOSE:
            np.testing.assert_allclose(mine, theirs, rtol=SIMULATED_CLOSE[law], err_msg=name)
        else:
            assert np.array_equal(mine, theirs, equal_nan=True), (point, name)
    for name, rtol in CLOSE.items():
        np.testing.assert_allclose(getattr(single, name), swept.results[name][point], rtol=rtol, err_msg=name)


@pytest.mark.slow
def test_a_power_law_point_does_not_depend_on_its_place_in_a_batch():
    """Three points, repeated in one call of 7 (7·3 state components: without the padding the
    last lane's time falls in the row left over from the 4-row tiles, and its restitution
    moved by 3e-15), and in reverse order: each point's results are bitwise the same wherever
    it sits. (One compiled program: a power law's takes ~20 s to compile.)"""
    scene = named_method(load_scene(CONFIGS / "power_law.yaml"))  # its ODE solve, not the quadrature
    velocities = np.array([0.12, 2.0, 0.3, 0.12, 2.0, 0.3, 0.3])  # m/s; v_s = 0.1315 m/s: 0.12 sticks
    batched = sweep(scene, {"initial.velocity": velocities.tolist()}, order="given", chunk=64)
    assert batched.stats["call_sizes"] == [7]
    assert 0 < np.count_nonzero(batched.stuck) < 7
    backwards = sweep(scene, {"initial.velocity": velocities[::-1].tolist()}, order="given", chunk=64)
    assert_bitwise({name: column[::-1] for name, column in backwards.results.items()}, batched.results, "reversed")
    first = {
        name: column[[np.flatnonzero(velocities == v)[0] for v in velocities]]
        for name, column in batched.results.items()
    }
    assert_bitwise(batched.results, first, "repeated points")


@pytest.mark.parametrize(
    ("config", "call"), [("maugis_dugdale.yaml", 16), ("greenwood_johnson.yaml", 16), ("thornton_ning.yaml", 40)]
)
def test_curve_laws_run_calls_of_at_most_sixteen_points_on_a_cpu(config, call):
    # Their rides' loops compile whole up to ~32 points a call and op by op from ~60, rounding
    # otherwise; the continuum law gives the same bits either way and runs a chunk in one call.
    plan = plan_sweep(make_spec(load_scene(CONFIGS / config), {"initial.velocity": np.linspace(0.1, 1.0, 40).tolist()}))
    cpu = jax.devices("cpu")[:1]
    assert _call_sizes(plan, plan.share(0, 1), 64, cpu) == {0: call}
    assert _call_sizes(plan, plan.share(0, 1), 1, cpu) == {0: 2}


@pytest.mark.parametrize("config", ["maugis_dugdale.yaml", "greenwood_johnson.yaml"])
def test_curve_laws_run_a_chunk_in_one_call_on_gpus(config):
    """The guard is XLA:CPU's: two GPUs take a chunk of 40 points in one call of 20 each."""
    plan = plan_sweep(make_spec(load_scene(CONFIGS / config), {"initial.velocity": np.linspace(0.1, 1.0, 40).tolist()}))
    gpus = [types.SimpleNamespace(platform="gpu")] * 2
    assert _call_sizes(plan, plan.share(0, 1), 64, gpus) == {0: 40}
    assert _call_sizes(plan, plan.share(0, 1), 1, gpus) == {0: 4}  # two lanes a device


X86 = platform.machine().lower() in ("x86_64", "amd64")
HAS_FMA = X86 and Path("/proc/cpuinfo").exists() and " fma " in Path("/proc/cpuinfo").read_text()


@pytest.mark.skipif(not X86, reason="the FMA flag is for XLA:CPU on x86-64")
def test_a_configured_process_runs_without_fused_multiply_adds_and_keeps_its_vectors():
    assert NO_FMA_FLAG in os.environ["XLA_FLAGS"]  # conftest called impact.configure()
    assert contracts_multiply_adds() is False
    assert compiler_options() == {}


def test_a_configured_process_compiles_every_program_with_the_elemental_emitters():
    """A scene's programs and a sweep's batches alike take XLA's elemental emitters (faster to
    compile, about as fast to run): a point is computed by the same code in a run and in a call
    of one, of six or of all."""
    assert ELEMENTAL_EMITTERS_FLAG in os.environ["XLA_FLAGS"].split()
    assert "xla_cpu_use_fusion_emitters" not in compiler_options()


def test_a_gpu_compiles_without_the_cpu_options(monkeypatch):
    """The options are XLA:CPU's; a GPU's compiler refuses a name it does not know ("No such
    compile option: 'xla_cpu_use_fusion_emitters'", seen on an H100 on 2026-11-27)."""
    monkeypatch.setattr(runtime, "contracts_multiply_adds", lambda: True)  # a CPU would get scalar lanes
    assert compiler_options() == SCALAR_LANES
    monkeypatch.setattr(jax, "default_backend", lambda: "gpu")
    assert compiler_options() == {}


def test_a_sweeps_batch_takes_the_options_of_its_devices_platform(monkeypatch, thornton_ning_scene):
    """A batch given CPU devices on a machine whose default device is a GPU still compiles with
    XLA:CPU's options, and one on GPUs without them."""
    monkeypatch.setattr(runtime, "contracts_multiply_adds", lambda: True)  # options to tell apart
    on_cpu = compiler_options()  # this process's default device is its CPU
    assert on_cpu == SCALAR_LANES
    monkeypatch.setattr(jax, "default_backend", lambda: "gpu")
    assert compiler_options(platform="cpu") == on_cpu
    assert compiler_options(platform="gpu") == {}
    compiled_with = []
    monkeypatch.setattr(batch_module, "_COMPILED", {})  # nothing kept for later tests
    monkeypatch.setattr(batch_module, "compile_stored", lambda *arguments: compiled_with.append(arguments[-1]))
    plan = plan_sweep(make_spec(thornton_ning_scene, {"initial.velocity": [0.5, 1.0]}))
    batch_module.compiled_batch(plan.choices[0], plan.physics, 2, jax.devices("cpu")[:1])
    assert compiled_with == [on_cpu]


@pytest.mark.skipif(not HAS_FMA, reason="needs an x86-64 CPU with FMA")
def test_a_process_with_fused_multiply_adds_runs_every_lane_scalar():
    """A process that never called `configure()` (its XLA contracts a·b + c into one FMA) gets
    vectors of one element, so that its lanes still round alike."""
    probe = "from impact._core.runtime import compiler_options as o; print(o())"
    environment = {key: value for key, value in os.environ.items() if key != "XLA_FLAGS"}
    shown = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, env=environment, check=True)
    assert shown.stdout.strip() == str(SCALAR_LANES)
