"""The continuum law without an ODE solve: each contact phase ended by its energy balance and
timed by quadrature (`solver.method: quadrature`).

Undamped, a body on the continuum law moves along a contact phase in one degree of freedom under
a conservative force, so its speed is a function of where it is: the phase's energy balance
v² = v₀² − 2∫F dd + 2g·(d − d₀) (unit mass, scaled), with the work in closed form for ĝ = Â·xⁿ
(`work.branch_work`, `work.hold_work`). A phase ends where that balance puts it, as with the
energy's ends of `continuum`: at the end of its segment where v² > 0 there, else at the first root
of v² (a turnaround: a scan, then the Illinois method). It lasts t = ∫ |dd/dx| / |v(x)| dx along
its radius x = a (riding the branch, dd/dx = h'(a)) or its depth x = d (held at a fixed radius,
outwards from a turnaround). x = x₀ + (x₁ − x₀)·(1 − cos πθ)/2 takes away the 1/√ singularity of
1/v at a turnaround at either end, and Gauss–Legendre panels in θ graded towards both ends take
the near-singular speed of a phase that only just reaches its end (an impact just above its
sticking velocity, a late bounce's slow touch).

The restitution and the deepest indentation are exact to round-off, as with the energy's ends;
the contact times carry the rule's error, largest where a phase only just reaches its end
(docs/src/accuracy.md, "Phases timed by quadrature"). No step is taken: a phase costs about a
hundred evaluations of the closed forms at any velocity.
"""

from collections.abc import Callable
from dataclasses import dataclass

import jax
import jax.numpy as jnp
import numpy as np

from .._core import derivatives
from .._core.pytree import replace_where, where
from .._core.quadrature import ordered_sum
from .._core.search import illinois_root
from .base import AbstractIntegrator
from .carry import Carry, Outcome, close_phase, run_phases, store_samples
from .codes import ADVANCE, DONE, HOLD, RECEDE, Status
from .flight import land_on_touch
from .problem import Options, Physics, Problem, build_problem
from .transitions import after_phase
from .work import active_branch, branch_work, hold_work, phase_summary, segment_end, squared_speed

# Panels of the rule in θ ∈ [0, ½], mirrored onto [½, 1], each with _PANEL_NODES Gauss–Legendre
# nodes: 80 nodes a leg.
PANEL_BREAKS = (0.0, 1e-3, 1e-2, 0.05, 0.2, 0.5)
_PANEL_NODES = 8
# Cells scanned for the first root of v² along a leg, then Illinois steps inside the cell.
_SCAN_CELLS = 8
_ILLINOIS_STEPS = 12
# |v²| at a turnaround found, relative to v₀² + |v² at the leg's far end| + 1 (the leg's energies),
# above which its root search did not settle (as `continuum`'s Newton steps at a turnaround): a
# phase ended there would lose that energy, so the run ends with `solver_failure` instead.
_SETTLED = 1e-9
# Gauss–Legendre nodes per interval between two trajectory samples.
SAMPLE_NODES = 4


def _rule() -> tuple[np.ndarray, np.ndarray]:
    """(the fraction (1 − cos πθ)/2 of a leg at each node θ, its weight w·dx/dθ / (x₁ − x₀)) of
    the graded rule on θ ∈ [0, 1]; NumPy arrays (a JAX array made at import would start JAX's
    backend before `jax.distributed.initialize`)."""
    nodes, weights = np.polynomial.legendre.leggauss(_PANEL_NODES)
    half = np.asarray(PANEL_BREAKS)
    breaks = np.concatenate([half, 1.0 - half[::-1][1:]])
    low, width = breaks[:-1, None], np.diff(breaks)[:, None]
    theta = (low + width * (nodes + 1.0) / 2.0).ravel()
    theta_weights = (width * weights / 2.0).ravel()
    fraction = (1.0 - np.cos(np.pi * theta)) / 2.0
    return fraction, theta_weights * np.pi / 2.0 * np.sin(np.pi * theta)


