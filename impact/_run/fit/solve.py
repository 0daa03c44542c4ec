"""`impact.fit`: weighted least squares by Levenberg–Marquardt (optimistix) on exact Jacobians.

The residuals r = (model − data)/σ of every row and observable (σ·|data| for a relative σ) are
minimised over search variables u that map smoothly onto the parameters' bounds (`bounds`); the
Jacobian is forward-mode (`jax.jacfwd`) through the model. The uncertainty follows from the
Jacobian in the physical parameters at the optimum (`uncertainty`). The data enter the compiled
programs as arguments: a second fit of the same model and bounds compiles nothing, and where
the model describes itself (impact's own models: the simulation, the closed forms) the programs
are stored traced in the cache (`impact._core.stored`), so that a later process neither traces
nor compiles them. The whole solve is one program without host callbacks (which would keep it
out of the cache): each step's χ² and parameters are recorded in it and reported after it.
"""

import dataclasses
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
import optimistix as optx

from ..._core.runtime import float64
from ..._core.stored import call_stored
from ..._scene.fit_spec import FUNCTION, FitError, FitSpec, make_fit_spec
from .bounds import Bounds
from .models import DESCRIBED, Model, simulation_model, theory_model
from .uncertainty import uncertainty

# Levenberg–Marquardt stops when a step changes u (of order 1) and the residuals by less than
# this in root mean square, relative and absolute. Near the optimum each step squares the error:
# the step that passes leaves the parameters far below any standard error from the optimum.
# (A max norm, or a tolerance of 1e-8, waits on rounding: many more steps to the same optimum.)
TOLERANCE = 1e-6
MAX_STEPS = 100
SIGMA_SOURCES = {
    True: "given: the standard errors follow from the σ of the data",
    False: "scatter: σ unknown, the covariance is scaled by χ²/dof",
}

Progress = Callable[[int, float, dict[str, float]], None]


@dataclass(frozen=True)
class FitResult:
    """A fit's outcome, in SI units. The matrices over the parameters follow the order of
    `spec.parameters`; those over the data have one row per data row, one column per observable.

    Attributes:
        spec: The validated fit: the scene, the data, the parameters and the observables.
        values: The fitted value of each parameter, by dotted path [SI].
        standard_errors: The standard error of each parameter, by dotted path [SI]; nan where the
            data do not determine it (see `unidentifiable`).
        covariance: The parameters' covariance matrix [p, p], in the products of their SI units
            [SI].
        correlation: The parameters' correlation matrix [p, p], dimensionless.
        chi2: χ², the sum of the squared weighted residuals (model − data)/σ at the fit,
            dimensionless.
        dof: Degrees of freedom: residuals less parameters.
        converged: Whether Levenberg–Marquardt met its tolerance within the allowed steps.
        iterations: Levenberg–Marquardt steps taken.
        sigma_source: Where the standard errors come from: the σ of the data (`given`), or
            the scatter of the residuals (σ unknown: the covariance is scaled by χ²/dof).
        unidentifiable: A message for each parameter, or combination, the data do not
            determine.
        model: The model at the fit [rows, observables], in the observables' units [SI].
        sigma: The σ each residual was weighted with [rows, observables], in the observables'
            units [SI]; 1 where σ is unknown.
        jacobian: The derivatives of the weighted residuals in the parameters
            [rows·observables, p], per SI unit of each parameter [SI].
    """

    spec: FitSpec
    values: dict[str, float]
    standard_errors: dict[str, float]
    covariance: np.ndarray = field(repr=False)
    correlation: np.ndarray = field(repr=False)
    chi2: float
    dof: int
    converged: bool
    iterations: int
    sigma_source: str
    unidentifiable: list[str]
    model: np.ndarray = field(repr=False)
    sigma: np.ndarray = field(repr=False)
    jacobian: np.ndarray = field(repr=False)


class Measurements(eqx.Module):
    """What the residuals take besides the parameters (traced: other data compile nothing)."""

    bounds: Bounds
    rows: jax.Array  # [rows, inputs]
    measured: jax.Array  # [rows, observables]
    sigma: jax.Array  # [rows, observables]
    scale: jax.Array  # the root mean square of the weighted residuals at the start


