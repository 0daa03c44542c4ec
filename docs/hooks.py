"""MkDocs hook: the scene reference, generated from the pydantic models of the scene file.

`scene_reference()` walks `impact.Scene` field by field: a field whose type is a section (a
pydantic model) opens a table of its own, the body profile (a union of models tagged by
`shape`) one table per shape; every other field is a row with its key, type and bounds, default
and the `description` of its `Field`. The key is its name within the section's table, with its
dotted path as title; keys, values and defaults are code that never breaks inside a name, so
that four columns read on a laptop's screen. `on_page_markdown` puts the tables in place
of `PLACEHOLDER` in scene-reference.md, so the page always matches the code.
"""

import html
import sys
import types
import typing
from pathlib import Path

import annotated_types
from pydantic import BaseModel
from pydantic.fields import FieldInfo

ROOT = Path(__file__).resolve().parents[1]
PLACEHOLDER = "<!-- scene-reference:generated -->"
PAGE = "scene-reference.md"

_BOUNDS = (
    (annotated_types.Gt, "gt", ">"),
    (annotated_types.Ge, "ge", "≥"),
    (annotated_types.Lt, "lt", "<"),
    (annotated_types.Le, "le", "≤"),
)


def _scene_model() -> type[BaseModel]:
    if str(ROOT) not in sys.path:
        sys.path.insert(0, str(ROOT))
    import impact

    return impact.Scene


def token(value: object, title: str | None = None) -> str:
    """`value` as code that never breaks inside (`code.nowrap` in stylesheets/extra.css)."""
    hint = f' title="{title}"' if title else ""
    return f'<code class="nowrap"{hint}>{html.escape(str(value))}</code>'


def key(path: str) -> str:
    """A key's cell: its name within its section, with its dotted path as title."""
    return token(path.rsplit(".", 1)[-1], title=path)


def _unwrap(annotation) -> tuple[list, bool]:
    """The alternatives of a type (Annotated and None stripped) and whether None is one of them."""
    while typing.get_origin(annotation) is typing.Annotated:
        annotation = typing.get_args(annotation)[0]
    if typing.get_origin(annotation) in (typing.Union, types.UnionType):
        options, optional = [], False
        for argument in typing.get_args(annotation):
            inner, none = _unwrap(argument)
            options += inner
            optional |= none
        return options, optional
    if annotation is type(None):
        return [], True
    return [annotation], False


def _models(annotation) -> list[type[BaseModel]]:
    """The pydantic models a field holds (a section, or the profile union), else []."""
    options, _ = _unwrap(annotation)
    if options and all(isinstance(option, type) and issubclass(option, BaseModel) for option in options):
        return options
    return []


def _type_name(annotation) -> str:
    options, optional = _unwrap(annotation)
    names = []
    for option in options:
        if typing.get_origin(option) is typing.Literal:
            names.append(" or ".join(token(value) for value in typing.get_args(option)))
        elif typing.get_origin(option) is list:
            (item,) = typing.get_args(option)
            names.append(f"list of {_type_name(item)}s")
        elif option is float:
            names.append("number")
        elif option is int:
            names.append("integer")
        elif option is str:
            names.append("string")
        elif option is bool:
            names.append("boolean")
        else:
            names.append(getattr(option, "__name__", str(option)))
    text = " or ".join(names)
    return f"{text} (optional)" if optional else text


def _default(field: FieldInfo) -> str:
    if field.is_required():
        return "**required**"
    default = field.get_default(call_default_factory=True)
    if default is None:
        return "none"
    if isinstance(default, BaseModel):
        return "section defaults"
    return token(default)


def _bounds(field: FieldInfo) -> str:
    from impact._scene.domains import domains_of

    marks = [
        f"{sign} {getattr(item, attribute)}"
        for item in field.metadata
        for kind, attribute, sign in _BOUNDS
        if isinstance(item, kind)
    ]
    return ", ".join([*marks, *(str(domain) for domain in domains_of(field))])


def _cell(text: str) -> str:
    return " ".join(text.split()).replace("|", "\\|")


def _summary(model: type[BaseModel]) -> str:
    doc = model.__doc__ or ""
    return _cell(doc.strip().split("\n\n")[0]) if doc.strip() else ""


def _tag(models: list[type[BaseModel]]) -> str:
    """The key whose value selects a member of a tagged union: a profile's `shape`, an adhesion's `model`."""
    return "shape" if "shape" in models[0].model_fields else "model"


def _tag_value(model: type[BaseModel], tag: str) -> str:
    options, _ = _unwrap(model.model_fields[tag].annotation)
    return typing.get_args(options[0])[0]


def _table(model: type[BaseModel], prefix: str) -> tuple[list[str], list[tuple[str, type[BaseModel] | list]]]:
    """The rows of one section, and the sections (or profile unions) nested in it."""
    lines = ["| key | type, allowed range | default | meaning (SI units) |", "|---|---|---|---|"]
    nested = []
    for name, field in model.model_fields.items():
        path = f"{prefix}{name}"
        models = _models(field.annotation)
        if models:
            nested.append((path, models))
            tag = _tag(models)
            kind = f"one of the {tag}s below, by `{tag}`" if len(models) > 1 else "section, below"
            _, optional = _unwrap(field.annotation)
            kind += " (optional)" if optional else ""
            summary = _summary(models[0]) if len(models) == 1 else {"shape": "the body's shape"}.get(tag, "")
            description = field.description or summary
            lines.append(f"| {key(path)} | {kind} | {_default(field)} | {_cell(description or '')} |")
            continue
        selects = {"shape": "selects this profile", "model": "selects this model"}
        description = field.description or selects.get(name, "")
        bounds = _bounds(field)
        kind = _cell(_type_name(field.annotation)) + (f"<br>{bounds}" if bounds else "")
        lines.append(f"| {key(path)} | {kind} | {_default(field)} | {_cell(description)} |")
    return lines, nested


def _section(path: str, models: list[type[BaseModel]], level: int) -> list[str]:
    hashes = "#" * min(level, 6)
    if len(models) > 1:  # a tagged union (`shape`, `model`): one table per member
        tag = _tag(models)
        out = [f"{hashes} `{path}`", "", f"A mapping whose `{tag}` selects one of {len(models)} {tag}s.", ""]
        for model in models:
            out += [f"{hashes}# `{tag}: {_tag_value(model, tag)}`", "", _summary(model), ""]
            lines, nested = _table(model, f"{path}.")
            out += [*lines, ""]
            for inner_path, inner in nested:
                out += _section(inner_path, inner, level + 2)
        return out
    (model,) = models
    out = [f"{hashes} `{path}`", "", _summary(model), ""]
    lines, nested = _table(model, f"{path}.")
    out += [*lines, ""]
    for inner_path, inner in nested:
        out += _section(inner_path, inner, level + 1)
    return out


def scene_reference(scene: type[BaseModel] | None = None) -> str:
    """Markdown tables of every key of the scene file, generated from the pydantic models."""
    scene = scene or _scene_model()
    lines, nested = _table(scene, "")
    out = ["## Top level", "", _summary(scene), "", *lines, ""]
    for path, models in nested:
        out += _section(path, models, 2)
    return "\n".join(out)


def on_page_markdown(markdown: str, page, config, files) -> str:
    """Replace the placeholder of the scene reference page by the generated tables."""
    if page.file.src_uri != PAGE:
        return markdown
    if PLACEHOLDER not in markdown:
        raise ValueError(f"{PAGE} lost its placeholder {PLACEHOLDER!r}")
    return markdown.replace(PLACEHOLDER, scene_reference())
