"""`impact sweep` and `impact merge`: parameter sweeps on the command line.

`register(app)` adds both commands to the `impact` typer app. Bad input (sweep file, options,
output folder) exits with code 2, names the field, prints no traceback and writes nothing.

    impact sweep SWEEP.yaml [-o DIR] [--chunk N] [--devices N] [--overwrite]
                 [--num-processes N --process-id I [--coordinator HOST:PORT] | --distributed]
    impact merge SHARD.h5 ... -o sweep.h5 [--overwrite]

A sweep writes DIR/sweep.h5 chunk by chunk (through a journal, see `sweep_io`) and, once
complete, DIR/restitution.png and a summary. Run the same command again after an interruption
and it continues where it stopped; a finished sweep is refused unless --overwrite, a partial
one of another definition always. With N processes (independent shares, or joined by
jax.distributed with --coordinator / --distributed) each writes DIR/shard-<i>-of-<N>.h5;
`impact merge` joins them.
"""

import math
import shutil
import time
import typing
from pathlib import Path
from typing import Annotated, Optional

import numpy as np
import typer
from rich import box
from rich.console import Console
from rich.progress import BarColumn, MofNCompleteColumn, Progress, ProgressColumn, TextColumn, TimeElapsedColumn, TimeRemainingColumn
from rich.table import Table
from rich.text import Text

from .._integrate.codes import RESULT_CODES
from .._scene.scene import SceneError

_out = Console(highlight=False)
_err = Console(stderr=True, highlight=False)

FIGURE = "restitution.png"


def register(app: typer.Typer) -> None:
    """Add the `sweep` and `merge` commands to the app."""
    app.command("sweep")(sweep_command)
    app.command("merge")(merge_command)


def _refuse(headline: str, problems: list[tuple[str, str]]) -> typing.NoReturn:
    _err.print(Text(f"error: {headline}", "bold red"), soft_wrap=True)
    for path, message in problems:
        _err.print(Text(f"  {path}: {message}" if path else f"  {message}"), soft_wrap=True)
    raise typer.Exit(2)


class _PointsPerSecond(ProgressColumn):
    """Points solved by this run over the time since its compilation ended."""

    def render(self, task) -> Text:
        rate = task.fields.get("rate")
        return Text("" if rate is None else f"{rate:,.0f} points/s", style="cyan")


class _Bar:
    """The sweep's progress (rich) as `sweep.Progress` callbacks."""

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


