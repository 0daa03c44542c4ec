"""A scene's velocity sweep run by LAMMPS (at dt and dt/2) and by `impact.sweep`, side by side.

LAMMPS's own time-step error is |X(dt) − X(dt/2)|: where the error of the run at dt goes as
dt^p (p ≥ 1), that error is the difference times 1/(1 − 2^−p) ≤ 2, so the two codes agree to
LAMMPS's time-step error where |X_lammps(dt) − X_impact| ≤ 2|X(dt) − X(dt/2)|, plus impact's own
accuracy. Contact times are counted in whole steps: their step error is at least dt.
"""

import math
import time
from dataclasses import dataclass

import numpy as np

from .. import theory
from .._integrate.codes import RESULT_CODES
from .._run.sweep import SweepResult, sweep
from .._scene.scene import Scene
from .granular import NormalModel
from .lammps_batch import BatchResult, run_batch
from .lammps_model import CompareError, LammpsModel, effective_radius, lammps_model

VELOCITY = "initial.velocity"
QUANTITIES = ("restitution", "contact_time", "max_force", "min_force")
DEFAULT_SPEEDS = 16  # speeds of the default sweep, from v0/4 to 2 v0
STEPS_PER_CONTACT = 2000  # default dt: the Hertz contact time at the fastest speed over this
LEAST_STEPS_PER_CONTACT = 20  # a dt above 1/20 of that contact time is refused
MOST_STEPS = 10**8  # steps of the run at dt/2 allowed
# The runs stop at this many Hertz contact times of the slowest speed: a particle in contact
# then is captured.
CAPTURE_CONTACTS = 20
# Agreement to the step error: the error of the run at dt is at most this many times |X(dt) − X(dt/2)|.
STEP_ERROR_FACTOR = 2.0
# impact's own relative accuracy at its default tolerance (restitution to 1e-9, contact times and
# forces to 1e-8: docs/src/accuracy.md), added to the step error when judging agreement.
IMPACT_ACCURACY = 1e-8
# The energy lost by both is compared where impact loses more than this fraction of the kinetic energy.
LEAST_LOSS = 1e-6


@dataclass(frozen=True)
class Comparison:
    """Both codes on the same speeds: LAMMPS at dt and dt/2, impact's sweep, their timings (s)."""

    scene: Scene
    model: LammpsModel
    velocities: np.ndarray
    lammps: BatchResult
    half_step: BatchResult
    impact: SweepResult
    impact_seconds: float

    def columns(self) -> dict[str, np.ndarray]:
        """The table: per speed, each quantity by both codes, LAMMPS at dt/2, the relative
        difference (lammps − impact)/impact, LAMMPS's relative step error |X(dt) − X(dt/2)|/impact
        (contact times: at least dt), and the ratio of the kinetic energies lost."""
        table: dict[str, np.ndarray] = {
            "velocity": self.velocities,
            "impact_status": np.array([RESULT_CODES[code] for code in self.impact.status.reshape(-1)]),
            "lammps_captured": self.lammps.captured,
        }
        for name in QUANTITIES:
            ours = getattr(self.impact, name).reshape(-1)
            theirs, half = getattr(self.lammps, name), getattr(self.half_step, name)
            with np.errstate(invalid="ignore"):  # inf − inf of points captured by both
                step, difference = np.abs(theirs - half), theirs - ours
            if name == "contact_time":
                step = np.maximum(step, self.lammps.dt)
            table |= {
                f"impact_{name}": ours,
                f"lammps_{name}": theirs,
                f"lammps_{name}_half_step": half,
                f"{name}_difference": _relative(difference, ours),
                f"{name}_step_error": _relative(step, ours),
            }
        lost = 1 - self.impact.restitution.reshape(-1) ** 2
        both_let_go = (self.impact.restitution.reshape(-1) > 0) & ~self.lammps.captured & (lost > LEAST_LOSS)
        table["energy_loss_ratio"] = np.where(both_let_go, _relative(1 - self.lammps.restitution**2, lost), np.nan)
        return table

    def agreement(self) -> dict[str, bool]:
        """Per quantity: whether |difference| ≤ STEP_ERROR_FACTOR × step error + IMPACT_ACCURACY
        (relative) at every speed both codes let go (finite values)."""
        table = self.columns()
        verdicts = {}
        for name in QUANTITIES:
            difference, step = table[f"{name}_difference"], table[f"{name}_step_error"]
            shown = np.isfinite(difference) & np.isfinite(step)
            bound = STEP_ERROR_FACTOR * step[shown] + IMPACT_ACCURACY
            verdicts[name] = bool(np.all(np.abs(difference[shown]) <= bound))
        return verdicts


