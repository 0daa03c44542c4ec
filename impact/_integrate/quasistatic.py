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
`springs.SpringArray`) is marched event by event with the same rules.
"""

import dataclasses
from dataclasses import dataclass

import equinox as eqx
import jax
import jax.numpy as jnp

from .._law.branches import build_branch
from .._law.law import ContactLaw
from .codes import RESULT_CODE
from ..profiles import Profile
from .._law.scales import Scales
from .problem import Problem
from .springs import SpringArray

__all__ = [
    "Loading",
    "QuasiStaticNumerics",
    "QuasiStaticOutcome",
    "EVENT_KINDS",
    "build",
    "march",
]

# March modes.
FREE, HOLD, RIDE, CASCADE = 0, 1, 2, 3
# Events along the curve, in the order of their codes.
EVENT_KINDS = ("touch", "snap_in", "snap_out", "pull_off", "reversal")
_EVENT = {kind: code for code, kind in enumerate(EVENT_KINDS)}

_BISECTION_STEPS = 100  # on a monotone interval: the root to the last bit
_SAME_RADIUS = 1e-9  # a cascade that moves the radius less than this (relative) is no jump
_TOP_MARGIN = 1.25  # the branches reach this far beyond the largest radius of the program
_OCTAVES = (-12, 120)  # radii 2^(k/4) searched for that radius (scaled)
_SCALE_DECADES = 100.0
_SCALE_STEPS = 128  # log-bisection steps over the 200 decades


class Loading(eqx.Module):
    """SI parameters of one quasi-static test (traced: new values do not recompile)."""

    profile: Profile
    E_star: jax.Array  # Pa
    work_of_adhesion: jax.Array  # Δγ (J/m²)
    approach_work_of_adhesion: jax.Array  # Δγa ≤ Δγ (J/m²)
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
    max_turns: int = 4  # turning points per edge function
    turn_grid: int = 384  # search grid for them
    samples: int = 33  # points per piece of an edge ridden
    steps_per_leg: int = 0  # 0: from the branch size (continuum) or 4N + 64 (springs)

    def steps(self, legs: int) -> int:
        if self.steps_per_leg:
            return legs * self.steps_per_leg
        if self.springs is not None:
            return legs * (4 * self.springs + 64)
        return legs * (8 * (self.max_turns + 2) + 32)


class QuasiStaticOutcome(eqx.Module):
    """Scaled result of a march."""

    status: jax.Array
    pull_off: jax.Array  # [3] a, d, F of the last stable state before the contact is lost (nan: none)
    rows: jax.Array  # [R, 4] a, d, F, leg (nan where unused)
    events: jax.Array  # [E, 2] row index, kind (−1 where unused)
    steps: jax.Array
    top: jax.Array  # radius the branch tables reach


# ---------------------------------------------------------------- setup


def _log_bisect(excess, lower, upper, steps=_SCALE_STEPS):
    """Where `excess` changes sign between two radii, bisected in log x; nan without a change."""
    sign = jnp.sign(excess(lower))
    crosses = sign * jnp.sign(excess(upper)) < 0

    def step(_, bracket):
        lo, hi = bracket
        mid = 0.5 * (lo + hi)
        same = jnp.sign(excess(jnp.exp(mid))) == sign
        return jnp.where(same, mid, lo), jnp.where(same, hi, mid)

    lo, hi = jax.lax.fori_loop(0, steps, step, (jnp.log(lower), jnp.log(upper)))
    return jnp.where(crosses, jnp.exp(0.5 * (lo + hi)), jnp.nan)


def loading_scales(loading: Loading, adhesive: bool) -> Scales:
    """Units: the jump-in radius a0 (g(a0) = √(2πa0Δγ/E*)) and its Heß length, as for impacts
    (`scales.adhesive_scales`), or the wall radius of a walled body; else the radius where the
    non-adhesive law reaches the program's peak, and g there."""
    profile, E_star = loading.profile, loading.E_star
    reference = profile.radius_scale()
    walled = jnp.isfinite(profile.extent())
    lower = jnp.maximum(reference * 10.0**-_SCALE_DECADES, 1e-300)
    upper = jnp.minimum(profile.extent(), jnp.minimum(reference * 10.0**_SCALE_DECADES, 1e300))

    def hess(x):
        return jnp.sqrt(2.0 * jnp.pi * x * loading.work_of_adhesion / E_star)

    def reach(x):  # the non-adhesive indentation or force at radius x, less the peak
        g = profile.g(x)
        return jnp.where(loading.force_control, 2.0 * E_star * (x * g - profile.G(x)), g) - loading.peak

    if adhesive:
        # A jump-in radius: h = g − Δl rises through 0 from below (n > 1/2). Where h starts
        # positive (n < 1/2) its far zero is no scale of the contact.
        rises = profile.g(lower) < hess(lower)
        jump_in = jnp.where(rises, _log_bisect(lambda x: profile.g(x) - hess(x), lower, upper), jnp.nan)
        adhesive_radius = jnp.where(jnp.isfinite(jump_in), jump_in, jnp.where(walled, upper, jnp.nan))
    else:
        adhesive_radius = jnp.full((), jnp.nan)
    peak_radius = _log_bisect(reach, lower, upper)
    radial = jnp.where(jnp.isfinite(adhesive_radius), adhesive_radius,
                       jnp.where(jnp.isfinite(peak_radius), peak_radius, reference))
    length = jnp.where(jnp.isfinite(adhesive_radius), hess(radial), profile.g(radial))
    normal = jnp.where(length > 0, length, radial)
    return Scales(radial=radial, normal=normal, force=E_star * radial * normal, time=jnp.ones(()))


