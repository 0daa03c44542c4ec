"""The method a sweep runs: the one its scene names (`solver.method`), else the fastest the scene
allows at every point, the quadrature (no ODE solve), else the scene's default ODE solver.

A single run keeps what its scene says; a sweep of a scene that names no method runs the
quadrature wherever `method_support.quadrature_refusal` lets every point run it. A point of such a
sweep equals a single run of its scene with `solver.method: quadrature` named. The choice and
its reason are the spec's `method_choice`, printed by `impact validate` and the sweep's summary
and stored with the sweep's file.
"""

from dataclasses import replace

from .errors import SweepError
from .method_support import quadrature_refusal
from .paths import with_values
from .scene import Scene
from .sections import QUADRATURE
from .sweep_points import check_points
from .sweep_spec import SweepSpec

NAMED = "named by the scene (solver.method)"
FASTER = "; 'quadrature' would run it without an ODE solve"
CHOSEN = "the scene names no method and 'quadrature' runs every point, without an ODE solve"
# The section whose fields set the ODE solve: an axis over one of them keeps the ODE solver.
SOLVER_SECTION = "solver."


def names_method(scene: Scene) -> bool:
    """Whether the scene names its integrator (`solver.method` given, whatever its value)."""
    return "method" in scene.solver.model_fields_set


def scene_sweep_method(scene: Scene) -> tuple[str, str]:
    """(method, why) a sweep of the scene runs, before its axes are known (`impact validate`)."""
    why = quadrature_refusal(scene)
    if names_method(scene):
        return scene.solver.method, _named(scene, why)
    if why is None:
        default = scene.solver.method
        return (
            QUADRATURE,
            f"the scene names no method and 'quadrature' runs it (a sweep keeps {default} "
            "where an axis takes a point outside it)",
        )
    return scene.solver.method, _default(why)


def with_sweep_method(spec: SweepSpec) -> SweepSpec:
    """The spec with the method its points run and why (`method_choice`), every point validated
    with it (`check_points`): SweepError where a point is invalid whatever the method."""
    scene = spec.scene
    why = quadrature_refusal(scene)
    if names_method(scene):
        check_points(spec)
        return replace(spec, method_choice=_named(scene, why))
    solver_axes = [path for path in spec.paths if path.startswith(SOLVER_SECTION)]
    if why is None and solver_axes:
        why = f"would leave the axis {solver_axes[0]} without effect (a setting of the ODE solve)"
    if why is None:
        fast = replace(spec, scene=with_values(scene, {"solver.method": QUADRATURE}), method_choice=CHOSEN)
        try:
            check_points(fast)
        except SweepError as error:
            why = "does not run every point: " + "; ".join(message for _, message in error.problems)
        else:
            return fast
    check_points(spec)
    return replace(spec, method_choice=_default(why))


def _named(scene: Scene, refusal: str | None) -> str:
    """Why a sweep runs the method the scene names, and that the quadrature would be faster where it is."""
    faster = refusal is None and scene.solver.method != QUADRATURE
    return NAMED + (FASTER if faster else "")


def _default(refusal: str) -> str:
    """Why a sweep runs the scene's default method: the refusal of the quadrature."""
    return f"the default: the scene names no method and 'quadrature' {refusal}"
