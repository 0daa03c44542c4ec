"""Reading errors of a convergence study: the round-off floor and the reliable envelope."""

import numpy as np

# Errors below this are round-off: they are drawn at it and left out of fits.
ERROR_FLOOR = 1e-15


def reliable(errors) -> np.ndarray:
    """Errors of settings ordered from loose to tight, raised to the worst of every tighter
    setting: a setting reaches ε reliably when it and all tighter ones do (errors that zigzag,
    like Verlet's over Δt or the array's over N, are not credited with a lucky point)."""
    errors = np.where(np.isnan(np.asarray(errors, float)), np.inf, np.asarray(errors, float))
    return np.maximum.accumulate(errors[::-1])[::-1]
