"""Results exported for other tools, written atomically: a table as CSV (one header line of
names with their units in brackets) and a dataset as netCDF-4 (through h5netcdf, part of the
extra `impact-mdr[analysis]`)."""

from pathlib import Path
from typing import TYPE_CHECKING

from .._run.labelled import require
from .files import atomic_path

if TYPE_CHECKING:
    import pandas
    import xarray


def csv_header(frame: "pandas.DataFrame") -> list[str]:
    """The column names of a table of `impact._run.labelled`, each with its unit in brackets
    ('restitution [1]', 'initial.velocity [m s-1]'; the status and booleans without)."""
    units = frame.attrs.get("units", {})
    return [f"{name} [{units[name]}]" if name in units else str(name) for name in frame.columns]


def write_csv(frame: "pandas.DataFrame", path: str | Path) -> Path:
    """A table as CSV: its header line (`csv_header`), then one line a row; numbers round-trip
    exactly, NaN as `nan`, the status by name."""
    path = Path(path)
    with atomic_path(path) as temporary:
        frame.to_csv(temporary, header=csv_header(frame), index=False, na_rep="nan")
    return path


def write_netcdf(dataset: "xarray.Dataset", path: str | Path) -> Path:
    """A dataset as a netCDF-4 file (HDF5 underneath, through h5netcdf)."""
    require("h5netcdf")
    path = Path(path)
    with atomic_path(path) as temporary:
        dataset.to_netcdf(temporary, engine="h5netcdf")
    return path
