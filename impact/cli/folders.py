"""The output folder of a command: checked before any work, or a fresh one made for it."""

import os
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
