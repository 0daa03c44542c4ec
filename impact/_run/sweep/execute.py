"""Running a sweep: chunks of like cost through the compiled batch, progress, shares."""

import contextlib
import logging
import math
import operator
import time
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path

import jax
import numpy as np

from ..._core.defaults import ACCELERATOR_CHUNK, DEFAULT_CHUNK
from ..._core.runtime import float64
from ..._scene.errors import SweepError
from ..._scene.scene import Scene
from ..._scene.sweep import make_spec
from ..._scene.sweep_spec import SweepSpec
from .batch import COMPILE_SECONDS, batch_sharding, compiled_batch, local_devices, sequential
from .plan import Plan, plan_sweep
from .result import SOLVED, SweepResult, chunk_columns, empty_results, result_names


class Progress:
    """Callbacks of a running sweep (override what you need)."""

    def compiling(self, group: int, groups: int) -> None: ...

    def compiled(self, seconds: float) -> None: ...

    def advance(self, points: int) -> None: ...


def default_chunk(devices: Sequence) -> int:
    """Points per compiled call unless asked otherwise: DEFAULT_CHUNK on CPU devices (calls of
    500–1000 lanes run fastest there), ACCELERATOR_CHUNK per device on GPUs."""
    if devices[0].platform == "cpu":
        return DEFAULT_CHUNK
    return ACCELERATOR_CHUNK * len(devices)


