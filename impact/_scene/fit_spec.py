"""Fit files: a scene, a table of measurements and what to fit, validated into a `FitSpec`.

A fit file is a YAML mapping::

    scene: ../thornton_ning.yaml        # a scene file (relative to the fit file) or an inline scene
    data: drops.csv                     # one row per measurement ('#' lines are comments)
    inputs: [initial.velocity]          # columns that set scene values row by row
    observables:                        # columns to match; sigma: a column name or a number
      restitution: {sigma: restitution_sigma}
      max_force: {sigma: 0.01, relative: true}
    parameters:                         # what is fitted: dotted scene paths
      effects.adhesion.work_of_adhesion: {start: 0.02, min: 1.0e-4, max: 1.0, scale: log}
      material.E_star: {start: 5.0e8, scale: log}
    model: simulation                   # or theory: the closed form instead of the simulation

A fit of a quasi-static indentation curve (a scene of kind indentation) takes the controlled
value (`indentation` or `force`) of each row as its input and may name a column of branch
labels (`branch: <column>`, approach or retract): see `fit_curve`.

Every problem is a `FitError` (a `SceneError`) naming the field by its dotted path
(`parameters.<path>.start`, `inputs.<path>`, `observables.<name>.sigma`, `data`, …).
"""

import csv
import dataclasses
import io
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal

import numpy as np
import yaml
from pydantic import Field, ValidationError, model_validator

from .errors import FieldProblem, SceneError, problems_of
from .fit_curve import BRANCH, branch_codes, control_column, curve_observables, curve_problems
from .overrides import apply_fit_overrides
from .paths import AbsentSection, NoField, resolve_field
from .profiles import Number
from .reading import MAX_TABLE_BYTES, parse_yaml, read_text, read_yaml
from .scene import Scene, load_scene
from .sections import Section
from .sweep_axes import field_values
from .sweep_points import point_problems
from .sweep_spec import MAX_LISTED, Axis, SweepSpec

# The scalar results of an impact a fit can match (the fields of `impact.Result` of that name).
OBSERVABLES = ("restitution", "contact_time", "max_indentation", "max_force", "min_force", "dissipated_energy")
# Numbers that set static choices of a run (changing them compiles anew): never an input of a fit.
STATIC_SECTIONS = ("solver",)
# (The closed-form curve of an indentation test takes the approach work of adhesion traced.)
STATIC_FIELDS = ("effects.adhesion.approach_work_of_adhesion",)
MODELS = ("simulation", "theory")
FUNCTION = "function"  # the model of a fit given a function in Python


class FitError(SceneError):
    """A fit that cannot be run; `problems` lists (dotted.path, message) pairs."""


class ObservableSpec(Section):
    """How one observable column is weighted: its standard deviation σ."""

    sigma: Number | str | None = Field(
        None,
        description="σ: a number (in the column's unit), or the name of a column of σ per row; "
        "leave out for unknown σ (then estimated from the scatter, χ²/dof)",
    )
    relative: bool = Field(False, description="σ is relative: the row's σ is σ·|value|")

    @model_validator(mode="after")
    def _positive_sigma(self):
        if isinstance(self.sigma, float) and not self.sigma > 0:
            raise FieldProblem("sigma", f"must be > 0, got {self.sigma:g}")
        return self


class ParameterSpec(Section):
    """One fitted scene value: where the search starts and where it may go."""

    start: Number = Field(description="starting value (SI units of the field)")
    min: Number | None = Field(None, description="lower bound (exclusive); default: none (0 on log scale)")
    max: Number | None = Field(None, description="upper bound (exclusive); default: none")
    scale: Literal["linear", "log"] = Field("linear", description="search in the value (linear) or its logarithm")

    @model_validator(mode="after")
    def _start_within_bounds(self):
        if self.scale == "log":
            for name in ("start", "min", "max"):
                value = getattr(self, name)
                if value is not None and not value > 0:
                    raise FieldProblem(name, f"must be > 0 on scale log, got {value:g}")
        if self.min is not None and self.max is not None and not self.min < self.max:
            raise FieldProblem("max", f"must exceed min = {self.min:g}, got {self.max:g}")
        low = -math.inf if self.min is None else self.min
        high = math.inf if self.max is None else self.max
        if not low < self.start < high:
            raise FieldProblem("start", f"{self.start:g} lies outside the bounds ({low:g}, {high:g})")
        return self


