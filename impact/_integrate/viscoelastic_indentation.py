"""An indentation test of a viscoelastic half-space at a rate: its program in time, on the spring
array of `_law.viscoelastic_springs` (no inertia: the indenter moves as the program says).

Each cycle loads at `rate` to the peak, holds it for `hold` seconds, and unloads at `rate` to
`unload_to` (the last cycle: until the contact is lost, the pull-off). Under displacement
control the indentation is linear in time on every leg, so the springs are advanced exactly
(any step: the steps only sample the curve). Under force control each step ends where the force
meets the program: the indentation at its end is found by bracketing and the Illinois method,
linear in time within the step (an error of second order in the step).

Units: lengths and forces of the relaxed medium at the program's peak (`quasistatic.setup.
loading_scales`), times in seconds.
"""

from dataclasses import dataclass

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.pytree import replace
from .._law.jkr import hess_coefficients
from .._law.law import ContactLaw
from .._law.viscoelastic import Viscoelastic
from .._law.viscoelastic_springs import SpringStates, ViscoelasticArray, spring_array
from .codes import Status, status_code
from .quasistatic.loading import EVENT, Loading
from .quasistatic.setup import loading_scales

# The array's default length: this margin over the radius of the relaxed, non-adhesive contact at
# the peak (the widest a rate-controlled test reaches without adhesion).
_LENGTH_MARGIN = 1.5
# Force control: doublings of the bracket around the step's indentation, then Illinois steps.
_BRACKET_DOUBLINGS = 60
_ILLINOIS_STEPS = 100
_SETTLED = 1e-14  # the bracket's width relative to the indentation
_EVENTS = 64


@dataclass(frozen=True)
class RateNumerics:
    """Static choices of a rate-controlled test (changing them recompiles)."""

    adhesive: bool
    capacity: int  # slots of the compiled array (the count, `Loading.spring_count`, is traced)
    force_control: bool
    cycles: int
    steps_per_leg: int = 200  # steps of each ramp and each hold
    pull_off_legs: int = 16  # the last unloading takes at most this many ramps' steps


class RateLoading(eqx.Module):
    """SI parameters of the test (traced)."""

    loading: Loading  # profile, E∞*, the law, the peak and unload_to (targets), the array's length
    rate: jax.Array  # m/s or N/s
    hold: jax.Array  # s


class RateOutcome(eqx.Module):
    """Scaled result of the test (times in s)."""

    status: jax.Array
    pull_off: jax.Array  # [3] a, d, F of the last state in contact
    rows: jax.Array  # [R, 5] a, d, F, leg, t (nan where unused)
    events: jax.Array  # [E, 2] row, kind
    steps: jax.Array
    top: jax.Array  # the radius the array covers


class _March(eqx.Module):
    springs: SpringStates
    t: jax.Array
    d: jax.Array
    force: jax.Array
    leg: jax.Array  # 0, 1, 2: load, hold, unload of cycle 0; 3, … of cycle 1
    step: jax.Array  # steps taken in this leg
    touched: jax.Array
    done: jax.Array
    status: Status
    pull_off: jax.Array
    rows: jax.Array
    count: jax.Array
    events: jax.Array
    event_count: jax.Array


def build_array(loading: Loading, numerics: RateNumerics):
    """(scales, the spring array) of the test."""
    law = loading.law
    assert isinstance(law, Viscoelastic), f"a rate-controlled test rides a Viscoelastic law, not {type(law).__name__}"
    scales = loading_scales(loading, numerics.adhesive)
    if numerics.adhesive:  # the relaxed medium's attach edge: the widest a loading reaches
        relaxed = hess_coefficients(law.work_of_adhesion, law.approach_work_of_adhesion, scales, loading.E_star)[1]
    else:
        relaxed = jnp.zeros(())
    elastic = ContactLaw(loading.profile, scales, jnp.zeros(()), relaxed, numerics.adhesive)
    # Where the relaxed contact reaches the peak: the edge h(a) = g(a) − λa·√a (displacement
    # control), F(a) = 2(a·g − G) without adhesion (force control).
    peak = loading.peak / jnp.where(loading.force_control, scales.force, scales.normal)
    grid = jnp.geomspace(1e-6, 1e6, 241)
    reached = jnp.where(loading.force_control, elastic.force(grid, elastic.g(grid)), elastic.edge(grid, relaxed))
    below = jnp.max(jnp.where(reached <= peak, jnp.arange(grid.shape[0]), 0))
    radius = grid[jnp.minimum(below + 1, grid.shape[0] - 1)]
    default = jnp.minimum(elastic.extent(), _LENGTH_MARGIN * radius)
    length = jnp.where(jnp.isnan(loading.spring_length), default, loading.spring_length / scales.radial)
    detach, attach = law.hess_lengths(scales, loading.E_star, numerics.adhesive)
    element = law.element(scales, loading.E_star)  # times in seconds: `loading_scales` keeps the test's clock
    count = loading.spring_count
    return scales, spring_array(element, elastic.g, length, count, numerics.capacity, detach, attach)


