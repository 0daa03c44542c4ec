"""What a point costs: `run(folder, plan)` times every workload of `impact bench speed` through
the sweep machinery (`plan_sweep`, `execute`, the compiled `jit(vmap(point))`) and writes
`speed.csv` and `speed.png`.

For each workload × points count:

- **µs per impact**: the sweep's solve time (after compile: `execute` compiles first and
  times the rest) over the points; the median, min and max of `repeats` runs.
- **accuracy**: max |e − e_ref| over the points, e_ref the sweep's own closed form
  (`theory_restitution`) where the chapter has one, else the same points (at most
  TIGHTER_POINTS of them, evenly strided) at rtol and atol / 100; a point that failed makes
  it inf.
- **compile**: the sweep's compile time (a later row with the same call size reuses the
  compiled batch: 0; a batch stored by an earlier process is loaded instead: run
  `impact --no-cache bench speed` for the compilation itself).
- **split**: one call of the sweep's size (its points spread over the sweep) through
  `jit(vmap(build))`, `jit(vmap(build + integrate))` (`solve`, the outcome's fields that the
  point function reads), each reduced to one number per point (`checksum`), and the
  sweep's compiled point function, each the median of SPLIT_REPEATS interleaved runs, per
  impact: build, integrate = the second − the first, post-process = the third − the second (the
  SI results and the closed form). Where the solve stage takes longer than the whole point
  function (it keeps fields that the point function's compilation trims), post-processing
  reads 0 (`split_times`); noise can still make the integration slightly negative.
- the mean solver steps, the peak RSS of the process so far (`resource.getrusage`) and, on
  GPUs, the most memory a device has held so far.

Results are reduced chunk by chunk (nothing of size N is kept besides the plan's inputs), so a
10⁶-point sweep runs in the memory of its plan.
"""

import csv
import io
import math
import resource
import sys
import time
from collections.abc import Callable
from copy import deepcopy
from pathlib import Path

import jax
import jax.numpy as jnp
import numpy as np

from .._core.runtime import compiler_options
from .._io.files import write_text
from .._plots.bench import save_speed_figure
from .._run.programs import solve
from .._run.sweep import execute, plan_sweep
from .._run.sweep.batch import POINT_READS, batch_sharding, compiled_batch, local_devices
from .._run.sweep.plan import Plan as SweepPlan
from .._scene.sweep import make_spec
from .workloads import CLOSED_FORM, TIGHTER_FACTOR, TIGHTER_POINTS, SpeedPlan, Workload

COLUMNS = (
    "workload",
    "points",
    "us_per_impact_median",
    "us_min",
    "us_max",
    "max_error",
    "error_reference",
    "compile_s",
    "build_us",
    "integrate_us",
    "post_us",
    "steps_mean",
    "springs",
    "chunk",
    "device",
    "peak_rss_mb",
    "device_peak_mb",
)


def run(folder: str | Path, plan: SpeedPlan, log: Callable[[str], None] = print) -> list[dict]:
    """Measure every workload × points count of `plan`; write speed.csv and speed.png into
    `folder` (each whole or not at all); return the rows. Needs float64."""
    if not jax.config.read("jax_enable_x64"):
        raise RuntimeError("the benchmark needs float64: jax.config.update('jax_enable_x64', True) first")
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    rows = []
    for workload, counts in plan.runs():
        for points in counts:
            row = measure(workload, points, plan.repeats, plan.chunk)
            rows.append(row)
            device = row["device_peak_mb"]
            log(
                f"[{time.perf_counter() - start:4.0f} s] {workload.key} × {points}: "
                f"{row['us_per_impact_median']:.3g} µs per impact, error {row['max_error']:.1e} "
                f"({row['error_reference']}), compile {row['compile_s']:.1f} s, peak RSS {row['peak_rss_mb']:.0f} MB"
                + (f", device peak {device:.0f} MB" if math.isfinite(device) else "")
            )
    write_text(folder / "speed.csv", speed_csv(rows))
    save_speed_figure(folder / "speed.png", rows)
    return rows


