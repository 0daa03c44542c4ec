"""The literal MDR spring array, integrated exactly from one spring event to the next.

N springs of stiffness E*·Δx sit at the midpoints x_i = (i − ½)·Δx of [0, L]. With the k inner
springs attached the force is F = 2Δx·(k·d − S_k), S_k = Σ_{i≤k} g(x_i) (prefix sums: O(1) per
evaluation whatever N). Between two events the motion is therefore harmonic (or ballistic with
no spring attached) and is advanced in closed form; an event is the next spring reaching its
threshold: attach at d = h_attach(x_{k+1}) while moving in, detach at d = h_detach(x_k) while
moving out, each followed by the cascade of neighbours whose thresholds are already passed.
Time stepping adds no error: what differs from the continuum is the spatial discretisation
alone, which converges as N⁻².
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from . import transitions
from .outcome import Carry, Outcome, finish, initial_carry, log_event
from .phases import ADVANCE, DONE, EVENT_CODE, FLIGHT, RECEDE, RESULT_CODE
from .setup import Numerics, Problem, radius_bound

# Default array length: the body's extent, or this margin over the bound on the contact radius.
_LENGTH_MARGIN = 1.25


class SpringArray(eqx.Module):
    """Thresholds and prefix sums of the N springs (scaled units)."""

    spacing: jax.Array  # Δx
    attach_level: jax.Array  # [N] h_attach(x_i)
    detach_level: jax.Array  # [N] h_detach(x_i)
    prefix: jax.Array  # [N+1] S_k = Σ_{i≤k} g(x_i)
    beyond_level: jax.Array  # attach threshold of a spring just past the array (inf at a wall)

    @property
    def count(self) -> int:
        return self.attach_level.shape[0]

    def force(self, attached, indentation):
        """F = 2Δx·(k·d − S_k)."""
        return 2.0 * self.spacing * (attached * indentation - self.prefix[attached])

    def work(self, attached, start, end):
        """∫F dd over an arc with k springs attached (F linear in d)."""
        return self.spacing * (attached * (end**2 - start**2) - 2.0 * self.prefix[attached] * (end - start))

    def attach_cascade(self, attached, indentation):
        """Attach the next springs while their attach thresholds lie at or below d."""

        def more(k):
            return (k < self.count) & (self.attach_level[jnp.minimum(k, self.count - 1)] <= indentation)

        return jax.lax.while_loop(more, lambda k: k + 1, attached)

    def detach_cascade(self, attached, indentation):
        """Detach the edge springs while their detach thresholds lie at or above d."""

        def more(k):
            return (k > 0) & (self.detach_level[jnp.maximum(k - 1, 0)] >= indentation)

        return jax.lax.while_loop(more, lambda k: k - 1, attached)


def build_array(problem: Problem, count: int, length) -> SpringArray:
    """Midpoint springs on [0, L]; L is `length` (m) if given, else the default."""
    law = problem.law
    default = jnp.minimum(
        law.extent(), _LENGTH_MARGIN * radius_bound(law, problem.attach.coefficient, problem.touch_speed)[0]
    )
    scaled = jnp.where(jnp.isnan(length), default, length / problem.scales.radial)
    spacing = scaled / count
    positions = (jnp.arange(count) + 0.5) * spacing
    return SpringArray(
        spacing=spacing,
        attach_level=law.edge(positions, problem.attach.coefficient),
        detach_level=law.edge(positions, problem.detach.coefficient),
        prefix=jnp.concatenate([jnp.zeros(1), jnp.cumsum(law.g(positions))]),
        beyond_level=jnp.where(
            scaled >= law.extent(), jnp.inf, law.edge((count + 0.5) * spacing, problem.attach.coefficient)
        ),
    )


def _arc(attached, spacing, prefix, gravity, d, v, level, inward):
    """Advance the closed-form motion to `level` or to the turnaround, whichever comes first.

    Returns (duration, d, v, turned). With k springs: harmonic about d_eq, ω² = 2Δx·k;
    with none: constant acceleration (only while moving in).
    """
    k = attached.astype(d.dtype)
    omega = jnp.sqrt(2.0 * spacing * jnp.maximum(k, 1.0))
    balance = (2.0 * spacing * prefix[attached] + gravity) / omega**2
    offset = d - balance
    amplitude = jnp.sqrt(offset**2 + (v / omega) ** 2)
    target = level - balance
    phase = jnp.arctan2(-v / omega, offset)  # offset = A·cos θ, v = −Aω·sin θ
    direction = jnp.where(inward, -1.0, 1.0)  # inward: θ ∈ (−π, 0]; outward: θ ∈ [0, π]
    reachable = jnp.where(inward, target < amplitude, target > -amplitude)
    ratio = jnp.clip(target / jnp.where(amplitude > 0, amplitude, 1.0), -1.0, 1.0)
    level_angle = direction * jnp.arccos(ratio)
    turn_angle = jnp.where(inward, 0.0, jnp.pi)
    angle = jnp.where(reachable, level_angle, turn_angle)
    duration_harmonic = jnp.maximum((angle - jnp.where(inward, jnp.minimum(phase, 0.0), jnp.maximum(phase, 0.0))) / omega, 0.0)
    speed = omega * jnp.sqrt(jnp.maximum((amplitude - target) * (amplitude + target), 0.0))
    d_harmonic = jnp.where(reachable, level, balance - direction * amplitude)
    v_harmonic = jnp.where(reachable, -direction * speed, 0.0)

    # No spring attached (loading that starts at a = 0): ballistic until the first spring.
    rise = jnp.maximum(level - d, 0.0)
    arrival = jnp.sqrt(v**2 + 2.0 * gravity * rise)
    duration_free = 2.0 * rise / jnp.where(v + arrival > 0.0, v + arrival, 1.0)

    free = attached == 0
    # A threshold already passed in the direction of motion acts at once (cascades).
    passed = jnp.where(inward, level <= d, level >= d)
    return (
        jnp.where(passed, 0.0, jnp.where(free, duration_free, duration_harmonic)),
        jnp.where(passed, d, jnp.where(free, level, d_harmonic)),
        jnp.where(passed, v, jnp.where(free, arrival, v_harmonic)),
        ~passed & ~free & ~reachable,
    )


def land(problem: Problem, numerics: Numerics, array: SpringArray, c: Carry) -> Carry:
    """Analytic flight to the next touch, whose jump-in attaches every spring with its
    threshold at or below d = 0; ends the run at a bound, or when the body flies off."""
    duration, speed, reaches = transitions.flight_to_touch(problem, c.d, c.v)
    touch_time = c.t + duration
    over_bounces = c.contacts >= numerics.max_bounces
    over_time = touch_time > problem.time_limit
    lands = reaches & ~over_bounces & ~over_time
    attached = array.attach_cascade(jnp.zeros((), int), 0.0)
    status = jnp.where(
        ~reaches,
        RESULT_CODE["separated"],
        jnp.where(over_bounces, RESULT_CODE["bounce_limit"], RESULT_CODE["time_limit"]),
    )
    c = log_event(c, touch_time, EVENT_CODE["touch"], lands)
    c = log_event(c, c.t, EVENT_CODE["limit"], reaches & ~lands)
    first = c.contacts == 0
    force = array.force(attached, 0.0)
    return eqx.tree_at(
        lambda s: (s.t, s.d, s.v, s.mode, s.segment, s.contacts, s.status, s.touch_velocity,
                   s.touch_time, s.contact_work, s.max_force, s.min_force),
        c,
        (
            jnp.where(lands, touch_time, c.t),
            jnp.where(lands, 0.0, c.d),
            jnp.where(lands, speed, c.v),
            jnp.where(lands, ADVANCE, DONE),
            jnp.where(lands, attached, 0),
            c.contacts + jnp.asarray(lands, int),
            jnp.where(lands, c.status, status),
            jnp.where(lands & first, speed, c.touch_velocity),
            jnp.where(lands & first, touch_time, c.touch_time),
            jnp.zeros(()),
            jnp.where(lands, jnp.maximum(c.max_force, force), c.max_force),
            jnp.where(lands, jnp.minimum(c.min_force, force), c.min_force),
        ),
    )


def integrate(problem: Problem, numerics: Numerics, length) -> Outcome:
    """Run one impact (possibly several bounces) on the spring array."""
    array = build_array(problem, numerics.springs, length)
    count = array.count
    events_per_contact = 2 * count + 16
    max_events = numerics.max_bounces * events_per_contact + 16
    rows = numerics.samples_per_phase * numerics.max_phases
    stride = max(1, -(-events_per_contact // max(rows, 1)))

    def store(c: Carry, valid):
        if rows == 0:
            return c
        index = c.steps // stride
        keep = valid & (c.steps % stride == 0) & (index < rows)
        row = jnp.stack([c.t, c.d, c.v, array.force(c.segment, c.d), c.segment * array.spacing])
        target = jnp.minimum(index, rows - 1)
        trajectory = c.trajectory.at[target].set(jnp.where(keep, row, c.trajectory[target]))
        return eqx.tree_at(lambda s: s.trajectory, c, trajectory)

    def flight(c: Carry) -> Carry:
        c = land(problem, numerics, array, c)
        return store(c, c.mode == ADVANCE)

    def spring_event(c: Carry) -> Carry:
        k = c.segment
        inward = c.mode == ADVANCE
        beyond = k >= count
        next_attach = jnp.where(beyond, array.beyond_level, array.attach_level[jnp.minimum(k, count - 1)])
        edge_detach = array.detach_level[jnp.maximum(k - 1, 0)]
        level = jnp.where(inward, next_attach, edge_detach)
        duration, d, v, turned = _arc(k, array.spacing, array.prefix, problem.gravity, c.d, c.v, level, inward)
        work = array.work(k, c.d, d)
        t = c.t + duration
        out_of_time = t > problem.time_limit
        # What the event does to the contact.
        attached_more = array.attach_cascade(jnp.minimum(k + 1, count), d)
        detached = array.detach_cascade(k - 1, d)
        overflow = inward & ~turned & beyond  # the contact outgrew the array
        new_k = jnp.where(turned, k, jnp.where(inward, attached_more, detached))
        separated = ~inward & ~turned & (new_k == 0)
        captured = ~inward & turned
        mode = jnp.where(
            out_of_time,
            DONE,
            jnp.where(
                inward,
                jnp.where(turned, RECEDE, jnp.where(overflow, DONE, ADVANCE)),
                jnp.where(captured, DONE, jnp.where(separated, FLIGHT, RECEDE)),
            ),
        )
        first = c.contacts == 1
        contact_work = c.contact_work + work
        forces = jnp.stack([array.force(k, d), array.force(new_k, d)])
        status = jnp.where(
            out_of_time,
            RESULT_CODE["time_limit"],
            jnp.where(overflow, RESULT_CODE["radius_overflow"], jnp.where(captured, RESULT_CODE["captured"], c.status)),
        )
        c = log_event(c, t, EVENT_CODE["max_indentation"], inward & turned)
        c = log_event(c, t, EVENT_CODE["separation"], separated)
        c = log_event(c, t, EVENT_CODE["capture"], captured)
        c = eqx.tree_at(
            lambda s: (s.t, s.d, s.v, s.mode, s.segment, s.status, s.stuck, s.separation_velocity,
                       s.separation_time, s.max_indentation, s.max_force, s.min_force, s.contact_work,
                       s.first_contact_work, s.steps, s.accepted),
            c,
            (
                t, d, v, mode, new_k, status, captured,
                jnp.where(first & separated, jnp.abs(v), c.separation_velocity),
                jnp.where(first & separated, t, c.separation_time),
                jnp.maximum(c.max_indentation, d),
                jnp.maximum(c.max_force, jnp.max(forces)),
                jnp.minimum(c.min_force, jnp.min(forces)),
                contact_work,
                jnp.where(first & (separated | captured), contact_work, c.first_contact_work),
                c.steps + 1,
                c.accepted + 1,
            ),
        )
        return store(c, True)

    def running(c: Carry):
        return (c.mode != DONE) & (c.steps < max_events)

    def advance(c: Carry):
        return jax.lax.cond(c.mode == FLIGHT, flight, spring_event, c)

    return finish(jax.lax.while_loop(running, advance, initial_carry(problem, numerics)))
