"""Stored results back as the objects that made them, for analysis without h5py: a sweep file
as a `SweepResult` (`open_sweep`), a run file as a `Result` or `IndentationResult` (`open_run`).

Each result read back carries the versions that wrote its file in `stats["provenance"]`, which
its `to_xarray()` states instead of this process's.
"""

import dataclasses
from pathlib import Path

import h5py

from .._core.runtime import float64
from .._run.impacts import Result
from .._run.indentation import IndentationResult
from .._run.shear import ShearResult
from .._run.sweep.result import SweepResult
from .._scene.errors import SweepError
from .h5md import CONFIG, stored_provenance
from .indentation import is_indentation_run, read_indentation
from .run import read_run
from .shear import is_shear_run, read_shear
from .sweep import SWEEP_FILE, read_sweep
from .sweep_journal import journal_state

RUN_FILE = "run.h5"  # what `impact run` writes into its output folder


@float64
def open_sweep(path: str | Path) -> SweepResult:
    """A stored sweep as the `SweepResult` that `impact.sweep` returns, in the sweep's shape.

    `path`: a sweep file (`sweep.h5` of `impact sweep`, a merged file, or one process's shard),
    or the folder holding `sweep.h5`. Points the file does not hold (a sweep killed before it
    finished, another process's share) have status −1 ('not run') and NaN results. `stats` holds
    the file's attributes (rows, expected, complete, ...) and `provenance`.

    Raises `impact.SceneError` (a `SweepError`) for a missing file or one that is no sweep file
    (or, killed inside a write, a file only its journal can rebuild: the message says how).
    """
    path = _in_folder(path, SWEEP_FILE)
    try:
        result = read_sweep(path)
    except SweepError:
        journal = journal_state(path)
        if journal is None:
            raise
        done = f"its journal holds {journal['rows']} finished points"
        again = "run `impact sweep` on its sweep file again to rebuild the file from the journal and resume it"
        raise SweepError([("", f"{path} cannot be read (a sweep killed inside a write): {done}; {again}")]) from None
    result.stats["provenance"] = _provenance(path, "parameters/sweep.yaml")
    return result


@float64
def open_run(path: str | Path) -> Result | IndentationResult | ShearResult:
    """A stored run as the result `impact.simulate` returned: a `Result` for an impact, an
    `IndentationResult` for an indentation test, a `ShearResult` for a shear test (the scene
    rebuilt from the stored YAML).

    `path`: a run file (`run.h5` of `impact run`) or the folder holding `run.h5`. `stats` holds
    the solver's counts, the scales and `provenance`.

    Raises FileNotFoundError for a missing file and ValueError for a file that is no run."""
    path = _in_folder(path, RUN_FILE)
    result: Result | IndentationResult | ShearResult
    if is_shear_run(path):
        result = read_shear(path)
    else:
        result = read_indentation(path) if is_indentation_run(path) else read_run(path)
    return dataclasses.replace(result, stats={**result.stats, "provenance": _provenance(path, CONFIG)})


def open_stored(path: str | Path) -> SweepResult | Result | IndentationResult | ShearResult:
    """Whichever result a file holds: a sweep (`open_sweep`) or a run (`open_run`).

    Raises FileNotFoundError for a missing file and ValueError for a file that is no HDF5 file;
    the errors of `open_sweep` or `open_run` for one that is not what it claims."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"no such file: {path}")
    try:
        with h5py.File(path, "r") as file:
            sweep = "sweep" in file
    except OSError:
        raise ValueError(f"{path} is not an HDF5 file") from None
    return open_sweep(path) if sweep else open_run(path)


def _in_folder(path: str | Path, name: str) -> Path:
    """`path`, or the file `name` inside it where `path` is a folder."""
    path = Path(path)
    return path / name if path.is_dir() else path


def _provenance(path: Path, dataset: str) -> dict:
    with h5py.File(path, "r") as file:
        return stored_provenance(file[dataset])
