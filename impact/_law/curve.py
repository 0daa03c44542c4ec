"""An equilibrium curve of a finite-range adhesive law: every quasi-static state (d, F, a, outer
radius) along one parameter s, split at the turning points of d(s) into monotone segments.

Under displacement control (and for a free body) the rising segments are stable: a state rides
one of them and, at its end, jumps at fixed d to the next rising state at that level (snap-in,
snap-out) or, with none left, lets go. Maugis–Dugdale (`dugdale`, §3.8) and Greenwood–Johnson
(`double_hertz`, §3.9) are such curves; `_integrate.curve` rides them.
"""

import abc
from collections.abc import Callable
from typing import Any, ClassVar, Protocol

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.derivatives import implicit_root
from .._core.lanes import only_where
from .._core.search import bisect
from .branches import next_rising, previous_rising, sign_changes
from .scales import Scales

# d(s) = depth on a rising segment: bisection to 2^-24 of the segment, then Newton steps
# (clamped to the bracket): each squares the error, the first to ≲ d''·(2^-24·Δs)² in d.
_INVERSION_STEPS = 24
_INVERSION_NEWTON_STEPS = 2
# A curve reaches this many times the contact radius where its loading work exceeds the energy.
TOP_MARGIN = 4.0


# Where a curve ends: the parameter s_top from the search grid and the states (d, F, a) along it.
Reach = Callable[[jax.Array, jax.Array, jax.Array, jax.Array], jax.Array]


def top_of_reach(grid, depths, forces, radii, speed):
    """The curve parameter (of `grid`, with the states `depths`, `forces`, `radii` along it,
    scaled) at `TOP_MARGIN` times the contact radius where the work ∫F dd from the start exceeds
    the impact energy v²/2 plus one unit and twice what the curve gave back on the way (the
    last grid point if it never does)."""
    steps = 0.5 * (forces[1:] + forces[:-1]) * (depths[1:] - depths[:-1])
    work = jnp.concatenate([jnp.zeros(1), jnp.cumsum(steps)])
    given_back = jnp.maximum(-jax.lax.cummin(work), 0.0)
    return _beyond(grid, radii, work >= 0.5 * speed**2 + 1.0 + 2.0 * given_back)


def top_of_peak(grid, depths, forces, radii, peak, force_control):
    """The curve parameter at `TOP_MARGIN` times the contact radius beyond which the controlled
    value (F under force control, else d) stays above `peak` (scaled): a quasi-static program
    loading to the peak stays below it."""
    values = jnp.where(force_control, forces, depths)
    return _beyond(grid, radii, jax.lax.cummin(jnp.where(jnp.isnan(values), -jnp.inf, values), reverse=True) > peak)


def _beyond(grid, radii, enough):
    """The first grid point at `TOP_MARGIN` times the radius where `enough` first holds (or the
    unit radius, if larger; the last grid point where neither is reached)."""
    reach = radii[jnp.where(jnp.any(enough), jnp.argmax(enough), grid.shape[0] - 1)]
    beyond = radii >= TOP_MARGIN * jnp.maximum(reach, 1.0)
    return grid[jnp.where(jnp.any(beyond), jnp.argmax(beyond), grid.shape[0] - 1)]


def force_turns(law, curve: "AbstractCurve", top, max_turns: int):
    """The turning points of F(s) on the curve's `grid` up to `top`, other than its junction
    (a kink, already a node): ([max_turns] padded with `top`, more than that many)."""
    grid = jnp.minimum(curve.grid(law), top)
    turns, valid, count = sign_changes(
        lambda s: curve.slopes(law, s)[1], grid, curve.slopes(law, grid)[1] > 0.0, max_turns
    )
    kink = jnp.abs(turns - curve.junction) <= 1e-12 * curve.junction
    return jnp.where(valid & ~kink, turns, top), count > max_turns


class CurveLaw(Protocol):
    """What a rider needs of a curve's law besides the curve: its units and the depth d where
    the interaction starts."""

    @property
    def scales(self) -> Scales: ...

    @property
    def onset(self) -> jax.Array: ...


