"""The quasi-static march of the spring array, event by event, with the same rules."""

import equinox as eqx
import jax
import jax.numpy as jnp

from ..._core.pytree import replace_where
from ..._law.springs import TabulatedSpringArray
from ..codes import RESULT_CODE
from .events import EventLog
from .loading import EVENT, QuasiStaticNumerics, QuasiStaticOutcome
from .setup import Built


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


def spring_array(built: Built, capacity: int, count, length) -> TabulatedSpringArray:
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
    return TabulatedSpringArray(
        spacing=spacing,
        attach_level=jnp.where(real, law.edge(positions, attach.coefficient), jnp.inf),
        detach_level=law.edge(positions, detach.coefficient),
        prefix=jnp.concatenate([jnp.zeros(1), jnp.cumsum(jnp.where(real, law.g(positions), 0.0))]),
        beyond_level=jnp.where(scaled >= law.extent(), jnp.inf, law.edge((count + 0.5) * spacing, attach.coefficient)),
    )


def march_springs(built: Built, numerics: QuasiStaticNumerics, length, count) -> QuasiStaticOutcome:
    """March the program on the spring array (`numerics.springs` its capacity), event by event."""
    assert numerics.springs is not None, "a spring-array march needs the array's capacity"
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
        c = replace_where(c, landed, landing=False, target=built.targets[c.leg], direction=built.directions[c.leg])
        finished = keep & ~landed
        leg = c.leg + 1
        more = leg < legs
        following = jnp.minimum(leg, legs - 1)
        log.event(EVENT["reversal"], finished & more & c.touching)
        return replace_where(
            c,
            finished,
            leg=following,
            done=~more,
            direction=built.directions[following],
            target=built.targets[following],
        )

    def equilibrium(k, F):
        """d with k springs attached under the force F (k > 0)."""
        return (0.5 * F / array.spacing + array.prefix[k]) / jnp.maximum(k, 1)

    def step(c: SpringCarry) -> SpringCarry:
        c = eqx.tree_at(lambda s: s.steps, c, c.steps + 1)
        log = EventLog()
        up = c.direction > 0
        k, d = c.k, c.d
        # Not touching: the approach to d = 0, then the touch with its jump-in.
        approach = ~c.touching
        touches = approach & up & (c.target >= 0.0)
        end = jnp.where(up, 0.0, jnp.where(jnp.isfinite(c.target), jnp.minimum(c.target, d), d))
        emit(log, jnp.zeros(2, int), jnp.stack([d, end]), approach & ~force_control & (touches | ~up), c.leg)
        jump_in = array.attach_cascade(jnp.zeros((), int), 0.0)
        emit(log, jnp.zeros((), int), 0.0, touches, c.leg)
        log.event(EVENT["touch"], touches)
        emit(log, jump_in, 0.0, touches, c.leg)
        log.event(EVENT["snap_in"], touches & (jump_in > 0))
        F_touch = force(jump_in, 0.0)
        lands = touches & force_control & (F_touch != 0.0) & (jump_in > 0)
        c = replace_where(c, touches, touching=True, k=jump_in, d=0.0)
        c = replace_where(
            c,
            lands,
            landing=True,
            target=0.0,
            pre=jnp.stack([jump_in, 0]).astype(float),
            direction=jnp.where(F_touch > 0.0, -1, 1),
        )
        c = complete(c, log, approach & ~touches)
        c = replace_where(c, approach & ~touches, d=end)

        # Touching: the next threshold in the direction of motion.
        contact = ~approach
        beyond = k >= N
        attach_next = jnp.where(beyond, array.beyond_level, array.attach_level[jnp.minimum(k, capacity - 1)])
        detach_edge = jnp.where(k > 0, array.detach_level[jnp.maximum(k - 1, 0)], d)  # no spring: gone at once
        level = jnp.where(up, attach_next, detach_edge)
        F_level = jnp.where(
            jnp.isfinite(level), force(k, jnp.where(jnp.isfinite(level), level, 0.0)), jnp.where(up, jnp.inf, -jnp.inf)
        )
        F_level = jnp.where(k > 0, F_level, jnp.where(up, 0.0, jnp.inf))  # no spring: F = 0
        value = jnp.where(force_control, F_level, level)
        reached = contact & jnp.where(up, c.target <= value, c.target >= value)
        aimed = jnp.where(force_control, jnp.where(k > 0, equilibrium(k, c.target), d), c.target)
        aimed = jnp.where(up, jnp.maximum(aimed, d), jnp.minimum(aimed, d))
        new_d = jnp.where(reached, aimed, level)
        # (each piece starts where the last one, or the last jump, ended: only its end is new)
        emit(log, k, new_d, contact & ~c.landing & jnp.isfinite(new_d), c.leg)
        c = replace_where(c, contact & jnp.isfinite(new_d), d=new_d)
        landed = reached & c.landing
        emit(log, k, c.d, landed, c.leg)
        log.event(jnp.where(k >= c.pre[0], EVENT["snap_in"], EVENT["snap_out"]), landed & (jnp.abs(k - c.pre[0]) > 1))
        c = complete(c, log, reached)

        # The threshold is passed: attach or detach, with the cascade at constant d.
        passes = contact & ~reached
        overflow = passes & up & beyond & jnp.isfinite(array.beyond_level)
        moves = passes & ~overflow
        d_now = c.d
        k_new = jnp.where(
            up, array.attach_cascade(jnp.minimum(k + 1, N), d_now), array.detach_cascade(jnp.maximum(k - 1, 0), d_now)
        )
        start = moves & force_control & ~c.landing
        c = replace_where(c, start, landing=True, target=force(k, d_now), pre=jnp.stack([k.astype(float), d_now]))
        gone = moves & ~up & (k_new == 0)
        before_k = jnp.where(c.landing, c.pre[0], k).astype(int)
        before_d = jnp.where(c.landing, c.pre[1], d_now)
        c = replace_where(c, gone, pull_off=jnp.stack([radius(before_k), before_d, force(before_k, before_d)]))
        emit(log, before_k, before_d, gone, c.leg)
        log.event(EVENT["pull_off"], gone)
        emit(log, jnp.zeros((), int), d_now, gone & ~force_control, c.leg)
        c = replace_where(
            c, gone, touching=False, k=0, landing=False, target=built.targets[c.leg], direction=built.directions[c.leg]
        )
        c = complete(c, log, gone & ~jnp.isfinite(built.targets[c.leg]))
        jumped = moves & ~gone
        emit(log, k_new, d_now, jumped & ~c.landing, c.leg)
        log.event(jnp.where(up, EVENT["snap_in"], EVENT["snap_out"]), jumped & ~c.landing & (jnp.abs(k_new - k) > 1))
        c = replace_where(c, jumped, k=k_new)
        F = force(k_new, d_now)
        overshoot = jumped & c.landing & jnp.where(up, F > c.target, F < c.target)
        c = replace_where(c, overshoot, direction=-c.direction)
        code = jnp.where(built.bounded, RESULT_CODE["radius_overflow"], RESULT_CODE["unbounded_contact"])
        return log.write(replace_where(c, overflow, status=code, done=True))

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
    return QuasiStaticOutcome(
        status=status, pull_off=end.pull_off, rows=end.rows, events=end.events, steps=end.steps, top=built.top
    )
