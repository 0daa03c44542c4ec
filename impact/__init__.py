"""impact: time-stepping simulator of adhesive impacts (MDR contact law on JAX and diffrax).

Call `impact.runtime.configure()` before use (the CLI does): float64, and XLA:CPU compiling the
spring arrays' loops whole (10× faster).
"""

from . import profiles
from ._core import runtime
from . import theory
from ._run.indentation import IndentationResult
from ._scene.scene import Scene, SceneError, load_scene
from ._run.simulate import Result, simulate
from ._run.sweep import SweepResult, sweep

__version__ = "0.1.0"

__all__ = [
    "IndentationResult",
    "Result",
    "Scene",
    "SceneError",
    "SweepResult",
    "load_scene",
    "profiles",
    "runtime",
    "simulate",
    "sweep",
    "theory",
    "__version__",
]
