"""The figure of a fit (fit.png): per observable, the data with error bars and the fitted
model against the input column (the row number without one), the closed-form curve at the
fitted values where one describes the scene, and the normalised residuals below."""

import math
from pathlib import Path
from typing import TYPE_CHECKING

import jax
import jax.numpy as jnp
import numpy as np

from .._run.fit import FitResult, theory_applies, theory_model
from .figures import si_prefix, write_figures
from .fit_curve import draw_curve

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

FIGURE = "fit.png"
UNITS = {"contact_time": "s", "max_indentation": "m", "max_force": "N", "min_force": "N", "dissipated_energy": "J"}
INPUT_UNITS = {"initial.velocity": "m/s", "initial.gap": "m", "body.mass": "kg"}


def fit_figure(result: FitResult) -> "Figure":
    """One column per observable: data ± σ (gid "data"), the model at the fit (gid "model"),
    the closed form (gid "theory") where it applies; (model − data)/σ below (gid "residuals")."""
    from matplotlib.figure import Figure

    spec = result.spec
    names = list(spec.observables)
    figure = Figure(figsize=(max(8.0, 5.0 * len(names)), 6.0), layout="constrained")
    axes = figure.subplots(2, len(names), sharex="col", height_ratios=(3, 1.2), squeeze=False)
    if spec.control is not None:
        for index in range(len(names)):
            draw_curve(axes[0, index], axes[1, index], result, index)
            axes[1, index].set_ylabel("(model − data)/σ")
            axes[0, index].legend(fontsize="small")
    else:
        _draw_impacts(axes, result)
    figure.suptitle(
        f"{spec.scene.name}: fit of {', '.join(spec.parameters)} (χ² = {result.chi2:.3g}, dof {result.dof})"
    )
    return figure


def _draw_impacts(axes, result: FitResult) -> None:
    """Each observable of a fit of impacts against the input column."""
    spec = result.spec
    x, label = _abscissa(result)
    curve = _theory_curve(result, x)
    for index, name in enumerate(spec.observables):
        _draw_observable(axes[0, index], axes[1, index], result, index, x, curve)
        _, prefix = si_prefix(float(np.max(np.abs(spec.data[name]))))
        unit = UNITS.get(name)
        axes[0, index].set_ylabel(f"{name} ({prefix}{unit})" if unit else name)
        axes[1, index].set_xlabel(label)
        axes[1, index].set_ylabel("(model − data)/σ")
        axes[0, index].legend(fontsize="small")


def _abscissa(result: FitResult) -> tuple[np.ndarray, str]:
    spec = result.spec
    if not spec.inputs:
        return np.arange(1, spec.rows + 1, dtype=float), "row"
    path = spec.inputs[0]
    unit = INPUT_UNITS.get(path)
    return spec.data[path], f"{path} ({unit})" if unit else path


def _draw_observable(top: "Axes", bottom: "Axes", result: FitResult, index: int, x, curve) -> None:
    name = list(result.spec.observables)[index]
    data, model, sigma = result.spec.data[name], result.model[:, index], result.sigma[:, index]
    factor, _ = si_prefix(float(np.max(np.abs(data))))
    order = np.argsort(x)
    top.errorbar(x, data * factor, yerr=sigma * factor, fmt="o", ms=3, color="C0", label="data ± σ", gid="data")
    top.plot(x[order], model[order] * factor, "-", color="C1", label="model at the fit", gid="model")
    if curve is not None:
        dense, values = curve
        top.plot(dense, values[:, index] * factor, ":", color="k", lw=1.0, label="closed form", gid="theory")
    bottom.axhline(0.0, color="0.6", lw=0.8)
    bottom.plot(x, (model - data) / sigma, "o", ms=3, color="C0", gid="residuals")
    if result.spec.inputs and np.all(x > 0) and x.max() > 5 * x.min():
        from matplotlib.ticker import FuncFormatter

        top.set_xscale("log")
        for axis in (top.xaxis, bottom.xaxis):
            axis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
            axis.set_minor_formatter(FuncFormatter(_minor_label))


def _minor_label(value: float, _) -> str:
    """Minor ticks of a log axis: label 2, 3 and 5 times a power of ten."""
    leading = round(value / 10.0 ** math.floor(math.log10(value)))
    return f"{value:g}" if leading in (2, 3, 5) else ""


def _theory_curve(result: FitResult, x: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """The closed form at the fitted values on a dense grid of the (single) input, or None."""
    spec = result.spec
    if len(spec.inputs) != 1 or not theory_applies(spec):
        return None
    dense = np.geomspace(x.min(), x.max(), 200) if x.min() > 0 else np.linspace(x.min(), x.max(), 200)
    model = theory_model(spec)
    with jax.enable_x64(True):
        values = jnp.asarray(list(result.values.values()))
        curve = jax.vmap(lambda row: model(jnp.concatenate([values, row[None]])))(jnp.asarray(dense))
    return dense, np.asarray(curve)


def save_fit_figure(result: FitResult, folder: str | Path) -> Path:
    """fit.png in `folder`, atomically."""
    return write_figures(folder, [(FIGURE, fit_figure(result))])[0]