def _problem(law: ContactLaw, attach, detach) -> Problem:
    """A `Problem` holding the law and its two branches (the impact-only fields are zero)."""
    given = {"law": law, "attach": attach, "detach": detach}
    zero = jnp.zeros(())
    return Problem(**{f.name: given.get(f.name, zero) for f in dataclasses.fields(Problem) if f.init})


class Built(eqx.Module):
    """The scaled law, its branches (λ and 3λ for attach and detach) and the program."""

    problem: Problem
    attach3: object  # Branch of the ξ = 3 attach edge: extrema of the loading force
    detach3: object  # Branch of the ξ = 3 detach edge: extrema of the unloading force
    force_control: jax.Array
    directions: jax.Array
    targets: jax.Array  # scaled
    legs: jax.Array
    top: jax.Array
    bounded: jax.Array  # the program's peak is reached at a finite radius

    @property
    def law(self) -> ContactLaw:
        return self.problem.law


def build(loading: Loading, numerics: QuasiStaticNumerics) -> Built:
    """Scale the loading, find how far the contact can grow and build the four branches."""
    profile = loading.profile
    scales = loading_scales(loading, numerics.adhesive)
    if numerics.adhesive:
        detach_coefficient = jnp.sqrt(2.0 * jnp.pi * scales.radial * loading.work_of_adhesion / loading.E_star) / scales.normal
        attach_coefficient = detach_coefficient * jnp.sqrt(loading.approach_work_of_adhesion / loading.work_of_adhesion)
    else:
        detach_coefficient = attach_coefficient = jnp.zeros(())
    law = ContactLaw(profile, scales, detach_coefficient, attach_coefficient, numerics.adhesive)
    unit = jnp.where(loading.force_control, scales.force, scales.normal)
    targets = loading.targets / unit
    peak = loading.peak / unit

    # How far the contact grows: beyond the first radius after which the loading value (d or F
    # along the attach edge) stays above the peak. None such: the contact grows without limit.
    low, high = _OCTAVES
    grid = jnp.minimum(2.0 ** (jnp.arange(4 * low, 4 * high + 1) / 4.0), law.extent())
    value = _value(law, grid, attach_coefficient, loading.force_control)
    value = jnp.where(jnp.isnan(value), -jnp.inf, value)
    floor = jax.lax.cummin(value, reverse=True)
    above = floor > peak
    index = jnp.argmax(above)
    bounded = jnp.any(above) | jnp.isfinite(law.extent())
    top = jnp.minimum(law.extent(), jnp.where(jnp.any(above), _TOP_MARGIN * grid[index], grid[-1]))

    coefficients = jnp.stack([attach_coefficient, detach_coefficient, 3.0 * attach_coefficient, 3.0 * detach_coefficient])
    branches = jax.vmap(lambda c: build_branch(law, c, top, numerics.max_turns, numerics.turn_grid, 0))(coefficients)
    attach, detach, attach3, detach3 = (jax.tree.map(lambda leaf: leaf[i], branches) for i in range(4))
    return Built(
        problem=_problem(law, attach, detach),
        attach3=attach3,
        detach3=detach3,
        force_control=jnp.asarray(loading.force_control),
        directions=loading.directions,
        targets=targets,
        legs=loading.legs,
        top=top,
        bounded=bounded,
    )