@dataclass(frozen=True)
class Residuals:
    """r = (model − data)/σ, flat."""

    model: Model

    def predicted(self, values, rows):
        """The model at every row: its `batched` form where it has one (which computes what does
        not depend on the row once), else the model mapped over the rows."""
        batched = getattr(self.model, "batched", None)
        if batched is not None:
            return batched(values, rows)
        return jax.vmap(lambda row: jnp.atleast_1d(self.model(jnp.concatenate([values, row]))))(rows)

    def weighted(self, values, data: Measurements):
        return ((self.predicted(values, data.rows) - data.measured) / data.sigma).reshape(-1)

    def __call__(self, u, data: Measurements):
        """The residuals LM sees: divided by their root mean square at the start, as its damping,
        which starts at 1, is not invariant to their scale."""
        return self.weighted(data.bounds.physical(u), data) / data.scale


class StepRecord(eqx.Module):
    """The state of `RecordingTrustRegion`: the trust region's own, and what each step evaluated."""

    search: Any  # the trust region's state
    steps: jax.Array  # how many steps were taken
    losses: jax.Array  # [max_steps] ½·|r|² at the point each step evaluated (NaN after the last)
    points: jax.Array  # [max_steps, p] that point u


class RecordingTrustRegion(optx.AbstractSearch):
    """Levenberg–Marquardt's classical trust region, recording each step's loss and point: the
    progress of a fit, read after the solve instead of printed from inside it."""

    search: optx.ClassicalTrustRegion
    max_steps: int = eqx.field(static=True)

    def init(self, y, f_info_struct) -> StepRecord:
        losses, points = (jnp.full(shape, jnp.nan, y.dtype) for shape in ((self.max_steps,), (self.max_steps, y.size)))
        return StepRecord(self.search.init(y, f_info_struct), jnp.array(0), losses, points)

    def step(self, first_step, y, y_eval, f_info, f_eval_info, state: StepRecord):
        step_size, accept, result, search = self.search.step(first_step, y, y_eval, f_info, f_eval_info, state.search)
        losses = state.losses.at[state.steps].set(0.5 * jnp.sum(f_eval_info.residual**2))
        points = state.points.at[state.steps].set(y_eval)
        return step_size, accept, result, StepRecord(search, state.steps + 1, losses, points)


def fit(
    scene,
    data: "Mapping | str | Path",
    parameters: Mapping[str, Mapping],
    observables: Mapping[str, Mapping],
    inputs: Sequence[str] = (),
    *,
    model: "Model | str" = "simulation",
    branch: str | None = None,
    progress: Progress | None = None,
    max_steps: int = MAX_STEPS,
) -> FitResult:
    """Fit scene values to measurements by weighted least squares (Levenberg–Marquardt).

    `scene`: a Scene, a scene file or mapping; `data`: columns by name or a CSV file (one row
    per measurement): the observables, their σ columns and the `inputs` (dotted scene paths
    set row by row); `parameters`: dotted path → {start, min, max, scale: linear|log};
    `observables`: result name → {sigma: number or column name (leave out when unknown),
    relative: bool}. `model`: "simulation" (the default), "theory" (a closed form instead of
    the simulation: Thornton–Ning, restitution and max_force), or any differentiable function
    of the vector [parameters, inputs] to the vector of the observables. An indentation scene
    fits its quasi-static curve: the data hold the controlled value of each row (`indentation`
    under displacement control, `force` under force control), appended to the model's vector
    with the row's branch code (0 approach, 1 retract) from the column of labels `branch`
    (approach, retract; default: approach up to the largest control value). `progress(step, chi2,
    values)` is called for every step, in order, once the solve (one compiled program) has
    ended: χ² and the parameters at the point the step evaluated. Raises `FitError` (a
    `SceneError`) naming a bad field."""
    kind = model if isinstance(model, str) else FUNCTION
    spec = make_fit_spec(scene, data, parameters, observables, inputs, kind, branch)
    return fit_spec(spec, model, progress, max_steps)


