"""`simulate` for scenes of kind `indentation`: a quasi-static loading program, results in SI.

The scene's program (peak, cycles, unload_to) becomes the legs of the march in `quasistatic`:
load to the peak, unload (to `unload_to`, or in the last cycle to pull-off), repeated. The
result holds the pull-off (the last stable state before the contact is lost) and the whole
curve (a, d, F) in program order, a jump showing as two points at the same control value.
"""

from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import TYPE_CHECKING

import jax
import numpy as np

from .._core.concrete import on_device
from .._core.pytree import fields
from .._core.stored import call_stored
from .._integrate.codes import RESULT_CODES
from .._integrate.quasistatic import EVENT_KINDS, Loading, QuasiStaticNumerics, march
from .._law.branches import Tabulation
from .._scene.scene import Scene
from .._scene.springs import spring_capacity

if TYPE_CHECKING:
    import pandas
    import xarray


@dataclass(frozen=True)
class PullOff:
    """The last stable state before the contact is lost (SI; nan if it never was)."""

    contact_radius: float  # m
    indentation: float  # m
    force: float  # N, < 0 adhesive


@dataclass(frozen=True)
class IndentationResult:
    """Outcome of a quasi-static indentation test, in SI units.

    The curve is in program order: `leg` numbers the program's legs (0 the first loading, 1 the
    first unloading, ...); a jump of the contact (jump-in, snap, landing at constant force,
    pull-off) shows as two consecutive points.

    Attributes:
        scene: The scene that was run.
        status: `separated` (pulled off), or why the program could not finish (the result codes
            of `impact.Result.status`).
        pull_off: The last stable state before the contact is lost: `.contact_radius` [m],
            `.indentation` [m] and `.force` [N] (< 0, adhesive); nan if it never was.
        contact_radius: Contact radius a of each point of the curve [m].
        indentation: Indentation d of each point [m], > 0 pressed in.
        force: Force F of each point [N], > 0 compressive.
        leg: The program leg of each point.
        events: (point index, kind) pairs, the kind one of `touch`, `snap_in`, `snap_out`,
            `pull_off`, `reversal`.
        stats: The march's `steps`, the radius its branches reach (`reach`, m) and its `scales`;
            read back by `impact.open_run`, the `provenance` of the file (the versions that wrote it).
        time: The time of each point [s] of a viscoelastic half-space's test at a rate
            (`program.rate`); None for a quasi-static test.
    """

    scene: Scene
    status: str  # codes.RESULT_CODES
    pull_off: PullOff
    contact_radius: np.ndarray = field(repr=False)
    indentation: np.ndarray = field(repr=False)
    force: np.ndarray = field(repr=False)
    leg: np.ndarray = field(repr=False)
    events: list[tuple[int, str]] = field(repr=False)  # kinds: quasistatic.EVENT_KINDS
    stats: dict = field(repr=False)
    time: np.ndarray | None = field(default=None, repr=False)

    @property
    def success(self) -> bool:
        """Whether the program ran to its pull-off."""
        return self.status == "separated"

    @property
    def xi(self) -> int:
        """The stability criterion of the control (3.35): 3 force, 1 displacement."""
        return 3 if self.scene.control == "force" else 1

    @property
    def max_force(self) -> float:
        """Largest compressive force of the curve [N] (0 if it never pressed)."""
        return float(np.max(self.force, initial=0.0))

    @property
    def max_indentation(self) -> float:
        """Deepest indentation of the curve [m] (0 if it never pressed in)."""
        return float(np.max(self.indentation, initial=0.0))

    @property
    def max_contact_radius(self) -> float:
        """Largest contact radius of the curve [m]."""
        return float(np.max(self.contact_radius, initial=0.0))

    def to_xarray(self) -> "xarray.Dataset":
        """The test as an `xarray.Dataset` (needs the extra `impact-mdr[analysis]`): the curve
        along `point`, the status, extremes and pull-off (`pull_off_force`, ...) as 0-d
        variables, the events along `event`; units, scene and versions as in
        `SweepResult.to_xarray`."""
        from .labelled import indentation_dataset

        return indentation_dataset(self)

    def to_pandas(self) -> "pandas.DataFrame":
        """The curve as a `pandas.DataFrame`, one row a point in program order (contact_radius,
        indentation, force, leg); `attrs["units"]` their units (needs the extra
        `impact-mdr[analysis]`)."""
        from .labelled import indentation_frame

        return indentation_frame(self)


_LEGS = 8  # programs of up to 4 cycles share one compilation (padded legs are never reached)


