"""The quasi-static march of the continuum law: along the edges, cascades and force jumps."""

import equinox as eqx
import jax
import jax.numpy as jnp

from ..._core.pytree import replace_where
from ..codes import RESULT_CODE
from .events import EventLog
from .loading import CASCADE, EVENT, FREE, HOLD, RIDE, SAME_RADIUS, QuasiStaticNumerics, QuasiStaticOutcome
from .setup import Built, bracketed_root, edge_path, edge_value


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


def march_continuum(built: Built, numerics: QuasiStaticNumerics) -> QuasiStaticOutcome:
    """March the program one piece per step: an approach, a hold, a ride over one interval
    between turning points, or a cascade. Every step solves one bisection, whatever its mode (a
    ride's crossing of the target, or where a cascade stops), so the loop body and its compile
    time stay small."""
    law, problem = built.law, built.problem
    attach, detach = problem.attach, problem.detach
    force_control = built.force_control
    legs = built.legs
    steps = numerics.steps(built.targets.shape[0])
    up_nodes, up_tags = edge_path(attach, built.attach3, built.top, True)
    down_nodes, down_tags = edge_path(detach, built.detach3, built.top, False)
    last = up_nodes.shape[0] - 1
    u = jnp.linspace(0.0, 1.0, numerics.samples)
    force = law.force
    extent = law.extent()

    def complete(c: Carry, log: EventLog, keep) -> Carry:
        """The current target is met: a landing ends (its jump logged), or the leg ends."""
        landed = keep & c.landing
        log.emit(c.a, c.d, force(c.a, c.d), landed, c.leg)
        kind = jnp.where(c.a >= c.pre[0], EVENT["snap_in"], EVENT["snap_out"])
        log.event(kind, landed & (c.a != c.pre[0]))
        leg_direction = built.directions[c.leg]
        c = replace_where(
            c,
            landed,
            landing=False,
            target=built.targets[c.leg],
            direction=leg_direction,
            mode=jnp.where(c.direction != leg_direction, HOLD, c.mode),
        )
        finished = keep & ~landed
        more = c.leg + 1 < legs
        following = jnp.minimum(c.leg + 1, legs - 1)
        log.event(EVENT["reversal"], finished & more & (c.mode != FREE))
        return replace_where(
            c,
            finished,
            leg=following,
            done=~more,
            direction=built.directions[following],
            target=built.targets[following],
            mode=jnp.where(c.mode == FREE, FREE, HOLD),
        )

    def instability(c: Carry, keep, a, d) -> Carry:
        """Force control: the applied force can no longer be met here; jump at constant force."""
        start = keep & force_control & ~c.landing
        return replace_where(c, start, landing=True, target=force(a, d), pre=jnp.stack([a, d]))

    def step(c: Carry) -> Carry:
        c = eqx.tree_at(lambda s: s.steps, c, c.steps + 1)
        log = EventLog()
        up = c.direction > 0
        is_free, is_hold, is_ride, is_cascade = (c.mode == m for m in (FREE, HOLD, RIDE, CASCADE))
        a, d = c.a, c.d

        # Approach (no contact): to the touch at d = 0, or away to the leg's target.
        touches = is_free & up & (c.target >= 0.0)
        free_end = jnp.where(up, 0.0, jnp.where(jnp.isfinite(c.target), jnp.minimum(c.target, d), d))

        # Hold (a fixed, F linear in d): to the target, or to the edge where a spring changes.
        safe = jnp.where(a > 0.0, a, 1.0)
        level = jnp.where(
            up, jnp.where(c.wall, jnp.inf, jnp.maximum(attach.level(law, a), d)), jnp.minimum(detach.level(law, a), d)
        )
        finite = jnp.isfinite(level)
        level_value = jnp.where(
            force_control, jnp.where(finite, force(a, jnp.where(finite, level, 0.0)), jnp.inf), level
        )
        hold_reached = jnp.where(up, c.target <= level_value, c.target >= level_value)
        aimed = jnp.where(force_control, jnp.where(a > 0.0, (0.5 * c.target + law.G(a)) / safe, d), c.target)
        aimed = jnp.where(up, jnp.maximum(aimed, d), jnp.minimum(aimed, d))
        hold_end = jnp.where(hold_reached, aimed, level)

        # Ride (d = h(a) on the edge of the direction) over one interval between turning points.
        nodes = jnp.where(up, up_nodes, down_nodes)
        tags = jnp.where(up, up_tags, down_tags)
        edge = jnp.where(up, attach.coefficient, detach.coefficient)
        j = jnp.where(
            up,
            jnp.searchsorted(up_nodes, a, side="right", method="compare_all") - 1,
            jnp.searchsorted(down_nodes, a, side="left", method="compare_all") - 1,
        )
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
        far_value = edge_value(law, far, edge, force_control)
        crossed = (
            moving
            & jnp.where(force_control, f_rising, True)
            & jnp.where(up, c.target <= far_value, c.target >= far_value)
        )

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
        root = bracketed_root(
            law,
            edge,
            force_control & ~is_cascade,
            jnp.where(is_cascade, d, c.target),
            jnp.where(is_cascade, branch.nodes[segment], lo),
            jnp.where(is_cascade, branch.nodes[segment + 1], hi),
        )

        # The piece, sampled: approach (F = 0), hold (d from d to its end) or ride (a to stop_at).
        stop_at = jnp.where(crossed, root, far)
        stop_level = law.edge(stop_at, edge)
        piece_a = jnp.where(is_ride, a + (stop_at - a) * u, jnp.where(is_hold, a, 0.0) * jnp.ones_like(u))
        piece_d = jnp.where(is_ride, law.edge(piece_a, edge), d + (jnp.where(is_hold, hold_end, free_end) - d) * u)
        piece_F = jnp.where(is_free, 0.0, force(piece_a, piece_d))
        shown = jnp.where(is_free, ~force_control & (touches | ~up), ~c.landing) & (is_free | is_hold | moving)
        log.emit(piece_a, piece_d, piece_F, shown, c.leg)
        c = replace_where(c, is_free & shown, d=free_end)
        c = replace_where(c, is_hold, d=hold_end)
        c = replace_where(c, moving, a=stop_at, d=stop_level, wall=False)
        c = instability(c, unstable, a, d)
        c = complete(c, log, (is_free & ~touches) | (is_hold & hold_reached) | crossed)
        at_node = moving & ~crossed
        c = instability(c, at_node & (tag == 1) & f_rising, far, stop_level)
        # A hold's end, a turning point of h, the tip or the touch: a cascade next step.
        log.emit(0.0, 0.0, 0.0, touches, c.leg)
        log.event(EVENT["touch"], touches)
        c = replace_where(c, touches, a=0.0, d=0.0)
        turn = (at_node & ((tag == 0) | (~up & (stop_at <= 0.0)))) | flat  # the tip ends every path
        c = replace_where(c, touches | (is_hold & ~hold_reached) | turn, mode=CASCADE)

        # Cascade: its outcome.
        radius = jnp.where(up, jnp.maximum(root, a), jnp.minimum(root, a))
        wall = up & none & (branch.nodes[-1] >= extent)
        stop = up & none & ~wall
        unbounded = (~branch.increasing[-1] & ~jnp.isfinite(extent)) | ~built.bounded
        code = jnp.where(unbounded, RESULT_CODE["unbounded_contact"], RESULT_CODE["radius_overflow"])
        radius = jnp.where(wall, branch.nodes[-1], jnp.where(none, 0.0, radius))
        c = after_cascade(c, log, is_cascade, a, d, radius, ~up & none, wall, stop, code, up)
        return log.write(c)

    def after_cascade(c: Carry, log: EventLog, keep, a, d, radius, gone, wall, stop, code, up) -> Carry:
        """The radius jumped (or not) at constant d from a: apply the outcome of the cascade."""
        moved = jnp.abs(radius - a) > SAME_RADIUS * jnp.maximum(a, SAME_RADIUS)  # scaled: O(1) radii
        # Force control: a jump that starts outside a landing is itself an instability.
        c = instability(c, keep & (moved | gone) & ~stop, a, d)
        # Separation: the pull-off is where the instability began (force) or this point.
        before = jnp.where(c.landing, c.pre, jnp.stack([a, d]))
        F_before = force(before[0], before[1])
        pulled = keep & gone
        c = replace_where(c, pulled, pull_off=jnp.concatenate([before, F_before[None]]))
        # The curve ends at the pull-off; under displacement control the force then drops to 0 at
        # constant d (under force control the body leaves at constant force: no state follows).
        log.emit(before[0], before[1], F_before, pulled, c.leg)
        log.event(EVENT["pull_off"], pulled)
        log.emit(0.0, d, 0.0, pulled & ~force_control, c.leg)
        c = replace_where(
            c,
            pulled,
            mode=FREE,
            a=0.0,
            d=d,
            wall=False,
            landing=False,
            target=built.targets[c.leg],
            direction=built.directions[c.leg],
        )
        c = complete(c, log, pulled & ~jnp.isfinite(built.targets[c.leg]))
        # A jump: log it (displacement control; a landing logs its own) and go on from the new radius.
        jumped = keep & ~gone & ~stop
        radius = jnp.where(moved, radius, a)
        shown = jumped & moved & ~c.landing
        log.emit(jnp.stack([a, radius]), jnp.stack([d, d]), jnp.stack([force(a, d), force(radius, d)]), shown, c.leg)
        log.event(jnp.where(up, EVENT["snap_in"], EVENT["snap_out"]), shown)
        c = replace_where(c, jumped, a=radius, d=d, wall=wall, mode=jnp.where(wall, HOLD, RIDE))
        # In a landing, a jump past the applied force turns the march back.
        F = force(radius, d)
        overshoot = jumped & c.landing & jnp.where(up, F > c.target, F < c.target)
        c = replace_where(c, overshoot, direction=-c.direction, mode=HOLD)
        return replace_where(c, keep & stop, status=code, done=True)

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
    start = replace_where(start, overflow, status=RESULT_CODE["branch_overflow"], done=True)
    end = jax.lax.while_loop(running, step, start)
    status = jnp.where(end.done, end.status, RESULT_CODE["phase_limit"])
    return QuasiStaticOutcome(
        status=status, pull_off=end.pull_off, rows=end.rows, events=end.events, steps=end.steps, top=built.top
    )
