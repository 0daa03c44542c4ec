"""The `impact` command line (typer + rich): run, validate and show scenes.

A refusal of bad input (scene file, `--set`, output folder) exits with code 2, names the field
by its dotted path, prints no traceback and leaves nothing on disk. A simulation that ends
without a physical outcome (status other than separated or captured) is still written, and the
command exits with code 1.
"""

import copy
import math
import shutil
import time
import typing
from datetime import datetime
from pathlib import Path
from typing import Annotated, Optional

import typer
import yaml
from pydantic import BaseModel
from rich.console import Console
from rich.table import Table
from rich.text import Text

from .._core.package import __version__
from .._core import runtime
from .._run.indentation import IndentationResult
from .._io.run import read_provenance, read_run, write_run, write_text
from .._io.indentation import is_indentation_run, read_indentation, read_indentation_provenance, write_indentation
from .._plots.run import save_figures, si_prefix
from .._plots.indentation import save_indentation_figures
from .._scene.scene import Scene, SceneError, load_scene, read_yaml, scene_yaml
from .._run.simulate import Result, simulate

app = typer.Typer(
    help="Simulate adhesive impacts (MDR contact law on JAX + diffrax).",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_show_locals=False,
)
_out = Console(highlight=False)
_err = Console(stderr=True, highlight=False)

SceneArgument = Annotated[Path, typer.Argument(metavar="SCENE.yaml", help="scene YAML file", show_default=False)]
SetOption = Annotated[
    Optional[list[str]],
    typer.Option(
        "--set",
        metavar="PATH=VALUE",
        help="override a scene field by its dotted path, e.g. --set initial.velocity=0.8 (repeatable)",
        show_default=False,
    ),
]


def main() -> None:
    """Console entry point: float64 physics and whole-loop compilation (`runtime.configure`),
    then the command line."""
    runtime.configure()
    app()


def _print_version(value: bool) -> None:
    if value:
        _out.print(f"impact {__version__}")
        raise typer.Exit()


@app.callback()
def _options(
    version: Annotated[
        bool, typer.Option("--version", callback=_print_version, is_eager=True, help="print the version and exit")
    ] = False,
) -> None:
    """Simulate adhesive impacts (MDR contact law on JAX + diffrax)."""


@app.command()
def run(
    scene_file: SceneArgument,
    output: Annotated[
        Optional[Path],
        typer.Option(
            "-o", "--output", help="output folder (default: runs/<name>/<YYYYmmdd-HHMMSS>)", show_default=False
        ),
    ] = None,
    assignments: SetOption = None,
    overwrite: Annotated[bool, typer.Option("--overwrite", help="write into an existing output folder")] = False,
) -> None:
    """Run one scene; write run.h5, config.yaml and plots to an output folder."""
    scene = _scene(scene_file, assignments)
    folder = output or Path("runs") / scene.name / datetime.now().strftime("%Y%m%d-%H%M%S")
    _check_output(folder, overwrite)
    start = time.perf_counter()
    result = simulate(scene)
    wall_time = time.perf_counter() - start
    _write_outputs(result, folder, wall_time, overwrite)
    _out.print(result_table(result, wall_time))
    _out.print(Text(f"run written to {folder}"), soft_wrap=True)
    if not result.success:
        _err.print(Text(f"warning: the run ended with status {result.status!r}, not a physical outcome", "yellow"))
        raise typer.Exit(1)


@app.command()
def validate(scene_file: SceneArgument, assignments: SetOption = None) -> None:
    """Check a scene without running it; print its resolved key facts."""
    scene = _scene(scene_file, assignments)
    _out.print(Text(f"OK: {scene_file} is a valid scene", "green"), soft_wrap=True)
    _out.print(facts_table(scene))


@app.command()
def show(
    run_file: Annotated[
        Path, typer.Argument(metavar="RUN.h5", help="run.h5 written by `impact run`", show_default=False)
    ],
) -> None:
    """Print the summary of a stored run (run.h5)."""
    indentation = is_indentation_run(run_file)
    try:
        result = read_indentation(run_file) if indentation else read_run(run_file)
        provenance = (read_indentation_provenance if indentation else read_provenance)(run_file)
    except (OSError, ValueError) as error:
        _refuse(f"cannot show {run_file}", [("", str(error))])
    _out.print(result_table(result, provenance["wall_time"]))
    versions = f"jax {provenance['jax']}, diffrax {provenance['diffrax']}"
    precision = "float64" if provenance["x64"] else "float32"
    _out.print(Text(f"written by impact {provenance['impact']} ({versions}, {precision})"), soft_wrap=True)


# --- scene input and --set ------------------------------------------------------------------


def _scene(scene_file: Path, assignments: list[str] | None) -> Scene:
    """The validated scene of a file with its overrides, or a refusal (exit code 2)."""
    try:
        return load_scene(apply_overrides(read_yaml(scene_file), assignments or []))
    except SceneError as error:
        _refuse(f"{scene_file} is not a valid scene", error.problems)


