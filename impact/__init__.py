"""impact: time-stepping simulator of adhesive impacts (MDR contact law on JAX and diffrax).

The public API is what this module exports; everything in a module whose name starts with an
underscore is private. Call `impact.configure()` first in scripts (the CLI does): float64, and
XLA:CPU compiling the spring arrays' loops whole (10× faster).
"""

from . import profiles as profiles
from . import theory as theory
from ._core.package import __version__ as __version__
from ._core.runtime import configure as configure
from ._run.impacts import Result as Result
from ._run.indentation import IndentationResult as IndentationResult
from ._run.simulate import simulate as simulate
from ._run.sweep import SweepResult as SweepResult
from ._run.sweep import sweep as sweep
from ._scene.scene import Scene as Scene
from ._scene.scene import SceneError as SceneError
from ._scene.scene import load_scene as load_scene

__all__ = [
    "IndentationResult",
    "Result",
    "Scene",
    "SceneError",
    "SweepResult",
    "__version__",
    "configure",
    "load_scene",
    "profiles",
    "simulate",
    "sweep",
    "theory",
]