def measure(workload: Workload, points: int, repeats: int, chunk: int | None = None) -> dict:
    """One row: time, accuracy, compile time and split of `points` impacts of `workload`, in
    calls of `chunk` points (None: the sweep's default for the devices)."""
    plan = plan_sweep(make_spec(workload.scene, workload.axis(points)))
    reduce = Reduction(points, workload.reference)
    first = execute(plan, chunk=chunk, on_chunk=reduce.add)
    per_impact = np.asarray([execute(plan, chunk=chunk)["solve_time"] / points for _ in range(repeats)]) * 1e6
    if workload.reference == CLOSED_FORM:
        error = reduce.error()
    else:
        error = tighter_error(workload, points, reduce, chunk)
    build, integrate, post = split(plan, max(first["call_sizes"]), repeats)
    return {
        "workload": workload.key,
        "points": points,
        "us_per_impact_median": float(np.median(per_impact)),
        "us_min": float(per_impact.min()),
        "us_max": float(per_impact.max()),
        "max_error": error,
        "error_reference": workload.reference,
        "compile_s": float(first["compile_time"]),
        "build_us": build,
        "integrate_us": integrate,
        "post_us": post,
        "steps_mean": reduce.steps / points,
        "springs": workload.springs,
        "chunk": first["chunk"],
        "device": device_name(),
        "peak_rss_mb": peak_rss_mb(),
        "device_peak_mb": device_peak_mb(),
    }


class Reduction:
    """What `measure` keeps of a sweep's results, chunk by chunk: the max error against the
    closed form, the total steps, and e at the strided points a tighter run checks."""

    def __init__(self, points: int, reference: str):
        self.closed_form = reference == CLOSED_FORM
        self.stride = max(1, math.ceil(points / TIGHTER_POINTS))
        self.worst, self.failed, self.steps = 0.0, 0, 0
        self.kept: dict[int, float] = {}

    def add(self, points: np.ndarray, values: dict) -> None:
        e, steps = values["restitution"], values["steps"]
        self.steps += int(np.sum(steps))
        if self.closed_form:
            difference = np.abs(e - values["theory_restitution"])
            self.failed += int(np.sum(~np.isfinite(difference)))
            if np.any(np.isfinite(difference)):
                self.worst = max(self.worst, float(np.nanmax(difference)))
        else:
            chosen = points % self.stride == 0
            self.kept.update(zip(points[chosen].tolist(), e[chosen].tolist(), strict=True))

    def error(self, reference: dict[int, float] | None = None) -> float:
        """The max error (inf where a point failed); against `reference` (point → e) if given."""
        if reference is not None:
            difference = np.abs(np.array([self.kept[p] - reference[p] for p in sorted(reference)]))
            self.failed = int(np.sum(~np.isfinite(difference)))
            self.worst = float(np.nanmax(difference)) if np.any(np.isfinite(difference)) else 0.0
        return math.inf if self.failed else self.worst


def tighter_error(workload: Workload, points: int, reduce: Reduction, chunk: int | None = None) -> float:
    """Max |e − e_tight| at the strided points, e_tight at rtol and atol / TIGHTER_FACTOR."""
    scene = deepcopy(workload.scene)
    solver = scene.setdefault("solver", {})
    solver["rtol"] = solver.get("rtol", 1e-10) / TIGHTER_FACTOR
    solver["atol"] = solver.get("atol", 1e-12) / TIGHTER_FACTOR
    chosen = np.arange(0, points, reduce.stride)
    velocities = workload.axis(points)["initial.velocity"][chosen]
    tight: dict[int, float] = {}

    def keep(indices: np.ndarray, values: dict) -> None:
        tight.update(zip(chosen[indices].tolist(), values["restitution"].tolist(), strict=True))

    execute(plan_sweep(make_spec(scene, {"initial.velocity": velocities})), chunk=chunk, on_chunk=keep)
    return reduce.error(tight)


_STAGES: dict = {}  # jit(vmap(build)) and jit(vmap(solve)) by static choices, this session
SPLIT_REPEATS = 3  # interleaved runs of each stage: the median is kept


