"""Every point of a sweep validated as a scene, cheaply.

The points go through the model validators (`mode="after"`) of the sections on the swept
paths, on one copy of the base scene whose swept fields are set in place point by point (far
cheaper than a full `Scene.model_validate`): this is what a full validation would
check, as the rest of the scene is the already valid base. Only the validators that read a
swept field run per point: one that reads none (tracked once, on the base) takes the same path
at every point, and so passes at every point as it passes at the base. The representability
check (units from the profile, in JAX) runs in batched calls of up to `_PENDING` points, on
columns of its inputs: each point's own value of an input that reads a swept field, the base's
of the others. Models with other kinds of validators fall back to a full validation per point.
"""

import contextlib
import copy
import gc
from collections.abc import Callable, Iterator

import jax
import numpy as np
from pydantic import BaseModel, ValidationError

from .._core.runtime import float64
from .errors import FieldProblem, SweepError, problems_of
from .paths import assign, resolve_field, section_at
from .representable import (
    UNIT_NUMBERS,
    Limits,
    UnitInputs,
    check_units,
    limits_of,
    passes,
    profile_unit_columns,
    unit_columns,
    unit_inputs,
    units_at,
)
from .scene import Scene
from .sweep_spec import MAX_LISTED, SweepSpec

# The scene's representability validator: checked for many points of a sweep at once.
_REPRESENTABLE = "_representable"
# Points whose representability waits to be checked together, at most: their inputs and units
# are Python objects of about a kilobyte each: those of 10⁶ points at once would take a gigabyte.
_PENDING = 16 * 4096


def check_points(spec: SweepSpec) -> None:
    """Validate every point of the sweep as a scene; SweepError naming the axes if one is invalid."""
    problems = point_problems(spec)
    if problems:
        params = spec.flat_params()
        listed = [
            ({path: params[path][index].item() for path in spec.paths}, message)
            for index, message in sorted(problems.items())[:MAX_LISTED]
        ]
        raise _invalid_points(spec, listed, len(problems))


@float64
def point_problems(spec: SweepSpec) -> dict[int, str]:
    """{point (flat index): why it makes the scene invalid} of every invalid point of the sweep."""
    chains = _chains(spec.scene, spec.paths)
    fast = all(
        all(
            decorator.info.mode == "after"
            for decorator in type(model).__pydantic_decorators__.model_validators.values()
        )
        for _, model in chains
    ) and not any(_has_field_validator(*resolve_field(spec.scene, path)) for path in spec.paths)
    params = spec.flat_params()
    columns = [params[path].tolist() for path in spec.paths]
    with _without_collection():
        return _fast_problems(spec, chains, columns) if fast else _full_problems(spec, columns)


def _fast_problems(spec: SweepSpec, chains, columns) -> dict[int, str]:
    """{point: complaint} from the after-validators, run on one private copy of the base scene
    whose swept fields are set in place point by point; the representability check of the
    impacts (the costly one: units from the profile) runs for many points at once, and only a
    point whose units it does not pass is checked alone (for its message)."""
    point = spec.scene.model_copy(deep=True)
    owners = [resolve_field(point, path) for path in spec.paths]
    models = [(prefix, section_at(point, prefix)) for prefix, _ in chains]
    profile_swept = any(path.startswith(("body.profile.", "counterpart.profile.")) for path in spec.paths)
    base_profile = None if profile_swept else spec.scene.contact_profile.build()
    checks = _reading_checks(models, owners)
    # what the units are checked against: the base's, unless it reads a swept field
    base_limits = None if _reads_swept(limits_of, point, owners) else limits_of(point)
    # the units' inputs of a point: with the base's profile, the base's numbers but those read
    # from a swept field (those alone are read per point); else every input per point
    varying: dict[str, Callable] = {}
    base_numbers: dict[str, float] = {}
    if base_profile is not None and spec.scene.kind == "impact":
        varying = _reading_numbers(point, owners)
        base_numbers = {name: read(spec.scene) for name, read in UNIT_NUMBERS.items()}

    def set_point(index: int) -> None:
        for (owner, name), column in zip(owners, columns, strict=True):
            owner.__dict__[name] = column[index]

    def point_inputs() -> "UnitInputs | tuple[float, ...]":
        if base_profile is None:
            return unit_inputs(point)
        return tuple(read(point) for read in varying.values())

    problems: dict[int, str] = {}
    pending: dict[tuple, list[tuple[int, UnitInputs | tuple[float, ...], Limits]]] = {}

    def check_pending(key: tuple) -> None:
        indices, inputs, limits = zip(*pending.pop(key), strict=True)
        if base_profile is None:
            values, depth = unit_columns(inputs, key[0])
        else:
            read = np.array(inputs, np.float64).reshape(len(inputs), len(varying))
            numbers: dict[str, np.ndarray | float] = {**base_numbers, **dict(zip(varying, read.T, strict=True))}
            values, depth = profile_unit_columns(base_profile, numbers, len(inputs), key[0])
        for row in np.flatnonzero(~passes(values, depth, limits)).tolist():
            set_point(indices[row])
            try:
                check_units(point, units_at(values, depth, row))
            except FieldProblem as error:
                problems[indices[row]] = f"{error.field}: {error}"

    for index in range(spec.size):
        set_point(index)
        message = _validators_problem(checks)
        if message is not None:
            problems[index] = message
        elif point.kind == "impact":
            inputs = point_inputs()
            structure = jax.tree.structure(inputs) if base_profile is None else None
            key = (point.active_adhesion is not None, structure)
            limits = limits_of(point) if base_limits is None else base_limits
            pending.setdefault(key, []).append((index, inputs, limits))
            if len(pending[key]) == _PENDING:
                check_pending(key)
    for key in list(pending):
        check_pending(key)
    return problems