class Quadrature(AbstractIntegrator):
    """The continuum MDR law (N → ∞ springs), its phases ended by their energy balance and timed
    by Gauss–Legendre quadrature of dt = dd / v (undamped, ĝ = Â·xⁿ)."""

    def build(self, physics: Physics, options: Options) -> Problem:
        return build_problem(physics, options)

    def integrate(self, problem: Problem, options: Options) -> Outcome:
        def contact(c: Carry) -> Carry:
            return _contact(problem, options, c)

        return run_phases(problem, options, lambda c: land_on_touch(problem, options, c), contact, landed_contact=True)


@dataclass(frozen=True)
class Leg:
    """A phase as a monotone stretch in x (the radius a, or the depth d): where it starts and
    where it would end, v²(x), the rate |dd/dx| and the sign of the speed along it."""

    start: jax.Array
    far: jax.Array
    squared: Callable[[jax.Array], jax.Array]
    rate: Callable[[jax.Array], jax.Array]
    direction: jax.Array

    def end(self):
        """(x where the leg ends, whether it turned there, whether that end is settled): its far
        end where v² > 0 there, else the first root of v² between (settled where |v²| there is
        within `_SETTLED` of the leg's energies)."""
        at_far = self.squared(self.far)
        cells = self.start + (self.far - self.start) * jnp.arange(1, _SCAN_CELLS + 1) / _SCAN_CELLS
        values = self.squared(cells)
        first = jnp.argmax(values <= 0.0)  # the last cell's end is `far`, where v² ≤ 0 when it turns
        low = jnp.where(first > 0, cells[jnp.maximum(first - 1, 0)], self.start)
        high = cells[first]
        root = illinois_root(self.squared, low, high, _ILLINOIS_STEPS)
        turned = at_far <= 0.0
        return jnp.where(turned, root, self.far), turned, ~turned | self.settled(root)

    def settled(self, end):
        """Whether |v²| at `end` is within `_SETTLED` of the leg's energies, v₀² + |v² at its far
        end| + 1: a turnaround found there."""
        energies = jnp.abs(self.squared(self.start)) + jnp.abs(self.squared(self.far)) + 1.0
        return jnp.abs(self.squared(end)) <= _SETTLED * energies

    def balance(self, end, turned) -> Callable[[jax.Array], jax.Array]:
        """v²(x) on the leg to `end`; where it turns at a settled end, less the residual v²(end)
        in proportion to (x − start)/(end − start), so that the turnaround is an exact root.
        Near the sticking velocity the root is nearly double (v² has its minimum just past it,
        at the segment's node): the Illinois search settles within `_SETTLED` a little past it,
        where the nodes just before `end` would see v² < 0 (`solver_failure` at e.g.
        v = (1 − 1.6e-7)·v_s of Thornton–Ning). An end that did not settle is not moved."""
        span = end - self.start
        residual = jnp.where(turned & (span != 0.0) & self.settled(end), self.squared(end), 0.0)
        safe_span = jnp.where(span != 0.0, span, 1.0)
        return lambda x: self.squared(x) - residual * (x - self.start) / safe_span

    def time(self, end, turned):
        """The leg's duration from its start to `end` (a turnaround where `turned`), and whether
        v² > 0 at every node between."""
        fraction, weight = RULE
        span = end - self.start
        x = self.start + span * fraction
        squared = self.balance(end, turned)(x)
        real = jnp.all(squared > 0.0) | (span == 0.0)
        speed = derivatives.sqrt(jnp.maximum(squared, jnp.finfo(squared.dtype).tiny))
        return jnp.abs(span) * ordered_sum(weight * self.rate(x) / speed), real

    def samples(self, end, turned, theta, duration):
        """(x, t since the leg's start, v) at the points θ ∈ [0, 1] (increasing, from 0 to 1) of
        the leg to `end` (a turnaround where `turned`): t by a small rule between neighbours,
        scaled to the leg's `duration` (from the full rule), so that the times rise to it."""
        nodes, weights = np.polynomial.legendre.leggauss(SAMPLE_NODES)
        span = end - self.start
        balance = self.balance(end, turned)
        lower = jnp.concatenate([theta[:1], theta[:-1]])
        inner = lower[:, None] + (theta - lower)[:, None] * jnp.asarray((nodes + 1.0) / 2.0)  # [P, nodes]
        x = self.start + span * (1.0 - jnp.cos(jnp.pi * inner)) / 2.0
        speed = derivatives.sqrt(jnp.maximum(balance(x), jnp.finfo(x.dtype).tiny))
        density = self.rate(x) / speed * jnp.pi / 2.0 * jnp.sin(jnp.pi * inner) * jnp.abs(span)
        times = jnp.cumsum(ordered_sum(density * jnp.asarray(weights / 2.0) * (theta - lower)[:, None]))
        times = duration * times / jnp.where(times[-1] > 0.0, times[-1], 1.0)
        points = self.start + span * (1.0 - jnp.cos(jnp.pi * theta)) / 2.0
        velocity = self.direction * derivatives.sqrt(jnp.maximum(balance(points), 0.0))
        return points, times, velocity