class AbstractCurve(eqx.Module):
    """The states of one law along s ≥ 0, with its segments (`nodes`: 0, turning points, …, the
    top; `levels`: d at the nodes; `increasing`: which segments rise).

    A curve that `remembers` (a hysteretic law, `dugdale_hysteresis`) is one path of a family:
    the state's memory picks the path (`at`), and turning back re-anchors it (`anchored`)."""

    remembers: ClassVar[bool] = False

    junction: eqx.AbstractVar[jax.Array]  # s where a contact closes (unloading there ends it)
    nodes: eqx.AbstractVar[jax.Array]  # [S+1]
    levels: eqx.AbstractVar[jax.Array]  # [S+1]
    increasing: eqx.AbstractVar[jax.Array]  # [S]
    overflow: eqx.AbstractVar[jax.Array]  # more turning points than the curve holds

    @abc.abstractmethod
    def state(self, law, s):
        """(d, F, a, outer radius) at s, scaled."""

    @abc.abstractmethod
    def grid(self, law):
        """The parameters searched for the curve's reach and turning points, sorted."""

    def riding(self, law, s, segment=None):
        """(d, F, dd/ds) at s; given the `segment` ridden, continued smoothly past its ends
        (`on_segment`), as an adaptive step that crosses an end sees it."""
        state = self.state if segment is None else lambda law, x: self.on_segment(law, x, segment)
        (depth, force), (slope, _) = jax.jvp(lambda x: state(law, x)[:2], (s,), (jnp.ones_like(s),))
        return depth, force, slope

    def closes(self, s):
        """Whether the node s is where a contact closes (riding on across it opens or closes it)."""
        return s == self.junction

    def switches(self, s):
        """Whether the node s is where a hysteretic path changes branch (none here)."""
        return jnp.zeros(jnp.shape(s), bool)

    def force_turns(self, law, top, max_turns: int):
        """The turning points of F(s) up to `top` (`force_turns`)."""
        return force_turns(law, self, top, max_turns)

    def holding(self, s, up):
        """The segment a state at s moves along, up (s growing) or down: at a node, the one
        beyond it in that direction."""
        side = jnp.where(
            up,
            jnp.searchsorted(self.nodes, s, side="right", method="compare_all"),
            jnp.searchsorted(self.nodes, s, side="left", method="compare_all"),
        )
        return jnp.clip(side - 1, 0, self.increasing.shape[0] - 1)

    def at(self, law, memory) -> "AbstractCurve":
        """The path of the state's `memory`: the curve itself, unless it `remembers`."""
        return self

    def anchored(self, law, s, memory) -> tuple["AbstractCurve", Any, jax.Array]:
        """The path of a state at s that turns back, its memory and the state's place on it: the
        same, unless the curve `remembers`."""
        return self, memory, s

    def resolves(self, law) -> jax.Array:
        """Whether the curve resolves the law's states: a discretised curve may be too coarse to
        be trusted (`DugdaleSpringCurve`); a continuum curve always does."""
        return jnp.asarray(True)

    def on_segment(self, law, s, segment):
        """(d, F, a, outer radius) at s on `segment` and its smooth continuation: `state`, where
        the curve is smooth across the segment's ends."""
        return self.state(law, s)

    def slopes(self, law, s):
        """(dd/ds, dF/ds) at s."""
        _, tangents = jax.jvp(lambda x: self.state(law, x)[:2], (s,), (jnp.ones_like(s),))
        return tangents

    def split_at(self, law, nodes, overflow):
        """The curve cut at `nodes` (sorted; repeats make empty segments): d at each node, which
        segments rise (dd/ds > 0 at their middles) and whether it `overflow`s."""
        middles = 0.5 * (nodes[:-1] + nodes[1:])
        rising = (self.slopes(law, middles)[0] > 0.0) & (nodes[1:] > nodes[:-1])
        return eqx.tree_at(
            lambda c: (c.nodes, c.levels, c.increasing, c.overflow),
            self,
            (nodes, self.depth(law, nodes), rising, overflow),
        )

    def depth(self, law, s):
        return self.state(law, s)[0]

    def force(self, law, s):
        return self.state(law, s)[1]

    def invert(self, law, depth, segment):
        """s with d(s) = depth on a rising segment (clamped to it): bisection, then Newton."""
        lower, upper = self.nodes[segment], self.nodes[segment + 1]
        lo, hi = bisect(lambda s: self.depth(law, s) < depth, lower, upper, _INVERSION_STEPS)

        def newton(_, s):
            value, _, slope = self.riding(law, s)
            step = jnp.where(slope > 0.0, (value - depth) / jnp.where(slope > 0.0, slope, 1.0), 0.0)
            return jnp.clip(s - step, lo, hi)

        root = jax.lax.fori_loop(0, _INVERSION_NEWTON_STEPS, newton, 0.5 * (lo + hi))
        return implicit_root(lambda s: self.depth(law, s) - depth, root)

    def cascade(self, law, outward, start, depth):
        """The cascade at level d from `start`: outward, the first rising state beyond it (s,
        segment, blocked); inward, the last rising state below it (s, segment, released:
        no state holds, the body leaves the range of the adhesive stress). One inversion of d(s)
        for either, where a rising state is found."""
        out_segment, blocked = next_rising(self.nodes, self.levels, self.increasing, start, depth)
        in_segment, released = previous_rising(self.nodes, self.levels, self.increasing, start, depth)
        segment = jnp.where(outward, out_segment, in_segment)
        # Inverted only where a rising state is found (a batch where none is skips it).
        found = jnp.where(outward, ~blocked, ~released)
        landing = only_where(found, lambda: self.invert(law, depth, segment), jnp.zeros_like(self.nodes[segment]))
        out_s = jnp.where(blocked, self.nodes[-1], jnp.maximum(landing, start))
        in_s = jnp.where(released, 0.0, jnp.minimum(landing, start))
        return jnp.where(outward, out_s, in_s), segment, jnp.where(outward, blocked, released)