class FitFile(Section):
    """The keys of a fit file (before the scene and the data are read)."""

    scene: str | dict = Field(description="a scene file (relative to the fit file) or an inline scene")
    data: str = Field(description="the CSV file of measurements (relative to the fit file)")
    inputs: list[str] = Field([], description="dotted scene paths set row by row from the column of that name")
    observables: dict[str, ObservableSpec] = Field(min_length=1, description="columns to match, by result name")
    parameters: dict[str, ParameterSpec] = Field(min_length=1, description="fitted scene values by dotted path")
    model: Literal["simulation", "theory"] = Field(
        "simulation", description="'simulation', or 'theory': the closed form instead of the simulation"
    )
    branch: str | None = Field(
        None,
        description="indentation curves: the column of branch labels (approach, retract); default: "
        "approach up to the row of the largest control value, retract after it",
    )


@dataclass(frozen=True)
class FitSpec:
    """A validated fit: the scene, the data columns (float64), and what is fitted and matched."""

    scene: Scene
    data: dict[str, np.ndarray]
    inputs: tuple[str, ...]
    observables: dict[str, ObservableSpec]
    parameters: dict[str, ParameterSpec]
    model: str = "simulation"
    branch: str | None = None  # the column of branch labels the data were read with
    source: str | None = field(default=None, repr=False, compare=False)  # verbatim fit file

    @property
    def rows(self) -> int:
        return len(next(iter(self.data.values())))

    @property
    def control(self) -> str | None:
        """The column of the controlled value of an indentation curve (None for impacts)."""
        return control_column(self.scene)

    @property
    def row_columns(self) -> tuple[str, ...]:
        """The columns a row hands the model after the parameters: the inputs, then for an
        indentation curve the controlled value and the branch code (0 approach, 1 retract)."""
        return self.inputs if self.control is None else (*self.inputs, self.control, BRANCH)

    def sigmas(self) -> np.ndarray | None:
        """σ of every row and observable, [rows, observables]; None where σ is unknown."""
        if any(spec.sigma is None for spec in self.observables.values()):
            return None
        columns = []
        for name, spec in self.observables.items():
            sigma = self.data[spec.sigma] if isinstance(spec.sigma, str) else np.full(self.rows, spec.sigma)
            columns.append(sigma * np.abs(self.data[name]) if spec.relative else sigma)
        return np.stack(columns, axis=1)


def load_fit(path: str | Path, assignments: Sequence[str] = ()) -> FitSpec:
    """A validated fit from a fit file (its scene and data paths relative to the file), with the
    `dotted.path=value` overrides of `impact fit --set` applied (see `overrides`)."""
    path = Path(path)
    try:
        text = read_text(path)
        data = parse_yaml(text, str(path))
    except SceneError as error:
        raise FitError(error.problems) from None
    if not isinstance(data, dict):
        raise FitError([("", f"{path} must hold a mapping with the keys {', '.join(FitFile.model_fields)}")])
    if assignments:
        entries: dict[str, type[Section]] = {"parameters": ParameterSpec, "observables": ObservableSpec}
        plain = tuple(name for name in FitFile.model_fields if name not in (*entries, "scene"))
        try:
            data = apply_fit_overrides(data, list(assignments), path.parent, entries, plain)
        except SceneError as error:
            raise FitError(error.problems) from None
        text = yaml.safe_dump(data, sort_keys=False, allow_unicode=True)
    try:
        file = FitFile.model_validate(data)
    except ValidationError as error:
        raise FitError(problems_of(error)) from None
    scene = _scene(file.scene, path.parent)
    table = read_table(path.parent / file.data)
    spec = make_fit_spec(scene, table, file.parameters, file.observables, file.inputs, file.model, file.branch)
    return dataclasses.replace(spec, source=text)


def _scene(entry, folder: Path) -> Scene:
    """The scene of a fit file: a path relative to it, or an inline mapping."""
    where = "the inline scene" if isinstance(entry, dict) else str(folder / entry)
    try:
        return load_scene(entry if isinstance(entry, dict) else read_yaml(folder / entry))
    except SceneError as error:
        raise FitError(
            [(f"scene.{path}" if path else "scene", f"{message} (in {where})") for path, message in error.problems]
        ) from None


