"""The output folder of a command: checked before any work, or a fresh one made for it, created
for the writing, and removed again where the writing fails."""

import os
import shutil
from collections.abc import Iterator
from contextlib import contextmanager
from datetime import datetime
from pathlib import Path

from .console import refuse


def check_output(folder: Path, overwrite: bool, holds: str = "run") -> None:
    """Refuse, before any work, an output folder that cannot take the `holds` (run, benchmark): a
    file in its place or in place of a parent, an unwritable place, or an existing folder
    without --overwrite."""
    if folder.exists() and not folder.is_dir():
        refuse("output folder", [("--output", f"{folder} exists and is not a folder")])
    if folder.exists() and not overwrite:
        refuse(
            "output folder", [("--output", f"folder {folder} exists; pass --overwrite to replace the {holds} in it")]
        )
    nearest = next(place for place in (folder.absolute(), *folder.absolute().parents) if place.exists())
    if not nearest.is_dir():
        refuse("output folder", [("--output", f"cannot create {folder}: {nearest} is a file, not a folder")])
    if not os.access(nearest, os.W_OK | os.X_OK):
        refuse("output folder", [("--output", f"cannot create {folder}: {nearest} is not writable")])


def make_folder(folder: Path, exist_ok: bool, holds: str = "run") -> None:
    """Create the output folder (and its parents); an existing one only where `exist_ok`. Refused
    as `check_output` says where one has taken its place since, else with the system's reason."""
    try:
        folder.mkdir(parents=True, exist_ok=exist_ok)
    except FileExistsError:
        check_output(folder, exist_ok, holds)
    except OSError as error:
        refuse("output folder", [("--output", f"cannot create {folder}: {error.strerror}")])


@contextmanager
def removed_on_failure(folder: Path, created: bool = False) -> Iterator[None]:
    """A folder that does not exist yet (or was `created` for this command by `fresh_folder`) is
    removed again, with what the block wrote into it, if the block fails or is interrupted: no
    half-written output is left."""
    created = created or not folder.exists()
    try:
        yield
    except BaseException:
        if created:
            shutil.rmtree(folder, ignore_errors=True)
        raise


def check_output_file(path: Path, option: str) -> None:
    """Refuse, before any work, a file `option` cannot write: a folder in its place, or a parent
    folder that is missing or not writable (an existing file is replaced)."""
    if path.is_dir():
        refuse("output file", [(option, f"{path} is a folder, not a file")])
    parent = path.absolute().parent
    if not parent.is_dir():
        refuse("output file", [(option, f"cannot write {path}: folder {parent} does not exist")])
    if not os.access(parent, os.W_OK | os.X_OK):
        refuse("output file", [(option, f"cannot write {path}: {parent} is not writable")])


def fresh_folder(parent: Path) -> Path:
    """A new folder parent/<YYYYmmdd-HHMMSS> of this second, made here: parent/<…>-2, -3, … where
    another command took that name first (mkdir is atomic, so commands started together each
    get their own). A place that cannot take it is refused (exit code 2)."""
    stem, number = datetime.now().strftime("%Y%m%d-%H%M%S"), 1
    while True:
        folder = parent / (stem if number == 1 else f"{stem}-{number}")
        try:
            folder.mkdir(parents=True)
            return folder
        except FileExistsError:
            number += 1
        except OSError as error:
            refuse("output folder", [("", f"cannot create {folder}: {error.strerror}")])
