"""Compilation: once per scene structure and machine. New values of traced parameters reuse the
compiled program; the persistent cache (in the directory that `configure` picks) lets a second
process load the traced program and its executable instead of tracing and compiling, with the
same results to the bit; a cache directory that cannot be written only warns."""

import copy
import dataclasses
import hashlib
import math
import os
import subprocess
import sys
import warnings
from pathlib import Path

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np
import platformdirs
import pytest
from jax import export

import impact
from impact._core import stored
from impact._core.cache import cache_directory, directory_in_use, use_cache
from impact._core.stored import EXPORTED, StoredProgramWarning, call_stored
from impact._run.parameters import integrator_for, options_for, physics_for
from impact._run.programs import solve, solve_by_field
from impact._scene.reading import read_yaml
from impact._scene.sweep import load_sweep
from impact.cli.console import show_warning
from tests.compilations import COMPILE, Compiles
from tests.scenes import CONFIGS, FITS, ROOT, SWEEPS, THORNTON_NING

CACHE_HIT = "/jax/compilation_cache/cache_hits"


def changed(path: tuple[str, ...], value, source: Path = THORNTON_NING) -> dict:
    scene = copy.deepcopy(read_yaml(source))
    section = scene
    for key in path[:-1]:
        section = section[key]
    section[path[-1]] = value
    return scene


TRACED = {
    "initial.velocity": (("initial", "velocity"), 0.8),
    "work of adhesion": (("effects", "adhesion", "work_of_adhesion"), 0.07),
    "E*": (("material", "E_star"), 2.0e9),
    "mass": (("body", "mass"), 2.0e-14),
    "paraboloid R": (("body", "profile", "R"), 2.0e-6),
    "a counterpart": (("counterpart",), {"mass": 5.0e-14, "velocity": 0.2}),  # a flat: same program
}


def test_new_traced_values_do_not_recompile():
    reference = impact.simulate(THORNTON_NING, trajectory=True)  # compiles here unless done before
    for name, (path, value) in TRACED.items():
        with Compiles() as compiles:
            result = impact.simulate(changed(path, value))
        assert compiles.count == 0, f"a new {name} recompiled ({compiles.count} compilations)"
        assert result.success and result.restitution != reference.restitution, name


def test_new_double_hertz_factors_do_not_recompile():
    """Greenwood–Johnson's k is traced: a new k (either side of k = 1, where the curve gains its
    turning point) runs the compiled program."""
    scene = read_yaml(CONFIGS / "greenwood_johnson.yaml")
    reference = impact.simulate(scene)  # compiles here unless done before
    for k in (0.5, 1e3):
        scene["effects"]["adhesion"]["k"] = k
        with Compiles() as compiles:
            result = impact.simulate(scene)
        assert compiles.count == 0, f"k = {k} recompiled ({compiles.count} compilations)"
        assert result.success and result.restitution != reference.restitution


def test_new_yield_pressures_and_velocities_do_not_recompile_a_plastic_impact():
    plastic = CONFIGS / "plastic_steel.yaml"
    reference = impact.simulate(plastic)
    for path, value in ((("effects", "plasticity", "yield_pressure"), 2.0e9), (("initial", "velocity"), 3.0)):
        with Compiles() as compiles:
            result = impact.simulate(changed(path, value, plastic))
        assert compiles.count == 0, f"a new {path[-1]} recompiled ({compiles.count} compilations)"
        assert result.success and result.restitution != reference.restitution


@pytest.mark.parametrize(
    ("variable", "arguments", "expected"),
    [
        (None, {}, Path(platformdirs.user_cache_dir("impact")) / "jax"),
        ("", {}, Path(platformdirs.user_cache_dir("impact")) / "jax"),
        ("/some/where", {}, Path("/some/where")),
        ("off", {}, None),
        ("OFF", {"cache_dir": "/else/where"}, Path("/else/where")),
        ("/some/where", {"cache_dir": "/else/where"}, Path("/else/where")),
        ("/some/where", {"cache": False}, None),
        (None, {"cache_dir": "~/cache"}, Path.home() / "cache"),
    ],
    ids=["default", "empty", "variable", "off", "argument-over-off", "argument-over-variable", "no-cache", "home"],
)
def test_cache_directory_follows_argument_then_variable_then_platform(variable, arguments, expected, monkeypatch):
    if variable is None:
        monkeypatch.delenv("IMPACT_CACHE_DIR", raising=False)
    else:
        monkeypatch.setenv("IMPACT_CACHE_DIR", variable)
    assert cache_directory(**arguments) == expected


