"""Timing: the best of a few repeats (the machine is shared and noisy), and ahead-of-time
compilation timed on its own."""

import time
from collections.abc import Callable

import jax

from .._core.runtime import compiler_options


def best_time(function: Callable, args: tuple, budget: float, repeats: int = 7, once: float = 1.0):
    """(best wall time in s, last result) of `function(*args)` with the result ready, repeated
    while within `budget` s (at least twice, unless one call takes more than `once` s)."""
    times: list[float] = []
    start, result = time.perf_counter(), None
    while len(times) < repeats:
        t0 = time.perf_counter()
        result = jax.block_until_ready(function(*args))
        times.append(time.perf_counter() - t0)
        if times[-1] > once or (len(times) >= 2 and time.perf_counter() - start > budget):
            break
    return min(times), result


def best_python_time(function: Callable, args: tuple, budget: float, repeats: int = 5):
    """(best wall time in s, last result) of a plain Python call `function(*args)`, repeated
    while within `budget` s (at least twice)."""
    times: list[float] = []
    start, result = time.perf_counter(), None
    while len(times) < repeats:
        t0 = time.perf_counter()
        result = function(*args)
        times.append(time.perf_counter() - t0)
        if len(times) >= 2 and time.perf_counter() - start > budget:
            break
    return min(times), result


def compile_ahead(function: Callable, *args):
    """(compiled executable of `jax.jit(function)` for `args`, with the options of impact's own
    programs; seconds to trace, lower and compile)."""
    start = time.perf_counter()
    compiled = jax.jit(function, compiler_options=compiler_options()).lower(*args).compile()
    return compiled, time.perf_counter() - start
