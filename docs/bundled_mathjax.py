"""MkDocs hook: MathJax served from the site itself, so that the equations render offline.

The docs extra installs `django-static-mathjax`, a copy of MathJax 3 (its JavaScript and fonts
only: it needs no Django). `on_files` adds to the site, under `TARGET`, the bundle that
mkdocs.yml loads (TeX and MathML in, CommonHTML out) with what it loads on demand from the
folder it was loaded from: TeX extensions (autoload), the fonts, the accessibility and menu
components, and MathJax's licence.
"""

from importlib.metadata import PackageNotFoundError, distribution
from pathlib import Path

from mkdocs.exceptions import PluginError
from mkdocs.structure.files import File, Files

DISTRIBUTION = "django-static-mathjax"
SOURCE = "mathjax/static/mathjax"  # MathJax's npm package, inside the distribution
TARGET = "vendor/mathjax"
BUNDLE = "tex-mml-chtml.js"
# Paths in MathJax's es5/ folder, as the bundle asks for them relative to itself.
PARTS = (BUNDLE, "input/tex/extensions", "input/mml", "output/chtml", "a11y", "ui", "sre", "adaptors")


def mathjax_root() -> Path:
    """The installed MathJax package (holding LICENSE and es5/)."""
    try:
        root = Path(str(distribution(DISTRIBUTION).locate_file(SOURCE)))
    except PackageNotFoundError:
        raise PluginError(
            f"MathJax is missing: install the docs extra (pip install -e '.[docs]'), {DISTRIBUTION}"
        ) from None
    if not (root / "es5" / BUNDLE).is_file():
        raise PluginError(f"{DISTRIBUTION} holds no {SOURCE}/es5/{BUNDLE}: reinstall the docs extra")
    return root


def bundled_files(root: Path) -> dict[str, Path]:
    """Site path → installed file, for every file the site serves MathJax from."""
    es5 = root / "es5"
    found = {f"{TARGET}/LICENSE": root / "LICENSE"}
    for part in PARTS:
        path = es5 / part
        for file in [path] if path.is_file() else sorted(item for item in path.rglob("*") if item.is_file()):
            found[f"{TARGET}/{file.relative_to(es5).as_posix()}"] = file
    return found


def on_files(files: Files, config) -> Files:
    """Add MathJax's files to the site."""
    for uri, path in bundled_files(mathjax_root()).items():
        files.append(File.generated(config, uri, abs_src_path=str(path)))
    return files
