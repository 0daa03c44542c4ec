"""Results as labelled arrays and tables: an `xarray.Dataset` and a `pandas.DataFrame` of a sweep
(one dimension per axis; one row a point), of an impact's time series (one row a sample) and of
an indentation test's curve (one row a point). xarray and pandas are the optional extra
`impact-mdr[analysis]`, imported only here and only when a conversion is called.

Conventions (CF, as xarray and the netCDF tools read them): every number has a `units` attribute
(UDUNITS, as the HDF5 files write units; '1' where dimensionless) and a `description`; `stuck`
is boolean; the status is an integer variable of result codes with `flag_values` and
`flag_meanings` (the names of `RESULT_CODES`, `not_run` for −1), and a categorical of the names
in a data frame. The attributes hold the resolved scene (YAML) and the versions that produced
the result: those stored with a file read back (`stats["provenance"]`), else this process's.
"""

import importlib
from types import ModuleType
from typing import TYPE_CHECKING, Any

import numpy as np

from .._core.package import DISTRIBUTION
from .._core.runtime import provenance
from .._integrate.codes import RESULT_CODE, RESULT_CODES
from .._scene.scene import Scene, scene_yaml
from .losses import NAMED_LOSSES
from .sweep.result import RESULTS
from .tangential import TANGENTIAL_SERIES
from .units import (
    CONTACT_SERIES,
    CURVE_TIME,
    DERIVED_LOSSES,
    INDENTATION_CURVE,
    MAXIMA_UNITS,
    PULL_OFF_UNITS,
    SCALAR_UNITS,
    VELOCITY_SERIES,
)

if TYPE_CHECKING:
    import pandas
    import xarray

    from .impacts import Result
    from .indentation import IndentationResult
    from .sweep.result import SweepResult

EXTRA = "analysis"
NOT_RUN = "not run"  # the status of a sweep's point not run (code −1)
STATUS_NAMES = (*RESULT_CODES, NOT_RUN)  # a data frame's categories, in the order of the codes
POINT = "point"  # the dimension of a zipped sweep and of an indentation curve; a sweep's table rows
SAMPLE = "sample"  # the dimension of an impact's time series
EVENT = "event"  # the dimension of a run's events
TIME = ("s", "time since the start of the run")


def require(name: str) -> ModuleType:
    """Import `name` (xarray or pandas), or ImportError naming the extra that installs it."""
    try:
        return importlib.import_module(name)
    except ImportError:
        raise ImportError(
            f"{name} is not installed: results as labelled arrays and tables need the optional extra "
            f"{DISTRIBUTION}[{EXTRA}] (pip install '{DISTRIBUTION}[{EXTRA}]')"
        ) from None


def number_attributes(unit: str, description: str = "") -> dict[str, str]:
    """`units` ('1' for a dimensionless number) and `description` (where given) of a variable."""
    return {"units": unit or "1", **({"description": description} if description else {})}


def status_attributes() -> dict[str, Any]:
    """The result codes as CF flags: `flag_values` −1, 0, 1, … and their `flag_meanings`."""
    return {
        "description": "result code: flag_meanings names each of flag_values",
        "flag_values": np.arange(-1, len(RESULT_CODES), dtype=np.int32),
        "flag_meanings": " ".join(name.replace(" ", "_") for name in STATUS_NAMES[-1:] + STATUS_NAMES[:-1]),
    }


def status_categories(codes: np.ndarray) -> "pandas.Categorical":
    """Result codes (−1: not run) as a categorical of their names."""
    pandas = require("pandas")
    codes = np.asarray(codes)
    return pandas.Categorical.from_codes(np.where(codes < 0, len(RESULT_CODES), codes), categories=STATUS_NAMES)


def attributes(scene: Scene, stats: dict, **more: str) -> dict[str, str | int]:
    """The attributes of a dataset: the resolved scene, `more`, and the versions that produced it
    (x64 as 0 or 1: netCDF has no boolean attribute)."""
    versions = stats.get("provenance") or provenance()
    return {
        "scene": scene_yaml(scene),
        **more,
        **{key: int(value) if isinstance(value, bool) else value for key, value in versions.items()},
    }


def frame_of(columns: dict[str, np.ndarray], units: dict[str, str], index: str) -> "pandas.DataFrame":
    """A data frame of `columns` (status codes become a categorical of their names) whose
    `attrs["units"]` holds the unit of every numeric column ('1' where dimensionless)."""
    pandas = require("pandas")
    data = {name: status_categories(column) if name == "status" else column for name, column in columns.items()}
    frame = pandas.DataFrame(data)
    frame.index.name = index
    frame.attrs["units"] = {name: units[name] or "1" for name in columns if name in units}
    return frame


# --- sweeps -------------------------------------------------------------------------------------


def sweep_units(result: "SweepResult") -> dict[str, str]:
    """The unit of every axis and numeric result column of a sweep ('' dimensionless)."""
    units = {axis.path: axis.unit for axis in result.spec.axes}
    units.update({name: RESULTS[name][2] for name in result.results if name not in ("status", "stuck")})
    return units


