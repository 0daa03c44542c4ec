"""Fuzzing the command line: random mutations of every file in configs/ through `impact validate`
and `impact run` must end with exit 0 or 2, never a traceback, never a partial file.

Mutations: a number scaled by 10^k (|k| ≤ 3: mostly valid scenes, so the runs simulate), a
value replaced (numbers from 1e-300 to 1e300 of either sign, NaN, ±inf, integers, booleans,
strings, None, lists, mappings), a key deleted, an unknown key added, a value wrapped
in a list or a mapping (wrong nesting), a cost bomb (a spring count up to 10⁹, a Verlet step
down to 1e-30 s), or the whole file replaced by random bytes. Exit 1 is accepted only from
`run`, for a run written with a named non-physical status (time_limit, …) and its warning.

Hostile shapes must be refused (exit 2) within seconds: a key given twice, nesting thousands
deep, an alias bomb, a file above the size limit, a tabulated profile of too many points, a
sweep of more than 10⁷ points; and the drop test's data (configs/fits) mutated (values out of
range, NaN, text, columns named twice, missing or renamed, rows removed) must fit (exit 0,
χ² a number) or be refused (exit 2, nothing written).

The CI portion is short; `IMPACT_FUZZ_EXAMPLES=10000 pytest tests/cli/test_fuzz.py` runs a
long one (validate examples; hostile shapes a fifth of them, at least 60; runs a fiftieth, at
least 15; fits and sweeps a hundredth, at least 10), not derandomized.
"""

import copy
import math
import os
import re
import tempfile
import time
from pathlib import Path

import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from impact._integrate.codes import RESULT_CODES
from impact._io.results import open_run
from impact._scene.cost import SWEEP_POINTS
from impact._scene.profiles import MAX_TABULATED_POINTS
from impact._scene.reading import MAX_DEPTH, MAX_YAML_BYTES
from impact.cli import app
from tests.scenes import CONFIGS