@pytest.fixture
def restore_cache():
    """Put the suite's cache back (conftest's IMPACT_CACHE_DIR) after a test that changed it."""
    yield
    assert impact.configure() == Path(os.environ["IMPACT_CACHE_DIR"])


def test_unusable_cache_directory_warns_and_compiles_without_a_cache(tmp_path, restore_cache):
    blocker = tmp_path / "a file"
    blocker.write_text("not a folder")
    unusable = blocker / "jax"
    message = f"compilation cache {unusable} is not usable (Not a directory); compiling without a cache"
    with pytest.warns(RuntimeWarning) as caught:
        assert impact.configure(unusable) is None
    assert [str(warning.message) for warning in caught] == [message]
    assert jax.config.jax_enable_compilation_cache is False
    result = impact.simulate(changed(("initial", "velocity"), 0.7))
    assert result.success


def test_usable_directory_is_switched_on(tmp_path, restore_cache):
    assert use_cache(tmp_path / "new" / "jax") == tmp_path / "new" / "jax"
    assert (tmp_path / "new" / "jax").is_dir()
    assert jax.config.jax_enable_compilation_cache is True
    assert jax.config.jax_compilation_cache_dir == str(tmp_path / "new" / "jax")
    assert jax.config.jax_persistent_cache_min_compile_time_secs == 0.0


# How a fresh process's script starts: JAX's compile and cache events recorded in `events`, the
# names of the programs traced, lowered and compiled in `programs`.
RECORDING = """
import sys, jax, impact
events, programs = [], []  # every event; the program each timed one was about
jax.monitoring.register_event_duration_secs_listener(
    lambda event, duration, **kw: (events.append(event), programs.append(kw.get("fun_name")))
)
jax.monitoring.register_event_listener(lambda event, **kw: events.append(event))
impact.configure()
"""
# What it prints first: how many programs it compiled and how many it loaded from the cache (JAX
# reports a load as a backend compilation and a cache hit).
COUNTS = f"events.count({COMPILE!r}) - events.count({CACHE_HIT!r}), events.count({CACHE_HIT!r})"

# A fresh process that runs the scene and says how many programs it compiled and loaded, whether
# it imported diffrax (only tracing a ride does) and whether scipy (only LAPACK kernels need it).
PROCESS = f"""{RECORDING}
result = impact.simulate(sys.argv[1])
imported = ["diffrax" in sys.modules, "scipy" in sys.modules]
print({COUNTS}, repr(result.restitution), *imported)
"""


def fresh_process(script: str, scene: Path, cache: Path) -> list[str]:
    """The words `script` prints, run in a fresh Python with `scene` as its argument and the
    compilation cache in `cache`."""
    env = dict(os.environ, IMPACT_CACHE_DIR=str(cache))
    command = [sys.executable, "-c", script, str(scene)]
    process = subprocess.run(command, capture_output=True, text=True, env=env, cwd=ROOT)
    assert process.returncode == 0, process.stderr
    return process.stdout.split()


def twice(script: str, scene: Path, cache: Path) -> tuple[list[str], list[str]]:
    """The words `script` prints in two fresh processes in turn, sharing the cache `cache`; the
    second stores no traced program the first did not."""
    first = fresh_process(script, scene, cache)
    stored = sorted((cache / EXPORTED).iterdir())
    second = fresh_process(script, scene, cache)
    assert sorted((cache / EXPORTED).iterdir()) == stored
    return first, second