def _relative(values: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """values/|reference|, NaN where the reference is 0 or not finite (captured, no outcome)."""
    usable = np.isfinite(reference) & (reference != 0)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(usable, values / np.abs(np.where(usable, reference, 1.0)), np.nan)


def default_velocities(scene: Scene) -> np.ndarray:
    """DEFAULT_SPEEDS speeds (m/s) from a quarter to twice the scene's initial velocity."""
    speed = scene.start.velocity
    return np.linspace(speed / 4, 2 * speed, DEFAULT_SPEEDS)


def hertz_time(scene: Scene, model: LammpsModel, speed: float) -> float:
    """Hertz's contact time (s) of the scene's contact at a body speed (m/s)."""
    approach = speed + model.particles.counterpart_velocity
    return float(theory.hertz_contact_time(approach, scene.reduced_mass, effective_radius(scene), model.E_star))


def time_step(scene: Scene, model: LammpsModel, velocities: np.ndarray, dt: float | None) -> float:
    """The time step (s): `dt`, or the Hertz contact time of the fastest speed over
    STEPS_PER_CONTACT; CompareError where it resolves that contact in fewer than
    LEAST_STEPS_PER_CONTACT steps or the run at dt/2 would take more than MOST_STEPS."""
    fastest, slowest = float(np.max(velocities)), float(np.min(velocities))
    shortest = hertz_time(scene, model, fastest)
    chosen = shortest / STEPS_PER_CONTACT if dt is None else dt
    largest = shortest / LEAST_STEPS_PER_CONTACT
    if not 0 < chosen <= largest:
        raise CompareError(
            [
                (
                    "--dt",
                    f"must be > 0 and resolve the shortest contact in {LEAST_STEPS_PER_CONTACT} steps: at most "
                    f"{largest:.4g} s (Hertz's contact time at {fastest:g} m/s is {shortest:.4g} s), got {chosen:g}",
                )
            ]
        )
    steps = CAPTURE_CONTACTS * hertz_time(scene, model, slowest) / (chosen / 2)
    if steps > MOST_STEPS:
        raise CompareError(
            [
                (
                    "--dt",
                    f"{chosen:g} s would take {steps:.3g} steps at dt/2, more than {MOST_STEPS:.0e}: take a larger dt",
                )
            ]
        )
    return chosen


def compare_lammps(
    scene: Scene,
    model: NormalModel | None = None,
    damping: str | None = None,
    velocities: np.ndarray | None = None,
    dt: float | None = None,
) -> Comparison:
    """Run the scene's speeds (default `default_velocities`) through LAMMPS's granular `model` at
    dt and dt/2 and through `impact.sweep`. Raises CompareError (before running anything) where
    LAMMPS cannot represent the scene, LammpsMissing without LAMMPS, LammpsFailed on its errors."""
    mapped = lammps_model(scene, model, damping)
    speeds = default_velocities(scene) if velocities is None else np.asarray(velocities, dtype=float)
    step = time_step(scene, mapped, speeds, dt)
    duration = CAPTURE_CONTACTS * hertz_time(scene, mapped, float(np.min(speeds)))
    lammps = run_batch(mapped, speeds, step, duration)
    half_step = run_batch(mapped, speeds, step / 2, duration)
    start = time.perf_counter()
    ours = sweep(scene, {VELOCITY: speeds}, order="given")
    seconds = time.perf_counter() - start
    return Comparison(scene, mapped, speeds, lammps, half_step, ours, seconds)


def finite_max(values: np.ndarray) -> float:
    """The largest |value| that is finite, NaN if none is."""
    shown = np.abs(values[np.isfinite(values)])
    return float(shown.max()) if shown.size else math.nan
