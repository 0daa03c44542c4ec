"""A sweep in an HDF5 file (after H5MD 1.1, as `impact._io.run`), written chunk by chunk.

Layout (values SI, `unit` attributes where dimensioned):

    h5md/                         version [1, 1], author, creator, modules/units (SI)
    parameters/
        scene.yaml                the resolved base scene (string)
        sweep.yaml                the resolved sweep definition: base scene inline, axes, mode,
                                  order (string; a resumed or merged sweep must match it)
        source.yaml               the sweep file as written (string; absent for the API)
    sweep/                        attrs: mode, shape, points (N of the whole sweep), rows (written
                                  here), expected (rows this file will hold), complete, chunk,
                                  process_index, process_count, result_codes, timings, method
                                  (the integrator every point ran) and method_choice (why)
        axes/<dotted.path>        the values of each axis (1-D), `unit` where dimensioned
        index[R]                  flat index (C order of `shape`) of the point in each row
        params/<dotted.path>[R]   the swept values of each row (`unit` as the axis)
        results/<name>[R]         restitution, stuck, status (result code), contact_time, ...;
                                  plastic_work, viscous_work, adhesion_hysteresis where the
                                  scene names plasticity, damping, adhesion; body_velocity_after
                                  and counterpart_velocity_after where it names a counterpart

Rows follow the processing order (group by group, by expected cost), so `index` maps them back
to the grid; `read_sweep` returns arrays in the sweep's shape. Every dataset along R is
resizable, chunked and compressed. A chunk of points is appended by opening the file, resizing,
writing, setting `rows` last and closing it, so the file on disk is closed and consistent
while the next chunk computes. A running sweep writes through a journal (`sweep_journal`).
"""

from contextlib import contextmanager
from dataclasses import replace
from pathlib import Path

import h5py
import numpy as np
import yaml

from .._integrate.codes import RESULT_CODES
from .._run.sweep.plan import plan_sweep
from .._run.sweep.result import RESULTS, SweepResult, empty_results, result_names
from .._scene.errors import SweepError
from .._scene.scene import scene_yaml
from .._scene.sweep import make_spec
from .._scene.sweep_spec import SweepSpec
from .files import atomic_path
from .h5md import new_h5md, read_string, stamp_provenance, write_string

SWEEP_FILE = "sweep.h5"
_COMPRESSION = dict(compression="gzip", compression_opts=4, shuffle=True)
_MAX_CHUNK_ROWS = 8192


def shard_name(index: int, count: int) -> str:
    """File of process `index` of `count` (a single process writes SWEEP_FILE)."""
    return SWEEP_FILE if count == 1 else f"shard-{index:03d}-of-{count:03d}.h5"


def create_sweep_file(path: Path, spec: SweepSpec, *, expected: int, chunk: int, share=(0, 1)) -> None:
    """A new sweep file with empty resizable datasets (written atomically)."""
    path = Path(path)
    rows_per_chunk = max(1, min(chunk, _MAX_CHUNK_ROWS))
    with new_h5md(path) as file:
        parameters = file.create_group("parameters")
        write_string(parameters, "scene.yaml", scene_yaml(spec.scene))
        stamp_provenance(write_string(parameters, "sweep.yaml", spec.definition()))
        if spec.source is not None:
            write_string(parameters, "source.yaml", spec.source)
        group = file.create_group("sweep")
        group.attrs.update(
            mode=spec.mode,
            order=spec.order,
            shape=np.array(spec.shape, dtype=np.int64),
            paths=np.array(spec.paths, dtype=h5py.string_dtype()),
            points=np.int64(spec.size),
            rows=np.int64(0),
            expected=np.int64(expected),
            complete=expected == 0,
            chunk=np.int64(chunk),
            process_index=np.int64(share[0]),
            process_count=np.int64(share[1]),
            result_codes=np.array(RESULT_CODES, dtype=h5py.string_dtype()),
            method=spec.method,
            method_choice=spec.method_choice,
        )
        axes = group.create_group("axes")
        for axis in spec.axes:
            _unit(axes.create_dataset(axis.path, data=axis.values), axis.unit)
        _column(group, "index", np.int64, rows_per_chunk).attrs["description"] = (
            "flat index (C order of shape) of each row's point"
        )
        params = group.create_group("params")
        for axis in spec.axes:
            _unit(_column(params, axis.path, axis.values.dtype, rows_per_chunk), axis.unit)
        results = group.create_group("results")
        for name in result_names(spec.scene):
            dtype, _, unit, description = RESULTS[name]
            dataset = _column(results, name, dtype, rows_per_chunk)
            dataset.attrs["description"] = description
            _unit(dataset, unit)