@float64
def fit_spec(
    spec: FitSpec, model: "Model | str" = "simulation", progress: Progress | None = None, max_steps: int = MAX_STEPS
) -> FitResult:
    """Run a validated fit (`impact.fit` after validation; `impact fit` with a fit file)."""
    names = tuple(spec.parameters)
    residuals, bounds = Residuals(_model(spec, model)), Bounds.of(spec.parameters)
    given = spec.sigmas()
    measured = np.stack([spec.data[name] for name in spec.observables], axis=1)
    sigma = np.ones(measured.shape) if given is None else given
    rows = np.stack([spec.data[column] for column in spec.row_columns], axis=1).reshape(spec.rows, -1)
    # The scale a placeholder until the start's residuals (which do not use it) give it.
    data = Measurements(bounds, *(jnp.asarray(array) for array in (rows, measured, sigma, np.float64(1.0))))
    start = jnp.asarray(bounds.internal([entry.start for entry in spec.parameters.values()]))
    at_start = np.asarray(_start_residuals(residuals, start, data))
    _check_start(spec, at_start.reshape(measured.shape))
    data = dataclasses.replace(data, scale=jnp.sqrt(jnp.mean(at_start**2)))
    solved = {name: np.asarray(value) for name, value in _compiled(_solve, residuals, max_steps, start, data).items()}
    scale = float(data.scale)
    if progress is not None:
        for step in range(int(solved["steps"])):
            chi2 = 2.0 * float(solved["losses"][step]) * scale**2
            progress(step, chi2, dict(zip(names, solved["history"][step].tolist(), strict=True)))
    values, weighted, jacobian, predicted = _at_optimum(solved, data)
    chi2, dof = float(weighted @ weighted), weighted.size - len(names)
    found = uncertainty(jacobian, values, names, list(spec.observables), 1.0 if given is not None else chi2 / dof)
    return FitResult(
        spec=spec,
        values=dict(zip(names, values.tolist(), strict=True)),
        standard_errors=dict(zip(names, found.standard_errors.tolist(), strict=True)),
        covariance=found.covariance,
        correlation=found.correlation,
        chi2=chi2,
        dof=dof,
        converged=bool(solved["converged"]),
        iterations=int(solved["steps"]),
        sigma_source=SIGMA_SOURCES[given is not None],
        unidentifiable=found.unidentifiable,
        model=predicted,
        sigma=sigma,
        jacobian=jacobian,
    )


# A weighted residual above this makes χ² (a sum of up to 10⁸ squares) overflow float64.
_LARGEST_RESIDUAL = 1e150


def _check_start(spec: FitSpec, weighted: np.ndarray) -> None:
    """FitError where the weighted residuals [rows, observables] at the parameters' start are
    not all numbers (the model gives none for a row there) or so large that χ² overflows: each
    observable's first rows named."""
    start = ", ".join(f"{path} = {entry.start:g}" for path, entry in spec.parameters.items())
    problems = []
    for column, name in enumerate(spec.observables):
        values = weighted[:, column]
        missing, huge = np.flatnonzero(np.isnan(values)), np.flatnonzero(~(np.abs(values) <= _LARGEST_RESIDUAL))
        if missing.size:
            problems.append(
                (
                    f"observables.{name}",
                    f"the model gives no number at the parameters' start ({start}) in {_rows(missing)}: change the "
                    "start or the data (with model simulation, the run of such a row ends without a physical "
                    "outcome there: `impact run` its scene with the row's inputs to see why)",
                )
            )
        elif huge.size:
            row = huge[0]
            problems.append(
                (
                    f"observables.{name}",
                    f"(model − measured)/σ is {values[row]:.3g} in {_rows(huge)} at the parameters' start: beyond "
                    f"{_LARGEST_RESIDUAL:g}, χ² overflows float64; check the measured value "
                    f"{spec.data[name][row]:g} and its σ",
                )
            )
    if problems:
        raise FitError(problems)


def _rows(indices: np.ndarray) -> str:
    """'data row 3', 'data rows 1, 2, 5' or 'data rows 1, 2, 5, 7 and 26 more'."""
    shown = ", ".join(str(index + 1) for index in indices[:4].tolist())
    more = f" and {indices.size - 4} more" if indices.size > 4 else ""
    return f"data row{'s' if indices.size > 1 else ''} {shown}{more}"


