"""How a computation runs over the lanes of a batch (`jax.vmap`) on XLA:CPU: values stored once
where XLA would compute them again in each consumer, and work done only where a lane needs it."""

from collections.abc import Callable
from typing import Any

import jax
import jax.numpy as jnp


def computed_once(function: Callable[[jax.Array], Any], points: jax.Array) -> Any:
    """`function` at `points` ([rows, …]), a row at a time (`jax.lax.map`): each value computed
    and stored once. Elementwise work evaluated at once is fused by XLA:CPU into every consumer
    of its values that reads more than one of them (a prefix sum, a cumulative extreme, a
    gather), and computed there again: for a curve's states, several times over."""
    return jax.lax.map(function, points)


def only_where(needed: jax.Array, compute: Callable[[], Any], otherwise: Any) -> Any:
    """`compute()` where `needed`, `otherwise` elsewhere; not computed at all where no lane of a
    batch needs it. A loop of at most one turn: under `jax.vmap` a loop turns while any lane's
    condition holds, each lane keeping its own state, where a `jax.lax.cond` computes both
    branches in every lane."""
    return jax.lax.while_loop(lambda state: state[0], lambda _: (jnp.asarray(False), compute()), (needed, otherwise))[1]
