"""How a process runs impact's JAX code: float64, XLA:CPU compiling small loops whole, and the
persistent compilation cache (`impact._core.cache`).

`configure()` is called by the CLI entry point and the tests' conftest, not at import (it
changes process-wide settings); call it first in scripts that use the Python API.
"""

import functools
import importlib.util
import os
import platform
from collections.abc import Callable
from importlib import metadata
from pathlib import Path
from typing import ParamSpec, TypeVar

import jax
import numpy as np

from .cache import cache_directory, use_cache
from .package import __version__

# XLA:CPU runs a while-loop whose body exceeds 1 kB op by op; the spring arrays' event and
# Verlet loops (the law evaluated inside) are a few kB: compiled whole they run many times faster.
SMALL_LOOP_OPTION = "xla_cpu_small_while_loop_byte_threshold=65536"

# A point's result must be bitwise the same alone or at any place of a batch of any size. XLA:CPU
# vectorises the loops over a vmapped batch; where it contracts multiply–adds into fused ones
# (FMA), it does so differently in the vector loop, its scalar remainder, a loop compiled whole
# and one run op by op, so that lanes rounded by their place (Thornton–Ning restitutions a few
# ulps apart; Maugis–Dugdale's, amplified on its DMT side, by far more, with other solver steps).
# Without FMA, vector and scalar code run the same IEEE operations: `configure()` caps
# XLA:CPU at AVX (no FMA) on x86-64, and every lane then keeps its vectors. A process started
# otherwise (FMA available) compiles with float64 vectors of one element: every lane runs the
# same scalar code, which is slower. Other backends ignore the option.
NO_FMA_FLAG = "--xla_cpu_max_isa=AVX"
SCALAR_LANES = {"xla_cpu_prefer_vector_width": 64}

# XLA:CPU's fusion emitters (its default) take markedly longer to compile a program than its
# elemental emitters, and the program runs at most a few per cent faster (the figures are in
# docs/src/accuracy.md, "Compiling with XLA's elemental emitters"). `configure()` makes the
# elemental emitters the process's default, for every program: a sweep's batch and a scene's run
# compile the same way.
ELEMENTAL_EMITTERS_FLAG = "--xla_cpu_use_fusion_emitters=false"

# A program that runs once (a scene's solve, an indentation test's march) compiles with XLA:CPU's
# backend (LLVM) optimization level 0: it compiles much faster, and the results stay bitwise the
# same, as XLA:CPU compiles without fast-math at any level and, without FMA (`NO_FMA_FLAG`),
# contracts nothing; its code runs slower, which a single run hardly notices. A sweep's batch and a
# fit's programs, which run many times, and the viscoelastic half-space's solve, whose run is long,
# keep the default level (docs/src/accuracy.md, "Compiling a run quickly").
RUN_ONCE = {"xla_backend_optimization_level": 0}


@functools.cache
def contracts_multiply_adds() -> bool:
    """Whether this process's XLA:CPU fuses a·b + c into one rounding (FMA): with a = 1 + 2⁻³⁰
    and b = 1 − 2⁻³⁰, a·b = 1 − 2⁻⁶⁰ rounds to 1, so a·b − 1 is 0 unfused and −2⁻⁶⁰ fused.
    Probed on the CPU, also where the default device is a GPU."""
    with jax.enable_x64(True):
        values = (np.float64(1 + 2**-30), np.float64(1 - 2**-30), np.float64(-1.0))  # copied: no program
        a, b, c = jax.device_put(values, jax.local_devices(backend="cpu")[0])
        return float(jax.jit(lambda a, b, c: a * b + c)(a, b, c)) != 0.0


def compiler_options(platform: str | None = None, *, once: bool = False) -> dict[str, int | bool]:
    """XLA options of a compiled impact program: scalar lanes where this process fuses
    multiply–adds (see `NO_FMA_FLAG`), else for a program that runs once (`once`) the quick
    compile of `RUN_ONCE`. `platform`: that of the devices the program runs on ("cpu", "gpu", ...;
    default: JAX's default backend), e.g. a sweep's batch given CPU devices on a machine whose
    default device is a GPU."""
    if (platform or jax.default_backend()) != "cpu":
        return {}  # XLA:CPU's options: a GPU's compiler refuses them ("No such compile option")
    if contracts_multiply_adds():
        return dict(SCALAR_LANES)
    return dict(RUN_ONCE) if once else {}


def _accelerator_plugins() -> bool:
    """Whether a GPU/TPU plugin of jax is installed (the CPU option is then not added): the
    `jax_plugins` namespace its PJRT part installs (jax-cuda*, jax-rocm*), or libtpu. Looked up
    by module name: reading every installed distribution's metadata would slow every start."""
    return any(importlib.util.find_spec(name) is not None for name in ("jax_plugins", "libtpu"))


def configure(cache_dir: str | os.PathLike[str] | None = None, *, cache: bool = True) -> Path | None:
    """Enable float64; on a CPU-only install, before the backend starts and unless XLA_FLAGS
    already sets them, let XLA:CPU compile loops of up to 64 kB into one kernel, compile with its
    elemental emitters (`ELEMENTAL_EMITTERS_FLAG`: faster to compile) and, on x86-64, generate
    code without fused multiply–adds (`NO_FMA_FLAG`: batches keep their vectors); and store
    compiled programs on disk, so that a later process loads them instead of compiling.

    The cache lives in `cache_dir`, else in $IMPACT_CACHE_DIR, else in the per-user cache
    directory (`platformdirs.user_cache_dir("impact")/jax`); `cache=False` or
    IMPACT_CACHE_DIR=off switches it off. A directory that cannot be written is skipped with a
    RuntimeWarning. Returns the cache directory in use (None: no cache)."""
    jax.config.update("jax_enable_x64", True)
    if not _accelerator_plugins():
        flags = os.environ.get("XLA_FLAGS", "")
        if "xla_backend_extra_options" not in flags:
            flags = f"{flags} --xla_backend_extra_options={SMALL_LOOP_OPTION}"
        if "xla_cpu_use_fusion_emitters" not in flags:
            flags = f"{flags} {ELEMENTAL_EMITTERS_FLAG}"
        if "xla_cpu_max_isa" not in flags and platform.machine().lower() in ("x86_64", "amd64"):
            flags = f"{flags} {NO_FMA_FLAG}"
        os.environ["XLA_FLAGS"] = flags.strip()
    return use_cache(cache_directory(cache_dir, cache=cache))


def provenance() -> dict[str, str | bool]:
    """What produced a result in this process: the versions of impact, jax and diffrax, and
    whether JAX's 64-bit mode is on process-wide (the keys are the attributes of a stored file)."""
    return {
        "impact_version": __version__,
        "jax_version": jax.__version__,
        "diffrax_version": metadata.version("diffrax"),  # not imported where a run needs none
        "x64": bool(jax.config.read("jax_enable_x64")),
    }


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