def _full_problems(spec: SweepSpec, columns) -> dict[int, str]:
    """{point: complaint} of a full validation of every point (models with other validators)."""
    base_data = spec.scene.model_dump(exclude_none=True)
    problems = {}
    for index in range(spec.size):
        values = {path: column[index] for path, column in zip(spec.paths, columns, strict=True)}
        message = _full_validation_problem(base_data, values)
        if message is not None:
            problems[index] = message
    return problems


@contextlib.contextmanager
def _without_collection():
    """Hold the cyclic garbage collector off: checking a point allocates a few dozen objects, none
    in a cycle, and the collections that they set off traverse every live one again and again.
    Cycles made meanwhile are collected after."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


def _invalid_points(spec: SweepSpec, failures: list[tuple[dict, str]], count: int) -> SweepError:
    """The refusal of a sweep with `count` invalid points, the first of them listed."""
    more = f"; and {count - len(failures)} more invalid points" if count > len(failures) else ""
    if len(spec.axes) == 1:
        path = spec.paths[0]
        listed = "; ".join(f"value {values[path]!r} makes the scene invalid: {message}" for values, message in failures)
        return SweepError([(f"axes.{path}", listed + more)])
    listed = "; ".join(
        "the point "
        + ", ".join(f"{path} = {value!r}" for path, value in values.items())
        + f" makes the scene invalid: {message}"
        for values, message in failures
    )
    return SweepError([("axes", listed + more)])


def _has_field_validator(owner: BaseModel, name: str) -> bool:
    validators = type(owner).__pydantic_decorators__.field_validators.values()
    return any(name in decorator.info.fields or "*" in decorator.info.fields for decorator in validators)


def _chains(scene: Scene, paths) -> list[tuple[str, BaseModel]]:
    """(prefix, model) of every section on the swept paths, deepest first, the scene last."""
    seen: dict[str, BaseModel] = {"": scene}
    for path in paths:
        keys = path.split(".")[:-1]
        for depth in range(len(keys)):
            prefix = ".".join(keys[: depth + 1])
            section = section_at(scene, prefix)
            if isinstance(section, BaseModel):  # not a list of sections (its entries are)
                seen.setdefault(prefix, section)
    return sorted(seen.items(), key=lambda item: -len(item[0].split(".")) if item[0] else 1)


class _SweptRead(BaseException):
    """A validator read a swept field (a BaseException, so that no `except Exception` hides it)."""


def _reading_checks(models, owners) -> list[tuple[str, BaseModel, Callable]]:
    """(prefix, model, validator) of the after-validators (but the batched representability) of
    the given (prefix, model) sections that read a swept field ((owner, name) in `owners`) when
    they run on the base point, in their order; any outcome but a clean pass counts as a read."""
    return [
        (prefix, model, decorator.func)
        for prefix, model in models
        for name, decorator in type(model).__pydantic_decorators__.model_validators.items()
        if name != _REPRESENTABLE and _reads_swept(decorator.func, model, owners)
    ]


def _reading_numbers(point: Scene, owners) -> dict[str, Callable]:
    """The `UNIT_NUMBERS` of the units' inputs that read a swept field on the base point."""
    return {name: read for name, read in UNIT_NUMBERS.items() if _reads_swept(read, point, owners)}


def _reads_swept(function: Callable, argument, owners) -> bool:
    """Whether `function(argument)` on the base point reads a swept field ((owner, name) in
    `owners`); any outcome but a clean return counts as a read."""
    try:
        with _tracking_reads(owners):
            function(argument)
    except (_SweptRead, Exception):  # a read, or (unexpected at the base) no clean return
        return True
    return False


@contextlib.contextmanager
def _tracking_reads(owners: list[tuple[BaseModel, str]]) -> Iterator[None]:
    """Within: reading a swept field of its owner (or the owner's `__dict__`, as a dump does)
    raises `_SweptRead`; the owners' classes get a tracking `__getattribute__`, then theirs back."""
    swept: dict[int, set[str]] = {}
    for owner, name in owners:
        swept.setdefault(id(owner), {"__dict__"}).add(name)

    def tracking(self, name):
        if name in swept.get(id(self), ()):
            raise _SweptRead(name)
        return object.__getattribute__(self, name)

    classes = {type(owner) for owner, _ in owners}
    saved = {cls: cls.__dict__.get("__getattribute__") for cls in classes}
    for cls in classes:
        cls.__getattribute__ = tracking  # type: ignore[method-assign]
    try:
        yield
    finally:
        for cls, own in saved.items():
            if own is None:
                delattr(cls, "__getattribute__")
            else:
                cls.__getattribute__ = own  # type: ignore[method-assign]


def _validators_problem(checks: list[tuple[str, BaseModel, Callable]]) -> str | None:
    """The first complaint of the given (prefix, model, validator) checks."""
    for prefix, model, validator in checks:
        try:
            validator(model)
        except (ValueError, AssertionError) as error:
            where = ".".join(part for part in (prefix, getattr(error, "field", "")) if part)
            return f"{where}: {error}" if where else str(error)
    return None


def _full_validation_problem(base_data: dict, values: dict) -> str | None:
    data = copy.deepcopy(base_data)
    for path, value in values.items():
        assign(data, path.split("."), value)
    try:
        Scene.model_validate(data)
    except ValidationError as error:
        return "; ".join(f"{path}: {message}" if path else message for path, message in problems_of(error))
    return None