def read_table(path: Path) -> dict[str, np.ndarray]:
    """The columns of a CSV file (a header row, then one row per measurement; lines starting
    with '#' skipped): float64 where every entry is a number, else the entries as text."""
    try:
        text = read_text(path, MAX_TABLE_BYTES)
    except SceneError as error:
        raise FitError([("data", message) for _, message in error.problems]) from None
    lines = [line for line in text.splitlines() if line.strip() and not line.lstrip().startswith("#")]
    rows = list(csv.reader(io.StringIO("\n".join(lines))))
    if len(rows) < 2:
        raise FitError([("data", f"{path} holds no header row and data rows")])
    header = [name.strip() for name in rows[0]]
    for column, name in enumerate(header):
        if name in header[:column]:
            first = header.index(name) + 1
            raise FitError(
                [("data", f"{path}: column {name!r} appears twice in the header (columns {first} and {column + 1})")]
            )
    for number, row in enumerate(rows[1:], start=1):
        if len(row) != len(header):
            raise FitError([("data", f"{path}, data row {number}: {len(row)} values for {len(header)} columns")])
    return {name: as_column([row[column] for row in rows[1:]]) for column, name in enumerate(header)}


def as_column(values) -> np.ndarray:
    """A data column: float64 where every entry is a number, else its entries as text."""
    entries = np.asarray(values).reshape(-1)
    try:
        return entries.astype(np.float64)
    except (TypeError, ValueError):
        return np.array([str(entry).strip() for entry in entries])


def make_fit_spec(
    scene,
    data: "Mapping | str | Path",
    parameters: Mapping,
    observables: Mapping,
    inputs=(),
    model: str = "simulation",
    branch: str | None = None,
) -> FitSpec:
    """Validate a fit given in Python (scene, data columns by name or a CSV file, parameter and
    observable specs by name, for an indentation curve the column of branch labels) into a
    FitSpec; the fit file's checks, each naming its field."""
    if isinstance(data, (str, Path)):
        data = read_table(Path(data))
    try:
        scene = load_scene(scene)
        file = FitFile.model_validate(
            dict(scene={}, data="", inputs=list(inputs), observables=observables, parameters=parameters)
        )
    except SceneError as error:
        raise FitError([(f"scene.{path}" if path else "scene", message) for path, message in error.problems]) from None
    except ValidationError as error:
        raise FitError(problems_of(error)) from None
    columns = {str(name): as_column(values) for name, values in data.items()}
    if model not in (*MODELS, FUNCTION):
        raise FitError([("model", f"expected one of {', '.join(MODELS)}, got {model!r}")])
    static = () if model == "theory" and scene.kind == "indentation" else STATIC_FIELDS
    problems = [problem for path in file.parameters for problem in _path_problems(scene, "parameters", path, static)]
    problems += [problem for path in file.inputs for problem in _path_problems(scene, "inputs", path, static)]
    problems += [(f"inputs.{path}", "is also a fitted parameter") for path in file.inputs if path in file.parameters]
    problems += curve_problems(scene, branch, model, columns)
    problems += _column_problems(file, columns, scene)
    if problems:
        raise FitError(problems)
    problems = _input_row_problems(scene, file.inputs, columns)
    if problems:
        raise FitError(problems)
    used = {name: columns[name] for name in _used_columns(file, scene)}
    control = control_column(scene)
    if control is not None:
        used[BRANCH] = branch_codes(branch, used[control], columns)
    return FitSpec(scene, used, tuple(file.inputs), file.observables, file.parameters, model, branch)


def _path_problems(scene: Scene, key: str, path: str, static: tuple[str, ...]) -> list[tuple[str, str]]:
    """Why a dotted path cannot be fitted or set row by row (none if it can); `static`: the
    fields that set static choices of the model."""
    try:
        owner, name = resolve_field(scene, path)
    except (NoField, AbsentSection) as error:
        return [(f"{key}.{path}", str(error))]
    value = getattr(owner, name)
    if value is None:
        return [(f"{key}.{path}", "is not set in the scene; give it a value there to fit or vary it")]
    if path.split(".")[0] in STATIC_SECTIONS or path in static or not isinstance(value, float):
        return [(f"{key}.{path}", f"is a static choice ({value!r}; changing it compiles anew), not a traced value")]
    return []