def sweep_dataset(result: "SweepResult") -> "xarray.Dataset":
    """See `SweepResult.to_xarray`."""
    xarray = require("xarray")
    spec = result.spec
    zipped = spec.mode == "zip"
    coordinates = {
        axis.path: (POINT if zipped else axis.path, axis.values, number_attributes(axis.unit, "swept scene field"))
        for axis in spec.axes
    }
    dimensions = (POINT,) if zipped else spec.paths
    variables = {}
    for name, column in result.results.items():
        _, _, unit, description = RESULTS[name]
        if name == "status":
            described = status_attributes()
        elif name == "stuck":
            described = {"description": description}
        else:
            described = number_attributes(unit, description)
        variables[name] = (dimensions, column, described)
    more = {"sweep": spec.definition(), "mode": spec.mode}
    return xarray.Dataset(variables, coordinates, attributes(result.scene, result.stats, **more))


def sweep_frame(result: "SweepResult") -> "pandas.DataFrame":
    """See `SweepResult.to_pandas`."""
    columns = {path: values.reshape(-1) for path, values in result.params.items()}
    columns.update({name: column.reshape(-1) for name, column in result.results.items()})
    return frame_of(columns, sweep_units(result), POINT)


# --- one impact ---------------------------------------------------------------------------------


def run_series(result: "Result") -> dict[str, tuple[np.ndarray, str, str]]:
    """An impact's time series by name: (values, unit, description), time first."""
    series = {"time": (result.t, *TIME)}
    series["indentation"] = (result.indentation, *CONTACT_SERIES["indentation"])
    series["velocity"] = (result.velocity, *VELOCITY_SERIES)
    for name in ("contact_radius", "force"):
        series[name] = (getattr(result, name), *CONTACT_SERIES[name])
    if result.scene.effects.friction is not None:
        for name, described in TANGENTIAL_SERIES.items():
            series[name] = (getattr(result, name), *described)
    return series


def run_scalars(result: "Result") -> dict[str, str]:
    """An impact's scalar results (name → unit) as its file stores them: the derived losses
    where the scene names what they describe."""
    derived = {name: "J" for name in DERIVED_LOSSES if NAMED_LOSSES[name](result.scene)}
    return {**SCALAR_UNITS, **derived}


def run_dataset(result: "Result") -> "xarray.Dataset":
    """See `Result.to_xarray`."""
    xarray = require("xarray")
    series = run_series(result)
    time, unit, description = series.pop("time")
    coordinates = {"time": (SAMPLE, time, number_attributes(unit, description))}
    variables: dict[str, tuple] = {
        name: (SAMPLE, values, number_attributes(*described)) for name, (values, *described) in series.items()
    }
    for name, unit in run_scalars(result).items():
        variables[name] = _scalar(name, getattr(result, name), unit)
    variables.update(_events(result.events, "event_time", np.float64, TIME))
    return xarray.Dataset(variables, coordinates, attributes(result.scene, result.stats))


def run_frame(result: "Result") -> "pandas.DataFrame":
    """See `Result.to_pandas`."""
    series = run_series(result)
    return frame_of({name: values for name, (values, _, _) in series.items()}, _units(series), SAMPLE)


# --- one indentation test -----------------------------------------------------------------------


def curve_series(result: "IndentationResult") -> dict[str, tuple[np.ndarray, str, str]]:
    """An indentation test's curve by name: (values, unit, description), with the time of a
    viscoelastic test at a rate."""
    series = {name: (getattr(result, name), unit, what) for name, (unit, what) in INDENTATION_CURVE.items()}
    if result.time is not None:
        series["time"] = (result.time, *CURVE_TIME)
    return series


def indentation_dataset(result: "IndentationResult") -> "xarray.Dataset":
    """See `IndentationResult.to_xarray`."""
    xarray = require("xarray")
    variables: dict[str, tuple] = {
        name: (POINT, values, number_attributes(*described))
        for name, (values, *described) in curve_series(result).items()
    }
    variables["status"] = _scalar("status", result.status, "")
    for name, unit in MAXIMA_UNITS.items():
        variables[name] = _scalar(name, getattr(result, name), unit)
    for name, unit in PULL_OFF_UNITS.items():
        variables[f"pull_off_{name}"] = _scalar(f"pull_off_{name}", getattr(result.pull_off, name), unit)
    at = ("", "index of the curve point where the event occurs")
    variables.update(_events(result.events, "event_point", np.int64, at))
    return xarray.Dataset(variables, attrs=attributes(result.scene, result.stats))


def indentation_frame(result: "IndentationResult") -> "pandas.DataFrame":
    """See `IndentationResult.to_pandas`."""
    series = curve_series(result)
    return frame_of({name: values for name, (values, _, _) in series.items()}, _units(series), POINT)


# --- parts --------------------------------------------------------------------------------------


def _units(series: dict[str, tuple[np.ndarray, str, str]]) -> dict[str, str]:
    return {name: unit for name, (_, unit, _) in series.items()}


def _scalar(name: str, value: Any, unit: str) -> tuple[tuple, Any, dict]:
    """A 0-d variable: the status as its code (CF flags), `stuck` boolean, a number with units."""
    description = RESULTS[name][3] if name in RESULTS else ""
    if name == "status":
        return (), np.int32(RESULT_CODE[value]), status_attributes()
    if name == "stuck":
        return (), np.bool_(value), {"description": description}
    return (), value, number_attributes(unit, description)


def _events(events: list, first: str, dtype: type, described: tuple[str, str]) -> dict[str, tuple]:
    """A run's events along their own dimension: where (`first`, of `dtype`, in the unit of
    `described`) and kind."""
    where: np.ndarray = np.array([place for place, _ in events], dtype=dtype)
    kinds = np.array([kind for _, kind in events], dtype=object)
    return {
        first: (EVENT, where, number_attributes(*described)),
        "event_kind": (EVENT, kinds, {"description": "kind of each event"}),
    }
