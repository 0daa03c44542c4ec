"""Bounds by reparameterisation: the search moves freely in u, each parameter is a smooth map of
its u onto its allowed interval (Levenberg–Marquardt itself knows no bounds).

On scale log the map acts on q = ln p (so p > 0 always), on scale linear on q = p:
  both bounds   q = q_min + (q_max − q_min)·σ(u), σ the logistic function;
  a lower bound q = q_min + w·eᵘ;   an upper bound q = q_max − w·eᵘ;   none  q = q₀ + w·u,
with w = 1 on scale log and w = |start| (1 for a start at 0) on scale linear, so that a unit
step in u is a change of order the value itself. Which map applies is static; the numbers are
traced (a fit from another start compiles nothing).
"""

import math
from collections.abc import Mapping

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np

from ..._scene.fit_spec import ParameterSpec


class Bound(eqx.Module):
    """The map u → p of one parameter."""

    log: bool = eqx.field(static=True)
    sides: tuple[bool, bool] = eqx.field(static=True)  # (a lower bound, an upper bound)
    low: jax.Array  # q_min (0 where none)
    high: jax.Array  # q_max (0 where none)
    origin: jax.Array  # q at u = 0 of an unbounded parameter
    width: jax.Array

    @classmethod
    def of(cls, spec: ParameterSpec) -> "Bound":
        log = spec.scale == "log"
        to_q = math.log if log else float
        sides = (spec.min is not None and not (log and spec.min <= 0), spec.max is not None)
        low = to_q(spec.min) if sides[0] and spec.min is not None else 0.0
        high = to_q(spec.max) if sides[1] and spec.max is not None else 0.0
        width = 1.0 if log else (abs(spec.start) or 1.0)
        numbers = (jnp.asarray(value, jnp.float64) for value in (low, high, to_q(spec.start), width))
        return cls(log, sides, *numbers)

    def physical(self, u):
        """p of u."""
        if self.sides == (True, True):
            q = self.low + (self.high - self.low) * jax.nn.sigmoid(u)
        elif self.sides[0]:
            q = self.low + self.width * jnp.exp(u)
        elif self.sides[1]:
            q = self.high - self.width * jnp.exp(u)
        else:
            q = self.origin + self.width * u
        return jnp.exp(q) if self.log else q

    def internal(self, p: float) -> float:
        """u of p (p strictly inside the bounds)."""
        q = math.log(p) if self.log else p
        low, high, origin, width = (float(value) for value in (self.low, self.high, self.origin, self.width))
        if self.sides == (True, True):
            x = (q - low) / (high - low)
            return math.log(x / (1.0 - x))
        if self.sides[0]:
            return math.log((q - low) / width)
        if self.sides[1]:
            return math.log((high - q) / width)
        return (q - origin) / width


class Bounds(eqx.Module):
    """The maps of every fitted parameter, in the order of the fit."""

    maps: tuple[Bound, ...]

    @classmethod
    def of(cls, parameters: Mapping[str, ParameterSpec]) -> "Bounds":
        return cls(tuple(Bound.of(spec) for spec in parameters.values()))

    def physical(self, u):
        """The parameters [p] of the search variables u [p]."""
        return jnp.stack([bound.physical(u[index]) for index, bound in enumerate(self.maps)])

    def internal(self, p) -> np.ndarray:
        return np.array([bound.internal(float(value)) for bound, value in zip(self.maps, p, strict=True)])