@pytest.mark.slow
def test_second_process_loads_the_compiled_programs_instead_of_compiling(tmp_path):
    def run() -> list[str]:
        return fresh_process(PROCESS, THORNTON_NING, tmp_path / "cache")

    compiled, loaded, restitution, traced, _ = run()
    assert int(compiled) >= 1 and loaded == "0" and traced == "True"
    # the traced programs, exported: the scene check's units and the solve (the larger)
    units, program = sorted((tmp_path / "cache" / EXPORTED).iterdir(), key=lambda path: path.stat().st_size)
    stored = program.read_bytes()
    # no tracing (diffrax not even imported): fewer programs than the first run; no LAPACK (no scipy)
    compiled_again, loaded_again, same, traced_again, scipy = run()
    assert compiled_again == "0" and int(loaded_again) >= 1 and same == restitution and traced_again == "False"
    assert scipy == "False"
    assert sorted((tmp_path / "cache" / EXPORTED).iterdir()) == sorted([units, program])
    assert program.read_bytes() == stored
    program.write_bytes(b"not a program")
    assert run()[:4] == ["0", compiled, restitution, "True"]  # traced and exported anew; its executables loaded
    assert program.read_bytes() == stored


# A fresh process that sweeps four velocities in one call and says how many programs it compiled
# and loaded, whether it imported diffrax (only tracing the batch does) and the
# restitutions' bits.
SWEEP_PROCESS = f"""{RECORDING}
result = impact.sweep(sys.argv[1], {{"initial.velocity": [0.5, 1.0, 2.0, 4.0]}}, chunk=4)
print({COUNTS}, "diffrax" in sys.modules, *[value.hex() for value in result.restitution])
"""


@pytest.mark.slow
def test_second_process_loads_a_sweeps_batch_instead_of_tracing_it(tmp_path):
    """A sweep's compiled batch is stored as a traced program too: a second process of the same
    structure neither traces (no diffrax) nor compiles it, and gets the same bits."""

    first, second = twice(SWEEP_PROCESS, THORNTON_NING, tmp_path / "cache")
    compiled, loaded, traced, *restitutions = first
    assert int(compiled) >= 1 and loaded == "0" and traced == "True" and len(restitutions) == 4
    compiled_again, loaded_again, traced_again, *same = second
    assert compiled_again == "0" and int(loaded_again) >= 1 and traced_again == "False"
    assert same == restitutions


# A fresh process that runs an indentation test and says how many programs it compiled and
# loaded, how many times it traced the march (itself, or inside `call_stored`'s
# `traced`) and the bits of its pull-off force and of its last force sample.
INDENTATION_PROCESS = f"""{RECORDING}
result = impact.simulate(sys.argv[1])
print({COUNTS}, programs.count("march") + programs.count("traced"), result.pull_off.force.hex(), result.force[-1].hex())
"""


@pytest.mark.slow
def test_second_process_loads_an_indentation_test_instead_of_tracing_it(tmp_path):
    """An indentation test's march is stored traced as an impact's solve is: a second process
    neither traces nor compiles it, and gets the same bits."""

    first, second = twice(INDENTATION_PROCESS, CONFIGS / "indentation_paraboloid.yaml", tmp_path / "cache")
    compiled, loaded, traced, *forces = first
    assert int(compiled) >= 1 and loaded == "0" and int(traced) >= 1
    compiled_again, loaded_again, traced_again, *same = second
    assert compiled_again == "0" and int(loaded_again) >= 1 and traced_again == "0"
    assert same == forces


# A fresh process that fits the drop test (the closed form) and says how many programs it
# compiled and loaded, how many it traced (inside `call_stored`'s `traced`) and the bits of the
# fitted values.
FIT_PROCESS = f"""{RECORDING}
from pathlib import Path
from impact._run.fit import fit_spec
from impact._scene.fit_spec import load_fit
result = fit_spec(load_fit(Path(sys.argv[1]), []), "theory")
print({COUNTS}, programs.count("traced"), *[value.hex() for value in result.values.values()])
"""


@pytest.mark.slow
def test_second_process_loads_a_fit_instead_of_tracing_it(tmp_path):
    """A fit's programs (the residuals at the start, the whole Levenberg–Marquardt solve) are
    stored traced: a second process neither traces nor compiles them, and fits the same bits."""

    first, second = twice(FIT_PROCESS, FITS / "drop_test.yaml", tmp_path / "cache")
    compiled, _, traced, *values = first
    assert int(compiled) >= 1 and int(traced) >= 2 and len(values) == 2
    compiled_again, loaded_again, traced_again, *same = second
    assert compiled_again == "0" and int(loaded_again) >= 2 and traced_again == "0"
    assert same == values