def _unit(dataset: h5py.Dataset, unit: str) -> None:
    if unit:
        dataset.attrs["unit"] = unit


def _column(group: h5py.Group, name: str, dtype, rows_per_chunk: int) -> h5py.Dataset:
    return group.create_dataset(
        name, shape=(0,), maxshape=(None,), dtype=dtype, chunks=(rows_per_chunk,), **_COMPRESSION
    )


def _datasets(group: h5py.Group):
    yield group["index"]
    yield from group["params"].values()
    yield from group["results"].values()


def append_chunk(path: Path, points: np.ndarray, params: dict, results: dict) -> int:
    """Append the rows of one finished chunk; returns the rows now in the file."""
    with h5py.File(path, "r+") as file:
        group = file["sweep"]
        start = int(group.attrs["rows"])
        stop = start + len(points)
        columns = {
            "index": points,
            **{f"params/{p}": v[points] for p, v in params.items()},
            **{f"results/{n}": v for n, v in results.items()},
        }
        for name, values in columns.items():
            dataset = group[name]
            dataset.resize((stop,))
            dataset[start:stop] = values
        group.attrs["rows"] = np.int64(stop)
        group.attrs["complete"] = stop >= int(group.attrs["expected"])
        file.flush()
    return stop


def set_attributes(path: Path, **attributes) -> None:
    with h5py.File(path, "r+") as file:
        file["sweep"].attrs.update(attributes)


@contextmanager
def _open_sweep(path: Path, mode: str = "r"):
    path = Path(path)
    if not path.is_file():
        raise SweepError([("", f"no such file: {path}")])
    try:
        file = h5py.File(path, mode)
    except OSError as error:
        raise SweepError(
            [("", f"{path} is not a readable HDF5 file ({error}); remove it or pass --overwrite")]
        ) from None
    with file:
        if "sweep" not in file or "parameters/sweep.yaml" not in file:
            raise SweepError([("", f"{path} is not an impact sweep file (no sweep group or parameters/sweep.yaml)")])
        yield file


def state(path: Path) -> dict:
    """What a sweep file holds: definition, rows, expected, complete, chunk, share."""
    with _open_sweep(path) as file:
        group = file["sweep"]
        return {
            "definition": read_string(file["parameters/sweep.yaml"]),
            "rows": int(group.attrs["rows"]),
            "expected": int(group.attrs["expected"]),
            "complete": bool(group.attrs["complete"]),
            "chunk": int(group.attrs["chunk"]),
            "share": (int(group.attrs["process_index"]), int(group.attrs["process_count"])),
        }


def truncate(path: Path) -> int:
    """Drop rows beyond `rows` (a write cut short); returns `rows`."""
    with _open_sweep(path, "r+") as file:
        group = file["sweep"]
        rows = int(group.attrs["rows"])
        for dataset in _datasets(group):
            if dataset.shape[0] != rows:
                dataset.resize((rows,))
        file.flush()
    return rows


def read_spec(path: Path) -> SweepSpec:
    """The sweep definition stored in a file, with the reason for its method where the file holds it
    (its definition names the method that ran)."""
    with _open_sweep(path) as file:
        spec = spec_from_definition(
            read_string(file["parameters/sweep.yaml"]),
            read_string(file["parameters/source.yaml"]) if "parameters/source.yaml" in file else None,
        )
        choice = file["sweep"].attrs.get("method_choice")
    return spec if choice is None else replace(spec, method_choice=str(choice))


def spec_from_definition(definition: str, source: str | None = None) -> SweepSpec:
    data = yaml.safe_load(definition)
    spec = make_spec(data["scene"], data["axes"], data["mode"], data["order"])
    return replace(spec, source=source)