def apply_overrides(data: dict, assignments: list[str]) -> dict:
    """A copy of the scene mapping with each `dotted.path=value` applied (value read as YAML).

    Raises SceneError for a malformed assignment or a path that is no field of the schema."""
    data = copy.deepcopy(data)
    for assignment in assignments:
        path, separator, text = assignment.partition("=")
        keys = path.strip().split(".")
        if not separator or not all(keys):
            raise SceneError([("--set", f"expected dotted.path=value, got {assignment!r}")])
        try:
            value = yaml.safe_load(text)
        except yaml.YAMLError:
            raise SceneError([(f"--set {path}", f"value {text!r} is not valid YAML")]) from None
        _check_field(data, keys)
        _assign(data, keys, value)
    return data


def _check_field(data: dict, keys: list[str]) -> None:
    """Refuse a dotted path that names no field of the scene schema (for the profile: of the
    shape the mapping names, if it names one)."""
    models, node = [Scene], data
    for depth, key in enumerate(keys):
        models = _of_named_shape(models, node)
        fields = [model.model_fields[key] for model in models if key in model.model_fields]
        if not fields:
            parent = ".".join(keys[:depth]) or "the scene"
            known = sorted({name for model in models for name in model.model_fields})
            hint = f"{parent} takes: {', '.join(known)}" if known else f"{parent} is a value, not a section"
            raise SceneError([("--set", f"no field {'.'.join(keys)!r} in the scene; {hint}")])
        models = [model for field in fields for model in _models_in(field.annotation)]
        node = node.get(key) if isinstance(node, dict) else None


def _models_in(annotation) -> list[type[BaseModel]]:
    """The pydantic models a field annotation admits (through Optional, unions, Annotated)."""
    if typing.get_origin(annotation) is None and isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return [annotation]
    return [model for argument in typing.get_args(annotation) for model in _models_in(argument)]


def _of_named_shape(models: list[type[BaseModel]], node) -> list[type[BaseModel]]:
    """Of several models (the profile shapes), the one whose `shape` the mapping names, if any."""
    shape = node.get("shape") if isinstance(node, dict) else None
    named = [model for model in models if shape and getattr(model.model_fields.get("shape"), "default", None) == shape]
    return named or models


def _assign(data: dict, keys: list[str], value) -> None:
    node = data
    for depth, key in enumerate(keys[:-1]):
        if node.get(key) is None:
            node[key] = {}
        if not isinstance(node[key], dict):
            raise SceneError([(".".join(keys[: depth + 1]), f"must be a mapping to --set {'.'.join(keys)}")])
        node = node[key]
    node[keys[-1]] = value


# --- output ---------------------------------------------------------------------------------


def _check_output(folder: Path, overwrite: bool) -> None:
    if folder.exists() and not folder.is_dir():
        _refuse("output folder", [("--output", f"{folder} exists and is not a folder")])
    if folder.exists() and not overwrite:
        _refuse("output folder", [("--output", f"folder {folder} exists; pass --overwrite to replace the run in it")])


def _write_outputs(result: "Result | IndentationResult", folder: Path, wall_time: float, overwrite: bool) -> None:
    """Create the folder and write config.yaml, run.h5 and the plots, each atomically; a folder
    created here is removed again if a write fails."""
    created = not folder.exists()
    try:
        folder.mkdir(parents=True, exist_ok=overwrite)
    except FileExistsError:
        _check_output(folder, overwrite)
    except OSError as error:
        _refuse("output folder", [("--output", f"cannot create {folder}: {error.strerror}")])
    try:
        write_text(folder / "config.yaml", scene_yaml(result.scene))
        if isinstance(result, IndentationResult):
            write_indentation(result, folder / "run.h5", wall_time=wall_time)
            save_indentation_figures(result, folder)
        else:
            write_run(result, folder / "run.h5", wall_time=wall_time)
            save_figures(result, folder)
    except BaseException:
        if created:
            shutil.rmtree(folder, ignore_errors=True)
        raise


# --- printing -------------------------------------------------------------------------------


def _refuse(headline: str, problems: list[tuple[str, str]]) -> typing.NoReturn:
    """Print what is wrong (dotted path: message) to stderr and exit with code 2."""
    _err.print(Text(f"error: {headline}", "bold red"), soft_wrap=True)
    for path, message in problems:
        _err.print(Text(f"  {path}: {message}" if path else f"  {message}"), soft_wrap=True)
    raise typer.Exit(2)


def quantity(value: float, unit: str) -> str:
    """A value with an SI prefix: 3.92e-8, "s" → "39.21 ns"."""
    factor, prefix = si_prefix(value)
    return f"{value * factor:.4g} {prefix}{unit}"


def result_table(result: "Result | IndentationResult", wall_time: float | None) -> Table:
    """The key results of an impact or an indentation test."""
    if isinstance(result, IndentationResult):
        return indentation_table(result, wall_time)
    return summary_table(result, wall_time)


