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
its dotted path: `axes.<path>` for an axis, `scene.<path>` for the base scene.

Validation is exact and cheap: each axis' values go through the field's own pydantic validator
in one call (bounds, numeric strings, integers), then every point of the sweep through the
model validators (`mode="after"`) of the sections on its paths, on a copy of the base scene
(a few µs a point instead of a full `Scene.model_validate`); this is what a full validation
would check, as the rest of the scene is the already valid base. Models with other kinds of
validators fall back to a full validation per point.
"""

import copy
import math
import typing
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated

import numpy as np
import yaml
from pydantic import BaseModel, TypeAdapter, ValidationError

from .scene import Scene, SceneError, load_scene, problems_of, read_yaml, scene_yaml

MODES = ("grid", "zip")
ORDERS = ("cost", "given")
GENERATORS = ("linspace", "geomspace", "logspace")
SWEEP_KEYS = ("scene", "set", "axes", "mode", "order")
# Fields that feed `simulate.numerics_for` (static choices: a new value compiles anew) sit
# under these sections; every other numeric field is a traced parameter of `Physics`.
STATIC_SECTIONS = ("solver", "limits", "contact", "effects")
_MAX_LISTED = 4


class SweepError(SceneError):
    """A sweep that cannot be run; `problems` lists (dotted.path, message) pairs."""


@dataclass(frozen=True)
class Axis:
    """One swept field: its dotted path, its validated values and how they were written."""

    path: str
    values: np.ndarray  # 1-D, float64 (or int64 for integer fields)
    spec: object = field(repr=False)  # canonical form: a list, or {generator: [start, stop, num]}

    @property
    def static(self) -> bool:
        """Whether the field may change the static choices (`Numerics`) of a point."""
        return self.path.split(".")[0] in STATIC_SECTIONS


@dataclass(frozen=True)
class SweepSpec:
    """A validated sweep: the base scene, its axes, how they combine and in what order to run."""

    scene: Scene
    axes: tuple[Axis, ...]
    mode: str = "grid"
    order: str = "cost"
    source: str | None = field(default=None, repr=False, compare=False)  # verbatim file text

    @property
    def shape(self) -> tuple[int, ...]:
        if self.mode == "zip":
            return (len(self.axes[0].values),)
        return tuple(len(axis.values) for axis in self.axes)

    @property
    def size(self) -> int:
        return math.prod(self.shape)

    @property
    def paths(self) -> tuple[str, ...]:
        return tuple(axis.path for axis in self.axes)

    def flat_params(self) -> dict[str, np.ndarray]:
        """Every swept value per point, flat in C order of `shape`."""
        if self.mode == "zip":
            return {axis.path: axis.values.copy() for axis in self.axes}
        grids = np.meshgrid(*(axis.values for axis in self.axes), indexing="ij")
        return {axis.path: grid.reshape(-1) for axis, grid in zip(self.axes, grids)}

    def definition(self) -> str:
        """The canonical sweep YAML (base scene resolved inline): equal texts, equal sweeps."""
        data = {
            "scene": yaml.safe_load(scene_yaml(self.scene)),
            "axes": {axis.path: axis.spec for axis in self.axes},
            "mode": self.mode,
            "order": self.order,
        }
        return yaml.safe_dump(data, sort_keys=False)


# --- reading ---------------------------------------------------------------------------------


def load_sweep(source: "str | Path | Mapping") -> SweepSpec:
    """A validated sweep from a YAML file (its `scene` path relative to the file) or a mapping."""
    text, folder = None, Path.cwd()
    if isinstance(source, Mapping):
        data = dict(source)
    else:
        path = Path(source)
        if not path.is_file():
            raise SweepError([("", f"no such file: {path}")])
        text, folder = path.read_text(), path.parent
        try:
            data = yaml.safe_load(text)
        except yaml.YAMLError as error:
            raise SweepError([("", f"invalid YAML in {path}: {error}")]) from None
        if not isinstance(data, dict):
            raise SweepError([("", f"{path} must hold a mapping with the keys {', '.join(SWEEP_KEYS)}")])
    problems = [(str(key), f"unknown key; a sweep file takes: {', '.join(SWEEP_KEYS)}")
                for key in data if key not in SWEEP_KEYS]
    problems += [(key, "missing (required)") for key in ("scene", "axes") if key not in data]
    if problems:
        raise SweepError(problems)
    scene = _base_scene(data["scene"], folder, data.get("set") or {})
    if not isinstance(data["axes"], Mapping):
        raise SweepError([("axes", "must be a mapping of dotted.path: values")])
    spec = make_spec(scene, data["axes"], data.get("mode", "grid"), data.get("order", "cost"))
    return SweepSpec(spec.scene, spec.axes, spec.mode, spec.order, source=text)


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
        node, keys = data, str(path).split(".")
        for depth, key in enumerate(keys[:-1]):
            if node.get(key) is None:
                node[key] = {}
            if not isinstance(node[key], dict):
                raise SweepError([(f"set.{path}", f"{'.'.join(keys[: depth + 1])} is a value, not a section")])
            node = node[key]
        node[keys[-1]] = value
    try:
        return load_scene(data)
    except SceneError as error:
        problems = []
        for path, message in error.problems:
            problems.append((f"scene.{path}" if path else "scene", f"{message} (in {where})" if path else message))
        raise SweepError(problems) from None


def make_spec(scene, axes: Mapping, mode: str = "grid", order: str = "cost") -> SweepSpec:
    """Validate axes (dotted path → values or generator) over a base scene into a SweepSpec."""
    try:
        scene = load_scene(scene)
    except SceneError as error:
        raise SweepError([(f"scene.{path}" if path else "scene", message) for path, message in error.problems]) from None
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
    built = []
    for path, entry in axes.items():
        try:
            built.append(_axis(scene, str(path), entry))
        except SweepError as error:
            problems += error.problems
    if problems:
        raise SweepError(problems)
    if mode == "zip":
        lengths = {axis.path: len(axis.values) for axis in built}
        if len(set(lengths.values())) > 1:
            listed = ", ".join(f"{path} has {length}" for path, length in lengths.items())
            raise SweepError([("axes", f"zip mode needs axes of equal length: {listed}")])
    spec = SweepSpec(scene, tuple(built), mode, order)
    check_points(spec)
    return spec


# --- one axis --------------------------------------------------------------------------------


def _axis(scene: Scene, path: str, entry) -> Axis:
    where = f"axes.{path}"
    owner, name = resolve_field(scene, path)
    raw, spec = _raw_values(where, entry)
    info = type(owner).model_fields[name]
    item = Annotated.__class_getitem__((info.annotation, *info.metadata)) if info.metadata else info.annotation
    adapter = TypeAdapter(list[item])
    try:
        values = adapter.validate_python(raw)
    except ValidationError as error:
        listed = []
        for item in error.errors()[:_MAX_LISTED]:
            index = item["loc"][0] if item["loc"] else "?"
            message = item["msg"].removeprefix("Value error, ")
            listed.append(f"value {item['input']!r} (#{index}): {message}")
        more = len(error.errors()) - len(listed)
        raise SweepError([(where, "; ".join(listed) + (f"; and {more} more" if more > 0 else ""))]) from None
    if any(value is None or isinstance(value, str) for value in values):
        raise SweepError([(where, "every value must be a number")])
    integer = all(isinstance(value, int) for value in values)
    array = np.asarray(values, dtype=np.int64 if integer else np.float64)
    if integer and isinstance(spec, list):
        spec = [int(value) for value in array]
    return Axis(path, array, spec)


def _raw_values(where: str, entry):
    """(values, canonical spec) of an axis entry: a list of numbers or one generator."""
    if isinstance(entry, np.ndarray):
        if entry.ndim != 1:
            raise SweepError([(where, f"expected a 1-D array of values, got shape {entry.shape}")])
        entry = entry.tolist()
    if isinstance(entry, (list, tuple)):
        if not entry:
            raise SweepError([(where, "the list of values is empty")])
        values = []
        for index, value in enumerate(entry):
            number = _number(value)
            if number is None:
                raise SweepError([(where, f"value {value!r} (#{index}) is not a number")])
            values.append(number)
        return values, [value if isinstance(value, int) else float(value) for value in values]
    if isinstance(entry, Mapping):
        keys = list(entry)
        if len(keys) != 1 or keys[0] not in GENERATORS:
            raise SweepError([(where, f"expected exactly one of {', '.join(GENERATORS)}: [start, stop, num], got keys {keys}")])
        kind = keys[0]
        arguments = entry[kind]
        if not isinstance(arguments, (list, tuple)) or len(arguments) != 3:
            raise SweepError([(where, f"{kind} takes [start, stop, num], got {arguments!r}")])
        start, stop, num = (_number(value) for value in arguments)
        if start is None or stop is None or not (math.isfinite(start) and math.isfinite(stop)):
            raise SweepError([(where, f"{kind}: start and stop must be finite numbers, got {arguments[0]!r}, {arguments[1]!r}")])
        if num is None or num != int(num) or num < 1:
            raise SweepError([(where, f"{kind}: num must be an integer >= 1, got {arguments[2]!r}")])
        if kind == "geomspace" and (start == 0 or stop == 0 or (start > 0) != (stop > 0)):
            raise SweepError([(where, f"geomspace: start and stop must be nonzero and of one sign, got {start}, {stop}")])
        values = getattr(np, kind)(float(start), float(stop), int(num))
        if not np.all(np.isfinite(values)):
            raise SweepError([(where, f"{kind}: the values overflow")])
        return values.tolist(), {kind: [float(start), float(stop), int(num)]}
    raise SweepError([(where, f"expected a list of numbers or one of {{{', '.join(GENERATORS)}: [start, stop, num]}}")])


def _number(value):
    """A number from an int, float or numeric string ('1e-3'); None otherwise (booleans too)."""
    if isinstance(value, bool) or value is None:
        return None
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value)
    if isinstance(value, str):
        try:
            return float(value)
        except ValueError:
            return None
    return None


def resolve_field(scene: Scene, path: str) -> tuple[BaseModel, str]:
    """(model instance owning the field, field name) of a numeric field of the base scene."""
    where = f"axes.{path}"
    keys = path.split(".")
    if not all(keys):
        raise SweepError([(where, "expected a dotted path such as initial.velocity")])
    node: object = scene
    for depth, key in enumerate(keys):
        parent = ".".join(keys[:depth]) or "the scene"
        if not isinstance(node, BaseModel):
            raise SweepError([(where, f"no field {path!r}: {parent} is a value, not a section")])
        fields = type(node).model_fields
        if key not in fields:
            raise SweepError([(where, f"no field {path!r} in the scene; {parent} takes: {', '.join(sorted(fields))}")])
        value = getattr(node, key)
        if depth == len(keys) - 1:
            if isinstance(value, BaseModel) or _models_in(fields[key].annotation):
                raise SweepError([(where, f"{path} is a section, not a numeric field")])
            if not _numeric(fields[key].annotation):
                raise SweepError([(where, f"{path} is not a numeric field (it holds {value!r}); only numbers can be swept")])
            return node, key
        if value is None:
            section = ".".join(keys[: depth + 1])
            if _models_in(fields[key].annotation):
                raise SweepError([(where, f"{section} is not in the base scene; sweeping its fields would switch it on, "
                                          f"which changes the static choices: add {section} to the base scene")])
            raise SweepError([(where, f"no field {path!r}: {section} is a value, not a section")])
        node = value
    raise AssertionError("unreachable")


def _numeric(annotation) -> bool:
    """Whether an annotation admits numbers (float or int, not bool) and no lists."""
    if annotation in (float, int):
        return True
    origin = typing.get_origin(annotation)
    if origin in (list, tuple, dict):
        return False
    if origin is Annotated:
        return _numeric(typing.get_args(annotation)[0])
    return any(_numeric(argument) for argument in typing.get_args(annotation) if argument is not type(None))


def _models_in(annotation) -> list:
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return [annotation]
    return [model for argument in typing.get_args(annotation) for model in _models_in(argument)]


# --- every point -----------------------------------------------------------------------------


def with_values(scene: Scene, values: Mapping[str, object]) -> Scene:
    """A copy of `scene` with fields set by dotted path, WITHOUT validation (values may be
    numpy arrays: the copy then describes a whole batch for vectorized formulas)."""
    tree: dict = {}
    for path, value in values.items():
        node = tree
        *parents, key = path.split(".")
        for parent in parents:
            node = node.setdefault(parent, {})
        node[key] = value
    return _replaced(scene, tree)


def _replaced(model: BaseModel, tree: dict) -> BaseModel:
    update = {key: _replaced(getattr(model, key), sub) if isinstance(sub, dict) else sub for key, sub in tree.items()}
    return model.model_copy(update=update)


def check_points(spec: SweepSpec) -> None:
    """Validate every point of the sweep as a scene; SweepError naming the axes if one is invalid."""
    chains = _chains(spec.scene, spec.paths)
    fast = all(
        all(decorator.info.mode == "after" for decorator in type(model).__pydantic_decorators__.model_validators.values())
        for _, model in chains
    ) and not any(_has_field_validator(*resolve_field(spec.scene, path)) for path in spec.paths)
    params = spec.flat_params()
    columns = [params[path].tolist() for path in spec.paths]
    failures, count = [], 0
    if fast:
        # One private deep copy of the base scene, its swept fields set in place point by point.
        point = spec.scene.model_copy(deep=True)
        owners = [resolve_field(point, path) for path in spec.paths]
        models = [(prefix, _model_at(point, prefix)) for prefix, _ in chains]
        for index in range(spec.size):
            for (owner, name), column in zip(owners, columns):
                owner.__dict__[name] = column[index]
            message = _validators_problem(models)
            if message is not None:
                count += 1
                if len(failures) < _MAX_LISTED:
                    failures.append(({path: column[index] for path, column in zip(spec.paths, columns)}, message))
    else:
        base_data = spec.scene.model_dump(exclude_none=True)
        for index in range(spec.size):
            values = {path: column[index] for path, column in zip(spec.paths, columns)}
            message = _full_validation_problem(base_data, values)
            if message is not None:
                count += 1
                if len(failures) < _MAX_LISTED:
                    failures.append((values, message))
    if not failures:
        return
    more = f"; and {count - len(failures)} more invalid points" if count > len(failures) else ""
    if len(spec.axes) == 1:
        path = spec.paths[0]
        listed = "; ".join(f"value {values[path]!r} makes the scene invalid: {message}" for values, message in failures)
        raise SweepError([(f"axes.{path}", listed + more)])
    listed = "; ".join(
        "the point " + ", ".join(f"{path} = {value!r}" for path, value in values.items()) + f" makes the scene invalid: {message}"
        for values, message in failures
    )
    raise SweepError([("axes", listed + more)])


def _has_field_validator(owner: BaseModel, name: str) -> bool:
    validators = type(owner).__pydantic_decorators__.field_validators.values()
    return any(name in decorator.info.fields or "*" in decorator.info.fields for decorator in validators)


def _chains(scene: Scene, paths) -> list[tuple[str, BaseModel]]:
    """(prefix, model) of every section on the swept paths, deepest first, the scene last."""
    seen: dict[str, BaseModel] = {"": scene}
    for path in paths:
        node, keys = scene, path.split(".")[:-1]
        for depth, key in enumerate(keys):
            node = getattr(node, key)
            seen.setdefault(".".join(keys[: depth + 1]), node)
    return sorted(seen.items(), key=lambda item: -len(item[0].split(".")) if item[0] else 1)


def _model_at(scene: Scene, prefix: str) -> BaseModel:
    model = scene
    for key in prefix.split(".") if prefix else ():
        model = getattr(model, key)
    return model


def _validators_problem(models) -> str | None:
    """The first complaint of the after-validators of the given (prefix, model) sections."""
    for prefix, model in models:
        for decorator in type(model).__pydantic_decorators__.model_validators.values():
            try:
                decorator.func(model)
            except (ValueError, AssertionError) as error:
                where = ".".join(part for part in (prefix, getattr(error, "field", "")) if part)
                return f"{where}: {error}" if where else str(error)
    return None


def _full_validation_problem(base_data: dict, values: dict) -> str | None:
    data = copy.deepcopy(base_data)
    for path, value in values.items():
        node = data
        *parents, key = path.split(".")
        for parent in parents:
            node = node.setdefault(parent, {})
        node[key] = value
    try:
        Scene.model_validate(data)
    except ValidationError as error:
        return "; ".join(f"{path}: {message}" if path else message for path, message in problems_of(error))
    return None