def legs(scene: Scene) -> tuple[np.ndarray, np.ndarray, int]:
    """(directions, targets in SI, count) of the program: +1 load to the peak, −1 unload
    (−inf: to pull-off); padded to a power of two (at least 8) beyond `count`."""
    program = scene.loading
    directions, targets = [], []
    for cycle in range(program.cycles):
        last = cycle == program.cycles - 1
        directions += [1, -1]
        targets += [program.peak, -np.inf if last or program.unload_to is None else program.unload_to]
    count = len(targets)
    size = max(_LEGS, 1 << (count - 1).bit_length())
    directions += [-1] * (size - count)
    targets += [-np.inf] * (size - count)
    return np.array(directions), np.array(targets, dtype=float), count


def indentation_numerics(scene: Scene) -> QuasiStaticNumerics:
    """The static choices of an indentation scene (changing them recompiles)."""
    springs = scene.contact.springs
    adhesion = scene.active_adhesion
    return QuasiStaticNumerics(
        adhesive=scene.adhesive,
        springs=None if springs == "continuum" else spring_capacity(springs),
        hysteresis=adhesion is not None and adhesion.curve_hysteresis(),
        tabulation=Tabulation.for_profile(scene.body.profile.build()),
    )


def indentation_loading(scene: Scene) -> Loading:
    """The traced SI parameters of an indentation scene (computed in NumPy, then copied into
    JAX arrays: `on_device`)."""
    directions, targets, count = legs(scene)
    springs = scene.contact.springs
    numbers = on_device(
        {
            "law": scene.contact_law(np),
            "E_star": np.asarray(scene.material.effective_modulus, np.float64),
            "force_control": np.asarray(scene.control == "force"),
            "directions": np.asarray(directions),
            "targets": np.asarray(targets, np.float64),
            "peak": np.asarray(scene.loading.peak, np.float64),
            "spring_length": np.asarray(np.nan if scene.contact.length is None else scene.contact.length, np.float64),
        }
    )
    return Loading(
        profile=scene.body.profile.build(),
        legs=jax.device_put(count),  # a Python int: weak-typed, as jnp.asarray makes it
        spring_count=jax.device_put(0 if springs == "continuum" else springs),
        **numbers,
    )


def simulate_indentation(scene: Scene) -> IndentationResult:
    """Run one scene of kind `indentation` (its program traced once per machine and structure:
    `impact._core.stored`)."""
    if scene.effects.viscoelasticity is not None:
        from .viscoelastic_indentation import simulate_rate_test  # it builds on this module

        return simulate_rate_test(scene)
    scales, outcome = call_stored(_march_by_field, indentation_loading(scene), indentation_numerics(scene), once=True)
    return to_indentation_result(scene, SimpleNamespace(**scales), SimpleNamespace(**outcome))


def _march_by_field(loading: Loading, numerics: QuasiStaticNumerics) -> tuple[dict, dict]:
    scales, outcome = march(loading, numerics)
    return fields(scales), fields(outcome)


def to_indentation_result(scene: Scene, scales, outcome) -> IndentationResult:
    """Scaled outcome → SI result (consecutive repeated points dropped); rows of five columns
    hold the time (s) of each point last."""
    radial, normal, force = (float(getattr(scales, name)) for name in ("radial", "normal", "force"))
    rows = np.asarray(outcome.rows)
    used = np.isfinite(rows[:, 0])
    count = int(np.sum(used))
    rows = rows[:count]
    repeated = np.zeros(count, dtype=bool)
    repeated[1:] = np.all(rows[1:, :3] == rows[:-1, :3], axis=1)
    kept = np.cumsum(~repeated) - 1  # new index of each old point (a repeat maps onto its original)
    rows = rows[~repeated]
    events = [
        (int(kept[min(max(index, 0), count - 1)]), EVENT_KINDS[int(kind)])
        for index, kind in np.asarray(outcome.events)
        if kind >= 0 and count
    ]
    a, d, F = np.asarray(outcome.pull_off, dtype=float)
    timed = rows.shape[1] > 4
    return IndentationResult(
        scene=scene,
        status=RESULT_CODES[int(outcome.status)],
        pull_off=PullOff(contact_radius=a * radial, indentation=d * normal, force=F * force),
        contact_radius=rows[:, 0] * radial,
        indentation=rows[:, 1] * normal,
        force=rows[:, 2] * force,
        leg=rows[:, 3].astype(int),
        events=events,
        stats={
            "steps": int(outcome.steps),
            "reach": float(outcome.top) * radial,
            "scales": {"radial": radial, "normal": normal, "force": force},
        },
        time=rows[:, 4] if timed else None,
    )
