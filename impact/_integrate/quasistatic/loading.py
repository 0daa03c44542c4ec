"""What a quasi-static test is given and returns: the loading, its numerics, the outcome."""

from dataclasses import dataclass, field

import equinox as eqx
import jax

from ..._law.base import AbstractContactLaw
from ..._law.branches import Tabulation
from ...profiles import Profile

# March modes.
FREE, HOLD, RIDE, CASCADE = 0, 1, 2, 3

# Events along the curve, in the order of their codes.


EVENT_KINDS = ("touch", "snap_in", "snap_out", "pull_off", "reversal")
EVENT = {kind: code for code, kind in enumerate(EVENT_KINDS)}

BISECTION_STEPS = 100  # on a monotone interval: the root to the last bit
SAME_RADIUS = 1e-9  # a cascade that moves the radius less than this (relative) is no jump
TOP_MARGIN = 1.25  # the branches reach this far beyond the largest radius of the program
OCTAVES = (-12, 120)  # radii 2^(k/4) searched for that radius (scaled)
SCALE_DECADES = 100.0
SCALE_STEPS = 128  # log-bisection steps over the 200 decades


class Loading(eqx.Module):
    """SI parameters of one quasi-static test (traced: new values do not recompile)."""

    profile: Profile
    E_star: jax.Array  # Pa
    law: (
        AbstractContactLaw  # the contact law and its parameters (adhesion unused unless `QuasiStaticNumerics.adhesive`)
    )
    force_control: jax.Array  # bool: the program is in N (force) or m (displacement)
    directions: jax.Array  # [L] +1 load, −1 unload (padded: see `legs`)
    targets: jax.Array  # [L] where each leg ends (N or m); −inf: unload to pull-off
    legs: jax.Array  # legs of the program (≤ L): padding lets programs share a compilation
    peak: jax.Array  # largest target (N or m), sets the extent of the branch tables
    spring_length: jax.Array  # radius covered by a spring array (m); nan: the default
    spring_count: jax.Array  # springs of the array (≤ the capacity `QuasiStaticNumerics.springs`)


@dataclass(frozen=True)
class QuasiStaticNumerics:
    """Static choices (changing them recompiles)."""

    adhesive: bool
    springs: int | None = None  # capacity of the spring array (None: continuum law)
    hysteresis: bool = False  # Maugis–Dugdale with approach hysteresis, Δγa < Δγ (`_law.dugdale_hysteresis`)
    tabulation: Tabulation = field(default_factory=Tabulation)  # turning points per edge function and their search
    samples: int = 33  # points per piece of an edge ridden
    steps_per_leg: int = 0  # 0: from the branch size (continuum) or 4N + 64 (springs)

    def steps(self, legs: int) -> int:
        if self.steps_per_leg:
            return legs * self.steps_per_leg
        if self.springs is not None:
            return legs * (4 * self.springs + 64)
        return legs * (8 * (self.tabulation.max_turns + 2) + 32)


class QuasiStaticOutcome(eqx.Module):
    """Scaled result of a march."""

    status: jax.Array
    pull_off: jax.Array  # [3] a, d, F of the last stable state before the contact is lost (nan: none)
    rows: jax.Array  # [R, 4] a, d, F, leg (nan where unused)
    events: jax.Array  # [E, 2] row index, kind (−1 where unused)
    steps: jax.Array
    top: jax.Array  # radius the branch tables reach
