"""Refusals of bad input, each naming the field at fault by its dotted path.

`SceneError` (and its `SweepError`) carries (dotted.path, message) pairs; `FieldProblem` is how a
section's cross-field check names one of its fields; `problems_of` turns a pydantic validation
error into such pairs.
"""

import functools
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


@functools.cache
def _union_tags() -> frozenset[str]:
    """Tags pydantic inserts into error locations for unions; they are not scene keys."""
    return frozenset(_profile_shapes()) | frozenset(_adhesion_models()) | {"int", "literal['continuum']"}


def _dotted(location: tuple) -> str:
    return ".".join(str(part) for part in location if not (isinstance(part, str) and part in _union_tags()))


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
    elif error["type"] == "union_tag_invalid":
        text = f"unknown shape {error['ctx']['tag']!r}; known shapes: {', '.join(_profile_shapes())}"
        path = ".".join(part for part in (path, "shape") if part)
    elif error["type"] == "union_tag_not_found":
        text = f"missing shape; known shapes: {', '.join(_profile_shapes())}"
        path = ".".join(part for part in (path, "shape") if part)
    return path, text


def problems_of(error: ValidationError) -> list[tuple[str, str]]:
    """(dotted.path, message) for each error of a pydantic validation."""
    problems = []
    for item in error.errors():
        entry = _path_and_message(item)
        if entry not in problems:
            problems.append(entry)
    return problems
