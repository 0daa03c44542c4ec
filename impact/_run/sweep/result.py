"""The results of a sweep: every scalar result of every point, in the sweep's shape."""

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..._integrate.codes import RESULT_CODE, RESULT_CODES
from ..._scene.paths import with_values
from ..._scene.scene import Scene
from ..._scene.sweep_spec import SweepSpec
from ..impacts import velocities_after
from ..losses import NAMED_LOSSES
from ..tangential import TANGENTIAL_RESULTS

if TYPE_CHECKING:
    import pandas
    import xarray

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
    "plastic_work": (np.float64, np.nan, "J", "the part of dissipated_energy lost to plastic flow"),
    "viscous_work": (np.float64, np.nan, "J", "the part of dissipated_energy lost to damping or a viscoelastic medium"),
    "adhesion_hysteresis": (
        np.float64,
        np.nan,
        "J",
        "the rest of dissipated_energy: the jump-in and snap-off of the adhesive contact",
    ),
    "unrecovered_elastic_energy": (
        np.float64,
        np.nan,
        "J",
        "the rest of dissipated_energy of a damped contact without adhesion: elastic energy left in the surface",
    ),
    "body_velocity_after": (
        np.float64,
        np.nan,
        "m s-1",
        "the body's velocity after the first contact, lab frame, along its approach (< 0: rebounding)",
    ),
    "counterpart_velocity_after": (
        np.float64,
        np.nan,
        "m s-1",
        "the counterpart's velocity after the first contact, lab frame, along the body's approach",
    ),
    "steps": (np.int64, -1, "", "solver steps"),
    "accepted_steps": (np.int64, -1, "", "accepted solver steps"),
    "rejected_steps": (np.int64, -1, "", "rejected solver steps"),
    "theory_restitution": (np.float64, np.nan, "", "closed-form restitution of the chapter (NaN where none)"),
    **{name: (np.float64, np.nan, unit, what) for name, (unit, what) in TANGENTIAL_RESULTS.items()},
}

# The columns a sweep holds only where its base scene names what they describe (an axis can set
# a named effect's values, never name one).
NAMED_BY: dict[str, Callable[[Scene], bool]] = {
    **NAMED_LOSSES,
    "body_velocity_after": lambda scene: scene.counterpart is not None,
    "counterpart_velocity_after": lambda scene: scene.counterpart is not None,
    **{name: (lambda scene: scene.effects.friction is not None) for name in TANGENTIAL_RESULTS},
}
LOSSES = tuple(NAMED_LOSSES)
# The columns computed on the host from a chunk's solved columns (the rest come from the batch).
LAB_VELOCITIES = ("body_velocity_after", "counterpart_velocity_after")
SOLVED = tuple(name for name in RESULTS if name not in LAB_VELOCITIES)


def result_names(scene: Scene) -> tuple[str, ...]:
    """The result columns of a sweep of `scene`, in the order of RESULTS."""
    return tuple(name for name in RESULTS if name not in NAMED_BY or NAMED_BY[name](scene))


def chunk_columns(scene: Scene, params: dict[str, np.ndarray], points: np.ndarray, solved: dict) -> dict:
    """The result columns of a chunk's points (`params`: the sweep's flat swept values) from
    the batch's `solved` columns: with a counterpart, both bodies' lab-frame velocities after
    the first contact as `simulate` gives them (`velocities_after`, NaN without a physical
    outcome)."""
    columns = dict(solved)
    if scene.counterpart is not None:
        success = (solved["status"] == RESULT_CODE["separated"]) | (solved["status"] == RESULT_CODE["captured"])
        rebound = np.where(success, solved["separation_velocity"], np.nan)
        batch = with_values(scene, {path: values[points] for path, values in params.items()})
        _, columns["body_velocity_after"], columns["counterpart_velocity_after"] = velocities_after(batch, rebound)
    return {name: np.asarray(columns[name], dtype=RESULTS[name][0]) for name in result_names(scene)}


