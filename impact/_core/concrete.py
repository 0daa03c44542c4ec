"""Concrete values (a scene's numbers, a figure's curve) into JAX without a program per operation.

Called on concrete values, each jax.numpy operation compiles a program of its own (the first
time its operation, shapes and dtypes occur in a process), `jnp.asarray` of a NumPy array or
scalar included: a closed form of a dozen operations compiles a dozen programs. `evaluate`
compiles the whole function once instead, quickly (`runtime.RUN_ONCE`), and JAX's persistent
cache keeps it for later processes; `on_device` copies NumPy values to JAX arrays, compiling
nothing.
"""

import functools
from collections.abc import Callable
from typing import Any

import jax
import numpy as np

from .runtime import compiler_options, float64


@float64
def evaluate(function: Callable[..., Any], *arguments: Any) -> Any:
    """`function(*arguments)` in float64, compiled as one program; `arguments` are pytrees of
    arrays and numbers (all traced), the value a pytree of JAX arrays."""
    return _compiled(function)(*arguments)


@functools.cache
def _compiled(function: Callable[..., Any]) -> Callable[..., Any]:
    """`function` jitted once per process with the options of a program that runs once."""
    return jax.jit(function, compiler_options=compiler_options(once=True))


def on_device(tree: Any) -> Any:
    """`tree` with its NumPy arrays and scalars copied into JAX arrays of the same dtypes
    (`jax.device_put`); its other leaves as they are."""
    return jax.tree.map(lambda leaf: jax.device_put(leaf) if isinstance(leaf, np.ndarray | np.generic) else leaf, tree)
