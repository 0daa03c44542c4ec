"""Fuzzing the command line: random mutations of every file in configs/ through `impact validate`
and `impact run` must end with exit 0 or 2, never a traceback, never a partial file.

Mutations: a number scaled by 10^k (|k| ≤ 3: mostly valid scenes, so the runs simulate), a
value replaced (numbers from 1e-300 to 1e300 of either sign, NaN, ±inf, integers, booleans,
strings, None, lists, mappings), a key deleted, an unknown key added, a value wrapped
in a list or a mapping (wrong nesting), or the whole file replaced by random bytes. Exit 1 is
accepted only from `run`, for a run written with a named non-physical status (time_limit, …)
and its warning. The CI portion is short; `IMPACT_FUZZ_EXAMPLES=10000 pytest tests/cli/test_fuzz.py`
runs a long one (validate examples; runs are a fiftieth of them, at least 15), not derandomized.
"""

import copy
import os
import tempfile
from pathlib import Path

import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from impact._integrate.codes import RESULT_CODES
from impact._io.results import open_run
from impact.cli import app

CONFIGS = Path(__file__).parents[2] / "configs"
FILES = sorted(CONFIGS.glob("*.yaml")) + sorted(CONFIGS.glob("*/*.yaml"))
LONG = "IMPACT_FUZZ_EXAMPLES" in os.environ
VALIDATE_EXAMPLES = int(os.environ.get("IMPACT_FUZZ_EXAMPLES", "300"))
RUN_EXAMPLES = max(15, VALIDATE_EXAMPLES // 50)
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
        else:
            node[key] = draw(st.sampled_from([[node[key]], {"value": copy.deepcopy(node[key])}]))
    text = yaml.safe_dump(data, allow_unicode=True)
    return text.encode()


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


@_settings(VALIDATE_EXAMPLES)
@given(content=mutated_scene())
def test_validate_ends_with_0_or_2(content):
    with tempfile.TemporaryDirectory() as folder:
        scene = Path(folder) / "scene.yaml"
        scene.write_bytes(content)
        result = _invoke("validate", scene)
    _assert_clean(result)
    assert result.exit_code in (0, 2), result.output


@_settings(RUN_EXAMPLES)
@given(content=mutated_scene(actions=("scale", "scale", "scale", "replace", "delete")))
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
