"""The output folder of a command, checked before any work."""

import os
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
