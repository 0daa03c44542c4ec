"""Event location: bisection on the bracket of the step where an event condition crossed."""

from collections.abc import Callable
from typing import Any, ClassVar

import jax.numpy as jnp
import optimistix as optx


class BracketBisection(optx.AbstractRootFinder):
    """Bisection that stops when the bracket is narrow, whatever the residual.

    `optimistix.Bisection` also asks for |f| < atol, which round-off can forbid once the
    condition's slope is large; diffrax passes the crossing step's ends as `lower`/`upper`.
    """

    rtol: float
    atol: float
    norm: ClassVar[Callable] = jnp.abs

    @property
    def _inner(self) -> optx.Bisection:
        # Event conditions cross upwards (direction=True): negative at the bracket's lower end.
        # flip=False also skips optimistix's runtime check, which fails a whole vmapped batch.
        return optx.Bisection(rtol=self.rtol, atol=self.atol, flip=False)

    def init(self, fn, y, args, options, f_struct, aux_struct, tags):
        return self._inner.init(fn, y, args, options, f_struct, aux_struct, tags)

    def step(self, fn, y, args, options, state, tags):
        return self._inner.step(fn, y, args, options, state, tags)

    def terminate(self, fn, y, args, options, state, tags):
        narrow = jnp.abs(state.lower - state.upper) < self.atol + self.rtol * jnp.abs(y)
        return narrow, optx.RESULTS.successful

    def postprocess(self, fn, y, aux, args, options, state, tags, result) -> tuple[Any, Any, dict]:
        return y, aux, {}