def split(plan: SweepPlan, size: int, repeats: int) -> tuple[float, float, float]:
    """(build, integrate, post-process) in µs per impact, on one call of `size` points spread
    evenly over the sweep's order (every cost, not only the first chunk's)."""
    choices = plan.choices[0]
    if choices not in _STAGES:
        integrator, options = choices
        _STAGES[choices] = (
            jax.jit(
                jax.vmap(lambda physics: checksum(integrator.build(physics, options))),
                compiler_options=compiler_options(),
            ),
            jax.jit(
                jax.vmap(lambda physics: checksum(read_by_point(solve(integrator, physics, options)))),
                compiler_options=compiler_options(),
            ),
        )
    devices = local_devices()
    sample = plan.order[np.linspace(0, plan.size - 1, size).round().astype(int)]
    batch = jax.device_put(jax.tree.map(lambda leaf: leaf[sample], plan.physics), batch_sharding(devices))
    stages = [*_STAGES[choices], compiled_batch(choices, plan.physics, size, devices)[0]]
    for stage in stages[:2]:
        jax.block_until_ready(stage(batch))  # compile outside the timing
    times = np.zeros((min(repeats, SPLIT_REPEATS), len(stages)))
    for run in range(len(times)):
        for s, stage in enumerate(stages):
            t0 = time.perf_counter()
            jax.block_until_ready(stage(batch))
            times[run, s] = time.perf_counter() - t0
    return split_times(*(np.median(times, axis=0) / size * 1e6))


def split_times(build: float, solved: float, full: float) -> tuple[float, float, float]:
    """(build, integrate, post-process) from the times of the three stages (any unit): the
    differences of the nested stages, build + integrate + post-process = full. The solve stage
    returns every field of the outcome that the point function reads, the point function only
    what its results need (XLA trims the rest): where the solve takes longer than the whole,
    the integration is capped at the whole less the build and post-processing reads 0."""
    integrate = min(solved, full) - build
    return float(build), float(integrate), float(full - build - integrate)


def read_by_point(solved) -> tuple:
    """(scales, the outcome's fields the point function reads) of `solve`'s result."""
    scales, outcome = solved
    return scales, [getattr(outcome, name) for name in POINT_READS]


def checksum(tree) -> jax.Array:
    """The sum of every number in `tree`: a stage's whole work is done (nothing is left out as
    unused) but only one number per point is written back, like the point function's scalars
    (returning the tables or the outcome itself costs more than the full point function)."""
    return sum((jnp.sum(jnp.asarray(leaf, float)) for leaf in jax.tree.leaves(tree)), jnp.zeros(()))


def device_name() -> str:
    """The local devices a sweep runs on, e.g. "cpu" or "2 × NVIDIA H100 80GB HBM3"."""
    devices = local_devices()
    kind = "cpu" if devices[0].platform == "cpu" else devices[0].device_kind
    return kind if len(devices) == 1 else f"{len(devices)} × {kind}"


def peak_rss_mb() -> float:
    """Peak resident memory of this process so far, MB (ru_maxrss: kB on Linux, bytes on macOS)."""
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return peak / (2**20 if sys.platform == "darwin" else 2**10)


def device_peak_mb() -> float:
    """The most memory any local accelerator has held so far, MB (its allocator's
    peak_bytes_in_use); nan on CPU devices, which keep no such count (memory_stats() is None)."""
    stats = [device.memory_stats() or {} for device in local_devices()]
    peaks = np.array([stat.get("peak_bytes_in_use", np.nan) for stat in stats], np.float64)
    return float(peaks.max()) / 2**20  # nan where a device keeps no count


def speed_csv(rows: list[dict]) -> str:
    """The rows as CSV text, columns COLUMNS."""
    text = io.StringIO()
    writer = csv.DictWriter(text, fieldnames=COLUMNS, lineterminator="\n")
    writer.writeheader()
    for row in rows:
        writer.writerow({name: _cell(row[name]) for name in COLUMNS})
    return text.getvalue()


def _cell(value):
    return f"{value:.6g}" if isinstance(value, float) else value
