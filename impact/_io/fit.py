"""A fit's outputs: `fit.yaml` (the summary a person reads) and `fit.h5` (everything, H5MD 1.1
flavoured: de Buyl et al., Comput. Phys. Commun. 185, 1546 (2014)).

fit.h5 layout (SI units; parameters and observables in the order of the fit file):

    h5md/                          version, author, creator, modules/units (as every file)
    fit/
        parameters/{name[p], value[p], standard_error[p]}   nan: not determined by the data
        covariance[p, p], correlation[p, p]
        jacobian[rows·observables, p]    ∂r/∂p of the weighted residuals r = (model − data)/σ
        data/<column>[rows]              the columns the fit read (inputs, observables, σ; an
                                         indentation curve's controlled value and branch, 0 approach)
        model/<observable>[rows]         the model at the fit
        sigma/<observable>[rows]         σ as weighted (1 where σ is unknown)
        attributes: chi2, dof, converged, iterations, sigma_source, model, unidentifiable
    parameters/
        config.yaml                      the resolved scene; provenance attributes
        fit.yaml                         the fit file as given, --set overrides applied (where there was one)
"""

import math
from pathlib import Path

import h5py
import numpy as np
import yaml

from .._run.fit import FitResult
from .files import write_text
from .h5md import new_h5md, read_string, write_scene, write_string

SUMMARY = ("chi2", "dof", "converged", "iterations", "sigma_source")


def _number(value: float) -> float | None:
    return None if math.isnan(value) else float(value)


def fit_summary(result: FitResult) -> dict:
    """The content of fit.yaml: parameters with value and standard error (null where the data
    do not determine it), correlation, χ², dof, convergence and the unidentifiable directions."""
    return {
        "parameters": {
            path: {"value": result.values[path], "standard_error": _number(result.standard_errors[path])}
            for path in result.values
        },
        "correlation": [[_number(entry) for entry in row] for row in result.correlation.tolist()],
        **{name: getattr(result, name) for name in SUMMARY},
        "model": result.spec.model,
        "unidentifiable": list(result.unidentifiable),
    }


def write_fit_yaml(result: FitResult, path: str | Path) -> Path:
    """fit.yaml, atomically."""
    write_text(path, yaml.safe_dump(fit_summary(result), sort_keys=False, allow_unicode=True, width=100))
    return Path(path)


def write_fit(result: FitResult, path: str | Path, *, author: str | None = None) -> Path:
    """fit.h5, atomically."""
    path = Path(path)
    with new_h5md(path, author) as file:
        group = file.create_group("fit")
        _write_parameters(group.create_group("parameters"), result)
        for name in ("covariance", "correlation", "jacobian"):
            group.create_dataset(name, data=getattr(result, name))
        for column, values in result.spec.data.items():
            group.create_dataset(f"data/{column}", data=values)
        for index, name in enumerate(result.spec.observables):
            group.create_dataset(f"model/{name}", data=result.model[:, index])
            group.create_dataset(f"sigma/{name}", data=result.sigma[:, index])
        for name in SUMMARY:
            group.attrs[name] = getattr(result, name)
        group.attrs["model"] = result.spec.model
        group.attrs["unidentifiable"] = yaml.safe_dump(list(result.unidentifiable), allow_unicode=True)
        parameters = file.create_group("parameters")
        write_scene(parameters, result.spec.scene)
        if result.spec.source is not None:
            write_string(parameters, "fit.yaml", result.spec.source)
    return path


def _write_parameters(group: h5py.Group, result: FitResult) -> None:
    group.create_dataset("name", data=list(result.values), dtype=h5py.string_dtype())
    group.create_dataset("value", data=np.array(list(result.values.values())))
    group.create_dataset("standard_error", data=np.array(list(result.standard_errors.values())))


def read_fit(path: str | Path) -> dict:
    """What `write_fit` stored: the summary of `fit_summary` plus the arrays (covariance,
    correlation, jacobian; data, model and sigma by column) and the fit file's text."""
    with h5py.File(path, "r") as file:
        group = file["fit"]
        names = [name.decode() if isinstance(name, bytes) else name for name in group["parameters/name"][()]]
        values, errors = group["parameters/value"][()], group["parameters/standard_error"][()]
        stored = {
            "parameters": {
                name: {"value": float(value), "standard_error": _number(error)}
                for name, value, error in zip(names, values, errors, strict=True)
            },
            **{name: group[name][()] for name in ("covariance", "correlation", "jacobian")},
            **{part: {name: group[part][name][()] for name in group[part]} for part in ("data", "model", "sigma")},
            **{name: _plain(group.attrs[name]) for name in (*SUMMARY, "model")},
            "unidentifiable": yaml.safe_load(group.attrs["unidentifiable"]),
        }
        if "fit.yaml" in file["parameters"]:
            stored["source"] = read_string(file["parameters/fit.yaml"])
    return stored


def _plain(value):
    """An HDF5 attribute as a Python value (numpy scalars to int, float, bool, str)."""
    return value.item() if isinstance(value, np.generic) else value
