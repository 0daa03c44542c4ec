"""Results where scientists analyse them (issue: xarray, pandas and CSV): a sweep's and a run's
`to_xarray()` / `to_pandas()` against their own arrays, units and closed forms; `open_sweep` /
`open_run` giving back the same datasets (a 2-axis grid, a zipped sweep, a killed and a merged
sweep); `impact export` to CSV and netCDF; the message naming the extra where xarray or pandas
is missing; refusals of bad input.

The sweeps are tiny (6 points) and share one compiled batch: the Thornton–Ning scene with
solver.method quadrature, each contact phase timed by Gauss quadrature, no ODE steps."""

import csv
import math
import sys
from pathlib import Path
from types import SimpleNamespace

import h5py
import jax
import numpy as np
import pandas as pd
import pytest
import xarray as xr
import yaml

import impact
from impact import theory
from impact._core.runtime import provenance
from impact._integrate.codes import RESULT_CODES
from impact._io.indentation import write_indentation
from impact._io.run import write_run
from impact._io.sweep import append_chunk, create_sweep_file, merge
from impact._io.sweep_journal import SweepWriter
from impact._run.sweep import RESULTS
from impact._scene.domains import udunits
from impact._scene.errors import SweepError
from impact._scene.scene import scene_yaml
from impact._scene.sweep import make_spec
from tests.command import invoke
from tests.scenes import CONFIGS, E_STAR, MASS, THORNTON_NING, R

INDENTATION = CONFIGS / "indentation_paraboloid.yaml"
VELOCITY, WORK = "initial.velocity", "effects.adhesion.work_of_adhesion"
VELOCITIES = [0.25, 0.6, 2.0]  # v_s = 0.303 m/s at Δγ = 0.05: captured at 0.25; 0.184 m/s at 0.03
WORKS = [0.03, 0.05]
GRID = {VELOCITY: VELOCITIES, WORK: WORKS}
ZIPPED = {VELOCITY: [0.3, 0.5, 0.8, 1.3, 2.1, 3.4], WORK: [0.01, 0.02, 0.03, 0.05, 0.08, 0.13]}
CHUNK = 8
AXIS_UNITS = {VELOCITY: "m s-1", WORK: "J m-2"}


def said(result) -> str:
    """A command's output as one line (without the frame typer draws around a usage error)."""
    return " ".join(result.output.replace("│", " ").split())


def base_scene() -> dict:
    data = yaml.safe_load(THORNTON_NING.read_text())
    data["solver"]["method"] = "quadrature"
    return data


def sweep_file(folder: Path, axes: dict, mode: str) -> Path:
    path = folder / f"{mode}.yaml"
    definition = {"scene": str(THORNTON_NING), "set": {"solver.method": "quadrature"}, "axes": axes, "mode": mode}
    path.write_text(yaml.safe_dump(definition, sort_keys=False))
    return path


@pytest.fixture(scope="module")
def grid():
    return impact.sweep(base_scene(), GRID, chunk=CHUNK)


@pytest.fixture(scope="module")
def zipped():
    return impact.sweep(base_scene(), ZIPPED, mode="zip", chunk=CHUNK)


@pytest.fixture(scope="module")
def stored(tmp_path_factory):
    """The same two sweeps run by `impact sweep`: {mode: folder holding sweep.h5}."""
    folder = tmp_path_factory.mktemp("sweeps")
    folders = {}
    for mode, axes in (("grid", GRID), ("zip", ZIPPED)):
        folders[mode] = folder / mode
        result = invoke("sweep", sweep_file(folder, axes, mode), "-o", folders[mode], "--chunk", CHUNK)
        assert result.exit_code == 0, result.output
    return folders


def decoded_status(variable: xr.DataArray) -> np.ndarray:
    """The names of a status variable's codes, read from its CF flags."""
    names = dict(zip(variable.attrs["flag_values"].tolist(), variable.attrs["flag_meanings"].split(), strict=True))
    return np.vectorize(names.get, otypes=[object])(variable.values)


# --- a sweep in memory ------------------------------------------------------------------------


