"""`--set dotted.path=value`: overrides of a scene file's or a fit file's values on the command
line, applied to the mapping before it is validated (the value is read as YAML, and a number
such as 2e9, which YAML 1.1 reads as a string, as a number).

In a fit file the keys of `parameters` and `observables` are themselves dotted (scene paths,
result names): `parameters.material.E_star.start=2.0e9` sets the `start` of the parameter
`material.E_star` (the last key names a field of the entry; without one the value replaces the
whole entry), and `scene.initial.velocity=0.8` sets a value of the scene (a scene file named by
the fit file is read and the fit then holds it inline).
"""

import copy
import re
from collections.abc import Mapping
from pathlib import Path

from pydantic import BaseModel

from .errors import SceneError
from .paths import NoField, NotASection, assign, check_path
from .reading import parse_yaml, read_yaml

# A number in exponent notation that YAML 1.1 (PyYAML) reads as a string: 2e9, 1.0e-3.
EXPONENT_NUMBER = re.compile(r"[-+]?(\d+\.?\d*|\.\d+)[eE][-+]?\d+")


def _split(assignment: str) -> tuple[list[str], object]:
    """(keys, value) of `dotted.path=value`; SceneError for a malformed one."""
    path, separator, text = assignment.partition("=")
    keys = path.strip().split(".")
    if not separator or not all(keys):
        raise SceneError([("--set", f"expected dotted.path=value, got {assignment!r}")])
    try:
        value = parse_yaml(text, f"the value of --set {path.strip()}")
    except SceneError as error:
        raise SceneError([(f"--set {path}", message) for _, message in error.problems]) from None
    if isinstance(value, str) and EXPONENT_NUMBER.fullmatch(value):
        value = float(value)
    return keys, value


def apply_overrides(data: dict, assignments: list[str]) -> dict:
    """A copy of the scene mapping with each `dotted.path=value` applied.

    Raises SceneError for a malformed assignment or a path that is no field of the schema."""
    data = copy.deepcopy(data)
    for assignment in assignments:
        keys, value = _split(assignment)
        _assign_scene(data, keys, value)
    return data


def _assign_scene(data: dict, keys: list[str], value) -> None:
    try:
        check_path(data, keys)
        assign(data, keys, value)
    except NoField as error:
        raise SceneError([("--set", str(error))]) from None
    except NotASection as error:
        raise SceneError([(error.section, f"must be a mapping to --set {'.'.join(keys)}")]) from None


def apply_fit_overrides(
    data: dict, assignments: list[str], folder: Path, entries: Mapping[str, type[BaseModel]], keys: tuple[str, ...]
) -> dict:
    """A copy of the fit mapping with each `dotted.path=value` applied: `scene.<path>` in the
    scene (read from its file, relative to `folder`, where the fit names one), `<section>.<key>`
    or `<section>.<key>.<field>` in the sections of `entries` (section → the model of an entry),
    and the plain `keys`. SceneError for a malformed assignment or a path that names nothing."""
    data = copy.deepcopy(data)
    for assignment in assignments:
        path, value = _split(assignment)
        head, rest = path[0], path[1:]
        if head == "scene" and rest:
            scene = data.get("scene")
            if isinstance(scene, str):
                try:
                    scene = read_yaml(folder / scene)
                except SceneError as error:
                    raise SceneError([("scene", message) for _, message in error.problems]) from None
            data["scene"] = scene if isinstance(scene, dict) else {}
            _assign_scene(data["scene"], rest, value)
        elif head in entries and rest:
            _assign_entry(data, head, rest, value, entries[head])
        elif head in keys and not rest:
            data[head] = value
        else:
            known = ", ".join(sorted({*keys, *entries, "scene"}))
            raise SceneError([("--set", f"no field {'.'.join(path)!r} in a fit file; it takes: {known}")])
    return data


def _assign_entry(data: dict, section: str, keys: list[str], value, entry: type[BaseModel]) -> None:
    """Set a field of an entry (`key.field`, the key itself dotted) or the whole entry (`key`)."""
    if not isinstance(data.get(section), dict):
        data[section] = {}
    if len(keys) > 1 and keys[-1] in entry.model_fields:
        name = ".".join(keys[:-1])
        current = data[section].get(name)
        if current is not None and not isinstance(current, dict):
            raise SceneError([(f"{section}.{name}", f"must be a mapping to --set {section}.{'.'.join(keys)}")])
        data[section][name] = {**(current or {}), keys[-1]: value}
    elif isinstance(value, dict):
        data[section][".".join(keys)] = value
    else:
        fields = ", ".join(entry.model_fields)
        message = f"no field {keys[-1]!r} of an entry of {section} ({fields}); set one, or the whole entry to a mapping"
        raise SceneError([(f"{section}.{'.'.join(keys)}", message)])
