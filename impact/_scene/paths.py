"""Dotted field paths of a scene (`initial.velocity`, `body.profile.R`; an entry of a list of
sections by its index, `effects.viscoelasticity.prony.0.time`).

One place walks them: against the schema for a scene mapping not yet validated (`check_path`,
the CLI's `--set`), into a mapping (`assign`), on a validated scene (`resolve_field`,
`section_at`; a sweep's axes), and into a copy of a scene (`with_values`). Each refusal is an
exception whose message (or `section`) the caller places under its own dotted path.
"""

import typing
from collections.abc import Mapping
from typing import TypeVar

from pydantic import BaseModel

from .scene import Scene


class NoField(ValueError):
    """A dotted path that names no field of the scene; the message says why."""


class NotASection(ValueError):
    """A path that goes through a value as if it were a section; `section` is that value's path."""

    def __init__(self, section: str):
        super().__init__(f"{section} is a value, not a section")
        self.section = section


class AbsentSection(ValueError):
    """A path through a section the scene leaves out (None); `section` is its path."""

    def __init__(self, section: str):
        super().__init__(f"{section} is not in the scene")
        self.section = section


def models_in(annotation) -> list[type[BaseModel]]:
    """The pydantic models a field annotation admits (through Optional, unions, Annotated)."""
    if typing.get_origin(annotation) is None and isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return [annotation]
    return [model for argument in typing.get_args(annotation) for model in models_in(argument)]


def _of_named_shape(models: list[type[BaseModel]], node) -> list[type[BaseModel]]:
    """Of several models (the profile shapes), the one whose `shape` the mapping names, if any."""
    shape = node.get("shape") if isinstance(node, dict) else None
    named = [model for model in models if shape and getattr(model.model_fields.get("shape"), "default", None) == shape]
    return named or models


def is_list(annotation) -> bool:
    """Whether a field annotation is a list (through Optional and Annotated)."""
    if typing.get_origin(annotation) is list:
        return True
    return any(is_list(argument) for argument in typing.get_args(annotation) if argument is not type(None))


def _entry(node: list, key: str, parent: str):
    """The entry of a list of sections at the index `key`; NoField where there is none."""
    if not key.isdigit() or int(key) >= len(node):
        raise NoField(f"{parent} is a list of {len(node)}: index it by 0 … {len(node) - 1}, not {key!r}")
    return node[int(key)]


def check_path(data: dict, keys: list[str]) -> None:
    """Refuse (NoField) a dotted path that names no field of the scene schema (for the profile:
    of the shape the mapping names, if it names one; an entry of a list by its index)."""
    models: list[type[BaseModel]] = [Scene]
    node: object = data
    listed = False
    for depth, key in enumerate(keys):
        parent = ".".join(keys[:depth]) or "the scene"
        if listed:
            node = _entry(node, key, parent) if isinstance(node, list) else None
            listed = False
            continue
        models = _of_named_shape(models, node)
        fields = [model.model_fields[key] for model in models if key in model.model_fields]
        if not fields:
            known = sorted({name for model in models for name in model.model_fields})
            hint = f"{parent} takes: {', '.join(known)}" if known else f"{parent} is a value, not a section"
            raise NoField(f"no field {'.'.join(keys)!r} in the scene; {hint}")
        models = [model for field in fields for model in models_in(field.annotation)]
        listed = any(is_list(field.annotation) for field in fields)
        node = node.get(key) if isinstance(node, dict) else None


def assign(data: dict, keys: list[str], value) -> None:
    """Set `value` at the dotted path `keys` of a nested mapping, creating the sections it
    lacks (or holds as None); NotASection where the path goes through a value."""
    node = data
    for depth, key in enumerate(keys[:-1]):
        if isinstance(node, list):
            node = _entry(node, key, ".".join(keys[:depth]))
            continue
        if node.get(key) is None:
            node[key] = {}
        if not isinstance(node[key], (dict, list)):
            raise NotASection(".".join(keys[: depth + 1]))
        node = node[key]
    if isinstance(node, list):
        raise NotASection(".".join(keys))
    node[keys[-1]] = value


def resolve_field(scene: BaseModel, path: str) -> tuple[BaseModel, str]:
    """(model instance owning the field, field name) of a field of a validated scene; NoField
    for a path that names none, AbsentSection for one through a section the scene leaves out."""
    keys = path.split(".")
    if not all(keys):
        raise NoField("expected a dotted path such as initial.velocity")
    node: object = scene
    for depth, key in enumerate(keys):
        parent = ".".join(keys[:depth]) or "the scene"
        if isinstance(node, list):
            node = _entry(node, key, parent)
            if depth == len(keys) - 1:
                raise NoField(f"no field {path!r}: {path} is a section, not a value")
            continue
        if not isinstance(node, BaseModel):
            raise NoField(f"no field {path!r}: {parent} is a value, not a section")
        fields = type(node).model_fields
        if key not in fields:
            raise NoField(f"no field {path!r} in the scene; {parent} takes: {', '.join(sorted(fields))}")
        value = getattr(node, key)
        if depth == len(keys) - 1:
            return node, key
        if value is None:
            section = ".".join(keys[: depth + 1])
            if models_in(fields[key].annotation):
                raise AbsentSection(section)
            raise NoField(f"no field {path!r}: {section} is a value, not a section")
        node = value
    raise AssertionError("unreachable")


def section_at(scene: BaseModel, prefix: str) -> BaseModel:
    """The section of a validated scene at a dotted prefix ('' for the scene itself)."""
    model = scene
    for key in prefix.split(".") if prefix else ():
        model = model[int(key)] if isinstance(model, list) else getattr(model, key)
    return model


def with_values(scene: Scene, values: Mapping[str, object]) -> Scene:
    """A copy of `scene` with fields set by dotted path, WITHOUT validation (values may be
    numpy arrays: the copy then describes a whole batch for vectorized formulas). Only fields
    the sections have can be set, and no choice of a section's kind (a profile's `shape`, an
    adhesion's `model`): ValueError; a changed kind needs a new scene (`load_scene`)."""
    tree: dict = {}
    for path, value in values.items():
        assign(tree, path.split("."), value)
    return _replaced(scene, tree)


Model = TypeVar("Model", bound=BaseModel)
# The fields that choose a section's class in its union (profiles by shape, adhesions by model).
_KIND_TAGS = ("shape", "model")


def _replaced(model: Model, tree: dict) -> Model:
    fields = type(model).model_fields
    for key, sub in tree.items():
        if key not in fields:
            raise ValueError(f"{type(model).__name__} has no field {key!r}: with_values sets existing fields")
        if key in _KIND_TAGS and sub != getattr(model, key):
            raise ValueError(
                f"{key} = {sub!r} changes the kind of {type(model).__name__}: load a new scene to change it"
            )
    update = {key: _replaced_node(getattr(model, key), sub) for key, sub in tree.items()}
    return model.model_copy(update=update)


def _replaced_node(node, sub):
    """`node` with the values of the tree `sub` (a section, or a list of sections by index)."""
    if not isinstance(sub, dict):
        return sub
    if isinstance(node, list):
        return [_replaced(entry, sub[str(index)]) if str(index) in sub else entry for index, entry in enumerate(node)]
    return _replaced(node, sub)
