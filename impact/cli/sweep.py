"""`impact sweep` and `impact merge`: parameter sweeps on the command line.

Declared in `commands`. Bad input (sweep file, options, output folder) exits with code 2,
names the field, prints no traceback and writes nothing.

    impact sweep SWEEP.yaml [-o DIR] [--chunk N] [--devices N] [--overwrite]
                 [--num-processes N --process-id I [--coordinator HOST:PORT] | --distributed]
    impact merge SHARD.h5 ... -o sweep.h5 [--overwrite]

A sweep writes DIR/sweep.h5 chunk by chunk (through a journal, see `impact._io.sweep_journal`)
and, once complete, DIR/restitution.png (and DIR/losses.png where the scene names a loss) and a
summary. Run the same command again after an
interruption and it continues where it stopped; a finished sweep is refused unless
--overwrite, a partial one of another definition always. With N processes (independent
shares, or joined by jax.distributed with --coordinator / --distributed) each writes
DIR/shard-<i>-of-<N>.h5; `impact merge` joins them.
"""

import contextlib
import shutil
import time
from pathlib import Path

import jax
import typer
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    ProgressColumn,
    TextColumn,
    TimeElapsedColumn,
    TimeRemainingColumn,
)
from rich.text import Text

from .._integrate.codes import REMEDIES
from .._io import sweep as sweep_store
from .._io.sweep_journal import SweepWriter, journal_state
from .._plots.figures import import_ahead
from .._plots.sweep import save_restitution_figure
from .._plots.sweep_losses import save_losses_figure
from .._run.sweep import Plan, SweepResult, default_chunk, execute, local_devices, plan_sweep, sticking_estimates
from .._run.sweep import Progress as SweepProgress
from .._scene.errors import SceneError, SweepError
from .._scene.sweep import load_sweep
from .._scene.sweep_spec import SweepSpec
from .console import err, out, refuse, refuse_value, say, warn
from .tables import OUTCOMES, outcome_counts, sticking_table, sweep_table

FIGURE = "restitution.png"
LOSSES_FIGURE = "losses.png"


class _PointsPerSecond(ProgressColumn):
    """Points solved by this run over the time since its compilation ended."""

    def render(self, task) -> Text:
        rate = task.fields.get("rate")
        return Text("" if rate is None else f"{rate:,.0f} points/s", style="cyan")


class _Bar(SweepProgress):
    """The sweep's progress (rich) as `impact._run.sweep.Progress` callbacks."""

    def __init__(self, progress: Progress, total: int, done: int):
        self.progress = progress
        self.task = progress.add_task("compiling", total=total, completed=done, rate=None)
        self.solved, self.start = 0, time.perf_counter()

    def compiling(self, group: int, groups: int) -> None:
        label = "compiling" if groups == 1 else f"compiling group {group + 1} of {groups}"
        self.progress.update(self.task, description=label)

    def compiled(self, seconds: float) -> None:
        self.progress.update(self.task, description="solving")
        self.start = time.perf_counter()

    def advance(self, points: int) -> None:
        self.solved += points
        rate = self.solved / max(time.perf_counter() - self.start, 1e-9)
        self.progress.update(self.task, advance=points, rate=rate)


