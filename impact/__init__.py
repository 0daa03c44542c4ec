"""impact: time-stepping simulator of adhesive impacts (MDR contact law on JAX and diffrax).

Enable float64 before use (the CLI does): `jax.config.update("jax_enable_x64", True)`.
"""

from . import profiles, theory
from .indentation import IndentationResult
from .scene import Scene, SceneError, load_scene
from .simulate import Result, simulate
from .sweep import SweepResult, sweep

__version__ = "0.1.0"

__all__ = [
    "IndentationResult",
    "Result",
    "Scene",
    "SceneError",
    "SweepResult",
    "load_scene",
    "profiles",
    "simulate",
    "sweep",
    "theory",
    "__version__",
]
