"""The pieces a continuum step moves along: the approach, a hold, a ride along an edge.

Each piece is found before the step's one bisection (`bracketed_root`), and `move` samples it
and updates the state once the root is known."""

import equinox as eqx
import jax
import jax.numpy as jnp

from ..._core.pytree import replace_where
from .continuum_state import Carry, ContinuumMarch, complete, instability
from .events import EventLog
from .loading import CASCADE, EVENT, FREE, HOLD, RIDE
from .setup import edge_value


class Approach(eqx.Module):
    """No contact: to the touch at d = 0, or away to the leg's target."""

    touches: jax.Array
    end: jax.Array  # d where the approach stops


class Hold(eqx.Module):
    """The radius a fixed, F linear in d: to the target, or to the edge where a spring changes."""

    reached: jax.Array  # the target comes first
    end: jax.Array  # d where the hold stops


class Ride(eqx.Module):
    """d = h(a) on the edge of the direction, over one interval between turning points."""

    edge: jax.Array  # the edge's coefficient
    lo: jax.Array  # the interval, bracketing a crossing of the target
    hi: jax.Array
    far: jax.Array  # its end in the direction of motion
    tag: jax.Array  # of that end: 0 a turning point of h, 1 of the force
    f_rising: jax.Array  # the force rises along the interval
    flat: jax.Array  # round-off at a turning point: cascade from here
    unstable: jax.Array  # force control: the jump starts here
    moving: jax.Array  # the radius moves along the interval
    crossed: jax.Array  # the target is met inside the interval


class Plan(eqx.Module):
    """What a step sets up from the state before its one bisection: the direction, the mode, and
    the piece of each mode that moves (the cascade's bracket is `cascade_bracket`)."""

    up: jax.Array
    is_free: jax.Array
    is_hold: jax.Array
    is_ride: jax.Array
    is_cascade: jax.Array
    free: Approach
    held: Hold
    rode: Ride


def plan(march: ContinuumMarch, c: Carry) -> Plan:
    """The direction, the mode and the pieces of a step from the state `c`."""
    up = c.direction > 0
    is_free, is_hold, is_ride, is_cascade = (c.mode == m for m in (FREE, HOLD, RIDE, CASCADE))
    return Plan(
        up=up,
        is_free=is_free,
        is_hold=is_hold,
        is_ride=is_ride,
        is_cascade=is_cascade,
        free=approach(c, up, is_free),
        held=hold(march, c, up),
        rode=ride(march, c, up, is_ride),
    )


def approach(c: Carry, up, is_free) -> Approach:
    """The approach (no contact) of a step in mode FREE."""
    touches = is_free & up & (c.target >= 0.0)
    end = jnp.where(up, 0.0, jnp.where(jnp.isfinite(c.target), jnp.minimum(c.target, c.d), c.d))
    return Approach(touches=touches, end=end)


def hold(march: ContinuumMarch, c: Carry, up) -> Hold:
    """A hold at the radius a: it ends at the target (d, or d where F meets it) or at the level of
    the edge of the direction, the attach level (none at the wall) or the detach level."""
    law, force_control, force = march.law, march.program.force_control, march.force
    a, d = c.a, c.d
    safe = jnp.where(a > 0.0, a, 1.0)
    level = jnp.where(
        up,
        jnp.where(c.wall, jnp.inf, jnp.maximum(march.attach.level(law, a), d)),
        jnp.minimum(march.detach.level(law, a), d),
    )
    finite = jnp.isfinite(level)
    level_value = jnp.where(force_control, jnp.where(finite, force(a, jnp.where(finite, level, 0.0)), jnp.inf), level)
    reached = jnp.where(up, c.target <= level_value, c.target >= level_value)
    aimed = jnp.where(force_control, jnp.where(a > 0.0, (0.5 * c.target + law.G(a)) / safe, d), c.target)
    aimed = jnp.where(up, jnp.maximum(aimed, d), jnp.minimum(aimed, d))
    return Hold(reached=reached, end=jnp.where(reached, aimed, level))


