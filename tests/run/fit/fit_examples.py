"""The example fits' scripts of configs/fits (data makers, coverage), loaded as modules (they are
no package)."""

import importlib.util
from types import ModuleType

from tests.scenes import FITS


def fit_script(name: str) -> ModuleType:
    """configs/fits/<name>.py, e.g. make_drop_data or coverage, as a module."""
    spec = importlib.util.spec_from_file_location(name, FITS / f"{name}.py")
    assert spec is not None and spec.loader is not None, f"no script {name}.py in {FITS}"
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module
