"""Traced programs kept across processes: a program whose key is in the compilation cache is not
traced again (tracing costs Python seconds, besides the compilation that JAX's persistent cache
saves).

The first call of a program (`call_stored`: one scene's programs, a fit's), or its first
compilation ahead of its calls (`compile_stored`: a sweep's batch, sharded over its devices;
`impact.as_function`'s value and Jacobian), traces it once
and serializes it with `jax.export` (StableHLO) into `exported/` of the cache directory; later
processes deserialize it and JAX's persistent cache supplies its compiled executable. A program
is keyed by everything that shapes it: impact's source, the versions of jax and the libraries it
traces, the platform, its name, the static parts of its arguments and the shapes and dtypes of
their arrays (and a batch's shardings); a program whose key differs is traced anew. Without a
cache directory (or without `flatbuffers`, which `jax.export` serializes with) it is traced in
every process.

A program traced here returns NaN where one of equinox's runtime checks fails (e.g. lineax's
linear solve in the implicit derivative of a located event, inside a fit's Jacobian) instead of
raising from a host callback, which `jax.export` cannot serialize: with or without a cache, so
that a result never depends on it.

The first call of a stored program on the CPU would initialize jaxlib's LAPACK kernels, which
imports `scipy.linalg` (a noticeable share of a short run) whatever the program calls; a program that calls no
LAPACK kernel is run without, and one that does initializes them as usual.
"""

import contextlib
import functools
import hashlib
import importlib.util
import os
from collections.abc import Callable, Iterator
from importlib import metadata
from pathlib import Path
from typing import Any

import equinox as eqx
import jax

# equinox's choice of what a failed runtime check does (private: no public switch scoped to one
# trace), read where a check is traced.
from equinox import _errors as _equinox_errors
from jax import export

# The lowering of a stored program's call; private, used only to skip an import (`_without_lapack`).
from jax._src.export import _export  # noqa: TID251 - no public switch; absent, nothing is skipped

from .cache import directory_in_use
from .runtime import compiler_options

EXPORTED = "exported"  # folder of the serialized programs inside the cache directory
_LIBRARIES = ("jax", "jaxlib", "diffrax", "equinox", "optimistix", "lineax")

_loaded: dict[str, Callable] = {}  # key → the program of this process
_LAPACK = b"lapack_"  # the prefix of jaxlib's LAPACK kernels in a program's StableHLO
# Kernels that `jax.export` does not list as stable across jaxlib versions (Q·x after a QR, in a
# fit's Levenberg–Marquardt steps): serialized all the same, as a stored program is read back
# only by the jaxlib that wrote it (its key holds the version).
_UNLISTED_KERNELS = ("lapack_dormqr_ffi",)


def call_stored(function: Callable[..., Any], *arguments: Any) -> Any:
    """`function(*arguments)` compiled, its arrays traced and the rest static (a static part is
    told apart by its repr); traced only where the cache holds no program of its key.

    `function` returns a pytree of dicts, tuples and lists of arrays (what `jax.export` can
    serialize: an `equinox.Module` is returned as {field name: value}, e.g. by `pytree.fields`).
    """
    dynamic, static = eqx.partition(arguments, eqx.is_array)
    leaves, structure = jax.tree.flatten(dynamic)

    def traced(*values: jax.Array) -> Any:
        return function(*eqx.combine(jax.tree.unflatten(structure, values), static))

    name = f"{function.__module__}.{function.__qualname__}"
    key = _key((name, repr(static), str(structure)), leaves)
    if key in _loaded:
        return _loaded[key](*leaves)
    jitted = jax.jit(traced, compiler_options=compiler_options())
    exported = _load_or_export(key, jitted, leaves)
    if exported is None:  # not stored: traced here (or by the export that failed: its trace is reused)
        _loaded[key] = jitted
        with _errors_as_nan():
            return jitted(*leaves)
    _loaded[key] = jax.jit(exported.call, compiler_options=compiler_options())
    with _lowering(exported):
        return _loaded[key](*leaves)  # the first call lowers the program