def sweep_command(
    sweep_file: Annotated[Path, typer.Argument(metavar="SWEEP.yaml", help="sweep YAML file", show_default=False)],
    output: Annotated[
        Optional[Path],
        typer.Option("-o", "--output", help="output folder (default: runs/sweeps/<file stem>)", show_default=False),
    ] = None,
    chunk: Annotated[Optional[int], typer.Option("--chunk", help="points per compiled call [default: 1000]", show_default=False)] = None,
    devices: Annotated[
        Optional[int], typer.Option("--devices", help="devices to shard each chunk over (default: all local devices)", show_default=False)
    ] = None,
    overwrite: Annotated[bool, typer.Option("--overwrite", help="discard a finished (or different) sweep in the folder and run anew")] = False,
    coordinator: Annotated[
        Optional[str], typer.Option("--coordinator", help="multi-host: HOST:PORT of process 0 (jax.distributed.initialize)", show_default=False)
    ] = None,
    num_processes: Annotated[Optional[int], typer.Option("--num-processes", help="multi-host: number of processes", show_default=False)] = None,
    process_id: Annotated[Optional[int], typer.Option("--process-id", help="multi-host: this process, 0 ≤ id < N", show_default=False)] = None,
    distributed: Annotated[
        bool, typer.Option("--distributed", help="multi-host: jax.distributed.initialize() from the cluster's environment (SLURM, Open MPI, ...)")
    ] = False,
) -> None:
    """Run a sweep of a scene over numeric fields; write sweep.h5, restitution.png and a summary."""
    import jax

    from .._run import sweep as sweeping
    from .._io import sweep as sweep_io
    from .._scene.sweep import SweepError, load_sweep

    share = _share(coordinator, num_processes, process_id, distributed)
    if devices is not None:
        _ask_devices(jax, devices)
    try:
        spec = load_sweep(sweep_file)
    except SceneError as error:
        _refuse(f"{sweep_file} is not a valid sweep", error.problems)
    if chunk is not None and chunk < 1:
        _refuse("options", [("--chunk", f"must be >= 1, got {chunk}")])
    folder = output or Path("runs") / "sweeps" / sweep_file.stem
    if folder.exists() and not folder.is_dir():
        _refuse("output folder", [("--output", f"{folder} exists and is not a folder")])
    joined = coordinator is not None or distributed
    if joined:
        try:
            jax.distributed.initialize(coordinator_address=coordinator, num_processes=num_processes, process_id=process_id)
        except Exception as error:  # noqa: BLE001 - any failure to join is the user's setup
            _refuse("multi-host", [("--coordinator", f"jax.distributed.initialize failed: {error}")])
        share = (jax.process_index(), jax.process_count())
    path = folder / sweep_io.shard_name(*share)
    resume, stored_chunk = _existing(path, spec, share, overwrite, sweep_io)
    try:
        device_list = sweeping.local_devices(devices)
    except SweepError as error:
        _refuse("devices", error.problems)
    if stored_chunk is not None and chunk is not None and chunk != stored_chunk:
        _out.print(Text(f"note: resuming with the stored chunk size {stored_chunk}, not --chunk {chunk}"), soft_wrap=True)
    chunk = stored_chunk or chunk or sweeping.DEFAULT_CHUNK
    plan = sweeping.plan_sweep(spec)
    expected = sum(len(points) for points in plan.share(*share))

    if resume:
        writer = sweep_io.SweepWriter.resume(path, spec, plan, expected=expected, chunk=chunk, share=share)
        _out.print(Text(f"resuming {path}: {writer.rows} of {expected} points done"), soft_wrap=True)
    else:
        created = not folder.exists()
        try:
            folder.mkdir(parents=True, exist_ok=True)
        except OSError as error:
            _refuse("output folder", [("--output", f"cannot create {folder}: {error.strerror}")])
        try:
            if overwrite:
                (folder / FIGURE).unlink(missing_ok=True)
            writer = sweep_io.SweepWriter.start(path, spec, plan, expected=expected, chunk=chunk, share=share)
        except BaseException:
            if created:
                shutil.rmtree(folder, ignore_errors=True)
            raise

    with Progress(
        TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), _PointsPerSecond(),
        TimeElapsedColumn(), TextColumn("eta"), TimeRemainingColumn(), console=_err, transient=False,
    ) as progress:
        bar = _Bar(progress, expected, writer.rows)
        try:
            stats = sweeping.execute(plan, chunk=chunk, devices=device_list, share=share, skip=writer.rows,
                                     on_chunk=writer.append, progress=bar)
        except KeyboardInterrupt:
            _err.print(Text(f"interrupted: the finished chunks are in {path}; run the same command again to resume", "yellow"))
            raise typer.Exit(130)
    sweep_io.set_attributes(path, **{f"last_{key}": value for key, value in stats.items() if isinstance(value, (int, float))})
    writer.finish()
    if joined:
        jax.distributed.shutdown()
    if share[1] > 1:
        _out.print(Text(f"shard {share[0]} of {share[1]} written to {path}; join the shards with `impact merge`"), soft_wrap=True)
        return
    result = sweep_io.read_sweep(path)
    sweeping.save_restitution_figure(result, folder / FIGURE)
    _print_summary(result, stats, f"sweep written to {folder}")


def _share(coordinator, num_processes, process_id, distributed) -> tuple[int, int]:
    """(this process, processes). --num-processes N --process-id I alone: an independent share
    (no communication at all); with --coordinator also jax.distributed.initialize."""
    if distributed:
        if any(value is not None for value in (coordinator, num_processes, process_id)):
            _refuse("options", [("--distributed", "takes the processes from the cluster's environment; "
                                                  "leave out --coordinator, --num-processes and --process-id")])
        return 0, 1  # replaced once jax.distributed has started
    if num_processes is None and process_id is None:
        if coordinator is not None:
            _refuse("options", [("--coordinator", "needs --num-processes and --process-id")])
        return 0, 1
    if num_processes is None or process_id is None:
        _refuse("options", [("--num-processes", "give --num-processes and --process-id together")])
    if num_processes < 1:
        _refuse("options", [("--num-processes", f"must be >= 1, got {num_processes}")])
    if not 0 <= process_id < num_processes:
        _refuse("options", [("--process-id", f"must lie in [0, {num_processes}), got {process_id}")])
    return process_id, num_processes


def _ask_devices(jax, devices: int) -> None:
    """On CPU, make `devices` host devices visible if the backend has not started yet."""
    from jax._src import xla_bridge

    if devices < 1:
        _refuse("options", [("--devices", f"must be >= 1, got {devices}")])
    if not xla_bridge.backends_are_initialized() and devices > jax.config.jax_num_cpu_devices:
        jax.config.update("jax_num_cpu_devices", devices)


def _existing(path: Path, spec, share, overwrite: bool, sweep_io) -> tuple[bool, int | None]:
    """(resume?, stored chunk): resume a partial sweep of the same definition (from its file,
    or from its journal where a kill left the file unreadable); start afresh where there is
    none or with --overwrite; refuse a finished sweep and a different one."""
    journal = sweep_io.journal_state(path)
    if overwrite or (not path.exists() and journal is None):
        return False, None
    try:
        found = sweep_io.state(path)
    except SceneError as error:
        if journal is not None and journal["definition"] == spec.definition() and journal["share"] == share:
            return True, journal["chunk"]  # rebuilt from the journal
        _refuse("output folder", [("--output", message) for _, message in error.problems])
    if found["definition"] != spec.definition():
        _refuse("output folder", [("--output", f"{path} holds a different sweep (its stored definition, parameters/sweep.yaml, "
                                              "differs from this one); choose another folder or pass --overwrite")])
    if found["share"] != share:
        _refuse("output folder", [("--output", f"{path} was written as process {found['share'][0]} of {found['share'][1]}")])
    if found["complete"]:
        _refuse("output folder", [("--output", f"{path} holds this sweep, finished ({found['rows']} points); "
                                              "pass --overwrite to run it again")])
    return True, found["chunk"]