@pytest.mark.slow
def test_a_grid_has_one_dimension_per_axis_with_units_and_every_result(grid):
    ds = grid.to_xarray()
    assert ds.restitution.dims == (VELOCITY, WORK) and ds.sizes == {VELOCITY: 3, WORK: 2}
    for path, values in GRID.items():
        assert np.array_equal(ds[path].values, values) and ds[path].attrs["units"] == AXIS_UNITS[path]
    assert set(ds.data_vars) == set(grid.results)
    for name, column in grid.results.items():
        assert np.array_equal(ds[name].values, column, equal_nan=True), name
        unit = RESULTS[name][2]
        if name not in ("status", "stuck"):
            assert ds[name].attrs["units"] == (unit or "1"), name
    assert ds.contact_time.attrs["units"] == "s" and ds.max_force.attrs["units"] == "N"
    assert ds.restitution.attrs["units"] == "1" and ds.dissipated_energy.attrs["units"] == "J"
    assert np.array_equal(decoded_status(ds.status), np.char.replace(grid.status_names().astype(str), " ", "_"))
    assert decoded_status(ds.status)[0, 1] == "captured" and ds.stuck.dtype == bool
    assert ds.attrs["scene"] == scene_yaml(grid.scene) and ds.attrs["sweep"] == grid.spec.definition()
    versions = {key: int(value) if isinstance(value, bool) else value for key, value in provenance().items()}
    assert {key: ds.attrs[key] for key in versions} == versions
    # Selected by value, a point is the closed form (3.50–3.51) to the quadrature's round-off.
    e = float(ds.restitution.sel({VELOCITY: 0.6, WORK: 0.05}))
    assert abs(e - float(theory.thornton_ning_restitution(0.6, MASS, R, E_STAR, 0.05))) < 1e-12
    assert math.isclose(e, 0.8629448823, abs_tol=1e-10)


@pytest.mark.slow
def test_a_zipped_sweep_is_one_dimension_with_the_paths_as_coordinates(zipped):
    ds = zipped.to_xarray()
    assert ds.restitution.dims == ("point",) and ds.sizes == {"point": 6}
    for path, values in ZIPPED.items():
        assert ds[path].dims == ("point",) and np.array_equal(ds[path].values, values)
        assert ds[path].attrs["units"] == AXIS_UNITS[path]
    assert ds.attrs["mode"] == "zip"
    velocities, works = np.array(ZIPPED[VELOCITY]), np.array(ZIPPED[WORK])
    expected = theory.thornton_ning_restitution(velocities, MASS, R, E_STAR, works)
    np.testing.assert_allclose(ds.restitution.values, expected, rtol=0, atol=1e-12)


def test_the_data_frame_has_one_row_a_point(grid):
    frame = grid.to_pandas()
    assert list(frame.columns) == [VELOCITY, WORK, *grid.results]
    assert len(frame) == 6 and frame.index.name == "point"
    # Rows in C order of the shape: velocity outer, work of adhesion inner.
    assert frame[VELOCITY].tolist() == [v for v in VELOCITIES for _ in WORKS]
    assert frame[WORK].tolist() == WORKS * 3
    for name, column in grid.results.items():
        if name != "status":
            assert np.array_equal(frame[name].to_numpy(), column.reshape(-1), equal_nan=True), name
    assert isinstance(frame.status.dtype, pd.CategoricalDtype)
    assert frame.status.tolist() == grid.status_names().reshape(-1).tolist()
    assert list(frame.status.cat.categories) == [*RESULT_CODES, "not run"]
    assert frame.attrs["units"][VELOCITY] == "m s-1" and frame.attrs["units"]["contact_time"] == "s"
    assert "status" not in frame.attrs["units"] and "stuck" not in frame.attrs["units"]


def test_units_of_swept_fields_come_from_their_domains(thornton_ning_scene):
    assert [udunits(u) for u in ("m/s", "J/m²", "kg/m³", "N s/m", "m/s²", "1/m", "Pa", "")] == [
        "m s-1",
        "J m-2",
        "kg m-3",
        "N s m-1",
        "m s-2",
        "m-1",
        "Pa",
        "",
    ]
    axes = {"body.profile.R": [1e-6], "material.E_star": [1e9], "body.mass": [1e-14], "solver.rtol": [1e-9]}
    made = make_spec(thornton_ning_scene, axes, "grid", "given")
    assert {axis.path: axis.unit for axis in made.axes} == {
        "body.profile.R": "m",
        "material.E_star": "Pa",
        "body.mass": "kg",
        "solver.rtol": "",
    }