# A fresh process that evaluates f = impact.as_function(scene, [initial.velocity], restitution)
# and its derivative at one point and says how many programs it compiled and loaded, how many
# it traced and lowered (inside `compile_stored`: `flat`) and the bits of f and f'.
GRADIENT_PROCESS = f"""{RECORDING}
f = impact.as_function(sys.argv[1], ["initial.velocity"], "restitution")
x = jax.numpy.array([1.0])
value, slope = float(f(x)), float(jax.grad(f)(x)[0])
print({COUNTS}, programs.count("jit(flat)"), value.hex(), slope.hex())
"""


@pytest.mark.slow
def test_second_process_loads_a_functions_programs_instead_of_tracing_them(tmp_path):
    """`impact.as_function`'s programs (its value and its forward-mode Jacobian, on concrete
    inputs) are stored traced: a second process neither traces nor compiles them, and gets the
    same bits. (A spring array: its Jacobian compiles fastest.)"""

    first, second = twice(GRADIENT_PROCESS, CONFIGS / "spring_array.yaml", tmp_path / "cache")
    compiled, _, traced, *values = first
    assert int(compiled) >= 2 and int(traced) == 2 and len(values) == 2
    assert len(list((tmp_path / "cache" / EXPORTED).iterdir())) == 3  # the scene check's, f's and f′'s
    compiled_again, loaded_again, traced_again, *same = second
    assert compiled_again == "0" and int(loaded_again) >= 2 and traced_again == "0"
    assert same == values


@pytest.mark.parametrize("cache", [True, False], ids=["stored", "without a cache"])
def test_a_failed_runtime_check_in_a_stored_program_gives_nan(cache, tmp_path, restore_cache):
    """equinox's runtime checks (a failed linear solve in a fit's Jacobian) return NaN in a
    stored program instead of raising from a host callback (which `jax.export` cannot store),
    with or without a cache."""
    use_cache(tmp_path / "jax" if cache else None)

    def checked(x, label):  # the label (static) keeps the two cases' programs apart
        return {"value": eqx.error_if(2.0 * x, x > 1.0, "x above 1")}

    with jax.enable_x64(True):
        assert float(call_stored(checked, jnp.asarray(0.5), cache)["value"]) == 1.0
        assert np.isnan(call_stored(checked, jnp.asarray(3.0), cache)["value"])
    assert bool(cache) == (tmp_path / "jax" / EXPORTED).is_dir()


@pytest.mark.slow
def test_stored_program_gives_the_traced_results_bit_for_bit(thornton_ning_scene):
    scene = thornton_ning_scene
    arguments = integrator_for(scene), physics_for(scene), options_for(scene, True)
    with jax.enable_x64(True):
        stored = solve_by_field(*arguments)
        traced = solve(*arguments)
    assert directory_in_use() is not None  # the stored program ran
    for mine, reference in zip(stored, traced, strict=True):
        for name, value in mine.items():
            assert np.array_equal(value, getattr(reference, name), equal_nan=True), name


def test_validating_a_sweep_compiles_per_structure_not_per_point(tmp_path):
    """Every point of a sweep is checked for what the scaled problem can represent; its numbers are
    traced in batches of one shape, so a second sweep of the same structure (10⁴ other points)
    compiles no new program."""
    load_sweep(SWEEPS / "thornton_ning_fast.yaml")  # compiles the checks of its structure once
    other = tmp_path / "other_numbers.yaml"
    other.write_text(
        f"scene: {THORNTON_NING}\n"
        "set:\n  solver.method: quadrature\n  effects.adhesion.work_of_adhesion: 0.07\n"
        "axes:\n  initial.velocity: {geomspace: [0.3, 30.0, 10001]}\n"
    )
    with Compiles() as compiles:
        spec = load_sweep(other)
    assert spec.size == 10_001
    assert compiles.count == 0


