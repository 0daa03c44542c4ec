"""The documentation keeps up with the code: every public name on the API page, every scene key in
the generated scene reference, the README short with its quick start, no link leaving the
repository."""

import importlib.util
import re
import types
import typing
from pathlib import Path

import pytest
from mkdocs_config import mkdocs_config
from pydantic import BaseModel

import impact

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
PAGES = DOCS / "src"
README = ROOT / "README.md"
QUICK_START = (
    "pip install -e . && impact run configs/thornton_ning.yaml",
    "pip install -e '.[test]' && pytest",
)
# Paths of files that are not part of this repository (design notes, the reference chapter).
FOREIGN = ("../shared", "DESIGN.md", "reference/", "adhesive-normal-contact")


def _markdown_files() -> list[Path]:
    return [README, *sorted(PAGES.rglob("*.md"))]


def _hooks():
    spec = importlib.util.spec_from_file_location("docs_hooks", DOCS / "hooks.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _documented() -> set[str]:
    """The identifiers of the `::: identifier` blocks of the API page."""
    text = (PAGES / "api.md").read_text()
    return set(re.findall(r"^::: +([\w.]+)\s*$", text, re.MULTILINE))


@pytest.mark.parametrize(
    ("module", "prefix"),
    [(impact, "impact"), (impact.profiles, "impact.profiles"), (impact.theory, "impact.theory")],
    ids=["impact", "profiles", "theory"],
)
def test_api_page_lists_every_public_name(module, prefix):
    documented = _documented()
    missing = [name for name in module.__all__ if f"{prefix}.{name}" not in documented]
    assert not missing, f"add `::: {prefix}.<name>` to docs/src/api.md for: {missing}"


def test_api_page_documents_only_public_names():
    public = {f"impact.{name}" for name in impact.__all__}
    public |= {f"impact.profiles.{name}" for name in impact.profiles.__all__}
    public |= {f"impact.theory.{name}" for name in impact.theory.__all__}
    assert _documented() <= public, sorted(_documented() - public)


def test_readme_is_short_and_keeps_the_quick_start():
    text = README.read_text()
    assert len(text.splitlines()) <= 250
    for command in QUICK_START:
        assert command in text.splitlines(), f"README lost the quick-start line {command!r}"


def test_readme_python_example_runs():
    text = README.read_text()
    (example,) = re.findall(r"```python\n(.*?)```", text, re.DOTALL)[:1]
    namespace: dict = {}
    exec(compile(example, "README.md", "exec"), namespace)
    assert namespace["result"].status == "separated"
    assert abs(namespace["result"].restitution - 0.8629448823) < 1e-9


def _alternatives(annotation) -> list:
    while typing.get_origin(annotation) is typing.Annotated:
        annotation = typing.get_args(annotation)[0]
    if typing.get_origin(annotation) in (typing.Union, types.UnionType):
        return [option for argument in typing.get_args(annotation) for option in _alternatives(argument)]
    return [] if annotation is type(None) else [annotation]


def _leaf_paths(model: type[BaseModel], prefix: str = "") -> set[str]:
    """Dotted paths of every field of the scene that is not itself a section (or profile union)."""
    paths = set()
    for name, field in model.model_fields.items():
        options = _alternatives(field.annotation)
        models = [option for option in options if isinstance(option, type) and issubclass(option, BaseModel)]
        if models and len(models) == len(options):
            for inner in models:
                paths |= _leaf_paths(inner, f"{prefix}{name}.")
        else:
            paths.add(f"{prefix}{name}")
    return paths


def test_scene_reference_covers_every_leaf_path():
    hooks = _hooks()
    generated = hooks.scene_reference()
    leaves = _leaf_paths(impact.Scene)
    assert {"body.profile.R", "effects.adhesion.work_of_adhesion", "solver.rtol", "program.peak"} <= leaves
    missing = sorted(path for path in leaves if hooks.key(path) not in generated)
    assert not missing, f"scene reference lacks: {missing}"


def test_scene_reference_page_has_the_placeholder():
    hooks = _hooks()
    assert hooks.PLACEHOLDER in (PAGES / hooks.PAGE).read_text()


def _link_targets(text: str) -> list[str]:
    """Targets of markdown links and images, and of HTML src/href attributes."""
    targets = re.findall(r"!?\[[^\]]*\]\(\s*<?([^)\s>]+)", text)
    targets += re.findall(r"""(?:src|href)=["']([^"']+)["']""", text)
    return targets


@pytest.mark.parametrize("path", _markdown_files(), ids=lambda path: str(path.relative_to(ROOT)))
def test_no_reference_leaves_the_repository(path):
    text = path.read_text()
    foreign = [marker for marker in FOREIGN if marker in text]
    assert not foreign, f"{path.name} refers to files outside the repository: {foreign}"
    for target in _link_targets(text):
        if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("#"):
            continue  # a URL (https:, mailto:) or an anchor on the same page
        file = (path.parent / target.split("#")[0]).resolve()
        assert file.is_relative_to(ROOT), f"{path.name}: link {target!r} leaves the repository"
        assert file.exists(), f"{path.name}: link {target!r} points to no file"


@pytest.mark.parametrize("path", _markdown_files(), ids=lambda path: str(path.relative_to(ROOT)))
def test_named_repository_files_exist(path):
    """Files of the repository named in the text (`configs/….yaml`, `tests/….py`) exist."""
    named = re.findall(r"\b((?:configs|tests|impact|docs)/[\w./-]+\.(?:py|yaml|yml|md|png))\b", path.read_text())
    missing = sorted({name for name in named if not (ROOT / name).exists()})
    assert not missing, f"{path.name} names files that do not exist: {missing}"


@pytest.mark.parametrize("path", _markdown_files(), ids=lambda path: str(path.relative_to(ROOT)))
def test_no_control_characters(path):
    """No tab, carriage return, backspace or other control character: a LaTeX command written
    through an escaping string (`\\rho`, `\\tfrac`, `\\beta`) leaves one and breaks its formula."""
    text = path.read_bytes().decode()
    found = sorted(
        {
            f"line {text.count(chr(10), 0, match.start()) + 1}: {match.group()!r}"
            for match in re.finditer(r"[\x00-\x08\x0b-\x1f\x7f]", text)
        }
    )
    assert not found, f"{path.name} holds control characters: {found}"


def test_home_page_leads_to_every_page():
    nav = mkdocs_config(DOCS / "mkdocs.yml")["nav"]
    pages = [page for entry in nav for page in entry.values() if page != "index.md"]
    section = (PAGES / "index.md").read_text().split("## Where to go next", 1)[1].split("\n## ", 1)[0]
    missing = [page for page in pages if f"]({page})" not in section]
    assert not missing, f"the home page's 'Where to go next' lacks: {missing}"
