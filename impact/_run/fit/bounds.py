"""Bounds by reparameterisation: the search moves freely in u, each parameter is a smooth map of
its u onto its allowed interval (Levenberg–Marquardt itself knows no bounds).

On scale log the map acts on q = ln p (so p > 0 always), on scale linear on q = p:
  both bounds   q = q_min + (q_max − q_min)·σ(u), σ the logistic function;
  a lower bound q = q_min + w·eᵘ;   an upper bound q = q_max − w·eᵘ;   none  q = q₀ + w·u,
with w = 1 on scale log and w = |start| (1 for a start at 0) on scale linear, so that a unit
step in u is a change of order the value itself.
"""

import math
from collections.abc import Mapping
from dataclasses import dataclass

import jax
import jax.numpy as jnp
import numpy as np

from ..._scene.fit_spec import ParameterSpec


@dataclass(frozen=True)
class Bound:
    """The map u → p of one parameter."""

    log: bool
    low: float  # q_min, -inf for none
    high: float  # q_max, +inf for none
    origin: float  # q at u = 0 of an unbounded parameter
    width: float

    @classmethod
    def of(cls, spec: ParameterSpec) -> "Bound":
        log = spec.scale == "log"
        to_q = math.log if log else float
        low = -math.inf if spec.min is None or (log and spec.min <= 0) else to_q(spec.min)
        high = math.inf if spec.max is None else to_q(spec.max)
        width = 1.0 if log else (abs(spec.start) or 1.0)
        return cls(log, low, high, to_q(spec.start), width)

    def physical(self, u):
        """p of u."""
        if math.isfinite(self.low) and math.isfinite(self.high):
            q = self.low + (self.high - self.low) * jax.nn.sigmoid(u)
        elif math.isfinite(self.low):
            q = self.low + self.width * jnp.exp(u)
        elif math.isfinite(self.high):
            q = self.high - self.width * jnp.exp(u)
        else:
            q = self.origin + self.width * u
        return jnp.exp(q) if self.log else q

    def internal(self, p: float) -> float:
        """u of p (p strictly inside the bounds)."""
        q = math.log(p) if self.log else p
        if math.isfinite(self.low) and math.isfinite(self.high):
            x = (q - self.low) / (self.high - self.low)
            return math.log(x / (1.0 - x))
        if math.isfinite(self.low):
            return math.log((q - self.low) / self.width)
        if math.isfinite(self.high):
            return math.log((self.high - q) / self.width)
        return (q - self.origin) / self.width


@dataclass(frozen=True)
class Bounds:
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
