"""The panels of a fit of a quasi-static indentation curve (fit.png): the data of each branch
with error bars against the controlled value, the closed-form curve of each branch at the
fitted values (its jumps drawn as they happen), and the normalised residuals below; of a
viscoelastic test at a rate, each curve (rate) against time with the model at its rows."""

from typing import TYPE_CHECKING

import jax
import jax.numpy as jnp
import numpy as np

from .._run.fit import FitResult, theory_applies, theory_model
from .._run.fit.curve import IndentationCurve
from .._scene.fit_curve import BRANCH, BRANCHES, TIME
from .figures import si_prefix

if TYPE_CHECKING:
    from matplotlib.axes import Axes

UNITS = {"indentation": "m", "force": "N", "contact_radius": "m", "time": "s"}
STYLES = {"approach": ("o", "C0"), "retract": ("s", "C3")}
DENSE = 400  # points of each branch's closed-form curve


def draw_curve(top: "Axes", bottom: "Axes", result: FitResult, index: int) -> None:
    """One observable of an indentation fit against the controlled value (gids as `fit_figure`)."""
    spec = result.spec
    assert spec.control is not None, "an indentation curve"
    name = list(spec.observables)[index]
    control, data = spec.data[spec.control], spec.data[name]
    model, sigma = result.model[:, index], result.sigma[:, index]
    x_factor, x_prefix = si_prefix(float(np.max(np.abs(control))))
    y_factor, y_prefix = si_prefix(float(np.max(np.abs(data))))
    curves = _closed_form(result, control)
    for label, rows, (marker, color) in _groups(result):
        x = control[rows] * x_factor
        top.errorbar(
            x, data[rows] * y_factor, yerr=sigma[rows] * y_factor, fmt=marker, ms=3, color=color,
            label=f"{label} ± σ", gid="data",
        )  # fmt: skip
        if curves is None:
            top.plot(x, model[rows] * y_factor, "x", color=color, label=f"{label}: model at the fit", gid="model")
        else:
            dense, values = curves[label]
            top.plot(dense * x_factor, values[:, index] * y_factor, "-", color=color, lw=1.2, gid="model",
                     label=f"{label}: closed form at the fit")  # fmt: skip
        bottom.plot(x, (model[rows] - data[rows]) / sigma[rows], marker, ms=3, color=color, gid="residuals")
    bottom.axhline(0.0, color="0.6", lw=0.8)
    top.set_ylabel(f"{name} ({y_prefix}{UNITS[name]})")
    bottom.set_xlabel(f"{spec.control} ({x_prefix}{UNITS[spec.control]})")


def _groups(result: FitResult):
    """(label, rows, style) of each group of rows drawn: the branches, or the curves of a test in
    time (one per value of its first input, e.g. the rate)."""
    spec = result.spec
    if spec.control != TIME:
        return [(label, spec.data[BRANCH] == code, STYLES[label]) for label, code in BRANCHES.items()]
    column = spec.data[spec.inputs[0]] if spec.inputs else np.zeros(spec.rows)
    values = np.unique(column)
    name = spec.inputs[0].rsplit(".", 1)[-1] if spec.inputs else ""
    return [
        (f"{name} {value:g}" if name else "curve", column == value, ("o", f"C{index}"))
        for index, value in enumerate(values)
    ]


def _closed_form(result: FitResult, control: np.ndarray) -> dict[str, tuple[np.ndarray, np.ndarray]] | None:
    """Per branch, the closed-form curve at the fitted values on a dense grid of the control
    (in the order of the test: approach rising, retract falling), or None where none applies."""
    spec = result.spec
    if spec.inputs or spec.control == TIME or not theory_applies(spec):
        return None
    model = theory_model(spec)
    assert isinstance(model, IndentationCurve), "the closed form of an indentation scene"
    rising = np.linspace(control.min(), control.max(), DENSE)
    curves = {}
    with jax.enable_x64(True):
        values = jnp.asarray(list(result.values.values()))
        evaluate = jax.jit(lambda points: model.batched(values, points))  # one curve, all points
        for label, code in BRANCHES.items():
            grid = rising if code == 0 else rising[::-1]
            points = jnp.stack([jnp.asarray(grid), jnp.full(DENSE, code)], axis=1)
            curves[label] = (grid, np.asarray(evaluate(points)))
    return curves