def compile_stored(function: Callable[[Any], Any], label: str, abstract: Any, options: dict) -> Callable[[Any], Any]:
    """`function` (of one pytree of arrays) lowered for `abstract` (the same pytree of
    `jax.ShapeDtypeStruct`, possibly sharded) and compiled with the XLA `options`; traced only
    where the cache holds no program of its key. `label` names everything static that shapes
    the program (the function and what it closes over)."""
    leaves, structure = jax.tree.flatten(abstract)
    shardings = repr([getattr(leaf, "sharding", None) for leaf in leaves])
    key = _key((label, str(structure), shardings), leaves)

    def flat(*values: jax.Array) -> Any:  # what `jax.export` serializes: arrays in, dicts out
        return function(jax.tree.unflatten(structure, values))

    jitted = jax.jit(flat, compiler_options=options)
    exported = _load_or_export(key, jitted, leaves)
    if exported is None:  # not stored: traced here (or by the export that failed: its trace is reused)
        with _errors_as_nan():
            compiled = jitted.lower(*leaves).compile()
    else:
        with _lowering(exported):
            compiled = jax.jit(exported.call, compiler_options=options).lower(*leaves).compile()
    return lambda tree: compiled(*jax.tree.leaves(tree))


@functools.cache
def _can_serialize() -> bool:
    """Whether `jax.export` can serialize here (it needs the flatbuffers package)."""
    return importlib.util.find_spec("flatbuffers") is not None


def _load_or_export(key: str, jitted: jax.stages.Wrapped, leaves: list[Any]) -> export.Exported | None:
    """The stored program of `key`, or `jitted` traced, exported and stored (a file that cannot
    be read back is replaced; one that cannot be written is skipped). None without a cache
    directory or `flatbuffers`, or where the program cannot be exported: it holds a host
    callback (an equinox check that raises, from a trace that a library's own jit cache kept
    from outside `_errors_as_nan`) or a kernel that `jax.export` refuses."""
    directory = directory_in_use()
    if directory is None or not _can_serialize():
        return None
    path = directory / EXPORTED / f"{key}.jaxexport"
    try:
        return export.deserialize(bytearray(path.read_bytes()))
    except Exception:  # noqa: BLE001 - missing, unreadable or damaged (struct.error, ...): trace anew
        pass
    allowed = [export.DisabledSafetyCheck.custom_call(kernel) for kernel in _UNLISTED_KERNELS]
    try:
        with _errors_as_nan():
            exported = export.export(jitted, disabled_checks=allowed)(*leaves)
    except (NotImplementedError, ValueError):  # what export refuses; an error of the program raises again
        return None
    partial = path.with_name(f"{path.name}.{os.getpid()}.partial")  # written whole, then renamed
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        partial.write_bytes(exported.serialize())
        os.replace(partial, path)
    except OSError:
        with contextlib.suppress(OSError):
            partial.unlink(missing_ok=True)
    return exported


def _lowering(exported: export.Exported) -> contextlib.AbstractContextManager:
    """Where a stored program is lowered: without jaxlib's LAPACK kernels unless it calls them."""
    return contextlib.nullcontext() if _LAPACK in exported.mlir_module_serialized else _without_lapack()


@contextlib.contextmanager
def _without_lapack() -> Iterator[None]:
    """Lower stored programs without initializing jaxlib's LAPACK kernels (and importing
    `scipy.linalg` for them): for a program that calls none. A later program that does call
    them initializes them where it is lowered."""
    initialize = getattr(_export, "_ensure_backends_initialized", None)
    if initialize is None:
        yield
        return
    _export._ensure_backends_initialized = lambda platforms: None
    try:
        yield
    finally:
        _export._ensure_backends_initialized = initialize


@contextlib.contextmanager
def _errors_as_nan() -> Iterator[None]:
    """Trace equinox's runtime checks as NaN where they fail, instead of a host callback that raises."""
    chosen = _equinox_errors.EQX_ON_ERROR
    _equinox_errors.EQX_ON_ERROR = "nan"
    try:
        yield
    finally:
        _equinox_errors.EQX_ON_ERROR = chosen


def _key(static: tuple[str, ...], leaves: list[jax.Array]) -> str:
    """SHA-256 of the source, the libraries, the platform, the static parts of one program and
    its traced arguments' shapes and dtypes."""
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
