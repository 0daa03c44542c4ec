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
- **split**: one call of the sweep's size (its points spread over the sweep) as three compiled
  programs in a row, each taking the one before's results: build (the scaled problem),
  integrate (the outcome's fields that the point function reads) and post-process (the SI
  results and the closed form); per impact, the parts of the run of median total of
  SPLIT_REPEATS (`staged_us`). Each part is the time between two clock readings, so none is
  negative and they add up to the staged total; that total exceeds the sweep's time by what
  the fused point saves (the problem and the outcome written out and read back, three calls).
- **method**: how the workload's impacts are integrated (`method_label`).
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
import numpy as np

from .._core.runtime import compiler_options
from .._io.files import write_text
from .._plots.bench import save_speed_figure
from .._run.sweep import execute, plan_sweep
from .._run.sweep.batch import batch_sharding, local_devices, point_reads, point_results
from .._run.sweep.plan import Plan as SweepPlan
from .._scene.scene import Scene
from .._scene.sections import QUADRATURE, Solver
from .._scene.sweep import make_spec
from .workloads import CLOSED_FORM, TIGHTER_FACTOR, TIGHTER_POINTS, SpeedPlan, Workload

SPRING_QUADRATURE_LABEL = "prefix sums"  # a spring array's contacts computed whole (`solver.method: quadrature`)

COLUMNS = (
    "workload",
    "method",
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
    "staged_us",
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
                f"[{time.perf_counter() - start:4.0f} s] {workload.key} ({row['method']}) × {points}: "
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
    plan = plan_sweep(make_spec(named_method(workload.scene), workload.axis(points)))
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
        "method": method_label(plan.spec.scene),
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
        "staged_us": build + integrate + post,
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
    """Max |e − e_tight| at the strided points, e_tight at rtol and atol / TIGHTER_FACTOR (of a
    quadrature workload: by the scene's default ODE solver at its default rtol and atol / that)."""
    scene = deepcopy(workload.scene)
    solver = scene.setdefault("solver", {})
    if solver.get("method", QUADRATURE) == QUADRATURE:  # against the ODE solver's tighter run
        solver["method"] = Solver.model_fields["method"].default
    solver["rtol"] = solver.get("rtol", 1e-10) / TIGHTER_FACTOR
    solver["atol"] = solver.get("atol", 1e-12) / TIGHTER_FACTOR
    chosen = np.arange(0, points, reduce.stride)
    velocities = workload.axis(points)["initial.velocity"][chosen]
    tight: dict[int, float] = {}

    def keep(indices: np.ndarray, values: dict) -> None:
        tight.update(zip(chosen[indices].tolist(), values["restitution"].tolist(), strict=True))

    execute(plan_sweep(make_spec(scene, {"initial.velocity": velocities})), chunk=chunk, on_chunk=keep)
    return reduce.error(tight)


def named_method(scene: dict) -> dict:
    """The workload's scene with its method named (the scene's default ODE solver where it names
    none): each row times its method as a single run of the scene runs it, where a sweep of a
    scene without one would choose the quadrature."""
    solver = {"method": Solver.model_fields["method"].default, **scene.get("solver", {})}
    return {**scene, "solver": solver}


_STAGES: dict = {}  # the three compiled stages by static choices, this session
SPLIT_REPEATS = 3  # runs of the three stages in a row: the one of median total is kept


def split(plan: SweepPlan, size: int, repeats: int) -> tuple[float, float, float]:
    """(build, integrate, post-process) in µs per impact, on one call of `size` points spread
    evenly over the sweep's order (every cost, not only the first chunk's).

    The point runs as three compiled programs in a row, each taking the one before's results
    (`stages`); a part is the time between two of the run's clock readings, so the parts are
    positive and add up to the run's total (`staged_us`, the run of median total)."""
    choices = plan.choices[0]
    if choices not in _STAGES:
        _STAGES[choices] = stages(choices)
    build, integrate, post = _STAGES[choices]
    devices = local_devices()
    sample = plan.order[np.linspace(0, plan.size - 1, size).round().astype(int)]
    batch = jax.device_put(jax.tree.map(lambda leaf: leaf[sample], plan.physics), batch_sharding(devices))
    jax.block_until_ready(post(batch, integrate(build(batch))))  # compile outside the timing
    runs = np.array([staged_run(build, integrate, post, batch) for _ in range(min(repeats, SPLIT_REPEATS))])
    kept = runs[np.argsort(runs.sum(axis=1))[len(runs) // 2]] / size * 1e6
    return float(kept[0]), float(kept[1]), float(kept[2])


def stages(choices) -> tuple[Callable, Callable, Callable]:
    """The point function of `choices` as three compiled, vmapped programs: build (physics →
    problem), integrate (problem → units and the outcome's fields a point reads) and post-process
    (physics, those → the SI results); run in a row they compute what the point function does."""
    integrator, options = choices

    def integrate(problem):
        return problem.scales, point_reads(integrator.integrate(problem, options))

    def post(physics, solved):
        return point_results(choices, physics, *solved)

    def compiled(function):
        return jax.jit(jax.vmap(function), compiler_options=compiler_options(platform=local_devices()[0].platform))

    return compiled(lambda physics: integrator.build(physics, options)), compiled(integrate), compiled(post)


def staged_run(build: Callable, integrate: Callable, post: Callable, batch) -> np.ndarray:
    """(build, integrate, post-process) in s of one run of the stages in a row: the differences
    of four clock readings, each taken once the stage's results are ready."""
    clock = [time.perf_counter()]
    problem = jax.block_until_ready(build(batch))
    clock.append(time.perf_counter())
    solved = jax.block_until_ready(integrate(problem))
    clock.append(time.perf_counter())
    jax.block_until_ready(post(batch, solved))
    clock.append(time.perf_counter())
    return np.diff(clock)


def method_label(scene: Scene) -> str:
    """How the scene's impacts are integrated, as a row names it: 'quadrature', a spring array's
    'prefix sums' (`solver.method: quadrature`), 'exact events' or 'verlet dt … s', else the
    diffrax solver and its rtol."""
    solver = scene.solver
    if solver.method == QUADRATURE:
        return QUADRATURE if scene.contact.springs == "continuum" else SPRING_QUADRATURE_LABEL
    if scene.contact.springs != "continuum":
        return "exact events" if solver.dt is None else f"verlet dt {solver.dt:g} s"
    return f"{solver.method} rtol {solver.rtol:g}"


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