RULE = _rule()


def _contact(problem: Problem, options: Options, c: Carry) -> Carry:
    """One contact phase: its end from the energy balance, its duration by quadrature."""
    law, gravity = problem.law, problem.motion.gravity
    in_contact = (c.mode == ADVANCE) | (c.mode == HOLD) | (c.mode == RECEDE)
    riding = (c.mode == ADVANCE) | (c.mode == RECEDE)
    branch = active_branch(c.mode, problem.attach, problem.detach)
    advancing = c.mode == ADVANCE
    node = segment_end(branch, c.mode, c.segment)
    start = (c.d, c.v)

    def squared(x):  # v² at x: the radius while riding, the depth while held
        work = jnp.where(riding, branch_work(law, branch, c.radius, x), hold_work(law, c.radius, c.d, x))
        return squared_speed(start, work, gravity, jnp.where(riding, branch.level(law, x), x))

    def rate(x):  # |dd/dx|
        return jnp.where(riding, jnp.abs(law.edge_slope(x, branch.coefficient)), 1.0)

    # Riding: from the radius to the segment's end; held: outwards, from the depth to the detach
    # depth. A hold starts at a turnaround (v = 0): only at a body's wall, which no profile of the
    # form g = A·xⁿ has, could it start inwards (left to the ODE solvers: `solver_failure` here).
    leg = Leg(
        jnp.where(riding, c.radius, c.d),
        jnp.where(riding, node, jnp.minimum(problem.detach.level(law, c.radius), c.d)),
        squared,
        rate,
        jnp.where(advancing, 1.0, -1.0),
    )
    x_end, turned, settled = leg.end()
    duration, real = leg.time(x_end, turned)
    a_end = jnp.where(riding, x_end, c.radius)
    d_end = jnp.where(riding, branch.level(law, x_end), x_end)
    v_end = jnp.where(turned, 0.0, leg.direction * derivatives.sqrt(jnp.maximum(squared(x_end), 0.0)))
    t_end = c.t + duration

    if options.samples_per_phase:
        x, t, v = leg.samples(x_end, turned, jnp.linspace(0.0, 1.0, options.samples_per_phase), duration)
        radii = jnp.where(riding, x, c.radius)
        depths = jnp.where(riding, branch.level(law, x), x)
        rows = jnp.stack([c.t + t, depths, v, law.force(radii, depths), radii], axis=1)
        rows = rows.at[-1].set(jnp.stack([t_end, d_end, v_end, law.force(a_end, d_end), a_end]))  # the end itself
        c = where(in_contact, store_samples(c, options, rows), c)

    summary = phase_summary(law, branch, riding, (c.radius, a_end), gravity, start, (d_end, v_end))
    nxt = after_phase(problem, c.mode, c.segment, a_end, d_end, turned)
    located, steps = jnp.asarray(True), (jnp.zeros((), int),) * 3  # no solver: every end is found
    closed = close_phase(c, in_contact, located, steps, (t_end, d_end, v_end), nxt, jnp.asarray(False), summary)
    # A speed that is not real at a node inside the leg (the balance cannot be followed there), a
    # turnaround whose search did not settle, or a hold that starts inwards; a ride that starts
    # off its edge function (`continuum`).
    unfollowed = in_contact & (~real | ~settled | (~riding & (c.v > 0.0)))
    closed = replace_where(closed, unfollowed, status=Status.solver_failure, mode=DONE)
    off_branch = in_contact & riding & branch.misses(law, c.radius, c.d)
    return replace_where(closed, off_branch, status=Status.off_branch, mode=DONE)
