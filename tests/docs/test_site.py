"""The built site reads as written: `mkdocs build --strict` into a temporary folder, then every
page is checked for a star of E* turned into emphasis, a Markdown list printed as text, a script
or stylesheet fetched from another host (the equations render offline), figures without their
full-size link, and the API page for the fields of the result classes with their units and for
signatures formatted to the column."""

import dataclasses
import fcntl
import html
import importlib.util
import os
import re
import subprocess
import sys
from pathlib import Path
from urllib.parse import urlsplit

import pytest
from mkdocs_config import mkdocs_config

import impact

if importlib.util.find_spec("mkdocs") is None and not os.environ.get("CI"):
    pytest.skip("the docs extra is not installed: pip install -e '.[docs]'", allow_module_level=True)

ROOT = Path(__file__).resolve().parents[2]
CONFIG = ROOT / "docs" / "mkdocs.yml"
RESULT_CLASSES = ("Result", "SweepResult", "IndentationResult", "FitResult")
# Members of the result classes that are no physical quantity (the scene, names, flags, counts,
# codes, containers): they state no unit. Every other field and property states its unit.
NOT_QUANTITIES = {
    "Result": {"scene", "status", "stuck", "bounces", "events", "stats", "success"},
    "SweepResult": {
        "spec",
        "scene",
        "status",
        "stuck",
        "bounces",
        "steps",
        "accepted_steps",
        "rejected_steps",
        "stats",
        "shape",
        "success",
    },
    "IndentationResult": {"scene", "status", "leg", "events", "stats", "success", "xi"},
    "FitResult": {"spec", "converged", "iterations", "dof", "sigma_source", "unidentifiable"},
}
# A unit in brackets, [m], [m/s], [J], [N·m], [s⁻¹], or [SI] for values in the SI unit of whatever
# they hold; or the word "dimensionless".
_SYMBOL = r"(?:kg|Pa|m|s|N|J)(?:[²³]|⁻[¹²³])?"
UNIT = re.compile(rf"\[(?:SI|{_SYMBOL}(?:[·/]{_SYMBOL})*)\]|\bdimensionless\b")
# An emphasis opened right after a letter, digit, prime or closing bracket: the star of E*, R*.
EMPHASIS_AFTER_SYMBOL = re.compile(r"[\w)\]}′’]<(em|strong)>")
SIGNATURE_WIDTH = 80  # characters: mkdocstrings' line_length (60) and what ruff cannot break


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    """The built site: built once per test session, by the first xdist worker that needs it."""
    shared = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        shared = shared.parent  # the session's folder, common to its workers
    out = shared / "docs-site"
    with open(shared / "docs-site.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not (out / "index.html").is_file():
            _build(out)
    return out


def _build(out: Path) -> None:
    command = [sys.executable, "-m", "mkdocs", "build", "--strict", "-q", "-f", str(CONFIG), "-d", str(out)]
    env = {**os.environ, "NO_MKDOCS_2_WARNING": "1"}
    built = subprocess.run(command, cwd=ROOT, capture_output=True, text=True, env=env)
    assert built.returncode == 0, f"mkdocs build --strict failed:\n{built.stdout[-4000:]}{built.stderr[-4000:]}"


def _pages(site: Path) -> list[Path]:
    return sorted(path for path in site.glob("*.html") if path.name != "404.html")


def _article(page: Path) -> str:
    """The page's content, without the theme's navigation around it."""
    text = page.read_text()
    start = text.index("<article")
    return text[start : text.index("</article>", start)]


def _text(fragment: str) -> str:
    return html.unescape(re.sub(r"<[^>]+>", "", fragment))


def _context(text: str, position: int) -> str:
    return " ".join(_text(text[max(0, position - 80) : position + 60]).split())


def test_the_site_has_every_page(site):
    names = {page.name for page in _pages(site)}
    assert {"index.html", "api.html", "theory.html", "finite-range.html", "scene-reference.html"} <= names


def test_no_emphasis_opened_right_after_a_symbol(site):
    """`E*` outside a code span or math opens an emphasis that runs to the next star."""
    found = [
        f"{page.name}: …{_context(article, match.start() + 1)}…"
        for page in _pages(site)
        for article in [_article(page)]
        for match in EMPHASIS_AFTER_SYMBOL.finditer(article)
    ]
    assert not found, "a star after a symbol became emphasis (write `E*` or \\(E^*\\)):\n" + "\n".join(found)
    escaped = [page.name for page in _pages(site) if "\\*" in _article(page)]
    assert not escaped, f"a backslash-escaped star inside code shows its backslash: {escaped}"


def test_no_list_item_printed_as_text(site):
    """A list item that Markdown did not take as one (a continuation indented by fewer than four
    spaces, say) shows as a paragraph line starting with its marker."""
    found = [
        f"{page.name}: {line.strip()[:80]!r}"
        for page in _pages(site)
        for paragraph in re.findall(r"<p\b[^>]*>(.*?)</p>", _article(page), re.DOTALL)
        for line in _text(paragraph).splitlines()
        if re.match(r"\s*(?:[-*+]|\d+\.) +\S", line)
    ]
    assert not found, "Markdown list items printed as text:\n" + "\n".join(found)


def _remote(url: str) -> bool:
    return url.startswith("//") or urlsplit(url).scheme in ("http", "https")


def _attribute(tag: str, name: str) -> str | None:
    match = re.search(rf"""\b{name}\s*=\s*["']([^"']*)["']""", tag)
    return match.group(1) if match else None


def _resources(page: Path) -> list[str]:
    """The scripts and stylesheets a page loads."""
    text = page.read_text()
    urls = [_attribute(tag, "src") for tag in re.findall(r"<script\b[^>]*>", text)]
    urls += [
        _attribute(tag, "href")
        for tag in re.findall(r"<link\b[^>]*>", text)
        if re.search(r"""\brel=["'][^"']*\b(?:stylesheet|preload|modulepreload|preconnect)\b""", tag)
    ]
    return [url for url in urls if url]


def test_no_script_or_stylesheet_from_another_host(site):
    remote = sorted({f"{page.name}: {url}" for page in _pages(site) for url in _resources(page) if _remote(url)})
    assert not remote, "the site loads from other hosts (it must work offline):\n" + "\n".join(remote)
    imports = sorted(
        str(path.relative_to(site))
        for path in site.rglob("*.css")
        if re.search(r"@import\s+url\(\s*['\"]?(?:https?:)?//", path.read_text())
    )
    assert not imports, f"stylesheets importing from other hosts: {imports}"


def test_every_script_and_stylesheet_is_in_the_site(site):
    missing = sorted(
        {
            f"{page.name}: {url}"
            for page in _pages(site)
            for url in _resources(page)
            if not _remote(url) and not (page.parent / urlsplit(url).path).is_file()
        }
    )
    assert not missing, "scripts or stylesheets missing from the site:\n" + "\n".join(missing)


def test_math_is_typeset_by_a_mathjax_the_site_serves(site):
    theory = site / "theory.html"
    assert _article(theory).count('class="arithmatex"') > 100
    (bundle,) = [theory.parent / url for url in _resources(theory) if url.endswith("tex-mml-chtml.js")]
    assert bundle.stat().st_size > 500_000  # MathJax itself, not a stub
    fonts = list((bundle.parent / "output/chtml/fonts/woff-v2").glob("MathJax_*.woff"))
    assert len(fonts) >= 20, "MathJax's CommonHTML fonts are not beside its bundle"
    assert (bundle.parent / "input/tex/extensions/ams.js").is_file()


def test_every_figure_links_to_its_full_size_file(site):
    """Multi-panel figures are shrunk to the column: a click must open them at full size."""
    unlinked, figures = [], 0
    for page in _pages(site):
        article = _article(page)
        for match in re.finditer(r"<img\b[^>]*>", article):
            figures += 1
            source = _attribute(match.group(0), "src")
            link = article.rfind("<a ", 0, match.start())
            if (
                link < article.rfind("</a>", 0, match.start())
                or _attribute(article[link : match.start()], "href") != source
            ):
                unlinked.append(f"{page.name}: {source}")
            elif not (page.parent / source).is_file():
                unlinked.append(f"{page.name}: {source} (no such file)")
    assert figures >= 10
    assert not unlinked, "figures without a link to their file:\n" + "\n".join(unlinked)


def _class_block(api: str, name: str) -> str:
    """The API page's block of `impact.<name>`: from its heading to the next heading of its level."""
    start = api.index(f'<h3 id="impact.{name}"')
    end = api.find("<h3 ", start + 1)
    return api[start : end if end > 0 else len(api)]


def _member_description(block: str, owner: str, name: str) -> str | None:
    """The description of a member: its row in the Attributes table, or its own entry (a property)."""
    row = re.search(
        rf'<tr class="doc-section-item">\s*<td><code><span title="impact\.{owner}\.{name}">{name}</span>'
        r"</code></td>(.*?)</tr>",
        block,
        re.DOTALL,
    )
    if row:
        return " ".join(_text(row.group(1)).split())
    anchor = block.find(f'id="impact.{owner}.{name}"')
    if anchor < 0:
        return None
    following = re.compile(r"<h[1-6] ").search(block, anchor)
    entry = block[block.rfind("<h", 0, anchor) : following.start() if following else len(block)]
    return " ".join(_text(entry).split())


def _members(cls: type) -> list[str]:
    """The fields and public properties of a result class."""
    properties = [name for name, value in vars(cls).items() if isinstance(value, property) and not name.startswith("_")]
    return [field.name for field in dataclasses.fields(cls)] + properties


@pytest.mark.parametrize("owner", RESULT_CLASSES)
def test_result_fields_on_the_api_page_with_their_units(site, owner):
    cls = getattr(impact, owner)
    assert NOT_QUANTITIES[owner] <= set(_members(cls)), "NOT_QUANTITIES names a member the class lacks"
    block = _class_block((site / "api.html").read_text(), owner)
    problems = []
    for name in _members(cls):
        description = _member_description(block, owner, name)
        if not description:
            problems.append(f"{name}: not on the API page (an `Attributes:` entry or a docstring)")
        elif name not in NOT_QUANTITIES[owner] and not UNIT.search(description):
            problems.append(f"{name}: no unit ([m], [J], ..., or dimensionless) in {description!r}")
    assert not problems, f"impact.{owner}:\n" + "\n".join(problems)


def test_signatures_are_formatted_to_the_column(site):
    api = (site / "api.html").read_text()
    signatures = [
        _text(block) for block in re.findall(r'<div class="doc-signature highlight"><pre>(.*?)</pre>', api, re.DOTALL)
    ]
    assert len(signatures) > 100
    long = [line for signature in signatures for line in signature.splitlines() if len(line) > SIGNATURE_WIDTH]
    message = f"signature lines wider than {SIGNATURE_WIDTH} characters (is ruff installed?):\n"
    assert not long, message + "\n".join(long)


def test_scene_reference_keys_do_not_break(site):
    """Each key of the generated tables is one unbreakable code span holding its dotted path."""
    article = _article(site / "scene-reference.html")
    keys = re.findall(r'<code class="nowrap" title="([\w.]+)">(\w+)</code>', article)
    assert len(keys) > 100
    assert all(path.rsplit(".", 1)[-1] == key for path, key in keys)
    css = (site / "stylesheets/extra.css").read_text()
    assert re.search(r"code\.nowrap\s*\{[^}]*white-space:\s*nowrap", css)


def test_pages_link_the_repository_and_name_their_address(site):
    config = mkdocs_config(CONFIG)
    assert config["site_url"].startswith("https://") and config["repo_url"].startswith("https://")
    index = (site / "index.html").read_text()
    assert f'<link rel="canonical" href="{config["site_url"]}index.html">' in index
    assert re.search(rf'<a href="{re.escape(config["repo_url"])}"[^>]*class="md-source"', index)
