"""Traced impact programs kept across processes: a run whose program is in the compilation cache
skips tracing it (about a second of Python) as well as compiling it.

The first run of a scene structure traces its solve once, serializes it with `jax.export`
(StableHLO) into `exported/` of the cache directory and runs it; later processes deserialize it
and JAX's persistent cache supplies its compiled executable. A program is keyed by everything
that shapes it: impact's source, the versions of jax and the libraries it traces, the platform,
the static choices of the integrator and the options, and the shapes and dtypes of the traced
parameters; a program whose key differs is traced anew. Without a cache directory (or without
`flatbuffers`, which `jax.export` serializes with) the solve is traced in every process.
"""

import contextlib
import dataclasses
import functools
import hashlib
import importlib.util
import os
from collections.abc import Callable
from importlib import metadata
from pathlib import Path

import equinox as eqx
import jax
from jax import export

from .._core.cache import directory_in_use
from .._core.runtime import COMPILER_OPTIONS
from .._integrate.base import AbstractIntegrator
from .._integrate.carry import Outcome
from .._integrate.problem import Options, Physics
from .._law.scales import Scales

EXPORTED = "exported"  # folder of the serialized programs inside the cache directory
_LIBRARIES = ("jax", "jaxlib", "diffrax", "equinox", "optimistix", "lineax")
Fields = dict[str, jax.Array]
Program = Callable[..., tuple[Fields, Fields]]

_loaded: dict[str, Program] = {}  # key → the program of this process


@eqx.filter_jit
def solve(integrator: AbstractIntegrator, physics: Physics, options: Options) -> tuple[Scales, Outcome]:
    """Scale, tabulate and integrate one impact; returns (scales, scaled outcome)."""
    return integrator.solve(physics, options)


def solve_by_field(integrator: AbstractIntegrator, physics: Physics, options: Options) -> tuple[Fields, Fields]:
    """`solve`, with the scales and the outcome as {field name: array}; traced only where the
    cache holds no program of its key."""
    dynamic, static = eqx.partition((integrator, physics), eqx.is_array)
    leaves, structure = jax.tree.flatten(dynamic)

    def by_field(*values: jax.Array) -> tuple[Fields, Fields]:
        solver, parameters = eqx.combine(jax.tree.unflatten(structure, values), static)
        scales, outcome = solver.solve(parameters, options)
        return _fields(scales), _fields(outcome)

    key = _key((repr(static), str(structure), repr(options)), leaves)
    if key not in _loaded:
        directory = directory_in_use()
        if directory is None or not _can_serialize():
            _loaded[key] = jax.jit(by_field, compiler_options=COMPILER_OPTIONS)
        else:
            _loaded[key] = _load_or_export(directory / EXPORTED / f"{key}.jaxexport", by_field, leaves)
    return _loaded[key](*leaves)


@functools.cache
def _can_serialize() -> bool:
    """Whether `jax.export` can serialize here (it needs the flatbuffers package)."""
    return importlib.util.find_spec("flatbuffers") is not None


def _fields(module: eqx.Module) -> Fields:
    return {field.name: getattr(module, field.name) for field in dataclasses.fields(module)}


def _load_or_export(path: Path, function: Callable, leaves: list[jax.Array]) -> Program:
    """The stored program at `path`, or `function` traced, exported and stored there (a file
    that cannot be read back is replaced; one that cannot be written is skipped)."""
    try:
        return jax.jit(export.deserialize(bytearray(path.read_bytes())).call, compiler_options=COMPILER_OPTIONS)
    except Exception:  # noqa: BLE001 - missing, unreadable or damaged (struct.error, ...): trace anew
        pass
    exported = export.export(jax.jit(function))(*leaves)
    partial = path.with_name(f"{path.name}.{os.getpid()}.partial")  # written whole, then renamed
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        partial.write_bytes(exported.serialize())
        os.replace(partial, path)
    except OSError:
        with contextlib.suppress(OSError):
            partial.unlink(missing_ok=True)
    return jax.jit(exported.call, compiler_options=COMPILER_OPTIONS)


def _key(static: tuple[str, ...], leaves: list[jax.Array]) -> str:
    """SHA-256 of the source, the libraries, the platform, the static parts of one program and
    its traced parameters' shapes and dtypes."""
    avals = [(leaf.shape, str(leaf.dtype), getattr(leaf, "weak_type", False)) for leaf in leaves]
    text = repr((_environment(), jax.default_backend(), static, avals))
    return hashlib.sha256(text.encode()).hexdigest()


@functools.cache
def _environment() -> str:
    """impact's source (every module's bytes) and the versions of the traced libraries."""
    digest = hashlib.sha256()
    package = Path(__file__).parents[1]
    for module in sorted(package.rglob("*.py")):
        digest.update(module.relative_to(package).as_posix().encode())
        digest.update(module.read_bytes())
    versions = [f"{name} {metadata.version(name)}" for name in _LIBRARIES]
    return f"{digest.hexdigest()} {versions}"