def ride(march: ContinuumMarch, c: Carry, up, is_ride) -> Ride:
    """The interval of the merged turning points (`edge_path`) that the radius a rides next, and
    whether d and F rise along it and the target is met inside it."""
    law, force_control = march.law, march.program.force_control
    a = c.a
    nodes = jnp.where(up, march.up.nodes, march.down.nodes)
    tags = jnp.where(up, march.up.tags, march.down.tags)
    edge = jnp.where(up, march.attach.coefficient, march.detach.coefficient)
    j = jnp.where(
        up,
        jnp.searchsorted(march.up.nodes, a, side="right", method="compare_all") - 1,
        jnp.searchsorted(march.down.nodes, a, side="left", method="compare_all") - 1,
    )
    j = jnp.clip(j, 0, march.up.nodes.shape[0] - 2)
    far = jnp.where(up, nodes[j + 1], nodes[j])
    lo, hi = jnp.minimum(a, far), jnp.maximum(a, far)
    mid = 0.5 * (lo + hi)
    empty = hi <= lo
    h_rising = (law.edge_slope(mid, edge) > 0.0) | empty
    f_rising = (law.edge_slope(mid, 3.0 * edge) > 0.0) | empty
    unstable = is_ride & h_rising & force_control & ~c.landing & ~f_rising
    moving = is_ride & h_rising & ~unstable
    far_value = edge_value(law, far, edge, force_control)
    crossed = (
        moving & jnp.where(force_control, f_rising, True) & jnp.where(up, c.target <= far_value, c.target >= far_value)
    )
    return Ride(
        edge=edge,
        lo=lo,
        hi=hi,
        far=far,
        tag=jnp.where(up, tags[j + 1], tags[j]),
        f_rising=f_rising,
        flat=is_ride & ~h_rising,
        unstable=unstable,
        moving=moving,
        crossed=crossed,
    )


def move(march: ContinuumMarch, c: Carry, log: EventLog, p: Plan, root) -> Carry:
    """Sample the step's piece (approach at F = 0, hold from d to its end, or ride from a to where
    it stops: the root where the target is crossed, else the interval's end) and move there. A
    met target completes; a force extremum starts an instability; a hold's end, a turning point of
    h, the tip or the touch leaves a cascade for the next step."""
    law, up, free, held, rode = march.law, p.up, p.free, p.held, p.rode
    is_free, is_hold, is_ride = p.is_free, p.is_hold, p.is_ride
    a, d, u = c.a, c.d, march.grid
    stop_at = jnp.where(rode.crossed, root, rode.far)
    stop_level = law.edge(stop_at, rode.edge)
    piece_a = jnp.where(is_ride, a + (stop_at - a) * u, jnp.where(is_hold, a, 0.0) * jnp.ones_like(u))
    piece_d = jnp.where(is_ride, law.edge(piece_a, rode.edge), d + (jnp.where(is_hold, held.end, free.end) - d) * u)
    piece_F = jnp.where(is_free, 0.0, march.force(piece_a, piece_d))
    shown = jnp.where(is_free, ~march.program.force_control & (free.touches | ~up), ~c.landing) & (
        is_free | is_hold | rode.moving
    )
    log.emit(piece_a, piece_d, piece_F, shown, c.leg)
    c = replace_where(c, is_free & shown, d=free.end)
    c = replace_where(c, is_hold, d=held.end)
    c = replace_where(c, rode.moving, a=stop_at, d=stop_level, wall=False)
    c = instability(march, c, rode.unstable, a, d)
    c = complete(march, c, log, (is_free & ~free.touches) | (is_hold & held.reached) | rode.crossed)
    at_node = rode.moving & ~rode.crossed
    c = instability(march, c, at_node & (rode.tag == 1) & rode.f_rising, rode.far, stop_level)
    log.emit(0.0, 0.0, 0.0, free.touches, c.leg)
    log.event(EVENT["touch"], free.touches)
    c = replace_where(c, free.touches, a=0.0, d=0.0)
    turn = (at_node & ((rode.tag == 0) | (~up & (stop_at <= 0.0)))) | rode.flat  # the tip ends every path
    return replace_where(c, free.touches | (is_hold & ~held.reached) | turn, mode=CASCADE)