FILES = sorted(CONFIGS.glob("*.yaml")) + sorted(CONFIGS.glob("*/*.yaml"))
LONG = "IMPACT_FUZZ_EXAMPLES" in os.environ
VALIDATE_EXAMPLES = int(os.environ.get("IMPACT_FUZZ_EXAMPLES", "300"))
RUN_EXAMPLES = max(15, VALIDATE_EXAMPLES // 50)
FEW_EXAMPLES = max(10, VALIDATE_EXAMPLES // 100)
HOSTILE_EXAMPLES = max(60, VALIDATE_EXAMPLES // 5)
SCENES = [path for path in FILES if "body" in yaml.safe_load(path.read_text())]  # not the sweeps and fits
SWEEPS = sorted((CONFIGS / "sweeps").glob("*.yaml"))
DROP_TEST = CONFIGS / "fits" / "drop_test.yaml"
NOT_PHYSICAL = set(RESULT_CODES) - {"separated", "captured"}


def _paths(node, prefix=()):
    """Every dotted path of a nested mapping (sections and values), as key tuples."""
    if isinstance(node, dict):
        for key, value in node.items():
            yield (*prefix, key)
            yield from _paths(value, (*prefix, key))


magnitudes = st.builds(
    lambda sign, mantissa, exponent: sign * mantissa * 10.0**exponent,
    st.sampled_from([1.0, -1.0]),
    st.floats(1.0, 9.99),
    st.integers(-300, 300),
)
values = st.recursive(
    st.one_of(
        magnitudes,
        st.floats(allow_nan=True, allow_infinity=True),
        st.sampled_from([0, 1, -1, 0.0, float("nan"), float("inf"), -float("inf"), True, False, None]),
        st.integers(-(10**20), 10**20),
        st.text(max_size=12),
        st.sampled_from(["1e-3", "continuum", "paraboloid", "cone", "verlet", "maugis_dugdale", "force"]),
    ),
    lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.text(max_size=6), inner, max_size=3),
    max_leaves=6,
)


@st.composite
def mutated_scene(draw, actions=("replace", "replace", "scale", "delete", "extra", "nest")) -> bytes:
    """The bytes of a mutated config file (or random bytes, one time in twenty)."""
    source = draw(st.sampled_from(FILES))
    if draw(st.integers(0, 19)) == 0:
        return draw(st.binary(max_size=64))
    data = yaml.safe_load(source.read_text())
    for _ in range(draw(st.integers(1, 3))):
        paths = list(_paths(data))
        if not paths:
            break
        *parents, key = draw(st.sampled_from(paths))
        node = data
        for parent in parents:
            node = node[parent]
        action = draw(st.sampled_from(actions))
        if action == "scale" and isinstance(node[key], int | float) and not isinstance(node[key], bool):
            node[key] = node[key] * 10.0 ** draw(st.integers(-3, 3))  # often still valid: it runs
        elif action in ("replace", "scale"):
            node[key] = draw(values)
        elif action == "delete":
            del node[key]
        elif action == "extra":
            node[draw(st.text(min_size=1, max_size=8))] = draw(values)
        elif action == "bomb":
            _cost_bomb(draw, data)
        else:
            node[key] = draw(st.sampled_from([[node[key]], {"value": copy.deepcopy(node[key])}]))
    text = yaml.safe_dump(data, allow_unicode=True)
    return text.encode()


def _cost_bomb(draw, data: dict) -> None:
    """Ask for a costly run: a spring array of up to 10⁹ springs, stepped by Verlet with a step
    down to 1e-30 s one time in two."""
    contact = data.setdefault("contact", {})
    if isinstance(contact, dict):
        contact["springs"] = draw(st.integers(1, 10**9))
    if draw(st.booleans()):
        data["solver"] = {"method": "verlet", "dt": 10.0 ** draw(st.integers(-30, -9))}


def _invoke(*args):
    return CliRunner().invoke(app, [str(arg) for arg in args])


def _assert_clean(result):
    assert "Traceback" not in result.output
    assert result.exception is None or isinstance(result.exception, SystemExit), repr(result.exception)


def _settings(examples: int):
    return settings(
        max_examples=examples,
        deadline=None,
        derandomize=not LONG,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
    )


@pytest.mark.slow
@_settings(VALIDATE_EXAMPLES)
@given(content=mutated_scene(actions=("replace", "replace", "scale", "delete", "extra", "nest", "bomb")))
def test_validate_ends_with_0_or_2(content):
    with tempfile.TemporaryDirectory() as folder:
        scene = Path(folder) / "scene.yaml"
        scene.write_bytes(content)
        result = _invoke("validate", scene)
    _assert_clean(result)
    assert result.exit_code in (0, 2), result.output


@_settings(RUN_EXAMPLES)
@given(content=mutated_scene(actions=("scale", "scale", "scale", "replace", "delete", "bomb")))
def test_run_ends_with_0_or_2_and_no_partial_file(content):
    with tempfile.TemporaryDirectory() as folder:
        scene, output = Path(folder) / "scene.yaml", Path(folder) / "out"
        scene.write_bytes(content)
        result = _invoke("run", scene, "-o", output)
        _assert_clean(result)
        if result.exit_code == 2:
            assert not output.exists(), result.output
            return
        assert result.exit_code in (0, 1), result.output
        status = open_run(output).status
        if result.exit_code == 1:  # written, with a named non-physical status and its warning
            assert status in NOT_PHYSICAL
            assert f"warning: the run ended with status {status!r}" in result.output
        else:
            assert status in ("separated", "captured", "completed")  # completed: a shear test


# --- hostile shapes, refused ----------------------------------------------------------------


def _key_twice(draw, text: str) -> str:
    """A line `key: …` of the text given once more just above itself, with a value of its own
    (above: the original's nested block, if any, stays below the original)."""
    lines = text.splitlines()
    keyed = [number for number, line in enumerate(lines) if re.match(r"^\s*[A-Za-z_][A-Za-z0-9_.]*:", line)]
    number = draw(st.sampled_from(keyed))
    indent, key = re.match(r"^(\s*)([A-Za-z_][A-Za-z0-9_.]*):", lines[number]).groups()
    lines.insert(number, f"{indent}{key}: {draw(st.sampled_from(['1.0', '60.0', 'x', '[1]', '{}']))}")
    return "\n".join(lines) + "\n"


@st.composite
def hostile_scene(draw) -> tuple[bytes, str]:
    """(the bytes of a config file made hostile, a phrase its refusal must hold)."""
    shape = draw(st.sampled_from(["twice", "deep", "aliases", "large", "tabulated"]))
    source = draw(st.sampled_from(SCENES if shape == "tabulated" else FILES))
    text = source.read_text()
    if shape == "twice":
        return _key_twice(draw, text).encode(), "appears twice in one mapping"
    if shape == "deep":
        depth = draw(st.integers(MAX_DEPTH + 1, 30_000))
        opening, closing = draw(st.sampled_from([("[", "]"), ("{a: ", "}")]))
        return f"{text}\nextra: {opening * depth}1{closing * depth}\n".encode(), f"nested deeper than {MAX_DEPTH}"
    if shape == "aliases":
        width, levels = draw(st.integers(8, 30)), draw(st.integers(7, 12))
        bomb = "".join(f"a{k}: &a{k} [{', '.join([f'*a{k - 1}' if k else '1'] * width)}]\n" for k in range(levels))
        return (text + bomb).encode(), "counting those its aliases repeat"
    if shape == "large":
        padding = "#" * 99 + "\n"
        return (text + padding * (MAX_YAML_BYTES // 100 + draw(st.integers(1, 10_000)))).encode(), "at most 2 MB"
    data = yaml.safe_load(text)
    points = draw(st.integers(MAX_TABULATED_POINTS + 1, 3 * MAX_TABULATED_POINTS))
    data["body"]["profile"] = {"shape": "tabulated", "r": [k * 1e-9 for k in range(points)], "f": [0.0] * points}
    return yaml.safe_dump(data).encode(), f"body.profile.r: at most {MAX_TABULATED_POINTS} values"


@_settings(HOSTILE_EXAMPLES)
@given(hostile=hostile_scene())
@pytest.mark.slow
def test_hostile_shapes_are_refused_within_seconds(hostile):
    content, phrase = hostile
    with tempfile.TemporaryDirectory() as folder:
        scene = Path(folder) / "scene.yaml"
        scene.write_bytes(content)
        started = time.monotonic()
        result = _invoke("validate", scene)
    _assert_clean(result)
    assert result.exit_code == 2, result.output
    assert phrase in " ".join(result.output.split()), result.output
    assert time.monotonic() - started < 30


@st.composite
def huge_sweep(draw) -> dict:
    """A sweep of configs/sweeps with more than 10⁷ points: one axis of up to 10¹⁸ values, or a
    grid of two axes whose product exceeds 10⁷."""
    data = yaml.safe_load(draw(st.sampled_from(SWEEPS)).read_text())
    data["scene"] = (
        str((CONFIGS / "sweeps" / data["scene"]).resolve()) if isinstance(data["scene"], str) else data["scene"]
    )
    path = draw(st.sampled_from(sorted(data["axes"])))
    if draw(st.booleans()):
        data["axes"] = {path: {"geomspace": [0.1, 1.0, draw(st.integers(SWEEP_POINTS + 1, 10**18))]}}
        data["mode"] = draw(st.sampled_from(["grid", "zip"]))
    else:
        first = draw(st.integers(4000, 10**9))
        second = draw(st.integers(SWEEP_POINTS // first + 1, 10**9))
        data["axes"] = {path: {"linspace": [0.1, 1.0, first]}, "initial.gap": {"linspace": [0.0, 1e-9, second]}}
        data["mode"] = "grid"
    return data


@_settings(FEW_EXAMPLES)
@given(data=huge_sweep())
def test_a_sweep_of_more_than_ten_million_points_is_refused_within_seconds(data):
    with tempfile.TemporaryDirectory() as folder:
        sweep, output = Path(folder) / "sweep.yaml", Path(folder) / "out"
        sweep.write_text(yaml.safe_dump(data))
        started = time.monotonic()
        result = _invoke("sweep", sweep, "-o", output)
        assert not output.exists()
    _assert_clean(result)
    assert result.exit_code == 2, result.output
    assert time.monotonic() - started < 30


# --- fit data, mutated ----------------------------------------------------------------------

cells = st.one_of(
    magnitudes.map(repr),
    st.sampled_from(["0", "-0.35", "1e300", "-1e300", "nan", "inf", "-inf", "", "abc", "1e-320", "1,5"]),
)


@st.composite
def mutated_table(draw) -> str:
    """The drop test's CSV (three comment lines, a header, 30 rows) mutated: cells replaced, a
    column given twice, removed or renamed, rows removed, or random text."""
    lines = (DROP_TEST.parent / "drops.csv").read_text().splitlines()
    comments, header, rows = lines[:3], lines[3].split(","), [line.split(",") for line in lines[4:]]
    if draw(st.integers(0, 19)) == 0:
        return draw(st.text(max_size=80))
    for _ in range(draw(st.integers(1, 3))):
        action = draw(st.sampled_from(["cell", "cell", "twice", "drop column", "rename", "rows"]))
        column = draw(st.integers(0, len(header) - 1))
        if action == "cell" and rows:
            rows[draw(st.integers(0, len(rows) - 1))][column] = draw(cells)
        elif action == "twice":
            header.append(header[column])
            rows = [[*row, row[column]] for row in rows]
        elif action == "drop column" and len(header) > 1:
            header.pop(column)
            rows = [row[:column] + row[column + 1 :] for row in rows]
        elif action == "rename":
            header[column] = draw(st.text(min_size=1, max_size=8).filter(lambda name: "," not in name))
        elif action == "rows":
            rows = rows[: draw(st.integers(0, len(rows)))]
    return "\n".join([*comments, ",".join(header), *(",".join(row) for row in rows)]) + "\n"


@_settings(FEW_EXAMPLES)
@given(table=mutated_table())
def test_a_fit_of_mutated_data_fits_or_is_refused(table):
    """Exit 0 with χ² a number, or exit 2 with nothing written (model theory: the closed forms)."""
    with tempfile.TemporaryDirectory() as folder:
        fit = yaml.safe_load(DROP_TEST.read_text())
        fit["scene"] = str((DROP_TEST.parent / fit["scene"]).resolve())
        (Path(folder) / "fit.yaml").write_text(yaml.safe_dump(fit))
        (Path(folder) / fit["data"]).write_text(table)
        output = Path(folder) / "out"
        result = _invoke("fit", Path(folder) / "fit.yaml", "-o", output)
        _assert_clean(result)
        assert result.exit_code in (0, 2), result.output
        if result.exit_code == 2:
            assert not output.exists(), result.output
        else:
            assert math.isfinite(yaml.safe_load((output / "fit.yaml").read_text())["chi2"]), result.output
