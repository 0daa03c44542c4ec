"""The literal MDR spring array without an event loop (`solver.method: quadrature` with
`contact.springs: N`): each contact computed whole from prefix sums over the springs.

The array's law is rate-independent and piecewise linear in d (`springs`): with k springs
attached F = 2Δx·(k·d − S_k). Moving in, spring i attaches once d reaches the running maximum
M_i = max_{j≤i} h_attach(x_j) (a cascade where a threshold is already passed), so the attached
count is a step function of d alone, with steps at the M_i: the loading segment of k springs
spans [M_{k−1}, M_k] (clamped to d ≥ 0; empty for the springs of the jump-in and of a cascade).
Its work is closed-form (F linear in d), so v² at every segment's end is one prefix sum,
v² = v₀² − 2Σ∫F dd + 2g·d, and the harmonic arc of each whole segment (ballistic with no
spring attached) is timed from its two ends at once (`_durations`). The potential is convex on a
segment (quadratic, k ≥ 0), so the turnaround lies in the first segment whose end the body does
not reach; its arc, and a capture's, are the event loop's (`springs._arc`). Moving out,
spring j (of the k* attached at the turnaround) detaches once d falls to the suffix minimum
m_j = min_{j≤i<k*} h_detach(x_i) (the rule of Heß, (3.26), its cascades), so unloading is the
same construction in reverse: the body separates at m_0 or is captured in the first segment
(the largest count) whose lower end it does not reach. Flights between contacts (gravity,
bounces) are the analytic ones of every integrator.

The result is the event loop's (`SpringArray`) to round-off: the same harmonic arcs, with the
speed at each event from the energy balance instead of the previous arc. The cost is O(N) vector work per
contact with no sequential dependence; N may still be traced, up to the compiled `capacity`.
Trajectory rows are the states after the events of a contact, `samples_per_phase` of them
evenly spaced in event order (the event loop stores every event, strided to its buffer).
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.pytree import replace
from .._law.springs import Attached, ComputedSpringArray
from .carry import Carry, Outcome, finish, initial_carry, log_event, record_contact, store_samples
from .codes import ADVANCE, DONE, EVENT_CODE, FLIGHT, Status
from .flight import land
from .problem import Options, Problem
from .springs import AbstractSpringArrayIntegrator, SpringArrayProblem, _arc
from .transitions import next_phase
from .work import ContactSummary


class SpringQuadrature(AbstractSpringArrayIntegrator):
    """The spring array with each contact computed whole from prefix sums over its springs;
    N (`Physics.spring_count`, traced) must not exceed `capacity` (else `branch_overflow`)."""

    capacity: int = eqx.field(static=True)  # spring slots compiled

    def integrate(self, problem: SpringArrayProblem, options: Options) -> Outcome:
        inner, array = problem.problem, problem.array
        table = loading_table(array, self.capacity)
        touch = next_phase(ADVANCE, 0, 0.0, EVENT_CODE["touch"])

        def flight(c: Carry) -> Carry:
            return land(inner, options, c, 0.0, touch, table.jump_in_force(array), samples=True)

        def contact(c: Carry) -> Carry:
            return _contact(inner, options, array, table, c)

        def running(c: Carry):
            return (c.mode != DONE) & (c.phases < options.max_phases)

        def turn(c: Carry) -> Carry:  # a contact and the flight after it: one turn a bounce
            c = jax.lax.cond(c.mode == ADVANCE, contact, lambda c: c, c)
            return jax.lax.cond(c.mode == FLIGHT, flight, lambda c: c, c)

        start = initial_carry(inner, options)
        start = jax.lax.cond(start.mode == FLIGHT, flight, lambda c: c, start)
        if not options.gravity:  # one contact at most: the flight after it never lands
            return finish(turn(start))
        return finish(jax.lax.while_loop(running, turn, start))


class LoadingTable(eqx.Module):
    """What loading does at every attached count k = 0..C (C = the capacity), scaled units:
    S_k and the segment [lower_k, upper_k] of d over which k springs are attached moving in;
    the detach threshold of every spring (inf past N)."""

    count: jax.Array  # N
    prefix: jax.Array  # [C+1] S_k = Σ_{i<k} g(x_i)
    lower: jax.Array  # [C+1] max(0, M_{k−1})
    upper: jax.Array  # [C+1] max(0, M_k); M_N includes the threshold just past the array
    detach: jax.Array  # [C] h_detach(x_i), inf for i ≥ N
    jump_in: jax.Array  # springs attached at the touch (attach threshold ≤ 0)

    def jump_in_force(self, array: ComputedSpringArray):
        """F at the touch, d = 0: −2Δx·S_k of the jump-in."""
        return -2.0 * array.spacing * self.prefix[self.jump_in]


def loading_table(array: ComputedSpringArray, capacity: int) -> LoadingTable:
    """The table of `array` over `capacity` slots (N = `array.count` of them real)."""
    index = jnp.arange(capacity + 1)
    real = index < array.count
    x = array.position(jnp.minimum(index, array.count - 1))  # the real springs' positions only
    g = jnp.where(real, array.law.g(x), 0.0)
    attach = jnp.where(
        real,
        array.law.edge(x, array.attach_coefficient),
        jnp.where(index == array.count, array.beyond_level, jnp.inf),
    )
    rising = _running(jnp.maximum, attach)  # M_k: a threshold below an inner one's attaches in its cascade
    below = jnp.concatenate([jnp.full(1, -jnp.inf), rising[:-1]])
    return LoadingTable(
        count=array.count,
        prefix=jnp.concatenate([jnp.zeros(1), _running(jnp.add, g[:-1])]),
        lower=jnp.maximum(below, 0.0),
        upper=jnp.maximum(rising, 0.0),
        detach=jnp.where(real, array.law.edge(x, array.detach_coefficient), jnp.inf)[:-1],
        jump_in=jnp.sum(real & (rising <= 0.0)),
    )


def _running(combine, values, reverse: bool = False):
    """The running `combine` (jnp.add, jnp.maximum, …) of a 1-D array, first to last (last to
    first with `reverse`): a sequential scan, the same in any batch, and under vmap cheaper on
    XLA:CPU than `jnp.cumsum`'s or `lax.cummax`'s logarithmic scans."""

    def step(total, value):
        total = combine(total, value)
        return total, total

    if reverse:
        return jnp.append(jax.lax.scan(step, values[-1], values[:-1], reverse=True)[1], values[-1])
    return jnp.concatenate([values[:1], jax.lax.scan(step, values[0], values[1:])[1]])


# Halvings of the angle before its Taylor series (tan of the angle then ≤ tan(π/32) < 0.0985),
# and the series' odd terms: the next one is below 1e-21 of the angle.
_HALVINGS = 3
_SERIES_TERMS = 10


def angle(y, x):
    """atan2(y, x) in elementwise arithmetic that XLA vectorises (square roots, divisions, a
    polynomial), within a few ulps of `jnp.arctan2`, which XLA:CPU evaluates element by element
    (the largest cost of a contact here). atan t for t = min/max(|x|, |y|) ∈ [0, 1] by
    `_HALVINGS` halvings atan t = 2·atan(t/(1 + √(1 + t²))) and its Taylor series, then the
    octant."""
    across, along = jnp.abs(y), jnp.abs(x)
    steep = across > along
    larger = jnp.where(steep, across, along)
    tangent = jnp.where(steep, along, across) / jnp.where(larger > 0.0, larger, 1.0)
    for _ in range(_HALVINGS):
        tangent = tangent / (1.0 + jnp.sqrt(1.0 + tangent * tangent))
    square = tangent * tangent
    series = jnp.zeros_like(tangent)
    for term in reversed(range(_SERIES_TERMS)):
        series = (-1.0) ** term / (2 * term + 1) + square * series
    base = 2.0**_HALVINGS * tangent * series
    base = jnp.where(steep, 0.5 * jnp.pi - base, base)
    base = jnp.where(x < 0.0, jnp.pi - base, base)
    return jnp.where(y < 0.0, -base, base)


def _total(values):
    """Σ of a 1-D array by a fixed pairwise tree of elementwise adds (the same in any batch, as
    `jnp.sum`'s reduce is not on XLA:CPU)."""
    size = 1 << (values.shape[0] - 1).bit_length()
    values = jnp.pad(values, (0, size - values.shape[0]))
    while values.shape[0] > 1:
        half = values.shape[0] // 2
        values = values[:half] + values[half:]
    return values[0]


def _attached(counts, prefix) -> Attached:
    """k springs with S_k, elementwise over arrays of counts."""
    return Attached(counts, prefix, jnp.zeros_like(prefix))


def _durations(attached: Attached, spacing, gravity, start, end):
    """Durations of whole arcs from `start` = (d, v) to `end` = (d, v) (arrays of segments): the
    angle swept in the phase plane of the harmonic motion with k springs, (x, y) = (d − d_eq,
    −v/ω) = A·(cos θ, sin θ), is atan2 of the cross and dot products of its ends, over ω; both
    products are taken times ω⁴, with ω²·(d − d_eq) = F(d) − g, so that no division is needed
    but the last. With no spring attached, the ballistic 2·(d₁ − d₀)/(v₀ + v₁)."""
    k = attached.count.astype(spacing.dtype)
    stiffness = 2.0 * spacing * jnp.maximum(k, 1.0)  # ω²
    omega = jnp.sqrt(stiffness)
    (d0, v0), (d1, v1) = start, end
    load = 2.0 * spacing * attached.profile_sum() + gravity  # ω²·d_eq
    x0, x1 = stiffness * d0 - load, stiffness * d1 - load
    harmonic = angle(omega * (v0 * x1 - x0 * v1), x0 * x1 + stiffness * v0 * v1) / omega
    sum_speed = v0 + v1
    free = 2.0 * (d1 - d0) / jnp.where(sum_speed != 0.0, sum_speed, 1.0)
    return jnp.where(attached.count == 0, free, harmonic)


def _contact(problem: Problem, options: Options, array: ComputedSpringArray, table: LoadingTable, c: Carry) -> Carry:
    """One contact from its touch (d = 0, v > 0) to separation, capture or overflow."""
    gravity, spacing = problem.motion.gravity, array.spacing
    capacity = table.detach.shape[0]
    counts = jnp.arange(capacity + 1)
    loaded = _attached(counts, table.prefix)

    # Loading: v² at each segment's upper end by the prefix sum of the segments' work; the
    # turnaround lies in the first segment whose end the body does not reach.
    lower, upper = table.lower, table.upper
    spans = (upper > lower) & jnp.isfinite(upper)
    work_in = jnp.where(spans, array.work(loaded, lower, jnp.where(spans, upper, lower)), 0.0)
    prefix_in = jnp.concatenate([jnp.zeros(1), _running(jnp.add, work_in)])
    squared_up = c.v**2 - 2.0 * prefix_in[1:] + 2.0 * gravity * jnp.where(spans, upper, lower)
    reached = (squared_up > 0.0) & jnp.isfinite(upper) & (counts <= table.count)
    first = jnp.argmax(jnp.concatenate([~reached, jnp.ones(1, bool)]))
    overflow = first > table.count  # the contact outgrew the array
    top = jnp.minimum(first, table.count)  # k*, the count at the turnaround (N at an overflow)
    speed_up = jnp.sqrt(jnp.maximum(squared_up, 0.0))
    speed_low = jnp.concatenate([c.v[None], speed_up[:-1]])
    whole_in = (counts < first) & spans
    duration_in = jnp.where(whole_in, _durations(loaded, spacing, gravity, (lower, speed_low), (upper, speed_up)), 0.0)
    # The turnaround's own arc, as the event loop takes it.
    last_in = _attached(top, table.prefix[top])
    turn_arc, turn_depth, _, _ = _arc(last_in, spacing, gravity, lower[top], speed_low[top], upper[top], True)
    deepest = jnp.where(overflow, upper[top], turn_depth)
    speed_in = jnp.where(overflow, speed_up[top], 0.0)
    turn_time = c.t + _total(duration_in) + jnp.where(overflow, 0.0, turn_arc)
    loading = counts <= top
    end_in = jnp.where(counts == top, deepest, upper)
    spans_in = loading & (end_in > lower)
    work_load = prefix_in[top] + array.work(last_in, lower[top], jnp.maximum(deepest, lower[top]))

    # Unloading from (deepest, 0) with the k* springs: spring j is attached while d > m_j; the
    # body is captured in the first segment (the largest count) whose lower end it does not reach.
    held = counts[:-1] < top
    floor = _running(jnp.minimum, jnp.where(held, table.detach, jnp.inf), reverse=True)  # m_j, j = 0..C−1
    upper_out = jnp.minimum(deepest, jnp.concatenate([floor[1:], jnp.full(1, jnp.inf)]))  # k = 1..C
    lower_out = jnp.minimum(deepest, floor)
    unloaded = _attached(counts[1:], table.prefix[1:])
    spans_out = lower_out < upper_out
    work_out = jnp.where(spans_out, array.work(unloaded, upper_out, jnp.where(spans_out, lower_out, upper_out)), 0.0)
    below_work = _running(jnp.add, work_out, reverse=True)  # ∫F dd from the turnaround down to m_{k−1}
    squared_low = -2.0 * below_work + 2.0 * gravity * (lower_out - deepest)
    stopped = spans_out & (squared_low <= 0.0) & ~overflow
    captured = jnp.any(stopped)
    last = jnp.where(captured, jnp.max(jnp.where(stopped, counts[1:], 0)), 1)  # the count at the end
    speed_low_out = -jnp.sqrt(jnp.maximum(squared_low, 0.0))
    speed_up_out = jnp.concatenate([speed_low_out[1:], jnp.zeros(1)])
    whole_out = (counts[1:] > last) | ((counts[1:] == last) & ~captured)
    whole_out = whole_out & spans_out & ~overflow
    duration_out = jnp.where(
        whole_out, _durations(unloaded, spacing, gravity, (upper_out, speed_up_out), (lower_out, speed_low_out)), 0.0
    )
    last_out = _attached(last, table.prefix[last])
    capture_arc, capture_depth, _, _ = _arc(
        last_out,
        spacing,
        gravity,
        upper_out[last - 1],
        speed_up_out[last - 1],
        lower_out[last - 1],
        False,
    )
    end_time = turn_time + _total(duration_out) + jnp.where(captured, capture_arc, 0.0)
    unloading = ~overflow & (counts[1:] >= last)
    end_out = jnp.where((counts[1:] == last) & captured, capture_depth, lower_out)
    spans_back = unloading & (end_out < upper_out)
    work_unload = jnp.where(
        overflow,
        0.0,
        below_work[last - 1] - work_out[last - 1] + array.work(last_out, upper_out[last - 1], end_out[last - 1]),
    )
    separated = ~overflow & ~captured

    # Forces at the ends of every stretch ridden (a cascade's inner counts are not ridden), and
    # F = 0 once the last spring has let go.
    ridden = jnp.stack([spans_in, spans_in, jnp.append(spans_back, False), jnp.append(spans_back, False)])
    forces = jnp.stack(
        [
            array.force(loaded, lower),
            array.force(loaded, end_in),
            jnp.append(array.force(unloaded, upper_out), 0.0),
            jnp.append(array.force(unloaded, end_out), 0.0),
        ]
    )
    released = jnp.where(separated, 0.0, jnp.nan)
    highest = jnp.fmax(jnp.max(jnp.where(ridden, forces, -jnp.inf)), released)
    lowest = jnp.fmin(jnp.min(jnp.where(ridden, forces, jnp.inf)), released)
    summary = ContactSummary(
        work=work_load + work_unload,
        lowest_force=lowest,
        highest_force=highest,
        deepest=deepest,
    )
    end_depth = jnp.where(overflow, deepest, end_out[last - 1])
    end_speed = jnp.where(overflow, speed_in, jnp.where(captured, 0.0, speed_low_out[0]))
    end = jnp.where(overflow, turn_time, end_time)

    if options.samples_per_phase:
        # The states after the events, in their order: the start of every stretch ridden in
        # (time, d, v, F, a), the turnaround, the start of every stretch ridden out, the end.
        load_start = c.t + jnp.concatenate([jnp.zeros(1), _running(jnp.add, duration_in)[:-1]])
        later = _running(jnp.add, duration_out, reverse=True)  # from the turnaround to the end of k's stretch
        out_start = turn_time + jnp.append(later[1:], 0.0)[::-1]
        radius = counts * spacing
        states = jnp.concatenate(
            [
                jnp.stack([load_start, lower, speed_low, array.force(loaded, lower), radius], axis=1),
                jnp.stack([turn_time, deepest, speed_in, array.force(last_in, deepest), radius[top]])[None],
                jnp.stack(
                    [
                        out_start,
                        upper_out[::-1],
                        speed_up_out[::-1],
                        array.force(unloaded, upper_out)[::-1],
                        radius[1:][::-1],
                    ],
                    axis=1,
                ),
                jnp.stack(
                    [
                        end,
                        end_depth,
                        end_speed,
                        jnp.where(captured, array.force(last_out, end_depth), 0.0),
                        jnp.where(captured, radius[last], 0.0),
                    ]
                )[None],
            ]
        )
        valid = jnp.concatenate([spans_in, jnp.ones(1, bool), spans_back[::-1], (~overflow)[None]])
        c = store_samples(c, options, _evenly(states, valid, options.samples_per_phase))
    c = log_event(c, turn_time, EVENT_CODE["max_indentation"], ~overflow)
    c = log_event(c, end, EVENT_CODE["separation"], separated)
    c = log_event(c, end, EVENT_CODE["capture"], captured)
    c = record_contact(c, (end, end_depth, end_speed), summary, separated, captured)
    beyond = table.count > capacity
    status = Status.where(
        beyond,
        Status.branch_overflow,
        Status.where(overflow, Status.radius_overflow, Status.where(captured, Status.captured, c.status)),
    )
    mode = jnp.where(beyond | overflow | captured, DONE, FLIGHT)
    return replace(c, mode=mode, status=status, phases=c.phases + 1)


def _evenly(states, valid, count: int):
    """`count` of the `valid` rows of `states`, evenly spaced in order (all of them, then nan
    rows, where there are fewer)."""
    rank = jnp.cumsum(valid)
    total = rank[-1]
    wanted = jnp.where(total <= count, jnp.arange(1, count + 1), jnp.round(jnp.linspace(1.0, total, count)).astype(int))
    picked = states[jnp.searchsorted(rank, wanted)]
    return jnp.where((wanted <= total)[:, None], picked, jnp.nan)
