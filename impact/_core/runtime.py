"""How a process runs impact's JAX code: float64, XLA:CPU compiling small loops whole, and the
persistent compilation cache (`impact._core.cache`).

`configure()` is called by the CLI entry point and the tests' conftest, not at import (it
changes process-wide settings); call it first in scripts that use the Python API.
"""

import functools
import importlib.util
import os
from collections.abc import Callable
from pathlib import Path
from typing import ParamSpec, TypeVar

import jax

from .cache import cache_directory, use_cache

# XLA:CPU runs a while-loop whose body exceeds 1 kB op by op; the spring arrays' event and
# Verlet loops (the law evaluated inside) are a few kB: compiled whole they run 10× faster.
SMALL_LOOP_OPTION = "xla_cpu_small_while_loop_byte_threshold=65536"

# Options of every compiled impact program, whatever the process settings: a point's result is
# bitwise the same alone or at any place of a batch of any size. XLA:CPU vectorises the loops over
# a vmapped batch, and lanes in SIMD registers round differently from lanes in the scalar
# remainder (measured: Thornton–Ning restitutions a few ulps apart, Maugis–Dugdale's up to 4e-7
# with 20 solver steps more or fewer). With float64 vectors of one element every lane runs the
# same scalar code. Other backends ignore the option.
COMPILER_OPTIONS = {"xla_cpu_prefer_vector_width": 64}


def _accelerator_plugins() -> bool:
    """Whether a GPU/TPU plugin of jax is installed (the CPU option is then not added): the
    `jax_plugins` namespace its PJRT part installs (jax-cuda*, jax-rocm*), or libtpu. Looked up
    by module name: reading every installed distribution's metadata took 0.1–0.2 s a process."""
    return any(importlib.util.find_spec(name) is not None for name in ("jax_plugins", "libtpu"))


def configure(cache_dir: str | os.PathLike[str] | None = None, *, cache: bool = True) -> Path | None:
    """Enable float64; on a CPU-only install, before the backend starts and unless XLA_FLAGS
    already sets backend options, let XLA:CPU compile loops of up to 64 kB into one kernel; and
    store compiled programs on disk, so that a later process loads them instead of compiling.

    The cache lives in `cache_dir`, else in $IMPACT_CACHE_DIR, else in the per-user cache
    directory (`platformdirs.user_cache_dir("impact")/jax`); `cache=False` or
    IMPACT_CACHE_DIR=off switches it off. A directory that cannot be written is skipped with a
    RuntimeWarning. Returns the cache directory in use (None: no cache)."""
    jax.config.update("jax_enable_x64", True)
    flags = os.environ.get("XLA_FLAGS", "")
    if "xla_backend_extra_options" not in flags and not _accelerator_plugins():
        os.environ["XLA_FLAGS"] = f"{flags} --xla_backend_extra_options={SMALL_LOOP_OPTION}".strip()
    return use_cache(cache_directory(cache_dir, cache=cache))


Arguments = ParamSpec("Arguments")
Returned = TypeVar("Returned")


def float64(function: Callable[Arguments, Returned]) -> Callable[Arguments, Returned]:
    """Run `function` with JAX's 64-bit mode on, whatever the process-wide flag says: the
    physics is float64 (in float32 the scaled problem under- and overflows), and a caller who
    never called `configure()` gets the same answer as one who did."""

    @functools.wraps(function)
    def in_float64(*args: Arguments.args, **kwargs: Arguments.kwargs) -> Returned:
        with jax.enable_x64(True):
            return function(*args, **kwargs)

    return in_float64
