"""impact: time-stepping simulator of adhesive impacts (MDR contact law on JAX and diffrax).

The public API is what this module exports; everything in a module whose name starts with an
underscore is private. Call `impact.configure()` first in scripts (the CLI does): float64,
XLA:CPU compiling the spring arrays' loops whole (many times faster), and the compilation cache.

The names are imported on first use (PEP 562), so that `import impact` (and `impact --help`)
does not load JAX until something needs it.
"""

import importlib
from typing import TYPE_CHECKING

from ._core.package import __version__ as __version__

if TYPE_CHECKING:
    from . import profiles as profiles
    from . import theory as theory
    from ._core.runtime import configure as configure
    from ._io.results import open_run as open_run
    from ._io.results import open_sweep as open_sweep
    from ._run.differentiable import as_function as as_function
    from ._run.fit import FitResult as FitResult
    from ._run.fit import fit as fit
    from ._run.impacts import Result as Result
    from ._run.indentation import IndentationResult as IndentationResult
    from ._run.shear import ShearResult as ShearResult
    from ._run.simulate import simulate as simulate
    from ._run.sweep import SweepResult as SweepResult
    from ._run.sweep import sweep as sweep
    from ._run.viscoelastic import Relaxation as Relaxation
    from ._scene.cost import allow_long as allow_long
    from ._scene.fit_spec import FitError as FitError
    from ._scene.scene import Scene as Scene
    from ._scene.scene import SceneError as SceneError
    from ._scene.scene import load_scene as load_scene

# Each public name → the module that defines it (the subpackages are their own modules).
_SOURCES = {
    "FitError": "._scene.fit_spec",
    "FitResult": "._run.fit",
    "IndentationResult": "._run.indentation",
    "Relaxation": "._run.viscoelastic",
    "Result": "._run.impacts",
    "Scene": "._scene.scene",
    "SceneError": "._scene.scene",
    "ShearResult": "._run.shear",
    "SweepResult": "._run.sweep",
    "allow_long": "._scene.cost",
    "as_function": "._run.differentiable",
    "configure": "._core.runtime",
    "fit": "._run.fit",
    "load_scene": "._scene.scene",
    "open_run": "._io.results",
    "open_sweep": "._io.results",
    "profiles": ".profiles",
    "simulate": "._run.simulate",
    "sweep": "._run.sweep",
    "theory": ".theory",
}

__all__ = [
    "FitError",
    "FitResult",
    "IndentationResult",
    "Relaxation",
    "Result",
    "Scene",
    "SceneError",
    "ShearResult",
    "SweepResult",
    "__version__",
    "allow_long",
    "as_function",
    "configure",
    "fit",
    "load_scene",
    "open_run",
    "open_sweep",
    "profiles",
    "simulate",
    "sweep",
    "theory",
]


def __getattr__(name: str) -> object:
    """Import a public name on first use and keep it in the module."""
    if name not in _SOURCES:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    module = importlib.import_module(_SOURCES[name], __name__)
    value = module if name in ("profiles", "theory") else getattr(module, name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})
