"""Gravity: a constant pull towards the surface; free flight between contacts is analytic."""

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.types import Parameter
from .._law.scales import Scales


class Gravity(eqx.Module):
    """Gravitational acceleration towards the surface (m/s², traced)."""

    acceleration: Parameter

    @staticmethod
    def none() -> "Gravity":
        """No gravity (the effect switched off)."""
        return Gravity(jnp.zeros(()))

    def touch_velocity(self, velocity, gap) -> jax.Array:
        """Speed (m/s) at the first touch after falling over `gap` (m) from speed `velocity`."""
        return jnp.sqrt(velocity**2 + 2.0 * self.acceleration * gap)

    def scaled(self, scales: Scales) -> Parameter:
        """The acceleration in the units of `scales`."""
        return self.acceleration * scales.time**2 / scales.normal


def flight_to_touch(gravity, indentation, velocity):
    """Analytic flight from d ≤ 0 to the touch at d = 0 under the scaled acceleration `gravity`
    (0 without gravity): (duration, touch speed, reaches).

    Without gravity the body reaches the surface only if it moves towards it.
    """
    speed_at_touch = jnp.sqrt(jnp.maximum(velocity**2 - 2.0 * gravity * indentation, 0.0))
    falling = gravity > 0.0
    closing = velocity + speed_at_touch
    safe_gravity = jnp.where(falling, gravity, 1.0)
    duration_falling = jnp.where(
        velocity < 0.0,
        (speed_at_touch - velocity) / safe_gravity,
        -2.0 * indentation / jnp.where(closing > 0.0, closing, 1.0),
    )
    duration_free = -indentation / jnp.where(velocity > 0.0, velocity, 1.0)
    duration = jnp.where(falling, duration_falling, duration_free)
    reaches = falling | (velocity > 0.0)
    return duration, jnp.where(falling, speed_at_touch, velocity), reaches
