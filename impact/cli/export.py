"""`impact export`: a stored sweep or run as CSV or netCDF, for spreadsheets, discrete-element
codes and analysis tools."""

from pathlib import Path

from .._io.export import write_csv, write_netcdf
from .._io.results import open_stored
from .._run.sweep.result import SweepResult
from .._scene.errors import SceneError
from .console import refuse, say

SUFFIXES = {"csv": ".csv", "netcdf": ".nc"}


def export_file(source: Path, form: str, output: Path | None, overwrite: bool) -> None:
    """Write the sweep or run in `source` as `form` (csv or netcdf) to `output` (default: beside
    `source`, its suffix replaced); every refusal exits with code 2 and writes nothing."""
    target = output or source.with_suffix(SUFFIXES[form])
    if target.exists() and not overwrite:
        refuse("output file", [("--output", f"{target} exists; pass --overwrite to replace it")])
    if not target.parent.is_dir():
        refuse("output file", [("--output", f"folder {target.parent} does not exist")])
    if target.resolve() == source.resolve():
        refuse("output file", [("--output", f"{target} is the file to export")])
    try:
        result = open_stored(source)
    except (OSError, ValueError) as error:
        problems = error.problems if isinstance(error, SceneError) else [("", str(error))]
        refuse(f"cannot export {source}", problems)
    try:
        if form == "csv":
            table = result.to_pandas()
            write_csv(table, target)
            rows = f"{len(table)} rows"
        else:
            dataset = result.to_xarray()
            write_netcdf(dataset, target)
            rows = ", ".join(f"{name} {size}" for name, size in dataset.sizes.items())
    except ImportError as error:
        refuse(f"cannot export {source}", [("", str(error))])
    kind = "sweep" if isinstance(result, SweepResult) else "run"
    say(f"{kind} {source} written to {target} ({rows})")