def _value(law: ContactLaw, x, coefficient, force_control):
    """The controlled quantity along an edge d = h(x): d itself, or the force there."""
    h = law.edge(x, coefficient)
    return jnp.where(force_control, law.force(x, h), h)


def _root(law: ContactLaw, coefficient, force_control, target, lower, upper):
    """x in [lower, upper] where the (increasing) edge value meets the target, by bisection."""

    def step(_, bracket):
        lo, hi = bracket
        mid = 0.5 * (lo + hi)
        below = _value(law, mid, coefficient, force_control) < target
        return jnp.where(below, mid, lo), jnp.where(below, hi, mid)

    lo, hi = jax.lax.fori_loop(0, _BISECTION_STEPS, step, (lower, upper))
    return 0.5 * (lo + hi)


def _path(h_branch, f_branch, top, up: bool):
    """Turning points of h and of the ξ = 3 edge, merged and sorted, with a tag (0: h, 1: force).

    At equal radii the h nodes come first on the way out and last on the way in, so a march
    meets a turning point of h before it leaves it; nodes at the top are h nodes (the end)."""
    first, second = (h_branch.nodes, f_branch.nodes) if up else (f_branch.nodes, h_branch.nodes)
    tags = jnp.concatenate([jnp.zeros(first.shape, int), jnp.ones(second.shape, int)])
    if not up:
        tags = 1 - tags
    nodes = jnp.concatenate([first, second])
    order = jnp.argsort(nodes, stable=True)
    nodes, tags = nodes[order], tags[order]
    return nodes, jnp.where(nodes >= top, 0, tags)


# ---------------------------------------------------------------- the continuum march


class Carry(eqx.Module):
    leg: jax.Array
    direction: jax.Array  # +1 up (d or F increasing), −1 down
    target: jax.Array  # the leg's target, or the force of a landing
    landing: jax.Array  # a jump at constant force in progress (force control)
    mode: jax.Array
    wall: jax.Array  # held at the body's wall
    a: jax.Array
    d: jax.Array
    pre: jax.Array  # [2] a, d where the current instability began
    pull_off: jax.Array  # [3]
    status: jax.Array
    done: jax.Array
    steps: jax.Array
    rows: jax.Array
    count: jax.Array
    events: jax.Array
    event_count: jax.Array


class _Log:
    """Points and events of one step, written to the carry's buffers in one scatter each (every
    scatter is a separate kernel for XLA to compile)."""

    def __init__(self):
        self.points, self.events, self.size = [], [], 0

    def emit(self, a, d, F, keep, leg):
        """Points (a, d, F) of program leg `leg`, kept where `keep`."""
        a, d, F = (jnp.atleast_1d(v) for v in (a, d, F))
        leg = jnp.broadcast_to(jnp.asarray(leg, a.dtype), a.shape)
        self.points.append((a, d, F, jnp.broadcast_to(keep, a.shape), leg))
        self.size += a.shape[0]

    def event(self, kind, keep):
        """An event at the last point emitted so far."""
        self.events.append((self.size - 1, kind, keep))

    def write(self, c):
        a, d, F, keep, leg = (jnp.concatenate(parts) for parts in zip(*self.points))
        position = c.count + jnp.cumsum(keep) - 1
        size = c.rows.shape[0]
        index = jnp.where(keep & (position < size), position, size)
        row = jnp.stack([a, d, F, leg], axis=-1)
        rows = c.rows.at[index].set(row, mode="drop")
        at = jnp.stack([position[i] if i >= 0 else c.count - 1 for i, _, _ in self.events])
        kinds = jnp.stack([jnp.asarray(kind) for _, kind, _ in self.events])
        logged = jnp.stack([jnp.asarray(k) for _, _, k in self.events])
        slot = c.event_count + jnp.cumsum(logged) - 1
        slots = c.events.shape[0]
        slot = jnp.where(logged & (slot < slots), slot, slots)
        events = c.events.at[slot].set(jnp.stack([at, kinds], axis=-1), mode="drop")
        return eqx.tree_at(
            lambda s: (s.rows, s.count, s.events, s.event_count),
            c,
            (rows, c.count + jnp.sum(keep), events, c.event_count + jnp.sum(logged)),
        )


def _set(c: Carry, keep, **changes) -> Carry:
    """Carry with the given fields replaced where `keep`."""
    names = tuple(changes)
    values = tuple(jnp.where(keep, jnp.asarray(v, getattr(c, k).dtype), getattr(c, k)) for k, v in changes.items())
    return eqx.tree_at(lambda s: tuple(getattr(s, k) for k in names), c, values)


