"""`impact run`, `impact validate` and `impact show`: one scene on the command line (declared in
`commands`).

A refusal of bad input (scene file, `--set`, output folder) exits with code 2, names the field
by its dotted path, prints no traceback and leaves nothing on disk. A simulation that ends
without a physical outcome (status other than separated or captured) is still written, and
`impact run` exits with code 1.
"""

import time
from pathlib import Path
from typing import TYPE_CHECKING

import typer
from rich.text import Text

from .._integrate.codes import REMEDIES
from .._io.files import write_text
from .._plots.figures import import_ahead
from .._plots.run import save_figures
from .._run.impacts import Result
from .._run.simulate import simulate
from .._scene.errors import SceneError
from .._scene.overrides import apply_overrides
from .._scene.reading import read_yaml
from .._scene.scene import Scene, load_scene, scene_yaml
from .console import out, refuse, say, warn
from .folders import check_output, fresh_folder, make_folder, removed_on_failure
from .long_runs import interruptible
from .tables import facts_table, result_table

if TYPE_CHECKING:
    from .._run.indentation import IndentationResult
    from .._run.shear import ShearResult

RUN_FILE = "run.h5"  # the file of a run in its folder

# Indentation tests' modules (their quasi-static march, files and figures) are imported where a
# run is one: an impact's run loads none of them; h5py is imported where a run is written or shown.


def run_scene(scene_file: Path, output: Path | None, assignments: list[str] | None, overwrite: bool) -> None:
    """`impact run`: run one scene; write run.h5, config.yaml and plots to an output folder."""
    scene = scene_of(scene_file, assignments)
    if output is not None:
        check_output(output, overwrite)
    import_ahead()  # matplotlib, for the figures, while the run loads and computes
    start = time.perf_counter()
    result = interruptible(lambda: simulate(scene))
    wall_time = time.perf_counter() - start
    folder = output or fresh_folder(Path("runs") / scene.name)
    write_outputs(result, folder, wall_time, overwrite, created=output is None)
    out.print(result_table(result, wall_time))
    say(f"run written to {folder}")
    if not result.success:
        remedy = REMEDIES.get(result.status)
        warn(f"warning: the run ended with status {result.status!r}, not a physical outcome")
        if remedy is not None:
            warn(f"  {result.status}: {remedy}")
        raise typer.Exit(1)


def validate_scene(scene_file: Path, assignments: list[str] | None) -> None:
    """`impact validate`: check a scene without running it; print its resolved key facts."""
    scene = scene_of(scene_file, assignments)
    out.print(Text(f"OK: {scene_file} is a valid scene", "green"), soft_wrap=True)
    out.print(facts_table(scene))


def show_run(run_file: Path) -> None:
    """`impact show`: print the summary of a stored run (run.h5, or the run folder holding it)."""
    from .._io.h5md import read_provenance
    from .._io.indentation import is_indentation_run, read_indentation, read_indentation_provenance
    from .._io.run import read_run
    from .._io.shear import is_shear_run, read_shear, read_shear_provenance

    if run_file.is_dir():
        if not (run_file / RUN_FILE).is_file():
            refuse(f"cannot show {run_file}", [("", f"{run_file} is a folder without a {RUN_FILE}")])
        run_file = run_file / RUN_FILE
    result: Result | IndentationResult | ShearResult
    try:
        if is_indentation_run(run_file):
            result, provenance = read_indentation(run_file), read_indentation_provenance(run_file)
        elif is_shear_run(run_file):
            result, provenance = read_shear(run_file), read_shear_provenance(run_file)
        else:
            result, provenance = read_run(run_file), read_provenance(run_file)
    except (OSError, ValueError) as error:
        refuse(f"cannot show {run_file}", [("", str(error))])
    out.print(result_table(result, provenance["wall_time"]))
    versions = f"jax {provenance['jax']}, diffrax {provenance['diffrax']}"
    precision = "float64" if provenance["x64"] else "float32"
    say(f"written by impact {provenance['impact']} ({versions}, {precision})")


# --- scene input and --set ------------------------------------------------------------------


def scene_of(scene_file: Path, assignments: list[str] | None) -> Scene:
    """The validated scene of a file with its overrides, or a refusal (exit code 2)."""
    try:
        return load_scene(apply_overrides(read_yaml(scene_file), assignments or []))
    except SceneError as error:
        refuse(f"{scene_file} is not a valid scene", error.problems)


# --- output ---------------------------------------------------------------------------------


def write_outputs(
    result: "Result | IndentationResult | ShearResult",
    folder: Path,
    wall_time: float,
    overwrite: bool,
    created: bool = False,
) -> None:
    """Create the folder (`created`: made already, by `fresh_folder`) and write config.yaml,
    run.h5 and the plots, each atomically; a folder created for them is removed again if a write
    fails or is interrupted."""
    with removed_on_failure(folder, created):
        if not created:
            make_folder(folder, exist_ok=overwrite)
        write_text(folder / "config.yaml", scene_yaml(result.scene))
        if isinstance(result, Result):
            from .._io.run import write_run

            write_run(result, folder / RUN_FILE, wall_time=wall_time)
            save_figures(result, folder)
            if result.scene.effects.friction is not None:
                from .._plots.oblique import save_run_tangential_figure

                save_run_tangential_figure(result, folder)
        else:
            from .._run.shear import ShearResult  # a shear test's or an indentation's: not loaded for an impact's

            if isinstance(result, ShearResult):
                from .._io.shear import write_shear
                from .._plots.shear import save_shear_figures

                write_shear(result, folder / "run.h5", wall_time=wall_time)
                save_shear_figures(result, folder)
            else:
                from .._io.indentation import write_indentation
                from .._plots.indentation import save_indentation_figures

                write_indentation(result, folder / RUN_FILE, wall_time=wall_time)
                save_indentation_figures(result, folder)