# --- a sweep read back ------------------------------------------------------------------------


@pytest.mark.slow
def test_open_sweep_gives_back_the_same_dataset(grid, zipped, stored):
    for mode, result in (("grid", grid), ("zip", zipped)):
        opened = impact.open_sweep(stored[mode] / "sweep.h5")
        assert opened.to_xarray().identical(result.to_xarray()), mode
        pd.testing.assert_frame_equal(opened.to_pandas(), result.to_pandas())
        assert opened.stats["complete"] and opened.stats["provenance"]["impact_version"] == impact.__version__
    assert impact.open_sweep(stored["grid"]).to_xarray().identical(grid.to_xarray())  # the folder will do
    with h5py.File(stored["grid"] / "sweep.h5", "r") as file:
        assert file["sweep/axes"][VELOCITY].attrs["unit"] == "m s-1"
        assert file["sweep/params"][WORK].attrs["unit"] == "J m-2"


def test_open_sweep_validates_in_float64_with_the_flag_off(grid, stored):
    """Reading a sweep validates its points again (units of the scaled problem): in float64
    whatever JAX's global flag, which it leaves as it found it."""
    jax.config.update("jax_enable_x64", False)
    try:
        opened = impact.open_sweep(stored["grid"])
        assert jax.config.read("jax_enable_x64") is False
    finally:
        jax.config.update("jax_enable_x64", True)
    assert np.array_equal(opened.restitution, grid.restitution)


def flat_columns(result) -> dict:
    return {name: column.reshape(-1) for name, column in result.results.items()}


def test_a_killed_sweep_opens_with_its_points_not_run(grid, tmp_path):
    """A sweep stopped after its first chunk of 2 points: the others are 'not run', NaN."""
    path = tmp_path / "sweep.h5"
    points = np.array([4, 1])
    create_sweep_file(path, grid.spec, expected=6, chunk=2)
    append_chunk(path, points, grid.spec.flat_params(), {k: v[points] for k, v in flat_columns(grid).items()})
    opened = impact.open_sweep(path)
    assert not opened.stats["complete"] and opened.stats["rows"] == 2
    ds = opened.to_xarray()
    done = np.zeros(6, dtype=bool)
    done[points] = True
    done = done.reshape(3, 2)
    assert np.array_equal(ds.restitution.values[done], grid.restitution[done])
    assert np.isnan(ds.restitution.values[~done]).all()
    assert (decoded_status(ds.status)[~done] == "not_run").all()
    assert opened.to_pandas().status.tolist().count("not run") == 4
    # The coordinates are the whole sweep's, whatever was run.
    assert np.array_equal(ds[VELOCITY].values, VELOCITIES)


def test_a_sweep_killed_inside_a_write_is_refused_with_the_way_out(grid, tmp_path):
    """The HDF5 file broken, the journal whole: `impact sweep` rebuilds it; reading says so."""
    path = tmp_path / "sweep.h5"
    writer = SweepWriter.start(path, grid.spec, SimpleNamespace(params=grid.spec.flat_params()), expected=6, chunk=2)
    writer.append(np.array([0, 1]), {name: column[:2] for name, column in flat_columns(grid).items()})
    path.write_bytes(path.read_bytes()[:2000])
    with pytest.raises(SweepError) as refused:
        impact.open_sweep(path)
    assert str(refused.value) == (
        f"{path} cannot be read (a sweep killed inside a write): its journal holds 2 finished points; "
        "run `impact sweep` on its sweep file again to rebuild the file from the journal and resume it"
    )