def _rows(file: h5py.File) -> tuple[np.ndarray, dict, dict]:
    group = file["sweep"]
    rows = int(group.attrs["rows"])
    index = group["index"][:rows]
    params = {name: dataset[:rows] for name, dataset in group["params"].items()}
    results = {name: dataset[:rows] for name, dataset in group["results"].items()}
    return index, params, results


def read_sweep(path: Path, spec: SweepSpec | None = None) -> SweepResult:
    """A stored sweep (or shard) as a SweepResult in the sweep's shape; points not in the file
    have status -1 and NaN results. `stats` holds the file's attributes (rows, complete, ...).

    `spec`: the sweep the caller has just written the file from (`impact sweep`): its points
    are then not validated a second time."""
    if spec is None:
        spec = read_spec(path)
    with _open_sweep(path) as file:
        index, _, stored = _rows(file)
        attributes = {key: _plain(value) for key, value in file["sweep"].attrs.items()}
    results = empty_results(spec.size, result_names(spec.scene))
    for name, column in results.items():
        if name in stored:  # a file written before the column existed lacks it
            column[index] = stored[name]
    return SweepResult.from_flat(spec, spec.flat_params(), results, attributes)


def _plain(value):
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    return value


def merge(paths: list[Path], output: Path) -> SweepResult:
    """Join the complete shards of one sweep into one file, rows in the processing order of a
    single-process run (so the merged file equals the one a single process would write)."""
    if not paths:
        raise SweepError([("SHARD.h5", "name at least one shard file")])
    states = [state(path) for path in paths]
    definition = states[0]["definition"]
    problems = []
    for path, entry in zip(paths, states, strict=True):
        if entry["definition"] != definition:
            problems.append((str(path), f"holds another sweep than {paths[0]} (its parameters/sweep.yaml differs)"))
        if not entry["complete"]:
            done = f"{entry['rows']} of {entry['expected']} points"
            problems.append((str(path), f"is not complete ({done}); run its process again to resume it"))
    counts = {entry["share"][1] for entry in states}
    indices = sorted(entry["share"][0] for entry in states)
    if len(counts) > 1:
        problems.append(("SHARD.h5", f"the shards come from runs with different process counts: {sorted(counts)}"))
    elif indices != list(range(counts.pop())):
        expected = states[0]["share"][1]
        missing = sorted(set(range(expected)) - set(indices))
        duplicated = sorted({i for i in indices if indices.count(i) > 1})
        detail = (f"missing process(es) {missing}" if missing else "") + (
            f" duplicated process(es) {duplicated}" if duplicated else ""
        )
        problems.append(("SHARD.h5", f"expected the shards of all {expected} processes: {detail.strip()}"))
    if problems:
        raise SweepError(problems)
    spec = read_spec(paths[0])
    parts = []
    for path in paths:
        with _open_sweep(path) as file:
            parts.append(_rows(file))
    index = np.concatenate([part[0] for part in parts])
    if len(index) != spec.size or len(np.unique(index)) != spec.size:
        raise SweepError([("SHARD.h5", f"the shards hold {len(np.unique(index))} distinct of {spec.size} points")])
    plan = plan_sweep(spec)
    rank = np.empty(spec.size, dtype=np.int64)
    rank[plan.order] = np.arange(spec.size)
    order = np.argsort(rank[index])
    names = result_names(spec.scene)
    results = {name: np.concatenate([part[2][name] for part in parts])[order] for name in names}
    points = index[order]
    chunk = states[0]["chunk"]
    with atomic_path(output) as temporary:
        create_sweep_file(temporary, spec, expected=spec.size, chunk=chunk)
        append_chunk(temporary, points, plan.params, results)
        set_attributes(temporary, merged_from=np.array([str(p) for p in paths], dtype=h5py.string_dtype()))
    flat = empty_results(spec.size, names)
    for name in names:
        flat[name][points] = results[name]
    return SweepResult.from_flat(spec, plan.params, flat, {"points": spec.size, "merged_from": [str(p) for p in paths]})
