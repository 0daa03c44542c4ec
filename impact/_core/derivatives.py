"""Values whose derivatives the plain formula gets wrong: a square root at zero, and a root
found by bisection (whose iterations carry no derivative of the root).

Both leave the value exactly as the plain formula computes it: only the derivative changes.
"""

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

    `function` may close over the traced values it depends on. The value is `root` as given."""
    found = jax.lax.stop_gradient(jnp.asarray(root))
    return jax.lax.custom_root(
        function,
        found,
        lambda _, __: found,
        lambda linear, rhs: rhs / linear(jnp.ones_like(rhs)),
    )