def run_sweep(
    sweep_file: Path,
    output: Path | None,
    chunk: int | None,
    devices: int | None,
    overwrite: bool,
    coordinator: str | None,
    num_processes: int | None,
    process_id: int | None,
    distributed: bool,
) -> None:
    """`impact sweep`: run a sweep of a scene over numeric fields; write sweep.h5, restitution.png
    and a summary."""
    share = _share(coordinator, num_processes, process_id, distributed)
    if devices is not None:
        _ask_devices(devices)
    if chunk is not None and chunk < 1:
        refuse_value("--chunk", chunk, "be >= 1")
    folder = output or Path("runs") / "sweeps" / sweep_file.stem
    if folder.exists() and not folder.is_dir():
        refuse("output folder", [("--output", f"{folder} exists and is not a folder")])
    joined = coordinator is not None or distributed
    if joined:  # before any JAX computation (checking the sweep's points computes their units)
        share = _join(coordinator, num_processes, process_id)
    spec = _sweep_spec(sweep_file)
    path = folder / sweep_store.shard_name(*share)
    resume, stored_chunk = _existing(path, spec, share, overwrite)
    try:
        device_list = local_devices(devices)
    except SweepError as error:
        refuse("devices", error.problems)
    if stored_chunk is not None and chunk is not None and chunk != stored_chunk:
        say(f"note: resuming with the stored chunk size {stored_chunk}, not --chunk {chunk}")
    chunk = stored_chunk or chunk or default_chunk(device_list)
    plan = plan_sweep(spec)
    expected = sum(len(points) for points in plan.share(*share))
    writer = _writer(path, plan, resume, overwrite, expected=expected, chunk=chunk, share=share)
    if share[1] == 1:
        import_ahead()  # matplotlib, for the figures, while the sweep computes
    stats = _solve(plan, writer, expected, chunk=chunk, devices=device_list, share=share)
    sweep_store.set_attributes(
        path, **{f"last_{key}": value for key, value in stats.items() if isinstance(value, (int, float))}
    )
    writer.finish()
    if joined:
        jax.distributed.shutdown()
    if share[1] > 1:
        say(f"shard {share[0]} of {share[1]} written to {path}; join the shards with `impact merge`")
        return
    result = sweep_store.read_sweep(path, spec)
    _save_figures(result, folder)
    _print_summary(result, stats, f"sweep written to {folder}")


def _save_figures(result: SweepResult, folder: Path) -> None:
    """restitution.png, losses.png where the scene names a loss, tangential.png where it names friction."""
    save_restitution_figure(result, folder / FIGURE)
    if result.named_losses():
        save_losses_figure(result, folder / LOSSES_FIGURE)
    if result.scene.effects.friction is not None:
        from .._plots.oblique import save_tangential_figure

        save_tangential_figure(result, folder)


def _sweep_spec(sweep_file: Path) -> SweepSpec:
    """The validated sweep of a file, or a refusal."""
    try:
        return load_sweep(sweep_file)
    except SceneError as error:
        refuse(f"{sweep_file} is not a valid sweep", error.problems)


def _share(coordinator, num_processes, process_id, distributed) -> tuple[int, int]:
    """(this process, processes). --num-processes N --process-id I alone: an independent share
    (no communication at all); with --coordinator also jax.distributed.initialize."""
    if distributed:
        if any(value is not None for value in (coordinator, num_processes, process_id)):
            message = (
                "takes the processes from the cluster's environment; "
                "leave out --coordinator, --num-processes and --process-id"
            )
            refuse("options", [("--distributed", message)])
        return 0, 1  # replaced once jax.distributed has started
    if num_processes is None and process_id is None:
        if coordinator is not None:
            refuse("options", [("--coordinator", "needs --num-processes and --process-id")])
        return 0, 1
    if num_processes is None or process_id is None:
        refuse("options", [("--num-processes", "give --num-processes and --process-id together")])
    if num_processes < 1:
        refuse_value("--num-processes", num_processes, "be >= 1")
    if not 0 <= process_id < num_processes:
        refuse_value("--process-id", process_id, f"lie in [0, {num_processes})")
    return process_id, num_processes


def _join(coordinator, num_processes, process_id) -> tuple[int, int]:
    """Start jax.distributed (or refuse); (this process, processes) as it numbers them."""
    try:
        jax.distributed.initialize(coordinator_address=coordinator, num_processes=num_processes, process_id=process_id)
    except Exception as error:  # noqa: BLE001 - any failure to join is the user's setup
        refuse("multi-host", [("--coordinator", f"jax.distributed.initialize failed: {error}")])
    return jax.process_index(), jax.process_count()


def _ask_devices(devices: int) -> None:
    """On CPU, make `devices` host devices visible if the backend has not started yet (JAX
    refuses the setting once it has: the devices there are then what the sweep gets)."""
    if devices < 1:
        refuse_value("--devices", devices, "be >= 1")
    if devices > jax.config.read("jax_num_cpu_devices"):
        with contextlib.suppress(RuntimeError):
            jax.config.update("jax_num_cpu_devices", devices)


