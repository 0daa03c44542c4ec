"""Sweep files: a base scene and axes over its numeric fields, validated into a `SweepSpec`.

A sweep file is a YAML mapping::

    scene: thornton_ning.yaml        # a path relative to the sweep file, or an inline scene mapping
    set: {solver.rtol: 1.0e-9}       # optional: base-scene fields changed by dotted path
    axes:                            # dotted paths of numeric scene fields
      initial.velocity: {geomspace: [0.2, 20.0, 400]}   # also linspace, logspace, or a list
      effects.adhesion.work_of_adhesion: [0.02, 0.05, 0.1]
    mode: grid                       # grid (default: every combination) or zip (axes side by side)
    order: cost                      # cost (default: bucket points by expected cost) or given

Every problem is reported as a `SweepError` (a `SceneError`) whose `problems` name the field by
its dotted path: `axes.<path>` for an axis, `scene.<path>` for the base scene. Validation is
exact and cheap: each axis' values through the field's own validator (`sweep_axes`), then every
point through the validators of the sections on its paths (`sweep_points`).
"""

import copy
import math
from collections.abc import Mapping
from dataclasses import replace
from pathlib import Path

from .cost import check_sweep_cost
from .errors import FieldProblem, SceneError, SweepError
from .paths import NotASection, assign
from .reading import parse_yaml, read_text, read_yaml
from .scene import Scene, load_scene
from .sweep_axes import build_axis
from .sweep_method import with_sweep_method
from .sweep_spec import MODES, ORDERS, SweepSpec

SWEEP_KEYS = ("scene", "set", "axes", "mode", "order")


def load_sweep(source: "str | Path | Mapping") -> SweepSpec:
    """A validated sweep from a YAML file (its `scene` path relative to the file) or a mapping."""
    text, folder = None, Path.cwd()
    if isinstance(source, Mapping):
        data = dict(source)
    else:
        path = Path(source)
        try:
            text, folder = read_text(path), path.parent
            data = parse_yaml(text, str(path))
        except SceneError as error:
            raise SweepError(error.problems) from None
        if not isinstance(data, dict):
            raise SweepError([("", f"{path} must hold a mapping with the keys {', '.join(SWEEP_KEYS)}")])
    problems = [
        (str(key), f"unknown key; a sweep file takes: {', '.join(SWEEP_KEYS)}") for key in data if key not in SWEEP_KEYS
    ]
    problems += [(key, "missing (required)") for key in ("scene", "axes") if key not in data]
    if problems:
        raise SweepError(problems)
    scene = _base_scene(data["scene"], folder, data.get("set") or {})
    if not isinstance(data["axes"], Mapping):
        raise SweepError([("axes", "must be a mapping of dotted.path: values")])
    spec = make_spec(scene, data["axes"], data.get("mode", "grid"), data.get("order", "cost"))
    return replace(spec, source=text)


def _base_scene(entry, folder: Path, changes) -> Scene:
    """The base scene from a path (relative to the sweep file) or a mapping, with the `set`
    changes (dotted path: value) applied before validation."""
    if isinstance(entry, Mapping):
        where, data = "the inline scene", copy.deepcopy(dict(entry))
    elif isinstance(entry, str):
        where = str(folder / entry)
        try:
            data = read_yaml(folder / entry)
        except SceneError as error:
            raise SweepError([("scene", message) for _, message in error.problems]) from None
    else:
        raise SweepError([("scene", "expected a scene file path (relative to the sweep file) or a scene mapping")])
    if not isinstance(changes, Mapping):
        raise SweepError([("set", "must be a mapping of dotted.path: value")])
    for path, value in changes.items():
        try:
            assign(data, str(path).split("."), value)
        except NotASection as error:
            raise SweepError([(f"set.{path}", str(error))]) from None
    try:
        return load_scene(data)
    except SceneError as error:
        problems = []
        for path, message in error.problems:
            problems.append((f"scene.{path}" if path else "scene", f"{message} (in {where})" if path else message))
        raise SweepError(problems) from None


def make_spec(scene, axes: Mapping, mode: str = "grid", order: str = "cost") -> SweepSpec:
    """Validate axes (dotted path → values or generator) over a base scene into a SweepSpec, with
    the method its points run (`sweep_method`: the scene's where it names one, else the quadrature
    where every point allows it)."""
    try:
        scene = load_scene(scene)
    except SceneError as error:
        raise SweepError(
            [(f"scene.{path}" if path else "scene", message) for path, message in error.problems]
        ) from None
    problems = []
    kind = getattr(scene, "kind", "impact")
    if kind != "impact":
        raise SweepError([("scene.kind", f"a sweep runs impacts; the base scene is of kind {kind!r}")])
    if mode not in MODES:
        problems.append(("mode", f"expected one of {', '.join(MODES)}, got {mode!r}"))
    if order not in ORDERS:
        problems.append(("order", f"expected one of {', '.join(ORDERS)}, got {order!r}"))
    if not isinstance(axes, Mapping) or not axes:
        problems.append(("axes", "name at least one field to sweep, e.g. initial.velocity: [0.5, 1.0]"))
    if problems:
        raise SweepError(problems)
    try:  # before any value is made: a grid of 10⁷ × 10⁷ is refused at once
        check_sweep_cost(_points_written(axes.values(), mode))
    except FieldProblem as error:
        raise SweepError([(error.field, str(error))]) from None
    built = []
    for path, entry in axes.items():
        try:
            built.append(build_axis(scene, str(path), entry))
        except SweepError as error:
            problems += error.problems
    if problems:
        raise SweepError(problems)
    if mode == "zip":
        lengths = {axis.path: len(axis.values) for axis in built}
        if len(set(lengths.values())) > 1:
            listed = ", ".join(f"{path} has {length}" for path, length in lengths.items())
            raise SweepError([("axes", f"zip mode needs axes of equal length: {listed}")])
    return with_sweep_method(SweepSpec(scene, tuple(built), mode, order))


def _points_written(entries, mode: str) -> int:
    """The points the axes' entries ask for as written (a list's length, a generator's num; 1 for
    an entry that names none, which `build_axis` refuses): the longest axis in zip mode, their
    product in a grid."""
    counts = []
    for entry in entries:
        count = len(entry) if isinstance(entry, (list, tuple)) else 1
        if isinstance(entry, Mapping) and len(entry) == 1:
            arguments = next(iter(entry.values()))
            if isinstance(arguments, (list, tuple)) and len(arguments) == 3 and isinstance(arguments[2], (int, float)):
                count = max(int(arguments[2]), 1) if math.isfinite(arguments[2]) else 1
        counts.append(count)
    return max(counts, default=1) if mode == "zip" else math.prod(counts)
