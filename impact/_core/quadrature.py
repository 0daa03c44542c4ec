"""Gauss–Legendre quadrature rules."""

import jax.numpy as jnp
import numpy as np
from jaxtyping import Array, Float


def gauss_legendre(nodes: int) -> tuple[Float[Array, " nodes"], Float[Array, " nodes"]]:
    """Nodes and weights of the `nodes`-point Gauss–Legendre rule on [0, 1]."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    return jnp.asarray(0.5 * (x + 1.0)), jnp.asarray(0.5 * w)