def test_a_merged_sweep_opens_as_the_single_process_one(grid, tmp_path):
    flat, params = flat_columns(grid), grid.spec.flat_params()
    shards = []
    for index, points in enumerate((np.array([0, 2, 4]), np.array([5, 3, 1]))):
        shard = tmp_path / f"shard-{index:03d}-of-002.h5"
        create_sweep_file(shard, grid.spec, expected=3, chunk=CHUNK, share=(index, 2))
        append_chunk(shard, points, params, {name: column[points] for name, column in flat.items()})
        shards.append(shard)
    part = impact.open_sweep(shards[0]).to_xarray()
    assert np.isnan(part.restitution.values.reshape(-1)[[1, 3, 5]]).all()
    merge(shards, tmp_path / "sweep.h5")
    assert impact.open_sweep(tmp_path).to_xarray().identical(grid.to_xarray())


# --- export -----------------------------------------------------------------------------------


def read_csv(path: Path) -> tuple[list[str], list[list[str]]]:
    with path.open(newline="") as file:
        header, *rows = list(csv.reader(file))
    return header, rows


def test_csv_has_every_point_with_units_in_its_header(grid, stored, tmp_path):
    target = tmp_path / "table.csv"
    result = invoke("export", stored["grid"] / "sweep.h5", "--format", "csv", "-o", target)
    assert result.exit_code == 0, result.output
    assert f"written to {target} (6 rows)" in said(result)
    header, rows = read_csv(target)
    assert header[:5] == [
        "initial.velocity [m s-1]",
        "effects.adhesion.work_of_adhesion [J m-2]",
        "restitution [1]",
        "stuck",
        "status",
    ]
    names = [VELOCITY, WORK, *grid.results]
    units = {**AXIS_UNITS, **{name: RESULTS[name][2] or "1" for name in grid.results}}
    assert header == [name if name in ("stuck", "status") else f"{name} [{units[name]}]" for name in names]
    assert len(rows) == 6
    columns = {name: [row[i] for row in rows] for i, name in enumerate(names)}
    assert columns["status"] == grid.status_names().reshape(-1).tolist()
    assert columns["stuck"] == [str(bool(s)) for s in grid.stuck.reshape(-1)]
    for name in names:
        if name not in ("stuck", "status"):
            expected = (grid.params | grid.results)[name].reshape(-1)
            assert np.array_equal(np.array(columns[name], dtype=np.float64), expected, equal_nan=True), name


def test_netcdf_holds_the_dataset(zipped, stored, tmp_path):
    result = invoke("export", stored["zip"] / "sweep.h5", "--format", "netcdf")
    assert result.exit_code == 0, result.output
    written = stored["zip"] / "sweep.nc"  # beside the input by default
    assert xr.load_dataset(written, engine="h5netcdf").identical(zipped.to_xarray())
    again = invoke("export", stored["zip"] / "sweep.h5", "--format", "netcdf")
    assert again.exit_code == 2 and "exists; pass --overwrite" in again.output
    assert invoke("export", stored["zip"] / "sweep.h5", "--format", "netcdf", "--overwrite").exit_code == 0


# --- one run ----------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def run():
    return impact.simulate(impact.load_scene(THORNTON_NING))


def test_a_run_is_its_time_series_with_units(run, tmp_path):
    ds = run.to_xarray()
    assert ds.time.dims == ("sample",) and ds.time.attrs["units"] == "s"
    assert np.array_equal(ds.time.values, run.t)
    series = {"indentation": "m", "velocity": "m s-1", "contact_radius": "m", "force": "N"}
    for name, unit in series.items():
        assert np.array_equal(ds[name].values, getattr(run, name)) and ds[name].attrs["units"] == unit
    assert float(ds.restitution) == run.restitution and ds.contact_time.attrs["units"] == "s"
    assert abs(float(ds.restitution) - float(theory.thornton_ning_restitution(0.6, MASS, R, E_STAR, 0.05))) < 1e-9
    assert float(ds.adhesion_hysteresis) == run.adhesion_hysteresis and ds.adhesion_hysteresis.attrs["units"] == "J"
    assert decoded_status(ds.status) == "separated"
    assert ds.event_kind.values.tolist() == [kind for _, kind in run.events]
    assert ds.event_time.values.tolist() == [time for time, _ in run.events]
    frame = run.to_pandas()
    assert list(frame.columns) == ["time", *series] and len(frame) == len(run.t)
    assert frame.attrs["units"] == {"time": "s", **series}

    path = write_run(run, tmp_path / "run.h5")
    assert impact.open_run(path).to_xarray().identical(ds)
    assert impact.open_run(tmp_path).to_xarray().identical(ds)
    exported = invoke("export", path, "--format", "csv")
    assert exported.exit_code == 0, exported.output
    header, rows = read_csv(tmp_path / "run.csv")
    assert header == ["time [s]", "indentation [m]", "velocity [m s-1]", "contact_radius [m]", "force [N]"]
    assert len(rows) == len(run.t)
    assert np.array_equal(np.array([row[4] for row in rows], dtype=np.float64), run.force)


