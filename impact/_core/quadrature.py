"""Gauss–Legendre quadrature rules, and sums whose order does not depend on the batch."""

import jax
import jax.numpy as jnp
import numpy as np
from jaxtyping import Array, Float


def gauss_legendre(nodes: int) -> tuple[Float[Array, " nodes"], Float[Array, " nodes"]]:
    """Nodes and weights of the `nodes`-point Gauss–Legendre rule on [0, 1]."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    return jnp.asarray(0.5 * (x + 1.0)), jnp.asarray(0.5 * w)


def ordered_sum(terms: jax.Array) -> jax.Array:
    """Σ over the last axis, added first to last, one elementwise add per term.

    `jnp.sum` is a reduce whose order XLA:CPU picks by the shape of the whole operand: under
    vmap, the rows of a batch of 100 or more points were added in another order than those of
    a batch of 60 (a quadrature of 48 nodes: the last bit of most rows). Chains of adds keep
    each point's sum, and so a sweep's results, the same in any batch."""
    total = terms[..., 0]
    for index in range(1, terms.shape[-1]):
        total = total + terms[..., index]
    return total