def _model(spec: FitSpec, model: "Model | str") -> Model:
    if callable(model):
        return model
    return theory_model(spec) if model == "theory" else simulation_model(spec)


def _compiled(function: Callable, residuals: Residuals, *arguments: Any) -> Any:
    """`function(residuals, *arguments)` compiled: stored traced across processes where the model
    describes itself (`models.DESCRIBED`: its repr names its program), else traced once in this
    process (a function passed to `impact.fit`, told apart by its identity)."""
    if isinstance(residuals.model, DESCRIBED):
        return call_stored(function, residuals, *arguments)
    return _TRACED[function](residuals, *arguments)


def _solve(residuals: Residuals, max_steps: int, start: jax.Array, data: Measurements) -> dict[str, jax.Array]:
    """Levenberg–Marquardt from `start` (in u): the optimum (u and the parameters), the
    residuals LM sees and their Jacobian in u (from its last accepted step: no program of the
    model compiled anew), the slope of each bound's map there, whether it converged, its steps,
    and each step's loss and parameters (`history`, physical)."""
    solver = optx.LevenbergMarquardt(rtol=TOLERANCE, atol=TOLERANCE, norm=optx.rms_norm)
    solver = eqx.tree_at(lambda lm: lm.search, solver, RecordingTrustRegion(solver.search, max_steps))
    solution = optx.least_squares(residuals, solver, start, data, max_steps=max_steps, throw=False)
    record = solution.state.search_state
    return {
        "value": solution.value,
        "parameters": data.bounds.physical(solution.value),
        "residual": solution.state.f_info.residual,
        "jacobian": solution.state.f_info.jac.as_matrix(),
        "slopes": jnp.diagonal(jax.jacfwd(data.bounds.physical)(solution.value)),
        "converged": solution.result == optx.RESULTS.successful,
        "steps": solution.stats["num_steps"],
        "losses": record.losses,
        "history": jax.vmap(data.bounds.physical)(record.points),
    }


def _weighted(residuals: Residuals, u: jax.Array, data: Measurements) -> jax.Array:
    """The weighted residuals at u: the model's value alone (its Jacobian is not compiled)."""
    return residuals.weighted(data.bounds.physical(u), data)


def _row(residuals: Residuals, x: jax.Array) -> jax.Array:
    """The model at one vector x [parameters, inputs]."""
    return jnp.atleast_1d(residuals.model(x))


_TRACED = {function: eqx.filter_jit(function) for function in (_solve, _weighted, _row)}


def _start_residuals(residuals: Residuals, u, data: Measurements) -> jax.Array:
    """The weighted residuals at the start: a model without a batched form called row by row,
    one compiled program for every row (one row's program compiles in much less time than a
    batch over the rows), a batched one in one call."""
    if getattr(residuals.model, "batched", None) is not None:
        return _compiled(_weighted, residuals, u, data)
    values = data.bounds.physical(u)
    predicted = jnp.stack([_compiled(_row, residuals, jnp.concatenate([values, row])) for row in data.rows])
    return ((predicted - data.measured) / data.sigma).reshape(-1)


def _at_optimum(solved: dict[str, np.ndarray], data: Measurements) -> tuple[np.ndarray, ...]:
    """The parameters, weighted residuals, their Jacobian and the model at the optimum. The
    Jacobian in u is the one in the parameters times the slope of each bound's map
    (elementwise), over the residuals' scale; a map saturated at its bound (slope 0 in float64)
    leaves its parameter a column of zeros: not determined by the data."""
    values = solved["parameters"]
    scale = float(data.scale)
    weighted = solved["residual"] * scale
    in_u = solved["jacobian"] * scale
    slopes = solved["slopes"]
    jacobian = np.divide(in_u, slopes, out=np.zeros_like(in_u), where=slopes != 0)
    predicted = weighted.reshape(data.measured.shape) * np.asarray(data.sigma) + np.asarray(data.measured)
    return values, weighted, jacobian, predicted
