"""The literal MDR spring array, integrated exactly from one spring event to the next.

N springs of stiffness E*·Δx sit at the midpoints x_i = (i − ½)·Δx of [0, L]. With the k inner
springs attached the force is F = 2Δx·(k·d − S_k), S_k = Σ_{i≤k} g(x_i). Nothing of size N is
stored: a spring's thresholds come from the law when asked (`ComputedSpringArray`), and S_k is
a running sum carried with k (`Attached`), updated with compensated summation as springs attach
and detach, so memory and the cost of an event are independent of N (and N may be traced: one
compilation serves every N). Between two events the motion is harmonic (or ballistic with no
spring attached) and is advanced in closed form; an event is the next spring reaching its
threshold: attach at d = h_attach(x_{k+1}) while moving in, detach at d = h_detach(x_k) while
moving out, each followed by the cascade of neighbours whose thresholds are already passed.
Time stepping adds no error: what differs from the continuum is the spatial discretisation
alone, which converges as N⁻².
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from . import transitions
from .._law.law import ContactLaw
from .carry import Carry, Outcome, finish, initial_carry, log_event
from .codes import ADVANCE, DONE, EVENT_CODE, FLIGHT, RECEDE, RESULT_CODE
from .problem import Numerics, Problem, radius_bound

# Default array length: the body's extent, or this margin over the bound on the contact radius.
_LENGTH_MARGIN = 1.25


class Attached(eqx.Module):
    """The k inner springs in contact and S_k = Σ_{i≤k} g(x_i) (scaled units).

    S_k is summed as springs attach and detach, compensated (Kahan–Babuška–Neumaier): `total`
    holds the rounded sum and `compensation` the round-off it lost, so S_k = total + compensation
    stays within an ulp or so of the exact sum over millions of events.
    """

    count: jax.Array  # k
    total: jax.Array
    compensation: jax.Array

    @staticmethod
    def none() -> "Attached":
        return Attached(jnp.zeros((), int), jnp.zeros(()), jnp.zeros(()))

    def profile_sum(self):
        """S_k."""
        return self.total + self.compensation

    def changed(self, step, term) -> "Attached":
        """k + step springs, S_k + term; back to an exact 0 once no spring is left."""
        total = self.total + term
        lost = jnp.where(
            jnp.abs(self.total) >= jnp.abs(term), (self.total - total) + term, (term - total) + self.total
        )
        count = self.count + step
        empty = count == 0
        return Attached(count, jnp.where(empty, 0.0, total), jnp.where(empty, 0.0, self.compensation + lost))


class SpringArray(eqx.Module):
    """Tabulated thresholds and prefix sums of N springs (scaled units, O(N) memory): the
    quasi-static march (`quasistatic`) pads them to a compiled capacity. The impact integrators
    use `ComputedSpringArray`, which stores nothing of size N."""

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


class ComputedSpringArray(eqx.Module):
    """N midpoint springs on [0, L] (scaled units); thresholds and g(x_i) are evaluated when
    needed, so nothing of size N is stored."""

    law: ContactLaw
    attach_coefficient: jax.Array  # λa of the attach edge h_attach
    detach_coefficient: jax.Array  # λ of the detach edge h_detach
    spacing: jax.Array  # Δx
    count: jax.Array  # N (an integer; may be traced)
    beyond_level: jax.Array  # attach threshold of a spring just past the array (inf at a wall)

    def position(self, index):
        """x of the spring at 0-based `index`: (index + ½)·Δx."""
        return (index + 0.5) * self.spacing

    def frontier(self, count, inward):
        """0-based index of the spring that changes next: k + 1 attaches moving in, k detaches
        moving out (spring 1 when none is attached)."""
        return jnp.where(inward, count, jnp.maximum(count - 1, 0))

    def next_level(self, count, inward):
        """Threshold of that spring: h_attach(x_{k+1}) moving in, h_detach(x_k) moving out."""
        coefficient = jnp.where(inward, self.attach_coefficient, self.detach_coefficient)
        return self.law.edge(self.position(self.frontier(count, inward)), coefficient)

    def change(self, attached: Attached, inward) -> Attached:
        """Attach spring k + 1 (moving in) or detach spring k (moving out)."""
        step = jnp.where(inward, 1, -1)
        return attached.changed(step, step * self.law.g(self.position(self.frontier(attached.count, inward))))

    def force(self, attached: Attached, indentation):
        """F = 2Δx·(k·d − S_k)."""
        return 2.0 * self.spacing * (attached.count * indentation - attached.profile_sum())

    def work(self, attached: Attached, start, end):
        """∫F dd over an arc with k springs attached (F linear in d)."""
        return self.spacing * (
            attached.count * (end**2 - start**2) - 2.0 * attached.profile_sum() * (end - start)
        )

    def cascade(self, attached: Attached, indentation, inward) -> Attached:
        """Moving in, attach the next springs while their attach thresholds lie at or below d;
        moving out, detach the edge springs while their detach thresholds lie at or above d."""

        def more(a: Attached):
            level = self.next_level(a.count, inward)
            return jnp.where(
                inward, (a.count < self.count) & (level <= indentation), (a.count > 0) & (level >= indentation)
            )

        return jax.lax.while_loop(more, lambda a: self.change(a, inward), attached)


def build_array(problem: Problem, count, length) -> ComputedSpringArray:
    """N = `count` midpoint springs on [0, L]; L is `length` (m) if given, else the default."""
    law = problem.law
    default = jnp.minimum(
        law.extent(), _LENGTH_MARGIN * radius_bound(law, problem.attach.coefficient, problem.touch_speed)[0]
    )
    scaled = jnp.where(jnp.isnan(length), default, length / problem.scales.radial)
    spacing = scaled / count
    return ComputedSpringArray(
        law=law,
        attach_coefficient=problem.attach.coefficient,
        detach_coefficient=problem.detach.coefficient,
        spacing=spacing,
        count=jnp.asarray(count),
        beyond_level=jnp.where(
            scaled >= law.extent(), jnp.inf, law.edge((count + 0.5) * spacing, problem.attach.coefficient)
        ),
    )


def _arc(attached: Attached, spacing, gravity, d, v, level, inward):
    """Advance the closed-form motion to `level` or to the turnaround, whichever comes first.

    Returns (duration, d, v, turned). With k springs: harmonic about d_eq, ω² = 2Δx·k;
    with none: constant acceleration (only while moving in).
    """
    k = attached.count.astype(d.dtype)
    omega = jnp.sqrt(2.0 * spacing * jnp.maximum(k, 1.0))
    balance = (2.0 * spacing * attached.profile_sum() + gravity) / omega**2
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

    free = attached.count == 0
    # A threshold already passed in the direction of motion acts at once (cascades).
    passed = jnp.where(inward, level <= d, level >= d)
    return (
        jnp.where(passed, 0.0, jnp.where(free, duration_free, duration_harmonic)),
        jnp.where(passed, d, jnp.where(free, level, d_harmonic)),
        jnp.where(passed, v, jnp.where(free, arrival, v_harmonic)),
        ~passed & ~free & ~reachable,
    )


def land(
    problem: Problem, numerics: Numerics, array: ComputedSpringArray, c: Carry
) -> tuple[Carry, Attached]:
    """Analytic flight to the next touch, whose jump-in attaches every spring with its
    threshold at or below d = 0; ends the run at a bound, or when the body flies off.
    Returns the carry and the springs attached (none unless it lands)."""
    duration, speed, reaches = transitions.flight_to_touch(problem, c.d, c.v)
    touch_time = c.t + duration
    over_bounces = c.contacts >= numerics.max_bounces
    over_time = touch_time > problem.time_limit
    lands = reaches & ~over_bounces & ~over_time
    jump_in = array.cascade(Attached.none(), 0.0, True)
    status = jnp.where(
        ~reaches,
        RESULT_CODE["separated"],
        jnp.where(over_bounces, RESULT_CODE["bounce_limit"], RESULT_CODE["time_limit"]),
    )
    c = log_event(c, touch_time, EVENT_CODE["touch"], lands)
    c = log_event(c, c.t, EVENT_CODE["limit"], reaches & ~lands)
    first = c.contacts == 0
    force = array.force(jump_in, 0.0)
    c = eqx.tree_at(
        lambda s: (s.t, s.d, s.v, s.mode, s.contacts, s.status, s.touch_velocity,
                   s.touch_time, s.contact_work, s.max_force, s.min_force),
        c,
        (
            jnp.where(lands, touch_time, c.t),
            jnp.where(lands, 0.0, c.d),
            jnp.where(lands, speed, c.v),
            jnp.where(lands, ADVANCE, DONE),
            c.contacts + jnp.asarray(lands, int),
            jnp.where(lands, c.status, status),
            jnp.where(lands & first, speed, c.touch_velocity),
            jnp.where(lands & first, touch_time, c.touch_time),
            jnp.zeros(()),
            jnp.where(lands, jnp.maximum(c.max_force, force), c.max_force),
            jnp.where(lands, jnp.minimum(c.min_force, force), c.min_force),
        ),
    )
    return c, jax.tree.map(lambda a, b: jnp.where(lands, a, b), jump_in, Attached.none())


def integrate(problem: Problem, numerics: Numerics, length, count) -> Outcome:
    """Run one impact (possibly several bounces) on an array of `count` springs (N may be
    traced: one compilation serves every N)."""
    array = build_array(problem, count, length)
    events_per_contact = 2 * array.count + 16
    max_events = numerics.max_bounces * events_per_contact + 16
    rows = numerics.samples_per_phase * numerics.max_phases
    stride = jnp.maximum(1, -(-events_per_contact // max(rows, 1)))

    def store(c: Carry, attached: Attached, valid):
        if rows == 0:
            return c
        index = c.steps // stride
        keep = valid & (c.steps % stride == 0) & (index < rows)
        row = jnp.stack([c.t, c.d, c.v, array.force(attached, c.d), attached.count * array.spacing])
        target = jnp.minimum(index, rows - 1)
        trajectory = c.trajectory.at[target].set(jnp.where(keep, row, c.trajectory[target]))
        return eqx.tree_at(lambda s: s.trajectory, c, trajectory)

    def flight(state):
        return land(problem, numerics, array, state[0])

    def spring_event(state):
        c, attached = state
        k = attached.count
        inward = c.mode == ADVANCE
        beyond = k >= array.count
        level = jnp.where(inward & beyond, array.beyond_level, array.next_level(k, inward))
        duration, d, v, turned = _arc(attached, array.spacing, problem.gravity, c.d, c.v, level, inward)
        work = array.work(attached, c.d, d)
        t = c.t + duration
        out_of_time = t > problem.time_limit
        # What the event does to the contact: unless it turned, d sits on the threshold of the
        # event's own spring, so that spring leads its cascade.
        now = jax.tree.map(lambda old, new: jnp.where(turned, old, new), attached, array.cascade(attached, d, inward))
        overflow = inward & ~turned & beyond  # the contact outgrew the array
        separated = ~inward & ~turned & (now.count == 0)
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
        forces = jnp.stack([array.force(attached, d), array.force(now, d)])
        status = jnp.where(
            out_of_time,
            RESULT_CODE["time_limit"],
            jnp.where(overflow, RESULT_CODE["radius_overflow"], jnp.where(captured, RESULT_CODE["captured"], c.status)),
        )
        c = log_event(c, t, EVENT_CODE["max_indentation"], inward & turned)
        c = log_event(c, t, EVENT_CODE["separation"], separated)
        c = log_event(c, t, EVENT_CODE["capture"], captured)
        c = eqx.tree_at(
            lambda s: (s.t, s.d, s.v, s.mode, s.status, s.stuck, s.separation_velocity,
                       s.separation_time, s.max_indentation, s.max_force, s.min_force, s.contact_work,
                       s.first_contact_work, s.steps, s.accepted),
            c,
            (
                t, d, v, mode, status, captured,
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
        return c, now

    def running(state):
        c, _ = state
        return (c.mode != DONE) & (c.steps < max_events)

    def advance(state):
        flying = state[0].mode == FLIGHT
        c, attached = jax.lax.cond(flying, flight, spring_event, state)
        # A flight stores the touch it lands with; every spring event is stored.
        return store(c, attached, ~flying | (c.mode == ADVANCE)), attached

    c, _ = jax.lax.while_loop(running, advance, (initial_carry(problem, numerics), Attached.none()))
    return finish(c)
