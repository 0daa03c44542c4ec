"""What happens at the end of each phase: the rules of attach, hold, detach and cascade.

Each function takes the phase state at a located event and returns the next one. They are
written once and used by both integrators (continuum and spring array).
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from .phases import ADVANCE, DONE, EVENT_CODE, FLIGHT, HOLD, RECEDE
from .setup import Problem

# Relative gap under which a turnaround that lands on the detach edge starts unloading at once
# (the reversible JKR law, Δγa = Δγ, has no hold phase).
_SAME_EDGE = 1e-12


class Next(eqx.Module):
    """The phase that follows an event."""

    mode: jax.Array
    segment: jax.Array
    radius: jax.Array  # contact radius at the start of the next phase
    event: jax.Array  # event code logged for this transition
    separated: jax.Array
    captured: jax.Array
    overflow: jax.Array


def _next(mode, segment, radius, event, separated=False, captured=False, overflow=False):
    return Next(
        mode=jnp.asarray(mode, int),
        segment=jnp.asarray(segment, int),
        radius=jnp.asarray(radius, jnp.float64),
        event=jnp.asarray(event, int),
        separated=jnp.asarray(separated),
        captured=jnp.asarray(captured),
        overflow=jnp.asarray(overflow),
    )


def select(condition, when_true: Next, when_false: Next) -> Next:
    return jax.tree.map(lambda a, b: jnp.where(condition, a, b), when_true, when_false)


def recede_from(problem: Problem, radius, indentation, event) -> Next:
    """Inward cascade from `radius` at level d: unloading on a lower segment, or separation."""
    law, detach = problem.law, problem.detach
    landing, segment, separated = detach.cascade_in(law, radius, indentation)
    gone = _next(FLIGHT, 0, 0.0, EVENT_CODE["separation"], separated=True)
    return select(separated, gone, _next(RECEDE, segment, landing, event))


def touch(problem: Problem) -> Next:
    """First contact at d = 0: the attach cascade from the tip sets the jump-in radius."""
    return advance_from(problem, jnp.zeros(()), jnp.zeros(()), EVENT_CODE["touch"])


def advance_from(problem: Problem, radius, indentation, event) -> Next:
    """Outward cascade: loading on a further segment, or held at the body's wall."""
    law, attach = problem.law, problem.attach
    wall, segment, blocked = attach.cascade_out(law, radius, indentation)
    at_wall = blocked & (attach.nodes[-1] >= law.extent())
    held = _next(HOLD, 0, wall, event)
    stuck_table = _next(DONE, 0, 0.0, event, overflow=True)
    return select(blocked, select(at_wall, held, stuck_table), _next(ADVANCE, segment, wall, event))


def after_advance(problem: Problem, segment, radius, indentation, turned) -> Next:
    """Loading ended: a turnaround starts the hold (or unloading at once), a local maximum of
    the attach edge makes the contact snap out."""
    law = problem.law
    edge = problem.detach.level(law, radius)
    on_edge = indentation <= edge + _SAME_EDGE * (1.0 + jnp.abs(indentation))
    hold = _next(HOLD, 0, radius, EVENT_CODE["max_indentation"])
    unload = recede_from(problem, radius, indentation, EVENT_CODE["max_indentation"])
    turnaround = select(on_edge, unload, hold)
    snap = advance_from(problem, problem.attach.nodes[segment + 1], indentation, EVENT_CODE["snap_in"])
    return select(turned, turnaround, snap)


def after_hold(problem: Problem, hold_radius, indentation, turned) -> Next:
    """Hold ended: the edge spring reached Δl (unloading starts), or the body turned: captured."""
    unload = recede_from(problem, hold_radius, indentation, EVENT_CODE["detach_start"])
    return select(turned, capture(), unload)


def after_recede(problem: Problem, segment, indentation, turned) -> Next:
    """Unloading ended: a local minimum of the detach edge starts a cascade, or captured."""
    cascade = recede_from(problem, problem.detach.nodes[segment], indentation, EVENT_CODE["snap_out"])
    return select(turned, capture(), cascade)


def capture() -> Next:
    """An outward turnaround in contact: the body can never reach the separation point again.

    The contact dissipates on every closed path and gravity only pulls the body in, so from
    rest at d_turn it cannot come back out below d_turn with any kinetic energy left.
    """
    return _next(DONE, 0, 0.0, EVENT_CODE["capture"], captured=True)


def after_phase(problem: Problem, mode, segment, radius, indentation, turned) -> Next:
    """Dispatch on the phase that ended; `radius` is the contact radius at its end."""
    return select(
        mode == ADVANCE,
        after_advance(problem, segment, radius, indentation, turned),
        select(
            mode == HOLD,
            after_hold(problem, radius, indentation, turned),
            after_recede(problem, segment, indentation, turned),
        ),
    )


def flight_to_touch(problem: Problem, indentation, velocity):
    """Analytic flight from d ≤ 0 to the touch at d = 0: (duration, touch speed, reaches).

    Without gravity the body reaches the surface only if it moves towards it.
    """
    gravity = problem.gravity
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

