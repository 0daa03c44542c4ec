"""Crash safety of every output: a writer SIGKILLed at any moment leaves either the old file or
the new one, complete, and every writer of the package goes through `atomic_path`."""

import ast
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import h5py
import numpy as np
import pytest

from tests.scenes import ROOT

PACKAGE = ROOT / "impact"

# A child that rewrites one text file and one HDF5 file as fast as it can, each version whole
# and self-checking (its number at both ends; the HDF5 dataset filled with its number).
_WRITER = """
import sys, h5py, numpy as np
from impact._io.files import atomic_path, write_text
text_path, h5_path = sys.argv[1], sys.argv[2]
print("ready", flush=True)
version = 1
while True:
    write_text(text_path, f"{version}\\n" + "x" * 2_000_000 + f"\\n{version}\\n")
    with atomic_path(h5_path) as temporary, h5py.File(temporary, "w") as file:
        file.create_dataset("version", data=np.full(200_000, version))
    version += 1
"""


def _check_text(path: Path) -> int:
    lines = path.read_text().split("\n")
    assert len(lines) == 4 and lines[0] == lines[2] and len(lines[1]) == 2_000_000, "a torn text file"
    return int(lines[0])


def _check_h5(path: Path) -> int:
    with h5py.File(path, "r") as file:
        values = file["version"][()]
    assert values.shape == (200_000,) and np.all(values == values[0]), "a torn HDF5 file"
    return int(values[0])


@pytest.mark.slow
def test_sigkill_at_random_moments_leaves_a_whole_old_or_new_file(tmp_path):
    text_path, h5_path = tmp_path / "speed.csv", tmp_path / "fit.h5"
    text_path.write_text("0\n" + "x" * 2_000_000 + "\n0\n")
    with h5py.File(h5_path, "w") as file:
        file.create_dataset("version", data=np.zeros(200_000, int))
    environment = {**os.environ, "PYTHONPATH": str(PACKAGE.parent)}
    generator = random.Random(20261125)
    versions = []
    for _ in range(8):
        child = subprocess.Popen(
            [sys.executable, "-c", _WRITER, str(text_path), str(h5_path)],
            stdout=subprocess.PIPE,
            env=environment,
        )
        assert child.stdout is not None and child.stdout.readline() == b"ready\n"
        time.sleep(generator.uniform(0.0, 0.4))
        child.send_signal(signal.SIGKILL)
        child.wait()
        versions.append((_check_text(text_path), _check_h5(h5_path)))
    # The kills fell while writing: at least one version after the first was written each time
    # (else the test proves nothing).
    assert all(text >= 1 or h5 >= 1 for text, h5 in versions[1:]), versions


def _writes_outside_atomic_path(tree: ast.AST) -> list[int]:
    """Lines that open a file for writing, save a figure or create an HDF5 file, other than
    inside `with atomic_path(...)` or through write_text/write_bytes of `impact._io.files`."""
    protected: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.With) and any(
            isinstance(item.context_expr, ast.Call) and getattr(item.context_expr.func, "id", "") == "atomic_path"
            for item in node.items
        ):
            protected.update(range(node.lineno, (node.end_lineno or node.lineno) + 1))
    lines = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call) or node.lineno in protected:
            continue
        name = getattr(node.func, "attr", getattr(node.func, "id", ""))
        if isinstance(node.func, ast.Attribute) and name in ("write_text", "write_bytes"):
            lines.append(node.lineno)  # Path.write_*: not the atomic helpers of impact._io.files
        modes = [arg.value for arg in node.args[1:2] if isinstance(arg, ast.Constant)]
        modes += [kw.value.value for kw in node.keywords if kw.arg == "mode" and isinstance(kw.value, ast.Constant)]
        writing = any(isinstance(mode, str) and set(mode) & set("wax+") for mode in modes)
        if name in ("savefig", "to_csv", "savez", "save") or (name in ("open", "File") and writing):
            lines.append(node.lineno)
    return lines


# The writes that are not atomic by atomic_path, each safe for its own reason.
_SAFE_OTHERWISE = {
    # Appends chunks in place once the journal holds them whole; a restart repairs it from the journal.
    "_io/sweep.py",
    "_io/sweep_journal.py",  # np.savez into memory; the bytes are written by write_bytes
    "_core/stored.py",  # the exported-program cache: written whole under a .partial name, then renamed
}


def test_every_writer_of_the_package_is_atomic():
    """A file the package writes goes through atomic_path (or write_text/write_bytes, which use it),
    but for the three writers safe by other means (`_SAFE_OTHERWISE`)."""
    offenders = {}
    for module in sorted(PACKAGE.rglob("*.py")):
        if module.name == "files.py" and module.parent.name == "_io":
            continue
        lines = _writes_outside_atomic_path(ast.parse(module.read_text()))
        if lines:
            offenders[str(module.relative_to(PACKAGE))] = lines
    assert set(offenders) == _SAFE_OTHERWISE, offenders
