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

A stored file holds the SHA-256 of the program before it: a file whose digest does not match
(a flipped bit, a cut write) is never handed to the StableHLO reader, which can fail, or hang,
on a damaged program. A file that does not match, or a program that fails to load, lower or
compile, is discarded with one warning (`StoredProgramWarning`) and the program is traced anew.

The first call of a stored program on the CPU would initialize jaxlib's LAPACK kernels, which
imports `scipy.linalg` (a noticeable share of a short run) whatever the program calls; a program that calls no
LAPACK kernel is run without, and one that does initializes them as usual.
"""

import contextlib
import functools
import hashlib
import importlib.util
import os
import warnings
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
_DIGEST = hashlib.sha256().digest_size  # bytes of the SHA-256 that a stored file starts with
_LIBRARIES = ("jax", "jaxlib", "diffrax", "equinox", "optimistix", "lineax")

_loaded: dict[str, Callable] = {}  # key → the program of this process
_LAPACK = b"lapack_"  # the prefix of jaxlib's LAPACK kernels in a program's StableHLO
# Kernels that `jax.export` does not list as stable across jaxlib versions (Q·x after a QR, in a
# fit's Levenberg–Marquardt steps): serialized all the same, as a stored program is read back
# only by the jaxlib that wrote it (its key holds the version).
_UNLISTED_KERNELS = ("lapack_dormqr_ffi",)


def call_stored(function: Callable[..., Any], *arguments: Any, once: bool = False) -> Any:
    """`function(*arguments)` compiled, its arrays traced and the rest static (a static part is
    told apart by its repr); traced only where the cache holds no program of its key. `once`: a
    program that runs once per run, compiled quickly (`runtime.RUN_ONCE`).

    `function` returns a pytree of dicts, tuples and lists of arrays (what `jax.export` can
    serialize: an `equinox.Module` is returned as {field name: value}, e.g. by `pytree.fields`).
    """
    dynamic, static = eqx.partition(arguments, eqx.is_array)
    leaves, structure = jax.tree.flatten(dynamic)

    def traced(*values: jax.Array) -> Any:
        return function(*eqx.combine(jax.tree.unflatten(structure, values), static))

    name = f"{function.__module__}.{function.__qualname__}"
    options = compiler_options(once=once)
    key = _key((name, repr(static), str(structure), repr(options)), leaves)
    if key in _loaded:
        return _loaded[key](*leaves)
    jitted = jax.jit(traced, compiler_options=options)
    compiled = _stored_compiled(key, jitted, leaves, options)
    if compiled is None:  # not stored: traced here (or by the export that failed: its trace is reused)
        _loaded[key] = jitted
        with _errors_as_nan():
            return jitted(*leaves)
    _loaded[key] = compiled
    return compiled(*leaves)


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
    compiled = _stored_compiled(key, jitted, leaves, options)
    if compiled is None:  # not stored: traced here (or by the export that failed: its trace is reused)
        with _errors_as_nan():
            compiled = jitted.lower(*leaves).compile()
    return lambda tree: compiled(*jax.tree.leaves(tree))


@functools.cache
def _can_serialize() -> bool:
    """Whether `jax.export` can serialize here (it needs the flatbuffers package)."""
    return importlib.util.find_spec("flatbuffers") is not None


class StoredProgramWarning(RuntimeWarning):
    """A stored program was damaged or could not be loaded: it was discarded and traced anew."""


def _stored_compiled(key: str, jitted: jax.stages.Wrapped, leaves: list[Any], options: dict) -> Any:
    """The stored program of `key` compiled for `leaves`, or `jitted` traced, exported, stored and
    compiled from its export. A stored file that is damaged or fails to deserialize, lower or
    compile is discarded (one `StoredProgramWarning`) and replaced. None without a cache
    directory or `flatbuffers`, or where the program cannot be exported: it holds a host
    callback (an equinox check that raises, from a trace that a library's own jit cache kept
    from outside `_errors_as_nan`) or a kernel that `jax.export` refuses."""
    directory = directory_in_use()
    if directory is None or not _can_serialize():
        return None
    path = directory / EXPORTED / f"{key}.jaxexport"
    try:
        stored = path.read_bytes()
    except OSError:  # missing or unreadable: traced anew
        stored = None
    if stored is not None:
        try:
            return _compiled(_deserialized(stored), leaves, options)
        except Exception as error:  # noqa: BLE001 - any failure of a stored program: trace anew
            _discard(path, error)
    allowed = [export.DisabledSafetyCheck.custom_call(kernel) for kernel in _UNLISTED_KERNELS]
    try:
        with _errors_as_nan():
            exported = export.export(jitted, disabled_checks=allowed)(*leaves)
    except (NotImplementedError, ValueError):  # what export refuses; an error of the program raises again
        return None
    _store(path, bytes(exported.serialize()))
    return _compiled(exported, leaves, options)


def _deserialized(stored: bytes) -> export.Exported:
    """The program of a stored file (its SHA-256, then the serialized program); ValueError where
    the digest does not match."""
    digest, program = stored[:_DIGEST], stored[_DIGEST:]
    if hashlib.sha256(program).digest() != digest:
        raise ValueError("its SHA-256 does not match (the file is damaged)")
    return export.deserialize(bytearray(program))


def _compiled(exported: export.Exported, leaves: list[Any], options: dict) -> Any:
    """An exported program lowered and compiled for `leaves` with the XLA `options`."""
    with _lowering(exported):
        return jax.jit(exported.call, compiler_options=options).lower(*leaves).compile()


def _store(path: Path, program: bytes) -> None:
    """Write a serialized program after its SHA-256, whole (a partial file renamed); skipped
    where it cannot be written."""
    partial = path.with_name(f"{path.name}.{os.getpid()}.partial")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        partial.write_bytes(hashlib.sha256(program).digest() + program)
        os.replace(partial, path)
    except OSError:
        with contextlib.suppress(OSError):
            partial.unlink(missing_ok=True)


def _discard(path: Path, error: Exception) -> None:
    """Remove a stored program that failed, with one warning line saying why."""
    with contextlib.suppress(OSError):
        path.unlink(missing_ok=True)
    reason = str(error).strip().splitlines()[0] if str(error).strip() else type(error).__name__
    warnings.warn(f"stored program {path.name} discarded and traced anew: {reason}", StoredProgramWarning, stacklevel=4)


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
