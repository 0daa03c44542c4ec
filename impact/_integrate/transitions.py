"""What happens at the end of each phase: the rules of attach, hold, detach and cascade.

Each function takes the phase state at a located event and returns the next one. They are
written once for the continuum law (its impacts and spring arrays land through `touch`); the
Maugis–Dugdale integrator states its own `Next` with `next_phase`.
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.pytree import where
from .codes import ADVANCE, DONE, EVENT_CODE, FLIGHT, HOLD, RECEDE, Status
from .problem import Problem

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
    stops: jax.Array  # the run ends here with the status `stop`
    stop: Status


def next_phase(mode, segment, radius, event, separated=False, captured=False, stops=False, stop=None) -> Next:
    """A `Next` from plain values; where it `stops`, the run ends with the status `stop`."""
    return Next(
        mode=jnp.asarray(mode, int),
        segment=jnp.asarray(segment, int),
        radius=jnp.asarray(radius, jnp.float64),
        event=jnp.asarray(event, int),
        separated=jnp.asarray(separated),
        captured=jnp.asarray(captured),
        stops=jnp.asarray(stops),
        stop=Status.separated if stop is None else stop,
    )


def recede_from(problem: Problem, radius, indentation, event) -> Next:
    """Inward cascade from `radius` at level d: unloading on a lower segment, or separation."""
    law, detach = problem.law, problem.detach
    landing, segment, separated = detach.cascade_in(law, radius, indentation)
    gone = next_phase(FLIGHT, 0, 0.0, EVENT_CODE["separation"], separated=True)
    return where(separated, gone, next_phase(RECEDE, segment, landing, event))


def touch(problem: Problem) -> Next:
    """First contact at d = 0: the attach cascade from the tip sets the jump-in radius."""
    return advance_from(problem, jnp.zeros(()), jnp.zeros(()), EVENT_CODE["touch"])


def advance_from(problem: Problem, radius, indentation, event) -> Next:
    """Outward cascade: loading on a further segment, or held at the body's wall."""
    law, attach = problem.law, problem.attach
    wall, segment, blocked = attach.cascade_out(law, radius, indentation)
    at_wall = blocked & (attach.nodes[-1] >= law.extent())
    held = next_phase(HOLD, 0, wall, event)
    # No spring beyond holds: the attach edge falls for good (n ≤ 1/2), or the tables end.
    falling = ~attach.increasing[-1]
    grows = next_phase(DONE, 0, wall, event, stops=True, stop=Status.unbounded_contact)
    beyond = next_phase(DONE, 0, wall, event, stops=True, stop=Status.radius_overflow)
    return where(
        blocked,
        where(at_wall, held, where(falling & ~jnp.isfinite(law.extent()), grows, beyond)),
        next_phase(ADVANCE, segment, wall, event),
    )


def after_phase(problem: Problem, mode, segment, radius, indentation, turned) -> Next:
    """The phase after an event; `radius` is the contact radius when the phase ended.

    Loading ends at a turnaround (hold, or unloading at once when the radius already sits on
    the detach edge, as in the reversible JKR law) or at a local maximum of the attach edge
    (outward cascade: snap-in). Hold ends when the edge spring reaches Δl (unloading), and
    unloading at a local minimum of the detach edge (inward cascade: snap-out or
    separation). An outward turnaround during hold or unloading is a capture.
    """
    law, attach, detach = problem.law, problem.attach, problem.detach
    advancing = mode == ADVANCE
    on_edge = indentation <= detach.level(law, radius) + _SAME_EDGE * (1.0 + jnp.abs(indentation))
    inward_start = jnp.where(mode == RECEDE, detach.nodes[segment], radius)
    inward_event = jnp.where(
        mode == HOLD,
        EVENT_CODE["detach_start"],
        jnp.where(mode == RECEDE, EVENT_CODE["snap_out"], EVENT_CODE["max_indentation"]),
    )
    inward = recede_from(problem, inward_start, indentation, inward_event)
    outward = advance_from(problem, attach.nodes[segment + 1], indentation, EVENT_CODE["snap_in"])
    hold = next_phase(HOLD, 0, radius, EVENT_CODE["max_indentation"])
    return where(
        advancing & ~turned,
        outward,
        where(advancing & ~on_edge, hold, where(~advancing & turned, capture(), inward)),
    )


def after_plastic_phase(advancing, turned, flowing: int) -> Next:
    """The phase after a ride of Thornton's plastic laws: loading turns into unloading or flows
    on (on segment `flowing`, where the ride had not flowed yet); unloading separates, or is
    captured where it turns (below the deepest state the elastic branches conserve energy)."""
    mode = jnp.where(advancing, jnp.where(turned, RECEDE, ADVANCE), jnp.where(turned, DONE, FLIGHT))
    event = jnp.where(
        advancing,
        jnp.where(turned, EVENT_CODE["max_indentation"], EVENT_CODE["yield"]),
        jnp.where(turned, EVENT_CODE["capture"], EVENT_CODE["separation"]),
    )
    return Next(
        mode=mode,
        segment=jnp.where(advancing & ~turned, flowing, 0),
        radius=jnp.zeros(()),
        event=event,
        separated=~advancing & ~turned,
        captured=~advancing & turned,
        stops=jnp.asarray(False),
        stop=Status.separated,
    )


def capture() -> Next:
    """An outward turnaround in contact: the body can never reach the separation point again.

    The contact dissipates on every closed path and gravity only pulls the body in, so from
    rest at d_turn it cannot come back out below d_turn with any kinetic energy left.
    """
    return next_phase(DONE, 0, 0.0, EVENT_CODE["capture"], captured=True)