def test_a_program_that_cannot_be_stored_is_traced_in_its_process(tmp_path, restore_cache):
    """A program `jax.export` refuses (here a host callback: an equinox check traced in raise
    mode by a library's own jit cache, say) runs traced in its process, and nothing is stored."""
    use_cache(tmp_path / "jax")

    def logged(x):
        jax.debug.callback(lambda value: None, x)
        return {"value": 2.0 * x}

    with jax.enable_x64(True):
        assert float(call_stored(logged, jnp.asarray(1.5))["value"]) == 3.0
    assert list((tmp_path / "jax").rglob("*.jaxexport")) == []


def _doubled_sine(x):
    return {"value": 2.0 * jnp.sin(x)}


def _stored_value(x: float) -> float:
    """`_doubled_sine(x)` through `call_stored`, as a fresh process would call it (no program of
    this process kept), from one call site (the stored program's locations name it)."""
    stored._loaded.clear()
    with jax.enable_x64(True):
        return float(call_stored(_doubled_sine, jnp.asarray(x))["value"])


@pytest.fixture
def stored_program(tmp_path, monkeypatch, restore_cache) -> Path:
    """The stored file of `_doubled_sine` in a cache of its own (this process's programs kept aside)."""
    monkeypatch.setattr(stored, "_loaded", {})
    use_cache(tmp_path / "jax")
    assert _stored_value(0.5) == 2.0 * math.sin(0.5)
    (path,) = (tmp_path / "jax" / EXPORTED).iterdir()
    return path


@pytest.mark.slow
def test_a_flipped_bit_anywhere_in_a_stored_program_is_discarded_and_traced_anew(stored_program):
    """One bit flipped at any of 64 positions spread over the file (its SHA-256 and the program;
    unchecked, some flips fail to deserialize or lower and one hung the StableHLO reader): one
    warning, the traced value, and the program stored again, sound."""
    good = stored_program.read_bytes()
    positions = sorted({round(k * (len(good) - 1) / 63) for k in range(64)})
    assert len(positions) == 64
    for k, position in enumerate(positions):
        damaged = bytearray(good)
        damaged[position] ^= 1 << (k % 8)
        stored_program.write_bytes(bytes(damaged))
        with pytest.warns(StoredProgramWarning) as caught:
            assert _stored_value(0.5) == 2.0 * math.sin(0.5), position
        assert [str(warning.message) for warning in caught] == [
            f"stored program {stored_program.name} discarded and traced anew: its SHA-256 does not match "
            "(the file is damaged)"
        ], position
        assert _loads_without_warning(), position


def _loads_without_warning() -> bool:
    """Whether the stored program of `_doubled_sine` loads (again) without a warning and gives its value."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", StoredProgramWarning)
        return _stored_value(0.75) == 2.0 * math.sin(0.75)


def _signed(program: bytes) -> bytes:
    return hashlib.sha256(program).digest() + program


@pytest.mark.parametrize("damage", ["not a program", "cut short", "StableHLO damaged"])
def test_a_stored_program_that_fails_to_load_or_lower_is_discarded_and_traced_anew(damage, stored_program):
    """A file whose digest matches but whose program fails (to deserialize, or to lower: the
    StableHLO inside a sound flatbuffer) is discarded with one warning and traced anew."""
    good = stored_program.read_bytes()
    program = good[hashlib.sha256().digest_size :]
    if damage == "not a program":
        program = b"not a program"
    elif damage == "cut short":
        program = program[: len(program) // 2]
    else:
        exported = export.deserialize(bytearray(program))
        program = bytes(dataclasses.replace(exported, mlir_module_serialized=b"ML\xefR damaged").serialize())
    stored_program.write_bytes(_signed(program))
    with pytest.warns(StoredProgramWarning, match=f"stored program {stored_program.name} discarded and traced anew: "):
        assert _stored_value(0.25) == 2.0 * math.sin(0.25)
    assert _loads_without_warning()


def test_a_python_warning_is_one_line_on_the_command_line(capsys):
    show_warning(StoredProgramWarning("stored program k.jaxexport discarded"), StoredProgramWarning, "stored.py", 1)
    assert capsys.readouterr().err == "warning: stored program k.jaxexport discarded\n"