def _column_problems(file: FitFile, columns: dict[str, np.ndarray], scene: Scene) -> list[tuple[str, str]]:
    """Missing columns, unknown observables, bad σ, text and non-finite values."""
    known = ", ".join(columns) or "none"
    observables = OBSERVABLES if scene.kind == "impact" else curve_observables(scene)
    problems = [
        (f"inputs.{path}", f"no column {path!r} in the data; its columns: {known}")
        for path in file.inputs
        if path not in columns
    ]
    for name, spec in file.observables.items():
        if name not in observables:
            problems.append((f"observables.{name}", f"unknown observable; known: {', '.join(observables)}"))
        elif name not in columns:
            problems.append((f"observables.{name}", f"no column {name!r} in the data; its columns: {known}"))
        problems += _sigma_problems(f"observables.{name}.sigma", spec.sigma, columns)
    if len({spec.sigma is None for spec in file.observables.values()}) > 1:
        problems.append(("observables", "give sigma for every observable or for none (then it is estimated)"))
    if problems:
        return problems
    used = [name for name in _used_columns(file, scene) if name in columns]  # else refused above
    sizes = {len(columns[name]) for name in used}
    if len(sizes) > 1:
        return [("data", "the columns differ in length")]
    for name in used:
        if columns[name].dtype.kind != "f":
            row = next(row for row, entry in enumerate(columns[name]) if not _is_number(entry))
            entry = str(columns[name][row])
            problems.append(("data", f"column {name!r}, data row {row + 1}: {entry!r} is not a number"))
            continue
        bad = np.flatnonzero(~np.isfinite(columns[name]))
        if bad.size:
            problems.append(("data", f"column {name!r} holds {columns[name][bad[0]]} in row {bad[0] + 1}"))
    for name, spec in file.observables.items():
        zero = np.flatnonzero(columns[name] == 0)
        if spec.relative and zero.size:
            problems.append((f"observables.{name}.relative", f"σ·|value| is 0 in row {zero[0] + 1}"))
    rows, count = min(sizes), len(file.parameters)
    measured = rows * len(file.observables)
    if measured <= count:
        problems.append(
            (
                "data",
                f"{rows} data row(s) × {len(file.observables)} observable(s) = {measured} measured value(s) for "
                f"{count} parameter(s): a fit needs more measured values than parameters (at least {count + 1}), to "
                "leave degrees of freedom for χ² and the standard errors",
            )
        )
    return problems


def _input_row_problems(scene: Scene, inputs: Sequence[str], columns: dict[str, np.ndarray]) -> list[tuple[str, str]]:
    """Rows whose input value lies outside its scene field's range, or whose inputs together make
    the scene invalid (as a sweep's points are checked, `sweep_points`): the first few named by
    column, data row and value."""
    problems, axes = [], []
    for path in inputs:
        owner, name = resolve_field(scene, path)
        raw = columns[path].tolist()
        values, invalid = field_values(owner, name, raw)
        problems += [
            ("data", f"column {path!r}, data row {index + 1}: {value!r} is refused by {path}: {why}")
            for index, value, why in invalid[:MAX_LISTED]
        ]
        axes.append(Axis(path, np.asarray(values, np.float64), raw))
    if problems or not axes:
        return problems
    invalid_rows = point_problems(SweepSpec(scene, tuple(axes), "zip", "given"))
    for index, why in sorted(invalid_rows.items())[:MAX_LISTED]:
        listed = ", ".join(f"{path} = {columns[path].tolist()[index]!r}" for path in inputs)
        problems.append(("data", f"data row {index + 1} ({listed}) makes the scene invalid: {why}"))
    return problems


def _sigma_problems(where: str, sigma, columns: dict[str, np.ndarray]) -> list[tuple[str, str]]:
    """A σ column that is missing or not positive in every row."""
    if not isinstance(sigma, str):
        return []
    if sigma not in columns:
        return [(where, f"no column {sigma!r} in the data; its columns: {', '.join(columns)}")]
    if columns[sigma].dtype.kind != "f":
        return []  # named by the check of every used column
    bad = np.flatnonzero(~(columns[sigma] > 0))
    if bad.size:
        return [(where, f"column {sigma!r} must be > 0, got {columns[sigma][bad[0]]:g} in row {bad[0] + 1}")]
    return []


def _is_number(entry) -> bool:
    try:
        float(entry)
    except ValueError:
        return False
    return True


def _used_columns(file: FitFile, scene: Scene) -> list[str]:
    """The numeric columns a fit reads: inputs (and an indentation's controlled value),
    observables and σ."""
    sigmas = [spec.sigma for spec in file.observables.values() if isinstance(spec.sigma, str)]
    control = control_column(scene)
    return list(dict.fromkeys([*file.inputs, *([control] if control else []), *file.observables, *sigmas]))
