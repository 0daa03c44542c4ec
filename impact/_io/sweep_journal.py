"""The journal of a sweep file: crash-safe appends of finished chunks (`SweepWriter`).

HDF5 is not crash-safe: a SIGKILL inside a write (with small chunks most of the run is
writing) can leave the file unreadable. So `SweepWriter` first writes each chunk to a journal,
`.<name>.chunks/<first row>.npz` beside the file (each written whole, then renamed: it exists
complete or not at all), then appends it to the HDF5 file. A restart drops rows beyond `rows`,
appends the chunks the journal holds beyond them, or rebuilds an unreadable file from the
journal; a finished sweep deletes its journal.
"""

import io
import shutil
from pathlib import Path

import numpy as np
import yaml

from .._run.sweep.result import result_names
from .._scene.errors import SweepError
from .._scene.sweep_spec import SweepSpec
from .files import write_bytes
from .sweep import append_chunk, create_sweep_file, state, truncate


def journal_folder(path: Path) -> Path:
    """The journal of a sweep file: the folder `.<stem>.chunks` beside it."""
    path = Path(path)
    return path.with_name(f".{path.stem}.chunks")


class SweepWriter:
    """Appends finished chunks to a sweep file through the journal (see the module doc)."""

    def __init__(self, path: Path, plan, rows: int):
        self.path = Path(path)
        self.plan = plan
        self.rows = rows
        self.journal = journal_folder(self.path)

    @classmethod
    def start(cls, path: Path, spec: SweepSpec, plan, *, expected: int, chunk: int, share=(0, 1)) -> "SweepWriter":
        """A fresh sweep file and journal (removing old ones)."""
        path = Path(path)
        discard(path)
        journal = journal_folder(path)
        journal.mkdir()
        record = {"definition": spec.definition(), "chunk": int(chunk), "share": [int(share[0]), int(share[1])]}
        write_bytes(journal / "state.yaml", yaml.safe_dump(record, sort_keys=False).encode())
        create_sweep_file(path, spec, expected=expected, chunk=chunk, share=share)
        return cls(path, plan, 0)

    @classmethod
    def resume(cls, path: Path, spec: SweepSpec, plan, *, expected: int, chunk: int, share=(0, 1)) -> "SweepWriter":
        """Continue a partial sweep: recover rows from the journal, or rebuild from it."""
        path = Path(path)
        journal = journal_folder(path)
        chunks = _journal_chunks(journal)
        try:
            rows = truncate(path)
        except SweepError:
            create_sweep_file(path, spec, expected=expected, chunk=chunk, share=share)  # rebuilt from the journal
            rows = 0
        writer = cls(path, plan, rows)
        for start, file in chunks:
            if start >= writer.rows:
                with np.load(file) as stored:
                    points = stored["index"]
                    writer._append_h5(points, {name: stored[name] for name in result_names(spec.scene)})
        return writer

    def append(self, points: np.ndarray, results: dict) -> None:
        """Journal one finished chunk (its points and results), then append it to the file."""
        write_bytes(self.journal / f"{self.rows:012d}.npz", npz_bytes(points, results))
        self._append_h5(points, results)

    def _append_h5(self, points, results) -> None:
        self.rows = append_chunk(self.path, points, self.plan.params, results)

    def finish(self) -> None:
        """Once complete, the journal goes."""
        if state(self.path)["complete"]:
            shutil.rmtree(self.journal, ignore_errors=True)


def discard(path: Path) -> None:
    """Remove a sweep file and its journal."""
    Path(path).unlink(missing_ok=True)
    shutil.rmtree(journal_folder(path), ignore_errors=True)


def journal_state(path: Path) -> dict | None:
    """What the journal of a sweep file was started for: definition, chunk, share (None: no
    journal), and the rows it holds."""
    file = journal_folder(path) / "state.yaml"
    if not file.is_file():
        return None
    record = yaml.safe_load(file.read_text())
    return {
        "definition": record["definition"],
        "chunk": int(record["chunk"]),
        "share": tuple(record["share"]),
        "rows": journal_rows(path),
    }


def journal_rows(path: Path) -> int:
    """Rows held by the journal's contiguous chunks from row 0."""
    return sum(_rows_of(file) for _, file in _journal_chunks(journal_folder(path)))


def _rows_of(file: Path) -> int:
    with np.load(file) as stored:
        return len(stored["index"])


def _journal_chunks(journal: Path) -> list[tuple[int, Path]]:
    """(first row, file) of the contiguous journal chunks from row 0."""
    if not journal.is_dir():
        return []
    found = sorted((int(file.stem), file) for file in journal.glob("*.npz") if file.stem.isdigit())
    chunks, expected = [], 0
    for start, file in found:
        if start != expected:
            break
        chunks.append((start, file))
        expected = start + _rows_of(file)
    return chunks


def npz_bytes(points: np.ndarray, results: dict) -> bytes:
    """One journal chunk: the points (`index`) and their results, as the bytes of an .npz file."""
    buffer = io.BytesIO()
    np.savez(buffer, index=points, **results)
    return buffer.getvalue()
