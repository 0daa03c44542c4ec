"""One axis of a sweep: a numeric field of the base scene and its values, validated by the
field's own pydantic validator in one call (bounds, numeric strings, integers).

An axis is written as a list of numbers or as one generator, {linspace | geomspace | logspace:
[start, stop, num]}; every refusal is a `SweepError` under `axes.<dotted.path>`.
"""

import math
import typing
from collections.abc import Mapping
from typing import Annotated, Any

import numpy as np
from pydantic import BaseModel, TypeAdapter, ValidationError
from pydantic.fields import FieldInfo

from .domains import domains_of, udunits
from .errors import SweepError
from .paths import AbsentSection, NoField, models_in, resolve_field
from .scene import Scene
from .sweep_spec import MAX_LISTED, Axis

GENERATORS = ("linspace", "geomspace", "logspace")


def build_axis(scene: Scene, path: str, entry) -> Axis:
    """The axis of a dotted path over the base scene, its values validated as the field's."""
    where = f"axes.{path}"
    owner, name = numeric_field(scene, path)
    raw, spec = _raw_values(where, entry)
    values, invalid = field_values(owner, name, raw)
    if invalid:
        listed = [f"value {value!r} (#{index}): {message}" for index, value, message in invalid[:MAX_LISTED]]
        more = len(invalid) - len(listed)
        raise SweepError([(where, "; ".join(listed) + (f"; and {more} more" if more > 0 else ""))])
    if any(value is None or isinstance(value, str) for value in values):
        raise SweepError([(where, "every value must be a number")])
    integer = all(isinstance(value, int) for value in values)
    array = np.asarray(values, dtype=np.int64 if integer else np.float64)
    if integer and isinstance(spec, list):
        spec = [int(value) for value in array]
    return Axis(path, array, spec, unit=field_unit(type(owner).model_fields[name]))


def field_unit(info: FieldInfo) -> str:
    """The unit of a numeric field's values (UDUNITS; '' dimensionless): its domain's."""
    units = {udunits(domain.unit) for domain in domains_of(info)}
    return units.pop() if len(units) == 1 else ""


def field_values(owner: BaseModel, name: str, raw: list) -> tuple[list, list[tuple[int, Any, str]]]:
    """(the values validated by the field `name` of `owner`, its type with its constraints: gt,
    ge, ...; the invalid ones as (index, value, why), by index)."""
    info = type(owner).model_fields[name]
    # The field's type with its constraints (gt, ge, ...), built at run time.
    field_type: Any = Annotated[(info.annotation, *info.metadata)] if info.metadata else info.annotation
    adapter: TypeAdapter[list] = TypeAdapter(list[field_type])
    try:
        return adapter.validate_python(raw), []
    except ValidationError as error:
        invalid = [
            (int(problem["loc"][0]) if problem["loc"] else -1, problem["input"], _message(problem))
            for problem in error.errors()
        ]
        return [], sorted(invalid, key=lambda problem: problem[0])


def _message(problem) -> str:
    return problem["msg"].removeprefix("Value error, ")


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
        return _generated(where, entry)
    raise SweepError([(where, f"expected a list of numbers or one of {{{', '.join(GENERATORS)}: [start, stop, num]}}")])


def _generated(where: str, entry: Mapping):
    """(values, canonical spec) of a generator entry {kind: [start, stop, num]}."""
    keys = list(entry)
    if len(keys) != 1 or keys[0] not in GENERATORS:
        raise SweepError(
            [(where, f"expected exactly one of {', '.join(GENERATORS)}: [start, stop, num], got keys {keys}")]
        )
    kind = keys[0]
    arguments = entry[kind]
    if not isinstance(arguments, (list, tuple)) or len(arguments) != 3:
        raise SweepError([(where, f"{kind} takes [start, stop, num], got {arguments!r}")])
    start, stop, num = (_number(value) for value in arguments)
    if start is None or stop is None or not (math.isfinite(start) and math.isfinite(stop)):
        raise SweepError(
            [(where, f"{kind}: start and stop must be finite numbers, got {arguments[0]!r}, {arguments[1]!r}")]
        )
    if num is None or num != int(num) or num < 1:
        raise SweepError([(where, f"{kind}: num must be an integer >= 1, got {arguments[2]!r}")])
    if kind == "geomspace" and (start == 0 or stop == 0 or (start > 0) != (stop > 0)):
        raise SweepError([(where, f"geomspace: start and stop must be nonzero and of one sign, got {start}, {stop}")])
    values = getattr(np, kind)(float(start), float(stop), int(num))
    if not np.all(np.isfinite(values)):
        raise SweepError([(where, f"{kind}: the values overflow")])
    return values.tolist(), {kind: [float(start), float(stop), int(num)]}


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


def numeric_field(scene: Scene, path: str) -> tuple[BaseModel, str]:
    """(model instance owning the field, field name) of a numeric field of the base scene."""
    where = f"axes.{path}"
    try:
        owner, name = resolve_field(scene, path)
    except AbsentSection as error:
        raise SweepError(
            [
                (
                    where,
                    f"{error.section} is not in the base scene; sweeping its fields would switch it on, "
                    f"which changes the static choices: add {error.section} to the base scene",
                )
            ]
        ) from None
    except NoField as error:
        raise SweepError([(where, str(error))]) from None
    annotation = type(owner).model_fields[name].annotation
    value = getattr(owner, name)
    if isinstance(value, BaseModel) or models_in(annotation):
        raise SweepError([(where, f"{path} is a section, not a numeric field")])
    if not _numeric(annotation):
        raise SweepError([(where, f"{path} is not a numeric field (it holds {value!r}); only numbers can be swept")])
    return owner, name


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
