"""A validated sweep: a base scene and axes over its numeric fields (`SweepSpec`, `Axis`).

`sweep.load_sweep` and `sweep.make_spec` build one; this module holds what it is.
"""

import math
from dataclasses import dataclass, field

import numpy as np
import yaml

from .scene import Scene, scene_yaml

MODES = ("grid", "zip")
ORDERS = ("cost", "given")
# Fields that feed the static choices of a point (a new value compiles anew) sit under these
# sections; every other numeric field is a traced parameter.
STATIC_SECTIONS = ("solver", "limits", "contact", "effects")
# Invalid values (or points) a refusal lists before it only counts the rest.
MAX_LISTED = 4


@dataclass(frozen=True)
class Axis:
    """One swept field: its dotted path, its validated values and how they were written."""

    path: str
    values: np.ndarray  # 1-D, float64 (or int64 for integer fields)
    spec: object = field(repr=False)  # canonical form: a list, or {generator: [start, stop, num]}
    unit: str = ""  # of the values, as the files write units ('m s-1'; '' dimensionless)

    @property
    def static(self) -> bool:
        """Whether the field may change the static choices (integrator, options) of a point."""
        return self.path.split(".")[0] in STATIC_SECTIONS


@dataclass(frozen=True)
class SweepSpec:
    """A validated sweep: the base scene, its axes, how they combine and in what order to run."""

    scene: Scene
    axes: tuple[Axis, ...]
    mode: str = "grid"
    order: str = "cost"
    source: str | None = field(default=None, repr=False, compare=False)  # verbatim file text
    # the method the points run (the scene's solver.method) and why (`sweep_method`)
    method_choice: str = field(default="", compare=False)

    @property
    def method(self) -> str:
        """The integrator every point runs (`solver.method` of the scene it runs)."""
        return self.scene.solver.method

    @property
    def shape(self) -> tuple[int, ...]:
        if self.mode == "zip":
            return (len(self.axes[0].values),)
        return tuple(len(axis.values) for axis in self.axes)

    @property
    def size(self) -> int:
        return math.prod(self.shape)

    @property
    def paths(self) -> tuple[str, ...]:
        return tuple(axis.path for axis in self.axes)

    def flat_params(self) -> dict[str, np.ndarray]:
        """Every swept value per point, flat in C order of `shape`."""
        if self.mode == "zip":
            return {axis.path: axis.values.copy() for axis in self.axes}
        grids = np.meshgrid(*(axis.values for axis in self.axes), indexing="ij")
        return {axis.path: grid.reshape(-1) for axis, grid in zip(self.axes, grids, strict=True)}

    def definition(self) -> str:
        """The canonical sweep YAML (base scene resolved inline): equal texts, equal sweeps."""
        data = {
            "scene": yaml.safe_load(scene_yaml(self.scene)),
            "axes": {axis.path: axis.spec for axis in self.axes},
            "mode": self.mode,
            "order": self.order,
        }
        return yaml.safe_dump(data, sort_keys=False)
