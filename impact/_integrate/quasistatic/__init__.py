"""Quasi-static indentation (scene kind `indentation`): a march along the MDR branches.

A slow test under force or displacement control has no dynamics: every state is an
equilibrium (a, d, F) of the same MDR law as the impacts, F = 2E*(a·d − G(a)) (3.28), with the
same hysteretic rules as `transitions`: a spring at x attaches once d ≥ h_a(x) = g(x) − λa√x,
the edge spring lets go once d ≤ h_d(a) = g(a) − λ√a (3.26). So the contact radius moves along
the attach edge while loading, holds between the edges, and recedes along the detach edge while
unloading; where an edge turns, the radius jumps at constant d to the next crossing of the
level d, on the same branches (`Branch`) and with the same segment choice as
`Branch.cascade_out`/`cascade_in` and `transitions.advance_from`/`recede_from` (wall, unbounded
growth). The cascade is written out here so that each step of the march solves a single
bisection (a ride's crossing, or where a cascade stops): that halves the compile time.

The control decides stability (3.35). Under displacement control the march runs in d and every
jump is a cascade at constant d: the contact is lost where h_d has its minimum on the path,
g'(a) = Δl'(a) (ξ = 1, (3.30)). Under force control the march runs in F; along an edge
F(a) = 2(a·h(a) − G(a)) has F'(a) = 2a·(g' − 3λ/(2√a)), so its extrema are the turning points
of the edge function with the coefficient 3λ (ξ = 3, (3.34)). At a force extremum the state
jumps at that constant force: it follows the attach (detach) path onward until the force is
met again (a landing: another stable branch, possibly across cascades), or off the surface.
Both are the same walk: intervals between the turning points of h (coefficient λ) and of the
ξ = 3 edge (coefficient 3λ), on which both d and F are monotone in a, so every crossing is a
bracketed root.

Units are those of `scales` (lengths in the jump-in radius and its Heß length); the pull-off
(the last stable state before the contact is lost) and the curve (a, d, F) in program order
come back in SI. The spring array (midpoint springs, thresholds and prefix sums of
`TabulatedSpringArray`) is marched event by event with the same rules.
"""

from .loading import EVENT_KINDS, Loading, QuasiStaticNumerics, QuasiStaticOutcome
from .march import finite_range_curve, finite_range_law, march
from .setup import build

__all__ = [
    "EVENT_KINDS",
    "Loading",
    "QuasiStaticNumerics",
    "QuasiStaticOutcome",
    "build",
    "finite_range_curve",
    "finite_range_law",
    "march",
]