def merge_command(
    shards: Annotated[list[Path], typer.Argument(metavar="SHARD.h5 ...", help="shard files of one sweep", show_default=False)],
    output: Annotated[Path, typer.Option("-o", "--output", help="merged sweep file, e.g. sweep.h5", show_default=False)],
    overwrite: Annotated[bool, typer.Option("--overwrite", help="replace an existing output file")] = False,
) -> None:
    """Join the shards of a multi-process sweep into one sweep.h5 (and restitution.png beside it)."""
    from .._run import sweep as sweeping
    from .._io import sweep as sweep_io

    if output.exists() and not overwrite:
        _refuse("output file", [("--output", f"{output} exists; pass --overwrite to replace it")])
    if not output.parent.is_dir():
        _refuse("output file", [("--output", f"folder {output.parent} does not exist")])
    try:
        start = time.perf_counter()
        result = sweep_io.merge(shards, output)
    except SceneError as error:
        _refuse("cannot merge the shards", error.problems)
    sweeping.save_restitution_figure(result, output.parent / FIGURE)
    _print_summary(result, {"merge_time": time.perf_counter() - start}, f"merged sweep written to {output}")


# --- summary ----------------------------------------------------------------------------------


def _print_summary(result, stats: dict, closing: str) -> None:
    from .._run.sweep import closed_form_names, sticking_estimates

    names = result.status_names().reshape(-1)
    counts = {name: int(np.sum(names == name)) for name in (*RESULT_CODES, "not run") if np.any(names == name)}
    rows = [
        ("points", f"{result.restitution.size} ({result.spec.mode} {' × '.join(map(str, result.shape))}: "
                   f"{', '.join(result.spec.paths)})"),
        ("outcomes", ", ".join(f"{name} {count}" for name, count in counts.items())),
    ]
    if "solve_time" in stats:
        rows += [
            ("chunks", f"up to {stats['chunk']} points (calls of {', '.join(map(str, stats['call_sizes']))}) "
                       f"on {stats['devices']} device(s), {stats['groups']} compiled group(s)"),
            ("time", f"plan {stats['plan_time']:.3g} s, compile {stats['compile_time']:.3g} s, solve {stats['solve_time']:.3g} s"),
            ("speed", f"{stats['points_per_second']:,.0f} points/s (this run: {stats['points']} points)"),
        ]
        if stats.get("solved_unbatched"):
            rows.append(("unbatched", f"{stats['solved_unbatched']} points: a runtime check stopped their batch, "
                                      "so they were solved one after another (slower, same results)"))
    error = result.max_theory_error()
    rows.append(("max |e − e_theory|", "no closed form for this scene" if math.isnan(error)
                 else f"{error:.3g} ({'; '.join(closed_form_names(result))})"))
    table = Table(title=Text(f"{result.scene.name} sweep"), show_header=False)
    table.add_column(style="bold")
    table.add_column()
    for name, value in rows:
        table.add_row(Text(name), Text(value))
    _out.print(table)
    estimates = sticking_estimates(result)
    if estimates:
        sticking = Table(title=Text("sticking velocity v_s (m/s): where e leaves 0 along initial.velocity"),
                         caption=Text("closed form: where e_theory leaves 0; Δe = e − e_theory"),
                         box=box.SIMPLE_HEAD, show_edge=False, pad_edge=False)
        sticking.add_column("other axes", overflow="fold")
        for column in ("captured ≤", "separated ≥", "estimate", "closed form", "max |Δe|"):
            sticking.add_column(column, justify="right")
        for row in estimates:
            label = ", ".join(f"{p.split('.')[-1]} = {v:.4g}" for p, v in row["fixed"].items()) or "—"
            low = "none" if math.isnan(row["low"]) else f"{row['low']:.6g}"
            high = "none" if math.isnan(row["high"]) else f"{row['high']:.6g}"
            if math.isnan(row["low"]) and not math.isnan(row["high"]):
                estimate = f"< {row['high']:.6g}"
            else:
                estimate = "—" if math.isnan(row["estimate"]) else f"{row['estimate']:.6g}"
            theory = "—" if math.isnan(row["theory"]) else f"{row['theory']:.6g}"
            err = "—" if math.isnan(row["max_error"]) else f"{row['max_error']:.3g}"
            sticking.add_row(Text(label), low, high, estimate, theory, err)
        _out.print(sticking)
    failed = sum(count for name, count in counts.items() if name not in ("separated", "captured"))
    if failed:
        _err.print(Text(f"warning: {failed} point(s) ended without a physical outcome (see sweep/results/status)", "yellow"))
    _out.print(Text(closing), soft_wrap=True)
