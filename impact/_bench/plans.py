"""What a benchmark run measures: the full and the quick plan, the reference constants."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

OUTPUTS = ("bench.h5", "work_precision.png", "table.md")

# The "micro" pair of the core tests: a 1 µm paraboloid on a stiff polymer.
RADIUS, E_STAR, WORK_OF_ADHESION, MASS = 1e-6, 1e9, 0.05, 1.0472e-14
CONE_ANGLE = 0.3  # slope angle (rad): f = r·tanθ, the power law n = 1, c = tanθ
POWER_N = 1.5
POWER_C = RADIUS ** (1.0 - POWER_N) / 2.0  # f = c·rⁿ through the paraboloid's f at r = R
TN_FACTORS = (1.001, 1.05, 2.0, 30.0)  # v0 / v_s of the Thornton–Ning cases
OTHER_FACTOR = 2.0  # v0 / v_s of the cone, power-law and attach-on-touch cases
BATCH_RANGE = (1.001, 30.0)  # v0 / v_s spanned by the batch

TARGETS = (1e-3, 1e-4, 1e-6, 1e-8, 1e-10)  # errors at which the costs are compared


@dataclass(frozen=True)
class Plan:
    """What one benchmark run measures."""

    solvers: tuple[str, ...]
    rtols: tuple[float, ...]
    groups: tuple[str, ...]  # case groups (one compile each): tn, cone, power, attach
    batch_size: int
    batch_budget: float  # s: a batch expected to take longer is skipped
    spring_counts: tuple[int, ...]
    cost_counts: tuple[int, ...]  # N at which time per spring event and memory are compared
    verlet_counts: tuple[int, ...]
    verlet_steps: tuple[float, ...]  # Δt in scaled time units
    scipy_methods: tuple[str, ...]
    scipy_rtols: tuple[float, ...]
    check_solve: tuple[float, ...]  # rtols at which `solve` itself (static tolerances) is timed
    timing_budget: float  # s spent repeating one timing
    passes: int  # sweeps over the settings, each timing anew (the best is kept: load spikes pass)


def _decades(start: float, stop: float, per_decade: float) -> tuple[float, ...]:
    count = int(round(abs(math.log10(stop) - math.log10(start)) * per_decade)) + 1
    exponents = np.linspace(math.log10(start), math.log10(stop), count)
    return tuple(float(10.0**x) for x in np.round(exponents, 6))


def _counts(low_exponent: float, high_exponent: float, per_decade: int) -> tuple[int, ...]:
    exponents = np.arange(low_exponent, high_exponent + 1e-9, 1.0 / per_decade)
    return tuple(int(n) for n in np.unique(np.round(10.0**exponents).astype(int)))


FULL = Plan(
    solvers=("tsit5", "dopri5", "dopri8", "kvaerno5"),
    rtols=_decades(1e-3, 1e-12, 1),
    groups=("tn", "cone", "power", "attach"),
    batch_size=1000,
    batch_budget=20.0,
    spring_counts=_counts(2, 6, 4),
    cost_counts=(10, 1_000_000),
    verlet_counts=(1000, 10_000, 100_000),
    verlet_steps=_decades(1e-2, 1e-5, 4),
    scipy_methods=("RK45", "DOP853"),
    scipy_rtols=_decades(1e-3, 1e-12, 1),
    check_solve=(1e-8,),
    timing_budget=0.1,
    passes=3,
)

QUICK = Plan(
    solvers=("tsit5",),
    rtols=_decades(1e-3, 1e-11, 0.5),
    groups=("tn",),
    batch_size=1000,
    batch_budget=5.0,
    spring_counts=_counts(2, 4.5, 4),
    cost_counts=(10, 1_000_000),
    verlet_counts=(1000,),
    verlet_steps=_decades(1e-2, 1e-4, 2),
    scipy_methods=("RK45", "DOP853"),
    scipy_rtols=(1e-3, 1e-6, 1e-9),
    check_solve=(),
    timing_budget=0.05,
    passes=2,
)
