"""Impacts on the equilibrium curve of a finite-range adhesive law without an ODE solve
(`solver.method: quadrature` with Maugis–Dugdale or Greenwood–Johnson adhesion).

Undamped, a body on a curve law moves along a rising segment of the curve d(s) in one degree of
freedom under a conservative force, so its speed is a function of where it is on the segment:
v²(s) = v₀² − 2∫F d'(s) ds + 2g·(d(s) − d₀) (unit mass, scaled). As for the continuum law
(`quadrature`), a phase ends at its segment's end where v² > 0 there, else at the first root of
v² (a turnaround), and lasts t = ∫ d'(s) / |v(s)| ds, by the same graded rule in θ with
s = s₀ + (s₁ − s₀)·(1 − cos πθ)/2 (which takes away the 1/√ singularity of 1/v at a turnaround).
The work ∫F d'(s) ds is the difference of the curve's energy where it has one in closed form
(the Maugis–Dugdale paraboloid: `_law.dugdale_energy`); elsewhere it is summed by Gauss–Legendre
from the phase's start, cell by cell along the segment (the curve is smooth on a segment). At
the rule's nodes it comes from its panels' spectral integration matrices (`_rule`). The jumps
between segments, the memory of a hysteretic path and the statuses are the ODE rider's
(`curve.after_ride`), so the two differ only in how a ride along a segment is followed.
"""

from typing import ClassVar

import jax
import jax.numpy as jnp
import numpy as np

from .._core import derivatives
from .._core.lanes import computed_once, only_where
from .._core.pytree import replace, replace_where, where
from .._core.quadrature import gauss_legendre, ordered_sum
from .._law.dugdale_energy import closed_energy
from .carry import Carry, close_phase, store_samples
from .codes import ADVANCE, DONE, Status
from .curve import CurveIntegrator, CurveProblem, after_ride
from .problem import Options
from .quadrature import PANEL_BREAKS, SAMPLE_NODES
from .ride import in_contact
from .work import ContactSummary, squared_speed

# Cells scanned along the segment for the first root of v², each summed by a Gauss–Legendre rule
# of _CELL_NODES (without a closed-form energy); the cell where v² reaches 0 scanned in
# _SUB_CELLS, then Newton steps on v² inside the sub-cell, the work within the cell from the
# polynomial through its rule's nodes; then _POLISH_STEPS Newton steps with the work by the
# cell's rule (with a closed-form energy, every step's work from it).
_SCAN_CELLS = 8
_CELL_NODES = 16
_SUB_CELLS = 8
_NEWTON_STEPS = 4
_POLISH_STEPS = 2
# Newton steps on dF/ds = 0 from the rule's node of least (of greatest) force.
_EXTREME_NEWTON_STEPS = 3
# As `quadrature._SETTLED`: |v²| at a turnaround found, relative to the leg's energies, above
# which its search did not settle (the run ends with solver_failure).
_SETTLED = 1e-9
# The rule in θ of `quadrature` (the same panels), with this many nodes a panel.
_PANEL_NODES = 12