def chunk_size(chunk: int, devices: int) -> int:
    """`chunk` rounded up to a multiple of the device count."""
    if chunk < 1:
        raise SweepError([("--chunk", f"must be >= 1, got {chunk}")])
    return -(-chunk // devices) * devices


def chunks_of(shares: list[np.ndarray], chunk: int, skip: int = 0) -> list[tuple[int, np.ndarray]]:
    """(group, points) of each chunk, in order, after the first `skip` points of the shares.

    A group of n points is cut into k = ceil(n/chunk) chunks of ceil(n/k) points (the last one
    may be shorter), so no call is mostly padding: 1200 points at chunk 1000 make two calls of
    600, not 1000 + 200 padded to 1000. The cut depends on n and `chunk` alone, not on the
    devices: a resumed sweep recomputes the same chunks."""
    out = []
    for group, points in enumerate(shares):
        if len(points) == 0:
            continue
        length = -(-len(points) // -(-len(points) // chunk))
        for begin in range(0, len(points), length):
            part = points[begin : begin + length]
            if skip >= len(part):
                skip -= len(part)
                continue
            out.append((group, part[skip:]))
            skip = 0
    return out


def execute(
    plan: Plan,
    *,
    chunk: int | None = None,
    devices: "int | Sequence | None" = None,
    share: tuple[int, int] = (0, 1),
    skip: int = 0,
    on_chunk: Callable[[np.ndarray, dict], None] | None = None,
    progress: Progress | None = None,
) -> dict:
    """Run the plan's points of this share (after the first `skip`), chunk by chunk; hand each
    finished chunk (its points, its result columns: `result_names` of the scene) to `on_chunk`
    in order; `chunk` points per compiled call (None: `default_chunk` of the devices). Returns
    timing stats."""
    with _quiet_callback_errors():
        return _execute(plan, chunk, devices, share, skip, on_chunk, progress or Progress())


@contextlib.contextmanager
def _quiet_callback_errors():
    """Keep the log of a failed runtime check (jax.pure_callback) off stderr: `execute`
    handles it by solving the chunk point by point."""
    logger = logging.getLogger("jax._src.callback")
    level = logger.level
    logger.setLevel(logging.CRITICAL)
    try:
        yield
    finally:
        logger.setLevel(level)


def _execute(plan: Plan, chunk: int | None, devices, share, skip, on_chunk, progress: Progress) -> dict:
    devices = local_devices(devices)
    if chunk is None:
        chunk = default_chunk(devices)
    if chunk < 1:
        raise SweepError([("--chunk", f"must be >= 1, got {chunk}")])
    sharding = batch_sharding(devices)
    shares = plan.share(*share)
    work = chunks_of(shares, chunk, skip)
    sizes = _call_sizes(plan, shares, chunk, devices)
    compiled, compile_time = _compile_groups(plan, sorted({group for group, _ in work}), sizes, devices, progress)
    start = time.perf_counter()
    fallbacks, fallback_compile = 0, COMPILE_SECONDS["unbatched"]
    pending, done = None, 0
    finished: list[tuple[np.ndarray, dict]] = []  # (points, solved values) of the chunk's calls so far

    def finish(group: int, points: np.ndarray, outputs, chunk_done: bool) -> None:
        nonlocal fallbacks, done
        values = _read_back(outputs)
        if values is None:
            # A runtime check inside the batch failed. Under vmap one lane's failed check
            # stops every lane, even a check in a branch that lane does not take (e.g. the
            # bracket check of the event root finder), so solve the call's points one after
            # another, unbatched, as `simulate` would.
            values = sequential(plan, group, points, sizes[group])
            fallbacks += len(points)
        finished.append((points, {name: np.asarray(values[name])[: len(points)] for name in SOLVED}))
        progress.advance(len(points))
        done += len(points)
        if chunk_done:
            chunk_points = np.concatenate([part for part, _ in finished])
            solved = {name: np.concatenate([values[name] for _, values in finished]) for name in SOLVED}
            finished.clear()
            if on_chunk is not None:
                on_chunk(chunk_points, chunk_columns(plan.spec.scene, plan.params, chunk_points, solved))

    for group, points in work:
        size = sizes[group]
        for begin in range(0, len(points), size):
            part = points[begin : begin + size]
            padded = np.concatenate([part, np.full(size - len(part), part[-1])])
            batch = jax.tree.map(operator.itemgetter(padded), plan.physics)
            try:
                outputs = compiled[group](jax.device_put(batch, sharding))  # dispatched, not awaited
            except jax.errors.JaxRuntimeError:
                outputs = None  # the error surfaces when reading back (`finish`), or here
            if pending is not None:
                finish(*pending)
            pending = (group, part, outputs, begin + size >= len(points))
    if pending is not None:
        finish(*pending)
    fallback_compile = COMPILE_SECONDS["unbatched"] - fallback_compile
    solve_time = time.perf_counter() - start - fallback_compile
    return {
        "points": done,
        "solved_unbatched": fallbacks,
        "chunk": chunk,
        "call_sizes": sorted(set(sizes.values())),
        "devices": len(devices),
        "groups": len(plan.choices),
        "compile_time": compile_time + fallback_compile,
        "solve_time": solve_time,
        "points_per_second": done / solve_time if solve_time > 0 else math.nan,
        "plan_time": plan.time,
        "order": plan.spec.order,
    }


# Lanes each device runs at least: XLA compiles a vmapped program of one lane as the
# unbatched one, fusing (and so rounding) its arithmetic differently from any batch (the
# Maugis–Dugdale law's zone radius moved by an ulp); a call of one point runs it twice.
_LEAST_LANES = 2


def _call_sizes(plan: Plan, shares: list[np.ndarray], chunk: int, devices: Sequence) -> dict[int, int]:
    """Points per compiled call of each group: its (first) chunk length, padded to a multiple
    of the device count and to `_LEAST_LANES` per device, and on CPU devices at most the
    integrator's `most_lanes` per device (a longer chunk runs in several calls)."""
    count = len(devices)
    sizes = {}
    for group, points in enumerate(shares):
        if len(points):
            size = chunk_size(len(chunks_of([points], chunk)[0][1]), count)
            most_lanes = plan.choices[group].integrator.most_lanes
            if most_lanes is not None and devices[0].platform == "cpu":
                size = min(size, most_lanes * count)
            sizes[group] = max(size, _LEAST_LANES * count)
    return sizes


def _compile_groups(plan: Plan, groups: list[int], sizes: dict[int, int], devices, progress: Progress):
    """({group: compiled batch}, compile time in s) of the groups that have points to run."""
    compiled: dict[int, Callable] = {}
    seconds = 0.0
    for group in groups:
        progress.compiling(group, len(plan.choices))
        compiled[group], taken = compiled_batch(plan.choices[group], plan.physics, sizes[group], devices)
        seconds += taken
        progress.compiled(taken)
    return compiled, seconds


def _read_back(outputs) -> dict | None:
    """The results of a dispatched batch on the host; None where it raised (or never ran)."""
    if outputs is None:
        return None
    try:
        return jax.device_get(outputs)
    except jax.errors.JaxRuntimeError:
        return None


@float64
def run_spec(
    spec: SweepSpec,
    *,
    chunk: int | None = None,
    devices: "int | Sequence | None" = None,
    progress: Progress | None = None,
) -> SweepResult:
    """Run a validated sweep in memory."""
    plan = plan_sweep(spec)
    results = empty_results(plan.size, result_names(spec.scene))

    def store(points, values):
        for name, column in values.items():
            results[name][points] = column

    stats = execute(plan, chunk=chunk, devices=devices, on_chunk=store, progress=progress)
    return SweepResult.from_flat(spec, plan.params, results, stats)


@float64
def sweep(
    scene: "Scene | Mapping | str | Path",
    axes: Mapping[str, object],
    mode: str = "grid",
    *,
    order: str = "cost",
    chunk: int | None = None,
    devices: "int | Sequence | None" = None,
    progress: Progress | None = None,
) -> SweepResult:
    """Simulate a scene over axes of its numeric fields (dotted path → values, or a generator
    such as {"geomspace": [0.2, 20, 400]}), combined as a grid or zipped (`mode`).

    The points run the method the scene names (`solver.method`), else the quadrature where every
    point allows it (`result.spec.method`, `.method_choice`). Returns every scalar result as an
    array in the sweep's shape, with the chapter's closed-form
    restitution where it has one, each named loss of the scene's effects (plastic work, viscous
    work, adhesion hysteresis, unrecovered elastic energy) and, with a counterpart, both bodies'
    lab velocities; it computes in float64 whatever JAX's global flag. `order`: "cost" runs
    points of like cost together, "given" in the order of the axes. `chunk`: points per compiled
    call (None: 1000 on CPU devices, 131 072 per GPU); `devices`: how many of the local devices
    (or which) each chunk is sharded over (None: all); `progress`: an object whose methods
    `compiling(group, groups)`, `compiled(seconds)` and `advance(points)` are called as it runs.
    Raises `impact.SceneError` (`.problems` names each bad field) before running anything."""
    return run_spec(make_spec(scene, axes, mode, order), chunk=chunk, devices=devices, progress=progress)
