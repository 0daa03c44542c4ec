"""Values whose derivatives the plain formula gets wrong: a square root at zero, and a root
found by bisection (whose iterations carry no derivative of the root).

Both leave the value exactly as the plain formula computes it: only the derivative changes.
"""

import functools
from collections.abc import Callable

import jax
import jax.numpy as jnp
from jaxtyping import Array, ArrayLike


def sqrt(x: ArrayLike) -> Array:
    """√x, with the derivative 0 (not nan) at x = 0, where a root of zero stays zero (a spring
    at the axis, no approach adhesion); nan for x < 0 as `jnp.sqrt`."""
    x = jnp.asarray(x)
    positive = x > 0.0
    return jnp.where(positive, jnp.sqrt(jnp.where(positive, x, 1.0)), jnp.where(x < 0.0, jnp.nan, 0.0))


def implicit_root(function: Callable[[Array], Array], root: ArrayLike) -> Array:
    """`root` (found by any search: bisection, golden sections) of the elementwise `function`,
    differentiated by the implicit function theorem: dx = −(∂f/∂θ)·dθ / f'(x).

    `function` may close over the traced values it depends on. The value is `root` as given.
    `function` is traced once, to a program whose derivatives are taken only where the root is
    differentiated (`jax.lax.custom_root` would trace it, its linearization and the tangent
    solve at every call)."""
    found = jax.lax.stop_gradient(jnp.asarray(root))
    converted, parameters = jax.closure_convert(function, found)
    return _implicit(converted, found, *parameters)


@functools.partial(jax.custom_jvp, nondiff_argnums=(0,))
def _implicit(function, root, *parameters):
    """`root` of `function(x, *parameters)`, given; its derivative in `_implicit_tangent`."""
    return root


@_implicit.defjvp
def _implicit_tangent(function, primals, tangents):
    """dx = −(∂f/∂θ·dθ) / f'(x) at the root x (the root's own tangent is not used: it is found);
    the root there is `_implicit` again, so that a derivative of this one is the implicit one."""
    root, *parameters = primals
    _, *parameter_tangents = tangents
    root = _implicit(function, root, *parameters)
    _, change = jax.jvp(lambda *values: function(root, *values), parameters, parameter_tangents)
    _, slope = jax.jvp(lambda x: function(x, *parameters), (root,), (jnp.ones_like(root),))
    return root, -(change / slope)