@dataclass
class SweepResult:
    """Every scalar result of a sweep as an array in the sweep's shape (grid: one axis per swept
    field, in the order given; zip: one axis), in SI units. Each point's results are those of
    `impact.Result` for its scene with the sweep's method named (`spec.method`).

    Attributes:
        spec: The validated sweep: the base scene, its axes, the mode and the order; `spec.method`, the
            integrator every point ran, and `spec.method_choice`, why (named by the scene, or chosen).
        params: The swept values of each point, by dotted path [SI].
        restitution: Rebound speed over touch speed of the first contact, dimensionless; 0 if
            captured, nan without a physical outcome.
        stuck: Whether the body ended captured.
        status: The result code of each point: the index of its name in the table of
            `impact.Result.status` (0 `separated`, 1 `captured`, ...; −1 for a point not run).
        contact_time: Duration of the first contact [s]; inf if it never let go, nan without a
            touch.
        max_indentation: Deepest indentation [m].
        max_force: Largest compressive force [N].
        min_force: Most adhesive (most negative) force [N].
        bounces: Contacts simulated.
        touch_velocity: Speed at the first touch [m/s].
        separation_velocity: Speed when the first contact let go [m/s]; 0 if captured.
        dissipated_energy: Energy lost in the first contact [J].
        steps: Solver steps.
        accepted_steps: Accepted solver steps.
        rejected_steps: Rejected solver steps.
        theory_restitution: The chapter's closed-form restitution, dimensionless, where the
            scene has one, else nan.
        stats: The cost of the run: `points`, `chunk`, `devices`, `groups`, `plan_time`,
            `compile_time`, `solve_time` (s), `points_per_second`; read back by
            `impact.open_sweep`, the file's attributes and its `provenance` (the versions that
            wrote it).
        plastic_work: The part of `dissipated_energy` lost to plastic flow [J]; only where the
            base scene names `effects.plasticity`, else None.
        viscous_work: The part of `dissipated_energy` lost to damping or to the dashpots of a
            viscoelastic medium [J]; only where the base scene names `effects.damping` or
            `effects.viscoelasticity`, else None.
        adhesion_hysteresis: The rest of `dissipated_energy`, lost at the jump-in and the
            snap-off of the adhesive contact [J]; only where the base scene names adhesion, else
            None.
        unrecovered_elastic_energy: The elastic energy left in the surface when the contact
            ends [J] (of a damped contact without adhesion, the rest of `dissipated_energy`);
            only where the base scene names damping or viscoelasticity, else None.
        body_velocity_after: The body's velocity after the first contact, lab frame, along its
            approach [m/s] (< 0: rebounding); only with a counterpart, else None.
        counterpart_velocity_after: The counterpart's velocity after the first contact, lab
            frame, along the body's approach [m/s]; only with a counterpart, else None.
        tangential_velocity_after: Velocity of the centre along the surface after the first
            contact [m/s]; only where the base scene names `effects.friction`, else None (as the
            five below; each as in `impact.Result`).
        spin_after: Spin after the first contact in radians per second [s⁻¹].
        tangential_restitution: |v_t′|/v_t of the centre, dimensionless.
        contact_point_tangential_restitution: −w′/w of the contact point, dimensionless.
        rebound_angle: Angle of the rebound from the surface normal in radians (dimensionless).
        friction_work: Energy lost to friction in the first contact [J].
    """

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
    # Present where the base scene names what they describe (`NAMED_BY`), else None:
    plastic_work: np.ndarray | None = None
    viscous_work: np.ndarray | None = None
    adhesion_hysteresis: np.ndarray | None = None
    unrecovered_elastic_energy: np.ndarray | None = None
    body_velocity_after: np.ndarray | None = None
    counterpart_velocity_after: np.ndarray | None = None
    tangential_velocity_after: np.ndarray | None = None
    spin_after: np.ndarray | None = None
    tangential_restitution: np.ndarray | None = None
    contact_point_tangential_restitution: np.ndarray | None = None
    rebound_angle: np.ndarray | None = None
    friction_work: np.ndarray | None = None

    @property
    def scene(self) -> Scene:
        """The base scene."""
        return self.spec.scene

    @property
    def shape(self) -> tuple[int, ...]:
        """The sweep's shape: one axis per swept field (grid), or one (zip)."""
        return self.spec.shape

    @property
    def axes(self) -> dict[str, np.ndarray]:
        """The values of each axis (1-D), by dotted path [SI]."""
        return {axis.path: axis.values for axis in self.spec.axes}

    @property
    def results(self) -> dict[str, np.ndarray]:
        """Every result column the sweep holds, by name (in the order of RESULTS) [SI]."""
        return {name: getattr(self, name) for name in RESULTS if getattr(self, name) is not None}

    @property
    def success(self) -> np.ndarray:
        """Points with a physical outcome (separated or captured)."""
        return (self.status == RESULT_CODE["separated"]) | (self.status == RESULT_CODE["captured"])

    def status_names(self) -> np.ndarray:
        """Result codes as names ('not run' for -1)."""
        names = np.array([*RESULT_CODES, "not run"], dtype=object)
        return names[np.where(self.status < 0, len(RESULT_CODES), self.status)]

    def named_losses(self) -> dict[str, np.ndarray]:
        """The columns of the named losses the scene has (J), by name: they sum to
        `dissipated_energy`."""
        return {name: column for name, column in self.results.items() if name in LOSSES}

    def energy_imbalance(self) -> float:
        """max |½m(v₀² − v₁²) − Σ named losses| over the points with a physical outcome, relative
        to the energy turned over there, ½mv₀² + Σ|named losses| (m the reduced mass; NaN if
        none): the balance of each point's first contact, closed to the solver's tolerance."""
        if not self.success.any():
            return math.nan
        batch = with_values(self.scene, {path: values[self.success] for path, values in self.params.items()})
        touch, separation = self.touch_velocity[self.success], self.separation_velocity[self.success]
        losses = [column[self.success] for column in self.named_losses().values()] or [np.zeros_like(touch)]
        lost = 0.5 * batch.reduced_mass * (touch**2 - separation**2)
        turnover = 0.5 * batch.reduced_mass * touch**2 + np.sum(np.abs(losses), axis=0)
        return float(np.max(np.abs(lost - np.sum(losses, axis=0)) / turnover))

    def max_theory_error(self) -> float:
        """max |e − e_theory| over the points with a physical outcome and a closed form (NaN if none)."""
        usable = self.success & np.isfinite(self.theory_restitution)
        if not usable.any():
            return math.nan
        return float(np.max(np.abs(self.restitution[usable] - self.theory_restitution[usable])))

    def to_xarray(self) -> "xarray.Dataset":
        """The sweep as an `xarray.Dataset` (needs the extra `impact-mdr[analysis]`).

        Dimensions: a grid's axes, each named by its dotted path, with the swept values as
        coordinates; a zipped sweep's one dimension `point`, with each zipped path a coordinate
        along it. Variables: every result column (`results`), with `units` (UDUNITS, '1' where
        dimensionless, coordinates too) and `description`; `status` holds the result codes as
        CF flags (`flag_values` −1, 0, 1, …; `flag_meanings` `not_run separated captured …`).
        Attributes: `scene` (the resolved base scene, YAML), `sweep` (the sweep's definition),
        `mode`, and `impact_version`, `jax_version`, `diffrax_version`, `x64` (those stored in
        the file for a sweep read by `impact.open_sweep`, else this process's). The variables
        hold the result's own arrays, not copies."""
        from ..labelled import sweep_dataset

        return sweep_dataset(self)

    def to_pandas(self) -> "pandas.DataFrame":
        """The sweep as a `pandas.DataFrame`, one row a point in C order of `shape` (needs the
        extra `impact-mdr[analysis]`): a column per swept path, then every result column;
        `status` a categorical of the names ('not run' for −1). `attrs["units"]` holds the unit
        of every numeric column ('1' where dimensionless)."""
        from ..labelled import sweep_frame

        return sweep_frame(self)

    @classmethod
    def from_flat(cls, spec: SweepSpec, params: dict, results: dict, stats: dict | None = None) -> "SweepResult":
        shape = spec.shape
        return cls(
            spec=spec,
            params={path: np.asarray(values).reshape(shape) for path, values in params.items()},
            **{name: np.asarray(results[name]).reshape(shape) for name in RESULTS if name in results},
            stats=dict(stats or {}),
        )


def empty_results(size: int, names: "tuple[str, ...] | None" = None) -> dict[str, np.ndarray]:
    """Columns of `size` points not run, by name (every one of RESULTS, or `names`)."""
    return {name: np.full(size, RESULTS[name][1], dtype=RESULTS[name][0]) for name in names or tuple(RESULTS)}