def march_at_rate(program: RateLoading, numerics: RateNumerics):
    """Run the test: (scales, `RateOutcome`)."""
    loading = program.loading
    scales, array = build_array(loading, numerics)
    unit = jnp.where(loading.force_control, scales.force, scales.normal)
    plan = _Program(
        array=array,
        rate=program.rate / unit,
        peak=loading.peak / unit,
        targets=loading.targets / unit,
        hold=program.hold,
        numerics=numerics,
    )
    rows = (3 * numerics.cycles + numerics.pull_off_legs) * numerics.steps_per_leg
    zero = jnp.zeros(())
    start = _March(
        springs=SpringStates.virgin(numerics.capacity, array.element.moduli.shape[-1]),
        t=zero,
        d=zero,
        force=zero,
        leg=jnp.zeros((), int),
        step=jnp.zeros((), int),
        touched=jnp.asarray(False),
        done=jnp.asarray(False),
        status=Status.separated,
        pull_off=jnp.full(3, jnp.nan),
        rows=jnp.full((rows, 5), jnp.nan),
        count=jnp.zeros((), int),
        events=jnp.full((_EVENTS, 2), -1),
        event_count=jnp.zeros((), int),
    )
    end = jax.lax.while_loop(lambda march: ~march.done, lambda march: plan.step(march), start)
    outcome = RateOutcome(
        status=status_code(end.status),
        pull_off=end.pull_off,
        rows=end.rows,
        events=end.events,
        steps=end.count,
        top=array.spacing * array.count,
    )
    return scales, outcome