def indentation_table(result: IndentationResult, wall_time: float | None) -> Table:
    """The pull-off (last stable state before the contact is lost) and the extremes of a test."""
    pull_off = result.pull_off

    def value(number: float, unit: str) -> str:
        return quantity(number, unit) if math.isfinite(number) else "—"

    snaps = sum(kind in ("snap_in", "snap_out") for _, kind in result.events)
    rows = [
        ("control", f"{result.scene.control} (ξ = {result.xi})"),
        ("status", result.status),
        ("pull-off force", value(pull_off.force, "N")),
        ("pull-off indentation", value(pull_off.indentation, "m")),
        ("pull-off contact radius", value(pull_off.contact_radius, "m")),
        ("max force", quantity(result.max_force, "N")),
        ("max indentation", quantity(result.max_indentation, "m")),
        ("max contact radius", quantity(result.max_contact_radius, "m")),
        ("jumps (snaps, jump-in)", str(snaps)),
        ("points", str(len(result.force))),
        ("wall time", "unknown" if wall_time is None else quantity(wall_time, "s")),
    ]
    return _table(f"{result.scene.name} (indentation)", rows)


def summary_table(result: Result, wall_time: float | None) -> Table:
    """The key results of a run (wall time in s, if known)."""
    stats = result.stats
    contact_time = result.contact_time
    rows = [
        ("restitution e", f"{result.restitution:.8g}"),
        ("stuck", "yes" if result.stuck else "no"),
        ("status", result.status),
        ("contact time", quantity(contact_time, "s") if math.isfinite(contact_time) else "∞ (never let go)"),
        ("max indentation", quantity(result.max_indentation, "m")),
        ("max force", quantity(result.max_force, "N")),
        ("min force", quantity(result.min_force, "N")),
        *([("Tabor parameter Λ", f"{result.tabor_parameter:.6g}")] if math.isfinite(result.tabor_parameter) else []),
        ("bounces (contacts)", str(result.bounces)),
        ("solver steps", f"{stats['steps']} ({stats['accepted_steps']} accepted, {stats['rejected_steps']} rejected)"),
        ("wall time", "unknown" if wall_time is None else quantity(wall_time, "s")),
    ]
    return _table(f"{result.scene.name}", rows)


def facts_table(scene: Scene) -> Table:
    """The resolved key facts of a scene, in SI units."""
    body, material, adhesion, gravity = scene.body, scene.material, scene.effects.adhesion, scene.effects.gravity
    parameters = ", ".join(f"{name} = {value:g}" if isinstance(value, float) else f"{name} = {value}"
                           for name, value in body.profile.model_dump(exclude={"shape"}).items())
    effects = []
    if scene.adhesive and adhesion.model == "maugis_dugdale":
        effects.append(
            f"Maugis–Dugdale adhesion (Δγ = {adhesion.work_of_adhesion:g} J/m², σ0 = {adhesion.adhesive_stress:.6g} Pa, "
            f"h = {adhesion.adhesion_range:.6g} m)"
        )
    elif scene.adhesive:
        effects.append(f"adhesion (Δγ = {adhesion.work_of_adhesion:g} J/m², Δγa = {adhesion.approach:g} J/m²)")
    if gravity is not None:
        effects.append(f"gravity (g = {gravity.g:g} m/s²)")
    springs = scene.contact.springs
    shape = ("shape", f"{body.profile.shape} ({parameters})")
    modulus = ("E*", f"{material.effective_modulus:.6g} Pa" + ("" if material.E_star is not None else " (from E and ν)"))
    effect_rows = [
        ("effects", ", ".join(effects) or "none (elastic Hertz/MDR contact)"),
        ("contact", "continuum" if springs == "continuum" else f"{springs} springs"),
    ]
    if scene.kind == "indentation":
        program = scene.program
        unit = "N" if scene.control == "force" else "m"
        cycles = f", {program.cycles} cycles" + ("" if program.unload_to is None else f" unloading to {program.unload_to:g} {unit}")
        rows = [
            ("kind", f"indentation, {scene.control} control"),
            shape,
            modulus,
            ("program", f"peak {program.peak:g} {unit}{cycles if program.cycles > 1 else ''}, then to pull-off"),
            *effect_rows,
        ]
        return _table(f"{scene.name} (SI units)", rows)
    density = "" if body.density is None else f" (density {body.density:g} kg/m³)"
    rows = [
        shape,
        ("mass", f"{body.resolved_mass:.6g} kg{density}"),
        modulus,
        ("initial", f"velocity {scene.initial.velocity:g} m/s, gap {scene.initial.gap:g} m"),
        *effect_rows,
        ("solver", f"{scene.solver.method}, " + (
            f"dt {scene.solver.dt:g} s" if scene.solver.method == "verlet" else f"rtol {scene.solver.rtol:g}, atol {scene.solver.atol:g}"
        )),
    ]
    return _table(f"{scene.name} (SI units)", rows)


def _table(title: str, rows: list[tuple[str, str]]) -> Table:
    table = Table(title=Text(title), show_header=False)
    table.add_column(style="bold")
    table.add_column()
    for name, value in rows:
        table.add_row(Text(name), Text(value))
    return table


def _register_commands() -> None:
    """Commands defined in their own modules: sweeps, merges of shards, the benchmark."""
    from . import bench as cli_bench
    from . import sweep as cli_sweep

    cli_sweep.register(app)
    cli_bench.register(app)


_register_commands()