def _select(keep, when_true: Carry, when_false: Carry) -> Carry:
    return jax.tree.map(lambda x, y: jnp.where(keep, x, y), when_true, when_false)


def _march_continuum(built: Built, numerics: QuasiStaticNumerics) -> QuasiStaticOutcome:
    """March the program one piece per step: an approach, a hold, a ride over one interval
    between turning points, or a cascade. Every step solves one bisection, whatever its mode (a
    ride's crossing of the target, or where a cascade stops), so the loop body and its compile
    time stay small."""
    law, problem = built.law, built.problem
    attach, detach = problem.attach, problem.detach
    force_control = built.force_control
    legs = built.legs
    steps = numerics.steps(built.targets.shape[0])
    up_nodes, up_tags = _path(attach, built.attach3, built.top, True)
    down_nodes, down_tags = _path(detach, built.detach3, built.top, False)
    last = up_nodes.shape[0] - 1
    u = jnp.linspace(0.0, 1.0, numerics.samples)
    force = law.force
    extent = law.extent()

    def complete(c: Carry, log: _Log, keep) -> Carry:
        """The current target is met: a landing ends (its jump logged), or the leg ends."""
        landed = keep & c.landing
        log.emit(c.a, c.d, force(c.a, c.d), landed, c.leg)
        kind = jnp.where(c.a >= c.pre[0], _EVENT["snap_in"], _EVENT["snap_out"])
        log.event(kind, landed & (c.a != c.pre[0]))
        leg_direction = built.directions[c.leg]
        c = _set(c, landed, landing=False, target=built.targets[c.leg], direction=leg_direction,
                 mode=jnp.where(c.direction != leg_direction, HOLD, c.mode))
        finished = keep & ~landed
        more = c.leg + 1 < legs
        following = jnp.minimum(c.leg + 1, legs - 1)
        log.event(_EVENT["reversal"], finished & more & (c.mode != FREE))
        return _set(c, finished, leg=following, done=~more, direction=built.directions[following],
                    target=built.targets[following], mode=jnp.where(c.mode == FREE, FREE, HOLD))

    def instability(c: Carry, keep, a, d) -> Carry:
        """Force control: the applied force can no longer be met here; jump at constant force."""
        start = keep & force_control & ~c.landing
        return _set(c, start, landing=True, target=force(a, d), pre=jnp.stack([a, d]))

    def step(c: Carry) -> Carry:
        c = eqx.tree_at(lambda s: s.steps, c, c.steps + 1)
        log = _Log()
        up = c.direction > 0
        is_free, is_hold, is_ride, is_cascade = (c.mode == m for m in (FREE, HOLD, RIDE, CASCADE))
        a, d = c.a, c.d

        # Approach (no contact): to the touch at d = 0, or away to the leg's target.
        touches = is_free & up & (c.target >= 0.0)
        free_end = jnp.where(up, 0.0, jnp.where(jnp.isfinite(c.target), jnp.minimum(c.target, d), d))

        # Hold (a fixed, F linear in d): to the target, or to the edge where a spring changes.
        safe = jnp.where(a > 0.0, a, 1.0)
        level = jnp.where(up, jnp.where(c.wall, jnp.inf, jnp.maximum(attach.level(law, a), d)),
                          jnp.minimum(detach.level(law, a), d))
        finite = jnp.isfinite(level)
        level_value = jnp.where(force_control, jnp.where(finite, force(a, jnp.where(finite, level, 0.0)), jnp.inf), level)
        hold_reached = jnp.where(up, c.target <= level_value, c.target >= level_value)
        aimed = jnp.where(force_control, jnp.where(a > 0.0, (0.5 * c.target + law.G(a)) / safe, d), c.target)
        aimed = jnp.where(up, jnp.maximum(aimed, d), jnp.minimum(aimed, d))
        hold_end = jnp.where(hold_reached, aimed, level)

        # Ride (d = h(a) on the edge of the direction) over one interval between turning points.
        nodes = jnp.where(up, up_nodes, down_nodes)
        tags = jnp.where(up, up_tags, down_tags)
        edge = jnp.where(up, attach.coefficient, detach.coefficient)
        j = jnp.where(up, jnp.searchsorted(up_nodes, a, side="right", method="compare_all") - 1,
                      jnp.searchsorted(down_nodes, a, side="left", method="compare_all") - 1)
        j = jnp.clip(j, 0, last - 1)
        far = jnp.where(up, nodes[j + 1], nodes[j])
        tag = jnp.where(up, tags[j + 1], tags[j])
        lo, hi = jnp.minimum(a, far), jnp.maximum(a, far)
        mid = 0.5 * (lo + hi)
        empty = hi <= lo
        h_rising = (law.edge_slope(mid, edge) > 0.0) | empty
        f_rising = (law.edge_slope(mid, 3.0 * edge) > 0.0) | empty
        flat = is_ride & ~h_rising  # round-off at a turning point: cascade from here
        unstable = is_ride & h_rising & force_control & ~c.landing & ~f_rising  # the jump starts here
        moving = is_ride & h_rising & ~unstable
        far_value = _value(law, far, edge, force_control)
        crossed = moving & jnp.where(force_control, f_rising, True) & jnp.where(up, c.target <= far_value, c.target >= far_value)

        # Cascade (at constant d, from the current state): where the next edge crossing is, on
        # the attach branch outward or the detach branch inward (`Branch.cascade_out`/`_in`).
        branch = jax.tree.map(lambda x, y: jnp.where(up, x, y), attach, detach)
        outward = branch.increasing & (branch.nodes[1:] > a) & (branch.levels[1:] > d)
        inward = branch.increasing & (branch.nodes[:-1] < a) & (branch.levels[:-1] < d)
        candidate = jnp.where(up, outward, inward)
        count = candidate.shape[0]
        segment = jnp.where(up, jnp.argmax(outward), count - 1 - jnp.argmax(inward[::-1]))
        none = ~jnp.any(candidate)  # outward: blocked (wall or no end); inward: separated

        # The one bisection of the step.
        root = _root(law, edge, force_control & ~is_cascade, jnp.where(is_cascade, d, c.target),
                     jnp.where(is_cascade, branch.nodes[segment], lo), jnp.where(is_cascade, branch.nodes[segment + 1], hi))

        # The piece, sampled: approach (F = 0), hold (d from d to its end) or ride (a to stop_at).
        stop_at = jnp.where(crossed, root, far)
        stop_level = law.edge(stop_at, edge)
        piece_a = jnp.where(is_ride, a + (stop_at - a) * u, jnp.where(is_hold, a, 0.0) * jnp.ones_like(u))
        piece_d = jnp.where(is_ride, law.edge(piece_a, edge), d + (jnp.where(is_hold, hold_end, free_end) - d) * u)
        piece_F = jnp.where(is_free, 0.0, force(piece_a, piece_d))
        shown = jnp.where(is_free, ~force_control & (touches | ~up), ~c.landing) & (is_free | is_hold | moving)
        log.emit(piece_a, piece_d, piece_F, shown, c.leg)
        c = _set(c, is_free & shown, d=free_end)
        c = _set(c, is_hold, d=hold_end)
        c = _set(c, moving, a=stop_at, d=stop_level, wall=False)
        c = instability(c, unstable, a, d)
        c = complete(c, log, (is_free & ~touches) | (is_hold & hold_reached) | crossed)
        at_node = moving & ~crossed
        c = instability(c, at_node & (tag == 1) & f_rising, far, stop_level)
        # A hold's end, a turning point of h, the tip or the touch: a cascade next step.
        log.emit(0.0, 0.0, 0.0, touches, c.leg)
        log.event(_EVENT["touch"], touches)
        c = _set(c, touches, a=0.0, d=0.0)
        turn = (at_node & ((tag == 0) | (~up & (stop_at <= 0.0)))) | flat  # the tip ends every path
        c = _set(c, touches | (is_hold & ~hold_reached) | turn, mode=CASCADE)

        # Cascade: its outcome.
        radius = jnp.where(up, jnp.maximum(root, a), jnp.minimum(root, a))
        wall = up & none & (branch.nodes[-1] >= extent)
        stop = up & none & ~wall
        unbounded = (~branch.increasing[-1] & ~jnp.isfinite(extent)) | ~built.bounded
        code = jnp.where(unbounded, RESULT_CODE["unbounded_contact"], RESULT_CODE["radius_overflow"])
        radius = jnp.where(wall, branch.nodes[-1], jnp.where(none, 0.0, radius))
        c = after_cascade(c, log, is_cascade, a, d, radius, ~up & none, wall, stop, code, up)
        return log.write(c)

    def after_cascade(c: Carry, log: _Log, keep, a, d, radius, gone, wall, stop, code, up) -> Carry:
        """The radius jumped (or not) at constant d from a: apply the outcome of the cascade."""
        moved = jnp.abs(radius - a) > _SAME_RADIUS * jnp.maximum(a, _SAME_RADIUS)  # scaled: O(1) radii
        # Force control: a jump that starts outside a landing is itself an instability.
        c = instability(c, keep & (moved | gone) & ~stop, a, d)
        # Separation: the pull-off is where the instability began (force) or this point.
        before = jnp.where(c.landing, c.pre, jnp.stack([a, d]))
        F_before = force(before[0], before[1])
        pulled = keep & gone
        c = _set(c, pulled, pull_off=jnp.concatenate([before, F_before[None]]))
        # The curve ends at the pull-off; under displacement control the force then drops to 0 at
        # constant d (under force control the body leaves at constant force: no state follows).
        log.emit(before[0], before[1], F_before, pulled, c.leg)
        log.event(_EVENT["pull_off"], pulled)
        log.emit(0.0, d, 0.0, pulled & ~force_control, c.leg)
        c = _set(c, pulled, mode=FREE, a=0.0, d=d, wall=False, landing=False, target=built.targets[c.leg],
                 direction=built.directions[c.leg])
        c = complete(c, log, pulled & ~jnp.isfinite(built.targets[c.leg]))
        # A jump: log it (displacement control; a landing logs its own) and go on from the new radius.
        jumped = keep & ~gone & ~stop
        radius = jnp.where(moved, radius, a)
        shown = jumped & moved & ~c.landing
        log.emit(jnp.stack([a, radius]), jnp.stack([d, d]), jnp.stack([force(a, d), force(radius, d)]), shown, c.leg)
        log.event(jnp.where(up, _EVENT["snap_in"], _EVENT["snap_out"]), shown)
        c = _set(c, jumped, a=radius, d=d, wall=wall, mode=jnp.where(wall, HOLD, RIDE))
        # In a landing, a jump past the applied force turns the march back.
        F = force(radius, d)
        overshoot = jumped & c.landing & jnp.where(up, F > c.target, F < c.target)
        c = _set(c, overshoot, direction=-c.direction, mode=HOLD)
        return _set(c, keep & stop, status=code, done=True)

    def running(c: Carry):
        return ~c.done & (c.steps < steps)

    rows = steps * (numerics.samples + 8)
    nan = jnp.full((), jnp.nan)
    start = Carry(
        leg=jnp.zeros((), int),
        direction=jnp.asarray(built.directions[0], int),
        target=built.targets[0],
        landing=jnp.asarray(False),
        mode=jnp.asarray(FREE),
        wall=jnp.asarray(False),
        a=jnp.zeros(()),
        d=jnp.zeros(()),
        pre=jnp.zeros(2),
        pull_off=jnp.full(3, nan),
        status=jnp.asarray(RESULT_CODE["separated"]),
        done=jnp.asarray(False),
        steps=jnp.zeros((), int),
        rows=jnp.full((rows, 4), nan),
        count=jnp.zeros((), int),
        events=jnp.full((4 * steps, 2), -1),
        event_count=jnp.zeros((), int),
    )
    overflow = attach.overflow | detach.overflow | built.attach3.overflow | built.detach3.overflow
    start = _set(start, overflow, status=RESULT_CODE["branch_overflow"], done=True)
    end = jax.lax.while_loop(running, step, start)
    status = jnp.where(end.done, end.status, RESULT_CODE["phase_limit"])
    return QuasiStaticOutcome(status=status, pull_off=end.pull_off, rows=end.rows, events=end.events,
                              steps=end.steps, top=built.top)


