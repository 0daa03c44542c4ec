"""The results of a sweep: every scalar result of every point, in the sweep's shape."""

import math
from dataclasses import dataclass, field

import numpy as np

from ..._integrate.codes import RESULT_CODE, RESULT_CODES
from ..._scene.scene import Scene
from ..._scene.sweep_spec import SweepSpec

# Scalar results per point: name → (dtype, fill value for points not run, unit, description).
RESULTS = {
    "restitution": (np.float64, np.nan, "", "rebound speed over touch speed of the first contact (0 if captured)"),
    "stuck": (np.bool_, False, "", "the body ended captured"),
    "status": (np.int32, -1, "", "result code, an index into RESULT_CODES (-1: not run)"),
    "contact_time": (
        np.float64,
        np.nan,
        "s",
        "duration of the first contact (inf if it never let go, NaN if no touch)",
    ),
    "max_indentation": (np.float64, np.nan, "m", "deepest indentation"),
    "max_force": (np.float64, np.nan, "N", "largest compressive force"),
    "min_force": (np.float64, np.nan, "N", "most adhesive (negative) force"),
    "bounces": (np.int32, -1, "", "contacts simulated"),
    "touch_velocity": (np.float64, np.nan, "m s-1", "speed at the first touch"),
    "separation_velocity": (np.float64, np.nan, "m s-1", "speed when the first contact let go (0 if captured)"),
    "dissipated_energy": (np.float64, np.nan, "J", "energy lost in the first contact"),
    "steps": (np.int64, -1, "", "solver steps"),
    "accepted_steps": (np.int64, -1, "", "accepted solver steps"),
    "rejected_steps": (np.int64, -1, "", "rejected solver steps"),
    "theory_restitution": (np.float64, np.nan, "", "closed-form restitution of the chapter (NaN where none)"),
}


@dataclass
class SweepResult:
    """Every scalar result of a sweep as an array in the sweep's shape (grid: one axis per swept
    field, in the order given; zip: one axis). `params[path]` holds the swept values per point,
    `status` the result codes (`impact._integrate.codes.RESULT_CODES`; -1 for a point not run), `stats` the
    cost of the run (points, chunk, devices, groups, plan/compile/solve time in s, points/s)."""

    spec: SweepSpec
    params: dict[str, np.ndarray]
    restitution: np.ndarray
    stuck: np.ndarray
    status: np.ndarray
    contact_time: np.ndarray
    max_indentation: np.ndarray
    max_force: np.ndarray
    min_force: np.ndarray
    bounces: np.ndarray
    touch_velocity: np.ndarray
    separation_velocity: np.ndarray
    dissipated_energy: np.ndarray
    steps: np.ndarray
    accepted_steps: np.ndarray
    rejected_steps: np.ndarray
    theory_restitution: np.ndarray
    stats: dict = field(default_factory=dict)

    @property
    def scene(self) -> Scene:
        return self.spec.scene

    @property
    def shape(self) -> tuple[int, ...]:
        return self.spec.shape

    @property
    def axes(self) -> dict[str, np.ndarray]:
        """The values of each axis (1-D)."""
        return {axis.path: axis.values for axis in self.spec.axes}

    @property
    def results(self) -> dict[str, np.ndarray]:
        return {name: getattr(self, name) for name in RESULTS}

    @property
    def success(self) -> np.ndarray:
        """Points with a physical outcome (separated or captured)."""
        return (self.status == RESULT_CODE["separated"]) | (self.status == RESULT_CODE["captured"])

    def status_names(self) -> np.ndarray:
        """Result codes as names ('not run' for -1)."""
        names = np.array([*RESULT_CODES, "not run"], dtype=object)
        return names[np.where(self.status < 0, len(RESULT_CODES), self.status)]

    def max_theory_error(self) -> float:
        """max |e − e_theory| over the points with a physical outcome and a closed form (NaN if none)."""
        usable = self.success & np.isfinite(self.theory_restitution)
        if not usable.any():
            return math.nan
        return float(np.max(np.abs(self.restitution[usable] - self.theory_restitution[usable])))

    @classmethod
    def from_flat(cls, spec: SweepSpec, params: dict, results: dict, stats: dict | None = None) -> "SweepResult":
        shape = spec.shape
        return cls(
            spec=spec,
            params={path: np.asarray(values).reshape(shape) for path, values in params.items()},
            **{name: np.asarray(results[name]).reshape(shape) for name in RESULTS},
            stats=dict(stats or {}),
        )


def empty_results(size: int) -> dict[str, np.ndarray]:
    return {name: np.full(size, fill, dtype=dtype) for name, (dtype, fill, _, _) in RESULTS.items()}
