"""A body's MDR profile g(a) and its integral G(a) sampled along the contact radius, for the
closed-form curves that figures draw under a run's path."""

import jax.numpy as jnp
import numpy as np

from .._core.concrete import evaluate
from ..profiles import Profile


def profile_along_radius(profile: Profile, largest_radius: float, points: int) -> tuple[np.ndarray, ...]:
    """(a, g(a), G(a)) in SI at `points` radii from 0 to `largest_radius` (m), at most the
    profile's extent; computed as one compiled program."""
    fractions = np.linspace(0.0, 1.0, points)
    return tuple(np.asarray(values) for values in evaluate(_sampled, profile, largest_radius, fractions))


def _sampled(profile: Profile, largest_radius, fractions):
    radius = jnp.minimum(largest_radius, profile.extent()) * fractions
    return radius, profile.g(radius), profile.G(radius)