def test_an_indentation_test_is_its_curve_with_units(tmp_path):
    test = impact.simulate(INDENTATION)
    ds = test.to_xarray()
    for name, unit in {"contact_radius": "m", "indentation": "m", "force": "N", "leg": "1"}.items():
        assert ds[name].dims == ("point",) and ds[name].attrs["units"] == unit
        assert np.array_equal(ds[name].values, getattr(test, name))
    # Force control pulls off at F = −(3/2)πRΔγ (JKR, (3.41)): R = 50 nm, Δγ = 0.1 J/m².
    assert math.isclose(float(ds.pull_off_force), -1.5 * math.pi * 5e-8 * 0.1, rel_tol=1e-7)
    assert ds.pull_off_force.attrs["units"] == "N" and decoded_status(ds.status) == "separated"
    assert ds.event_point.values.tolist() == [point for point, _ in test.events]
    path = write_indentation(test, tmp_path / "run.h5")
    opened = impact.open_run(path)
    assert isinstance(opened, impact.IndentationResult) and opened.to_xarray().identical(ds)
    assert list(test.to_pandas().columns) == ["contact_radius", "indentation", "force", "leg"]


# --- without the extra; bad input -------------------------------------------------------------


@pytest.mark.parametrize("module", ["xarray", "pandas"])
def test_a_missing_library_names_the_extra(grid, module, monkeypatch, tmp_path, stored):
    monkeypatch.setitem(sys.modules, module, None)  # `import xarray` now raises ImportError
    message = (
        f"{module} is not installed: results as labelled arrays and tables need the optional extra "
        "impact-mdr[analysis] (pip install 'impact-mdr[analysis]')"
    )
    convert = grid.to_xarray if module == "xarray" else grid.to_pandas
    with pytest.raises(ImportError) as raised:
        convert()
    assert str(raised.value) == message
    form = "netcdf" if module == "xarray" else "csv"
    result = invoke("export", stored["grid"] / "sweep.h5", "--format", form, "-o", tmp_path / "out")
    assert result.exit_code == 2 and message in said(result)
    assert not list(tmp_path.iterdir())  # nothing written


def test_bad_input_is_refused(stored, tmp_path):
    not_hdf5 = tmp_path / "notes.h5"
    not_hdf5.write_text("not an HDF5 file")
    other = tmp_path / "other.h5"
    with h5py.File(other, "w") as file:
        file.create_group("data")
    cases = [
        ((tmp_path / "missing.h5", "--format", "csv"), f"no such file: {tmp_path / 'missing.h5'}"),
        ((not_hdf5, "--format", "csv"), f"{not_hdf5} is not an HDF5 file"),
        ((other, "--format", "csv"), f"{other} is not an impact run (no h5md group or parameters/config.yaml)"),
        ((stored["grid"] / "sweep.h5", "--format", "xlsx"), "'xlsx' is not one of 'csv', 'netcdf'"),
        (
            (stored["grid"] / "sweep.h5", "--format", "csv", "-o", tmp_path / "no" / "t.csv"),
            f"folder {tmp_path / 'no'} does not exist",
        ),
    ]
    before = sorted(tmp_path.iterdir())
    for arguments, phrase in cases:
        result = invoke("export", *arguments)
        assert result.exit_code == 2, (arguments, result.output)
        assert phrase in said(result), (phrase, result.output)
        assert "Traceback" not in result.output
    assert sorted(tmp_path.iterdir()) == before
    with pytest.raises(SweepError, match="is not an impact sweep file"):
        impact.open_sweep(other)
    with pytest.raises(ValueError, match="is not an impact run"):
        impact.open_run(stored["grid"] / "sweep.h5")