# ---------------------------------------------------------------- the spring array


class SpringCarry(eqx.Module):
    leg: jax.Array
    direction: jax.Array
    target: jax.Array
    landing: jax.Array
    touching: jax.Array
    k: jax.Array  # springs attached
    d: jax.Array
    pre: jax.Array  # [2] k, d where the current instability began
    pull_off: jax.Array
    status: jax.Array
    done: jax.Array
    steps: jax.Array
    rows: jax.Array
    count: jax.Array
    events: jax.Array
    event_count: jax.Array


def spring_array(built: Built, capacity: int, count, length) -> SpringArray:
    """`count` ≤ `capacity` midpoint springs x_i = (i − ½)Δx on [0, L]; L is `length` (m) if
    given, else the radius the program can reach (or the body's wall). Slots beyond `count`
    never attach (threshold +inf), so one compiled march serves every count."""
    law = built.law
    scaled = jnp.where(jnp.isnan(length), built.top, length / law.scales.radial)
    spacing = scaled / count
    index = jnp.arange(capacity)
    real = index < count
    positions = jnp.where(real, (index + 0.5) * spacing, scaled)
    attach, detach = built.problem.attach, built.problem.detach
    return SpringArray(
        spacing=spacing,
        attach_level=jnp.where(real, law.edge(positions, attach.coefficient), jnp.inf),
        detach_level=law.edge(positions, detach.coefficient),
        prefix=jnp.concatenate([jnp.zeros(1), jnp.cumsum(jnp.where(real, law.g(positions), 0.0))]),
        beyond_level=jnp.where(scaled >= law.extent(), jnp.inf, law.edge((count + 0.5) * spacing, attach.coefficient)),
    )