class _Program(eqx.Module):
    """The program in the units of the test (lengths or forces scaled, times in s): legs 3c,
    3c + 1, 3c + 2 load, hold and unload cycle c."""

    array: ViscoelasticArray
    rate: jax.Array  # per s
    peak: jax.Array
    targets: jax.Array  # [2·cycles…] the peak and unload_to of each cycle (−inf: to pull-off)
    hold: jax.Array  # s
    numerics: RateNumerics = eqx.field(static=True)

    def leg(self, march: _March):
        """(direction, duration of a step, steps of the leg, ends at pull-off) of its leg."""
        numerics, targets = self.numerics, self.targets
        cycle, part = march.leg // 3, march.leg % 3
        unload_to = targets[2 * cycle + 1]
        to_pull_off = (part == 2) & ((cycle == numerics.cycles - 1) | ~jnp.isfinite(unload_to))
        low = jnp.where(cycle > 0, targets[jnp.maximum(2 * cycle - 1, 0)], 0.0)
        low = jnp.where(jnp.isfinite(low), low, 0.0)
        span = jnp.where(part == 0, self.peak - low, jnp.where(part == 2, self.peak - unload_to, 0.0))
        ramp = self.peak / self.rate
        duration = jnp.where(part == 1, self.hold, jnp.where(to_pull_off, ramp, span / self.rate))
        direction = jnp.where(part == 0, 1.0, jnp.where(part == 1, 0.0, -1.0))
        steps = jnp.where(to_pull_off, numerics.pull_off_legs * numerics.steps_per_leg, numerics.steps_per_leg)
        return direction, duration / numerics.steps_per_leg, steps, to_pull_off

    def step(self, march: _March) -> _March:
        """One step of the program, its point and its events."""
        array, force_control = self.array, self.numerics.force_control
        direction, h, steps, to_pull_off = self.leg(march)
        target = march.force + direction * self.rate * h
        if force_control:
            d = _indentation_at(array, march.springs, march.d, h, jnp.maximum(target, 0.0))
        else:
            d = march.d + direction * self.rate * h
        springs, _ = array.advance(march.springs, march.d, (d - march.d) / jnp.where(h > 0, h, 1.0), h)
        force = array.force(springs)
        contact = jnp.any(springs.attached)
        lost = march.touched & to_pull_off & (~contact | ((target <= 0.0) if force_control else False))
        last_contact = jnp.stack([array.contact_radius(march.springs), march.d, march.force])
        leg_done = (march.step + 1 >= steps) | (h == 0.0)
        exhausted = leg_done & to_pull_off & ~lost
        overflow = array.overflows(springs)
        next_leg = march.leg + jnp.asarray(leg_done, int)
        done = lost | exhausted | overflow | (next_leg >= 3 * self.numerics.cycles)
        # The program's legs as a quasi-static test numbers them: 0 the first loading (and its hold),
        # 1 the first unloading, … (a force-controlled contact lost at F = 0 adds no point).
        leg = 2 * (march.leg // 3) + jnp.asarray(march.leg % 3 == 2, int)
        row = jnp.stack([array.contact_radius(springs), d, force, leg.astype(d.dtype), march.t + h])
        written = ~lost if force_control else jnp.asarray(True)
        index = jnp.where(written, march.count, march.rows.shape[0])
        march = replace(march, rows=march.rows.at[index].set(row, mode="drop"), count=march.count + written)
        march = _log(march, EVENT["touch"], ~march.touched & contact)
        march = _log(march, EVENT["reversal"], leg_done & (march.leg % 3 > 0) & ~done)
        march = _log(march, EVENT["pull_off"], lost)
        status = Status.where(
            overflow, Status.radius_overflow, Status.where(exhausted, Status.phase_limit, march.status)
        )
        return replace(
            march,
            springs=springs,
            t=march.t + h,
            d=d,
            force=force,
            leg=next_leg,
            step=jnp.where(leg_done, 0, march.step + 1),
            touched=march.touched | contact,
            done=done,
            status=status,
            pull_off=jnp.where(lost, last_contact, march.pull_off),
        )


def _log(march: _March, kind: int, valid) -> _March:
    """An event at the last row written, where `valid`."""
    slot = jnp.where(valid & (march.event_count < _EVENTS), march.event_count, _EVENTS)
    events = march.events.at[slot].set(jnp.stack([march.count - 1, jnp.asarray(kind)]), mode="drop")
    return replace(march, events=events, event_count=march.event_count + jnp.asarray(valid, int))


def _indentation_at(array: ViscoelasticArray, springs: SpringStates, start, duration, target):
    """The indentation at the end of a step of `duration` from `start` (linear in between) where
    the force meets `target` (the force rises with it: no adhesion): a bracket doubled about
    `start`, then the Illinois method."""

    def excess(d):
        moved, _ = array.advance(springs, start, (d - start) / duration, duration)
        return array.force(moved) - target

    def widen(bracket):
        low, high, width, steps = bracket
        low = jnp.where(excess(low) > 0.0, start - width, low)
        high = jnp.where(excess(high) < 0.0, start + width, high)
        return low, high, 2.0 * width, steps + 1

    def open_(bracket):
        low, high, _, steps = bracket
        return ((excess(low) > 0.0) | (excess(high) < 0.0)) & (steps < _BRACKET_DOUBLINGS)

    width = jnp.maximum(jnp.abs(start), 1e-3)
    low, high, _, _ = jax.lax.while_loop(open_, widen, (start, start + width, width, 0))

    def illinois(_, state):
        low, high, f_low, f_high, side = state
        middle = (low * f_high - high * f_low) / (f_high - f_low)
        middle = jnp.where((middle > low) & (middle < high), middle, 0.5 * (low + high))
        f_middle = excess(middle)
        above = f_middle > 0.0
        f_low = jnp.where(above & (side == -1), 0.5 * f_low, f_low)
        f_high = jnp.where(~above & (side == 1), 0.5 * f_high, f_high)
        return (
            jnp.where(above, low, middle),
            jnp.where(above, middle, high),
            jnp.where(above, f_low, f_middle),
            jnp.where(above, f_middle, f_high),
            jnp.where(above, -1, 1),
        )

    def open_bracket(state):
        low, high, _, _, _, steps = state
        return (high - low > _SETTLED * jnp.maximum(jnp.abs(high), jnp.abs(low))) & (steps < _ILLINOIS_STEPS)

    def counted(state):
        return (*illinois(None, state[:5]), state[5] + 1)

    state = (low, high, excess(low), excess(high), jnp.zeros((), int), jnp.zeros((), int))
    low, high, f_low, f_high, _, _ = jax.lax.while_loop(open_bracket, counted, state)
    return jnp.where(jnp.abs(f_low) < jnp.abs(f_high), low, high)