def _rule() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(the fraction (1 − cos πθ)/2 of a ride at each node θ, the weight of dt at each node, the
    matrix of the work within each panel) of the graded rule on θ ∈ [0, 1] (`quadrature`'s
    panels), the nodes [panels, nodes].

    The work from the ride's start to a node is (s₁ − s₀)·Σ F·d'(s)·weight over the whole panels
    before it and, within its own panel, Σₘ A[panel, node, m]·F·d'(s) at the panel's nodes m: the
    integral of the polynomial through them (a spectral integration matrix), times dx/dθ/(s₁ − s₀)."""
    nodes, weights = np.polynomial.legendre.leggauss(_PANEL_NODES)
    legendre = np.polynomial.legendre
    integrals = np.stack(
        [legendre.legval(nodes, legendre.legint(np.eye(_PANEL_NODES)[k], lbnd=-1)) for k in range(_PANEL_NODES)], 1
    )
    partial = integrals @ np.linalg.inv(legendre.legvander(nodes, _PANEL_NODES - 1))  # ∫ from -1 to node j
    half = np.asarray(PANEL_BREAKS)
    breaks = np.concatenate([half, 1.0 - half[::-1][1:]])
    low, width = breaks[:-1, None], np.diff(breaks)[:, None]
    theta = low + width * (nodes + 1.0) / 2.0
    stretch = np.pi / 2.0 * np.sin(np.pi * theta)  # dx/dθ / (s₁ − s₀)
    within = width[:, :, None] / 2.0 * partial[None, :, :] * stretch[:, None, :]
    return (1.0 - np.cos(np.pi * theta)) / 2.0, width * weights / 2.0 * stretch, within


_FRACTION, _TIME_WEIGHTS, _WORK_MATRIX = _rule()


class CurveQuadrature(CurveIntegrator):
    """The equilibrium curve of a curve law (Maugis–Dugdale, Greenwood–Johnson; with
    `hysteresis` the path of a law with approach hysteresis), each ride along a rising segment
    ended by its energy balance and timed by Gauss–Legendre quadrature of dt = dd / v."""

    # No diffrax ride: the phase loop runs op by op at any batch (its rule's arrays are larger
    # than XLA:CPU's threshold for a whole-kernel loop), the same in any batch, and fastest
    # unsplit (`impact bench speed`): no cap on the lanes of a call.
    most_lanes: ClassVar[int | None] = None
    landed_contact: ClassVar[bool] = True

    def contact(self, problem: CurveProblem, options: Options, c: Carry) -> Carry:
        """One ride along a rising segment: its end from the energy balance, its duration by
        quadrature; then the jump or turn the ODE rider books there."""
        law, gravity = problem.law, problem.motion.gravity
        active = in_contact(c)
        curve = problem.curve.at(law, c.memory)
        advancing = c.mode == ADVANCE
        lower, upper = curve.nodes[c.segment], curve.nodes[c.segment + 1]
        start, far = c.radius, jnp.where(advancing, upper, lower)
        direction = jnp.where(advancing, 1.0, -1.0)

        def riding(s):  # (d, F, dd/ds), continued smoothly past the segment's ends
            return curve.riding(law, s, c.segment)

        def squared(depth, work):  # v² at the depth d after the work ∫F dd from the start
            return squared_speed((c.d, c.v), work, gravity, depth)

        # The work at the cells' ends, cumulative from the start, and v² there: from the curve's
        # energy where it has one in closed form (`closed_energy`), else summed by each cell's
        # Gauss–Legendre rule (the work density F·d'(s) at its nodes).
        cells = start + (far - start) * jnp.arange(_SCAN_CELLS + 1) / _SCAN_CELLS
        energy = closed_energy(law, curve)
        if energy is None:
            nodes, weights = gauss_legendre(_CELL_NODES)
            widths = cells[1:] - cells[:-1]
            _, cell_forces, cell_slopes = riding(cells[:-1, None] + widths[:, None] * nodes)
            densities = cell_forces * cell_slopes
            cell_work = _prefix_sums(widths * ordered_sum(densities * weights))
            cell_depths = curve.depth(law, cells)
        else:
            origin = energy(start)
            cell_depths, cell_energies = computed_once(lambda x: (curve.depth(law, x), energy(x)), cells[None])
            cell_work = cell_energies[0] - origin
            cell_depths = cell_depths[0]
        values = squared(cell_depths, cell_work)
        turned = values[-1] <= 0.0
        first = jnp.argmax(values[1:] <= 0.0)  # the cell where v² first reaches 0
        cell = (cells[first], cells[first + 1])

        def turnaround():
            if energy is None:
                estimate, exact = _cell_work(riding, cell, cell_work[first], densities[first])
            else:
                estimate = exact = lambda x: energy(x) - origin
            return _turnaround(riding, squared, cell, cell_work[first], estimate, exact, gravity)

        s_end, work, settled = only_where(turned, turnaround, (far, cell_work[-1], jnp.zeros_like(far)))
        energies = jnp.abs(values[0]) + jnp.abs(values[-1]) + 1.0
        settled = ~turned | (settled <= _SETTLED * energies)
        s_end = jnp.where(turned, s_end, far)
        work = jnp.where(turned, work, cell_work[-1])
        d_end = curve.depth(law, s_end)
        v_end = jnp.where(turned, 0.0, direction * derivatives.sqrt(jnp.maximum(squared(d_end, work), 0.0)))

        # The duration: the graded rule in θ, v² at its nodes from the work up to them (`_rule`),
        # from the start on the first half, from the end on the second (v² is small near an end
        # that is a turnaround: each half's v² is the work over the stretch to its own end).
        span = s_end - start
        depth, force, slope = computed_once(riding, start + span * _FRACTION)
        work_density = force * slope
        panels = ordered_sum(_TIME_WEIGHTS * work_density)  # each panel's work / span
        from_start = span * (_prefix_sums(panels)[:-1, None] + ordered_sum(_WORK_MATRIX * work_density[:, None, :]))
        to_end = span * ordered_sum(panels) - from_start
        end_squared = jnp.where(turned, 0.0, v_end**2)
        node_squared = jnp.where(
            _FRACTION < 0.5,
            squared(depth, from_start),
            end_squared + 2.0 * to_end + 2.0 * gravity * (depth - d_end),
        )
        real = jnp.all(node_squared > 0.0) | (span == 0.0)
        speed = derivatives.sqrt(jnp.maximum(node_squared, jnp.finfo(node_squared.dtype).tiny))
        t_end = c.t + jnp.abs(span) * ordered_sum(ordered_sum(jnp.abs(slope) / speed * _TIME_WEIGHTS))

        if options.samples_per_phase:
            c = where(active, store_samples(c, options, _rows(problem, options, c, curve, (s_end, t_end, v_end))), c)
        low_force, high_force = _force_extremes(
            lambda s: curve.force(law, s), start, s_end, start + span * _FRACTION, force
        )
        summary = ContactSummary(
            work=work, lowest_force=low_force, highest_force=high_force, deepest=jnp.maximum(c.d, d_end)
        )
        nxt, memory = after_ride(problem, curve, advancing, turned, c.segment, s_end, d_end, c.memory)
        steps = (jnp.zeros((), int),) * 3  # no solver: every end is found
        booked = close_phase(
            c, active, jnp.asarray(True), steps, (t_end, d_end, v_end), nxt, jnp.asarray(False), summary
        )
        booked = replace(booked, memory=where(active, memory, c.memory))
        # A speed that is not real at a node inside the ride (the balance cannot be followed
        # there), or a turnaround whose search did not settle.
        return replace_where(booked, active & (~real | ~settled), status=Status.solver_failure, mode=DONE)


def _prefix_sums(values):
    """[0, v₀, v₀ + v₁, …, Σv] of a short vector, added first to last (as `ordered_sum`: the
    same in any batch)."""
    sums = [jnp.zeros_like(values[0])]
    for value in values:
        sums.append(sums[-1] + value)
    return jnp.stack(sums)


def _integral_within(fraction, values):
    """∫ from 0 to `fraction` (any shape) of the polynomial through `values` (a vector) at the
    nodes of the Gauss–Legendre rule of as many nodes on [0, 1]. In t = 2x − 1 that polynomial is
    Σₖ (2k + 1)·gₖ·Pₖ(t), gₖ = Σₘ wₘ·Pₖ(tₘ)·valuesₘ (the rule is exact for every Pₖ·Pⱼ of
    k, j below its nodes), and ∫ from −1 to t of Pₖ is (Pₖ₊₁ − Pₖ₋₁)/(2k + 1) (P₀: t + 1), so
    the integral is ½·(g₀·(t + 1) + Σₖ≥₁ gₖ·(Pₖ₊₁(t) − Pₖ₋₁(t)))."""
    count = values.shape[-1]
    nodes, weights = np.polynomial.legendre.leggauss(count)
    moments = ordered_sum(0.5 * weights * np.polynomial.legendre.legvander(nodes, count - 1).T * values)
    t = 2.0 * fraction - 1.0
    legendre = [jnp.ones_like(t), t]  # P₀ … P_count at t (Bonnet's recursion)
    for k in range(1, count):
        legendre.append(((2 * k + 1) * t * legendre[k] - k * legendre[k - 1]) / (k + 1))
    terms = [moments[0] * (t + 1.0)] + [moments[k] * (legendre[k + 1] - legendre[k - 1]) for k in range(1, count)]
    return 0.5 * ordered_sum(jnp.stack(terms, axis=-1))


def _force_extremes(force_at, start, end, points, forces):
    """(min, max) of F(s) on the ride from `start` to `end`, from its `forces` at the rule's
    `points` (in the ride's order): Newton steps on dF/ds = 0 from the node of least and the
    node of greatest force, each kept between that node's neighbours, then the least and the
    greatest of F there, at the nodes and at the ride's ends."""
    points, forces = points.ravel(), forces.ravel()
    neighbours = jnp.concatenate([start[None], points, end[None]])
    best = jnp.stack([jnp.argmin(forces), jnp.argmax(forces)])
    before, after = neighbours[best], neighbours[best + 2]
    low, high = jnp.minimum(before, after), jnp.maximum(before, after)

    def force_slope(s):
        return jax.jvp(force_at, (s,), (jnp.ones_like(s),))[1]

    s = points[best]
    for _ in range(_EXTREME_NEWTON_STEPS):
        slope, curvature = jax.jvp(force_slope, (s,), (jnp.ones_like(s),))
        usable = curvature != 0.0
        s = jnp.clip(s - jnp.where(usable, slope / jnp.where(usable, curvature, 1.0), 0.0), low, high)
    candidates = jnp.concatenate([force_at(jnp.concatenate([jnp.stack([start, end]), s])), forces[best]])
    return jnp.min(candidates), jnp.max(candidates)


def _cell_work(riding, cell, cell_work, densities):
    """(a quick, an exact) work ∫F dd from the ride's start to s in `cell`, given the work
    `cell_work` at its start and the work density F·d'(s) `densities` at its Gauss nodes: from
    the polynomial through those densities (`_integral_within`), and by the cell's
    Gauss–Legendre rule from its start."""
    low, high = cell
    width = high - low
    safe_width = jnp.where(width != 0.0, width, 1.0)

    def interpolated_work(s):
        return cell_work + width * _integral_within((s - low) / safe_width, densities)

    def work_to(s):
        nodes, weights = gauss_legendre(_CELL_NODES)
        _, force, slope = riding(low + (s - low) * nodes)
        return cell_work + (s - low) * ordered_sum(force * slope * weights)

    return interpolated_work, work_to


def _turnaround(riding, squared, cell, cell_work, estimate, exact, gravity):
    """(s, the work ∫F dd from the ride's start to s, |v²| there) at the first root of v² in
    `cell` (v² > 0 at its start, ≤ 0 at its end; the work `cell_work` at its start). Newton steps
    on v² (d(v²)/ds = 2(g − F)·d'(s)), bisecting where a step would leave the bracket: first with
    the work `estimate(s)`, in the sub-cell of `_SUB_CELLS` where v² so found turns; then
    `_POLISH_STEPS` from the best point so found, with the work `exact(s)`. The point polished of
    least |v²| is kept."""
    low, high = cell
    width = high - low

    def newton(s, work, lower, upper, best):  # a step from s, the bracket and the best point
        depth, force, slope = riding(s)
        value = squared(depth, work)
        best = jax.tree.map(lambda x, y: jnp.where(jnp.abs(value) < best[2], x, y), (s, work, jnp.abs(value)), best)
        lower, upper = jnp.where(value > 0.0, s, lower), jnp.where(value > 0.0, upper, s)
        derivative = 2.0 * (gravity - force) * slope
        target = s - value / jnp.where(derivative != 0.0, derivative, 1.0)
        inside = (derivative != 0.0) & ((target - lower) * (target - upper) <= 0.0)  # either order
        return jnp.where(inside, target, 0.5 * (lower + upper)), lower, upper, best

    subs = low + width * jnp.arange(_SUB_CELLS + 1) / _SUB_CELLS
    sub_values = squared(riding(subs)[0], estimate(subs))
    first = jnp.argmax(sub_values[1:] <= 0.0)
    lower, upper = subs[first], subs[first + 1]
    above, below = sub_values[first], sub_values[first + 1]
    s = jnp.clip(lower + (upper - lower) * above / jnp.where(above > below, above - below, 1.0), lower, upper)

    def located(state, _):
        s, lower, upper, best = state
        return newton(s, estimate(s), lower, upper, best), None

    unknown = (low, cell_work, jnp.asarray(jnp.inf))
    (_, _, _, (s, _, _)), _ = jax.lax.scan(located, (s, lower, upper, unknown), None, length=_NEWTON_STEPS)
    lower, upper, best = low, high, unknown
    for _ in range(_POLISH_STEPS):
        s, lower, upper, best = newton(s, exact(s), lower, upper, best)
    work = exact(s)
    last = jnp.abs(squared(riding(s)[0], work))
    return jax.tree.map(lambda x, y: jnp.where(last <= best[2], x, y), (s, work, last), best)


def _rows(problem: CurveProblem, options: Options, c: Carry, curve, end):
    """Trajectory rows (t, d, v, F, a) of a ride from the carry's state to `end` = (s, t, v):
    times by a small rule between neighbouring samples, scaled to the ride's duration."""
    law, gravity = problem.law, problem.motion.gravity
    s_end, t_end, v_end = end
    theta = jnp.linspace(0.0, 1.0, options.samples_per_phase)
    nodes, weights = gauss_legendre(SAMPLE_NODES)
    span = s_end - c.radius
    lower = jnp.concatenate([theta[:1], theta[:-1]])
    inner = lower[:, None] + (theta - lower)[:, None] * nodes
    points = c.radius + span * (1.0 - jnp.cos(jnp.pi * theta)) / 2.0
    inner_points = c.radius + span * (1.0 - jnp.cos(jnp.pi * inner)) / 2.0

    def squared(s):  # v² by the work from the start (each sample's own rule: rows only)
        x, w = gauss_legendre(_CELL_NODES)
        _, force, slope = curve.riding(law, c.radius + (s - c.radius)[..., None] * x, c.segment)
        work = (s - c.radius) * ordered_sum(force * slope * w)
        return squared_speed((c.d, c.v), work, gravity, curve.depth(law, s))

    _, _, slope = curve.riding(law, inner_points, c.segment)
    speed = derivatives.sqrt(jnp.maximum(squared(inner_points), jnp.finfo(span.dtype).tiny))
    density = jnp.abs(slope) / speed * jnp.pi / 2.0 * jnp.sin(jnp.pi * inner) * jnp.abs(span)
    times = jnp.cumsum(ordered_sum(density * weights * (theta - lower)[:, None]))
    times = (t_end - c.t) * times / jnp.where(times[-1] > 0.0, times[-1], 1.0)
    direction = jnp.where(c.mode == ADVANCE, 1.0, -1.0)
    velocity = direction * derivatives.sqrt(jnp.maximum(squared(points), 0.0))
    depth, force, radius, _ = curve.state(law, points)
    rows = jnp.stack([c.t + times, depth, velocity, force, radius], axis=1)
    d_end, f_end, a_end, _ = curve.state(law, s_end)
    return rows.at[-1].set(jnp.stack([t_end, d_end, v_end, f_end, a_end]))