def _march_springs(built: Built, numerics: QuasiStaticNumerics, length, count) -> QuasiStaticOutcome:
    array = spring_array(built, numerics.springs, count, length)
    N = count
    capacity = array.count
    force_control = built.force_control
    legs = built.legs
    steps = numerics.steps(built.targets.shape[0])

    def force(k, d):
        return array.force(k, d)

    def radius(k):
        return k * array.spacing

    def emit(log, k, d, keep, leg):
        k, d = jnp.atleast_1d(k), jnp.atleast_1d(d)
        log.emit(radius(k), d, force(k, d), keep, leg)

    def complete(c, log, keep):
        landed = keep & c.landing
        c = _set(c, landed, landing=False, target=built.targets[c.leg], direction=built.directions[c.leg])
        finished = keep & ~landed
        leg = c.leg + 1
        more = leg < legs
        following = jnp.minimum(leg, legs - 1)
        log.event(_EVENT["reversal"], finished & more & c.touching)
        return _set(c, finished, leg=following, done=~more, direction=built.directions[following],
                    target=built.targets[following])

    def equilibrium(k, F):
        """d with k springs attached under the force F (k > 0)."""
        return (0.5 * F / array.spacing + array.prefix[k]) / jnp.maximum(k, 1)

    def step(c: SpringCarry) -> SpringCarry:
        c = eqx.tree_at(lambda s: s.steps, c, c.steps + 1)
        log = _Log()
        up = c.direction > 0
        k, d = c.k, c.d
        # Not touching: the approach to d = 0, then the touch with its jump-in.
        approach = ~c.touching
        touches = approach & up & (c.target >= 0.0)
        end = jnp.where(up, 0.0, jnp.where(jnp.isfinite(c.target), jnp.minimum(c.target, d), d))
        emit(log, jnp.zeros(2, int), jnp.stack([d, end]), approach & ~force_control & (touches | ~up), c.leg)
        jump_in = array.attach_cascade(jnp.zeros((), int), 0.0)
        emit(log, jnp.zeros((), int), 0.0, touches, c.leg)
        log.event(_EVENT["touch"], touches)
        emit(log, jump_in, 0.0, touches, c.leg)
        log.event(_EVENT["snap_in"], touches & (jump_in > 0))
        F_touch = force(jump_in, 0.0)
        lands = touches & force_control & (F_touch != 0.0) & (jump_in > 0)
        c = _set(c, touches, touching=True, k=jump_in, d=0.0)
        c = _set(c, lands, landing=True, target=0.0, pre=jnp.stack([jump_in, 0]).astype(float),
                 direction=jnp.where(F_touch > 0.0, -1, 1))
        c = complete(c, log, approach & ~touches)
        c = _set(c, approach & ~touches, d=end)

        # Touching: the next threshold in the direction of motion.
        contact = ~approach
        beyond = k >= N
        attach_next = jnp.where(beyond, array.beyond_level, array.attach_level[jnp.minimum(k, capacity - 1)])
        detach_edge = jnp.where(k > 0, array.detach_level[jnp.maximum(k - 1, 0)], d)  # no spring: gone at once
        level = jnp.where(up, attach_next, detach_edge)
        F_level = jnp.where(jnp.isfinite(level), force(k, jnp.where(jnp.isfinite(level), level, 0.0)),
                            jnp.where(up, jnp.inf, -jnp.inf))
        F_level = jnp.where(k > 0, F_level, jnp.where(up, 0.0, jnp.inf))  # no spring: F = 0
        value = jnp.where(force_control, F_level, level)
        reached = contact & jnp.where(up, c.target <= value, c.target >= value)
        aimed = jnp.where(force_control, jnp.where(k > 0, equilibrium(k, c.target), d), c.target)
        aimed = jnp.where(up, jnp.maximum(aimed, d), jnp.minimum(aimed, d))
        new_d = jnp.where(reached, aimed, level)
        # (each piece starts where the last one, or the last jump, ended: only its end is new)
        emit(log, k, new_d, contact & ~c.landing & jnp.isfinite(new_d), c.leg)
        c = _set(c, contact & jnp.isfinite(new_d), d=new_d)
        landed = reached & c.landing
        emit(log, k, c.d, landed, c.leg)
        log.event(jnp.where(k >= c.pre[0], _EVENT["snap_in"], _EVENT["snap_out"]), landed & (jnp.abs(k - c.pre[0]) > 1))
        c = complete(c, log, reached)

        # The threshold is passed: attach or detach, with the cascade at constant d.
        passes = contact & ~reached
        overflow = passes & up & beyond & jnp.isfinite(array.beyond_level)
        moves = passes & ~overflow
        d_now = c.d
        k_new = jnp.where(up, array.attach_cascade(jnp.minimum(k + 1, N), d_now),
                          array.detach_cascade(jnp.maximum(k - 1, 0), d_now))
        start = moves & force_control & ~c.landing
        c = _set(c, start, landing=True, target=force(k, d_now), pre=jnp.stack([k.astype(float), d_now]))
        gone = moves & ~up & (k_new == 0)
        before_k = jnp.where(c.landing, c.pre[0], k).astype(int)
        before_d = jnp.where(c.landing, c.pre[1], d_now)
        c = _set(c, gone, pull_off=jnp.stack([radius(before_k), before_d, force(before_k, before_d)]))
        emit(log, before_k, before_d, gone, c.leg)
        log.event(_EVENT["pull_off"], gone)
        emit(log, jnp.zeros((), int), d_now, gone & ~force_control, c.leg)
        c = _set(c, gone, touching=False, k=0, landing=False, target=built.targets[c.leg],
                 direction=built.directions[c.leg])
        c = complete(c, log, gone & ~jnp.isfinite(built.targets[c.leg]))
        jumped = moves & ~gone
        emit(log, k_new, d_now, jumped & ~c.landing, c.leg)
        log.event(jnp.where(up, _EVENT["snap_in"], _EVENT["snap_out"]), jumped & ~c.landing & (jnp.abs(k_new - k) > 1))
        c = _set(c, jumped, k=k_new)
        F = force(k_new, d_now)
        overshoot = jumped & c.landing & jnp.where(up, F > c.target, F < c.target)
        c = _set(c, overshoot, direction=-c.direction)
        code = jnp.where(built.bounded, RESULT_CODE["radius_overflow"], RESULT_CODE["unbounded_contact"])
        return log.write(_set(c, overflow, status=code, done=True))

    def running(c):
        return ~c.done & (c.steps < steps)

    nan = jnp.full((), jnp.nan)
    start = SpringCarry(
        leg=jnp.zeros((), int),
        direction=jnp.asarray(built.directions[0], int),
        target=built.targets[0],
        landing=jnp.asarray(False),
        touching=jnp.asarray(False),
        k=jnp.zeros((), int),
        d=jnp.zeros(()),
        pre=jnp.zeros(2),
        pull_off=jnp.full(3, nan),
        status=jnp.asarray(RESULT_CODE["separated"]),
        done=jnp.asarray(False),
        steps=jnp.zeros((), int),
        rows=jnp.full((2 * steps + 64 * built.targets.shape[0], 4), nan),
        count=jnp.zeros((), int),
        events=jnp.full((steps // 2 + 64, 2), -1),
        event_count=jnp.zeros((), int),
    )
    end = jax.lax.while_loop(running, step, start)
    status = jnp.where(end.done, end.status, RESULT_CODE["phase_limit"])
    return QuasiStaticOutcome(status=status, pull_off=end.pull_off, rows=end.rows, events=end.events,
                              steps=end.steps, top=built.top)


@eqx.filter_jit
def march(loading: Loading, numerics: QuasiStaticNumerics):
    """Build and march one quasi-static program; returns (scales, scaled outcome)."""
    built = build(loading, numerics)
    if numerics.springs is None:
        return built.law.scales, _march_continuum(built, numerics)
    return built.law.scales, _march_springs(built, numerics, loading.spring_length, loading.spring_count)