def _existing(path: Path, spec: SweepSpec, share: tuple[int, int], overwrite: bool) -> tuple[bool, int | None]:
    """(resume?, stored chunk): resume a partial sweep of the same definition (from its file,
    or from its journal where a kill left the file unreadable); start afresh where there is
    none or with --overwrite; refuse a finished sweep and a different one."""
    journal = journal_state(path)
    if overwrite or (not path.exists() and journal is None):
        return False, None
    try:
        found = sweep_store.state(path)
    except SceneError as error:
        if journal is not None and journal["definition"] == spec.definition() and journal["share"] == share:
            return True, journal["chunk"]  # rebuilt from the journal
        refuse("output folder", [("--output", message) for _, message in error.problems])
    if found["definition"] != spec.definition():
        problem = (
            f"{path} holds a different sweep (its stored definition, parameters/sweep.yaml, "
            "differs from this one); choose another folder or pass --overwrite"
        )
    elif found["share"] != share:
        problem = f"{path} was written as process {found['share'][0]} of {found['share'][1]}"
    elif found["complete"]:
        problem = f"{path} holds this sweep, finished ({found['rows']} points); pass --overwrite to run it again"
    else:
        return True, found["chunk"]
    refuse("output folder", [("--output", problem)])


def _writer(path: Path, plan: Plan, resume: bool, overwrite: bool, **layout) -> SweepWriter:
    """The writer of the sweep file: resumed (saying how far it got), or started afresh in a
    folder created here (and removed again if starting fails)."""
    if resume:
        writer = SweepWriter.resume(path, plan.spec, plan, **layout)
        say(f"resuming {path}: {writer.rows} of {layout['expected']} points done")
        return writer
    folder = path.parent
    created = not folder.exists()
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        refuse("output folder", [("--output", f"cannot create {folder}: {error.strerror}")])
    try:
        if overwrite:
            (folder / FIGURE).unlink(missing_ok=True)
            (folder / LOSSES_FIGURE).unlink(missing_ok=True)
        return SweepWriter.start(path, plan.spec, plan, **layout)
    except BaseException:
        if created:
            shutil.rmtree(folder, ignore_errors=True)
        raise


def _solve(plan: Plan, writer: SweepWriter, expected: int, **options) -> dict:
    """Run the points left to this process with a progress bar on stderr; each finished chunk
    goes to the writer. Ctrl-C keeps the finished chunks and exits with code 130."""
    columns = (TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), _PointsPerSecond())
    timing = (TimeElapsedColumn(), TextColumn("eta"), TimeRemainingColumn())
    with Progress(*columns, *timing, console=err, transient=False) as progress:
        bar = _Bar(progress, expected, writer.rows)
        try:
            return execute(plan, skip=writer.rows, on_chunk=writer.append, progress=bar, **options)
        except KeyboardInterrupt:
            warn(f"interrupted: the finished chunks are in {writer.path}; run the same command again to resume")
            raise typer.Exit(130) from None


def merge_shards(shards: list[Path], output: Path, overwrite: bool) -> None:
    """`impact merge`: join the shards of a multi-process sweep into one sweep.h5 (and
    restitution.png beside it)."""
    if output.exists() and not overwrite:
        refuse("output file", [("--output", f"{output} exists; pass --overwrite to replace it")])
    if not output.parent.is_dir():
        refuse("output file", [("--output", f"folder {output.parent} does not exist")])
    try:
        start = time.perf_counter()
        result = sweep_store.merge(shards, output)
    except SceneError as error:
        refuse("cannot merge the shards", error.problems)
    _save_figures(result, output.parent)
    _print_summary(result, {"merge_time": time.perf_counter() - start}, f"merged sweep written to {output}")


def _print_summary(result: SweepResult, stats: dict, closing: str) -> None:
    """The sweep's table, its sticking velocities (if it runs along the velocity), a warning
    for points without a physical outcome, and the closing line."""
    out.print(sweep_table(result, stats))
    estimates = sticking_estimates(result)
    if estimates:
        out.print(sticking_table(estimates))
    counts = outcome_counts(result)
    failed = sum(count for name, count in counts.items() if name not in OUTCOMES)
    if failed:
        warn(f"warning: {failed} point(s) ended without a physical outcome (see sweep/results/status)")
    for name in counts:
        if name in REMEDIES:
            warn(f"  {name} ({counts[name]}): {REMEDIES[name]}")
    say(closing)
