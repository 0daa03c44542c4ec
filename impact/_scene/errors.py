"""Refusals of bad input, each naming the field at fault by its dotted path.

`SceneError` (and its `SweepError`) carries (dotted.path, message) pairs; `FieldProblem` is how a
section's cross-field check names one of its fields; `problems_of` turns a pydantic validation
error into such pairs.
"""

import functools
import re
from typing import get_args

from pydantic import ValidationError

from .profiles import ProfileSpec


class SceneError(ValueError):
    """A scene that cannot be run; `problems` lists (dotted.path, message) pairs."""

    def __init__(self, problems: list[tuple[str, str]]):
        self.problems = problems
        super().__init__("\n".join(f"{path}: {message}" if path else message for path, message in problems))


class SweepError(SceneError):
    """A sweep that cannot be run; `problems` lists (dotted.path, message) pairs."""


class FieldProblem(ValueError):
    """A cross-field check's complaint about one field, named relative to the section."""

    def __init__(self, field: str, message: str):
        super().__init__(message)
        self.field = field


def _profile_shapes() -> tuple[str, ...]:
    union = get_args(ProfileSpec)[0]
    return tuple(model.model_fields["shape"].default for model in get_args(union))


def _adhesion_models() -> tuple[str, ...]:
    from .adhesion import MODEL_NAMES  # the models import this module for `FieldProblem`

    return MODEL_NAMES


# Tags pydantic inserts into error locations for the choices of a union ('continuum' or an
# integer: `function-after[check(), int]`, `literal['continuum']`); they are not scene keys.
_CHOICE_TAG = re.compile(r"[a-z-]+\[.*\]|int|float|str|bool")
# Errors of a value that should have been a section (a mapping of keys).
_NOT_A_MAPPING = ("model_type", "model_attributes_type", "dict_type")
_SHOWN = 60  # characters of a refused value shown at most


@functools.cache
def _union_tags() -> frozenset[str]:
    """The tags of the tagged unions (a profile's shapes, an adhesion's models)."""
    return frozenset(_profile_shapes()) | frozenset(_adhesion_models())


def _is_tag(part) -> bool:
    return isinstance(part, str) and (part in _union_tags() or _CHOICE_TAG.fullmatch(part) is not None)


def _dotted(location: tuple) -> str:
    return ".".join(str(part) for part in location if not _is_tag(part))


def _shown(value) -> str:
    """A refused value as the message shows it: its repr, cut to `_SHOWN` characters."""
    text = repr(value)
    return text if len(text) <= _SHOWN else f"{text[: _SHOWN - 1]}…"


def _path_and_message(error) -> tuple[str, str]:
    path = _dotted(error["loc"])
    cause = error.get("ctx", {}).get("error")
    if isinstance(cause, FieldProblem):
        return ".".join(part for part in (path, cause.field) if part), str(cause)
    text = error["msg"]
    if text.startswith("Value error, "):
        text = text[len("Value error, ") :]
    if error["type"] == "extra_forbidden":
        text = "unknown key"
    elif error["type"] == "missing":
        text = "missing (required)"
    elif error["type"] == "union_tag_invalid" and error["ctx"]["discriminator"] != "'shape'":
        text = f"unknown model {error['ctx']['tag']!r}; known models: {', '.join(_adhesion_models())}"
        path = ".".join(part for part in (path, "model") if part)
    elif error["type"] == "too_long":
        text = f"at most {error['ctx']['max_length']} values, got {error['ctx']['actual_length']}"
    elif error["type"] in _NOT_A_MAPPING:
        text = f"expected a mapping of keys (a section), got {_shown(error['input'])}"
    elif error["type"] == "union_tag_invalid":
        text = f"unknown shape {error['ctx']['tag']!r}; known shapes: {', '.join(_profile_shapes())}"
        path = ".".join(part for part in (path, "shape") if part)
    elif error["type"] == "union_tag_not_found":
        text = f"missing shape; known shapes: {', '.join(_profile_shapes())}"
        path = ".".join(part for part in (path, "shape") if part)
    return path, text


def problems_of(error: ValidationError) -> list[tuple[str, str]]:
    """(dotted.path, message) for each error of a pydantic validation; the errors of the choices
    of one union ('continuum' or an integer) as one, "expected 'continuum' or a valid integer,
    got 'abc'", unless one choice says what is wrong (an integer outside its range)."""
    problems: list[tuple[str, str]] = []
    choices: dict[str, tuple[list[str], object]] = {}  # path → (each choice's complaint, the value)
    for item in error.errors():
        if any(_is_tag(part) for part in item["loc"]) and item["msg"].startswith("Input should be "):
            path = _dotted(item["loc"])
            wanted = item["msg"].removeprefix("Input should be ").split(",")[0]
            choices.setdefault(path, ([], item["input"]))[0].append(wanted)
            entry = (path, "")  # its message once every choice is known
        else:
            entry = _path_and_message(item)
        if entry not in problems:
            problems.append(entry)
    complained = {path for path, text in problems if text}  # a choice's own complaint says more
    return [
        (path, text or f"expected {' or '.join(choices[path][0])}, got {_shown(choices[path][1])}")
        for path, text in problems
        if text or path not in complained
    ]
