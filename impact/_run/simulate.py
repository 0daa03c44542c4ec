"""`simulate(scene)`: one scene, of either kind, results back in SI units."""

from pathlib import Path
from typing import TYPE_CHECKING

from .._core.runtime import float64
from .._scene.scene import Scene, load_scene
from .impacts import Result, simulate_impact

if TYPE_CHECKING:  # imported where a scene is one: an impact needs none of them
    from .indentation import IndentationResult
    from .shear import ShearResult


@float64
def simulate(
    scene: "Scene | dict | str | Path", *, trajectory: bool = True
) -> "Result | IndentationResult | ShearResult":
    """Run one scene (a `Scene`, a mapping or a YAML file). An impact gives a `Result`
    (`trajectory=False` skips its time series: faster); an indentation test (kind
    `indentation`) gives an `IndentationResult` (its curve is always kept), with a `shear`
    program a `ShearResult`. Computes in float64 whatever JAX's global flag."""
    scene = load_scene(scene)
    if scene.kind == "indentation" and scene.shear is not None:
        from .shear import simulate_shear

        return simulate_shear(scene)
    if scene.kind == "indentation":
        from .indentation import simulate_indentation

        return simulate_indentation(scene)
    return simulate_impact(scene, trajectory)
