"""Monotone branches of an edge function h(x) = g(x) − λ·√x, and the cascades between them.

The contact radius only ever sits where h is increasing: a spring at x stays attached while
d > h_detach(x) and the next one attaches once d ≥ h_attach(x). A `Branch` splits [0, x_top]
at the turning points of h into segments. Roots of h(x) = d on a segment come from a
bracketed Newton iteration; where they are needed at every step (loading integrated in time)
the branch also keeps, for each increasing segment, a table of x against
u = √((d − h(p))/(h(q) − h(p))), in which x is smooth even at a critical point (where
a ∝ √(d − d_c)): a radius is then one look-up and three Newton steps, O(1).

Cascades: when the edge spring at a turning point lets go (detach) or the next one catches
(attach), the contact radius jumps to the next point where h crosses the level d;
`cascade_in` and `cascade_out` find it.
"""

from dataclasses import dataclass

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.derivatives import implicit_root
from .._core.search import bisect
from ..profiles import Profile, Tabulated, WavyParaboloid
from .law import ContactLaw, half_power_root

# The search grid starts at the smaller of 1e-8 (scaled: the adhesion scale is 1) and
# 1e-12·x_top. Below it the turning point nearest the tip (where the Heß term's slope,
# ∝ 1/√x, overtakes g') is bisected in log x down to the smallest normal float (in SI): it sits
# near the edge's own jump-in radius, which for Δγa ≪ Δγ lies any number of decades below the
# units.
_GRID_LOWEST = 1e-8
_GRID_DECADES = 12.0
_SMALLEST_RADIUS = float(jnp.finfo(jnp.float64).tiny)
# Log bisection of that turning point to a bracket of 1e-5 relative (log x spans 682 from the
# smallest float to 1e-12): narrow enough for the grid, wide enough that h' keeps a clear
# sign at both ends whatever the round-off; the refinement of every turn then takes over.
_TIP_BISECTION_STEPS = 26
_BISECTION_STEPS = 64
_TABLE_BISECTION_STEPS = 32  # the table only starts Newton: 2^-32 of a segment is plenty
_SAFEGUARDED_STEPS = 80
_SETTLED = 4.0 * float(jnp.finfo(jnp.float64).eps)  # relative change at which a search stops
_NEWTON_STEPS = 3


@dataclass(frozen=True)
class Tabulation:
    """How the edge functions are searched for turning points (static: changing it recompiles)."""

    max_turns: int = 4  # turning points an edge function may have
    turn_grid: int = 384  # points searched for them
    tip_search: bool = True  # also look below the grid for the attach edge's turn (0 < Δγa < Δγ)

    @staticmethod
    def for_profile(profile: Profile, tip_search: bool = True) -> "Tabulation":
        """The default, or more turning points and a finer search for the profiles whose edge
        functions may turn many times (wavy and tabulated bodies)."""
        turns, grid = _MANY_TURNS.get(type(profile), (4, 384))
        return Tabulation(max_turns=turns, turn_grid=grid, tip_search=tip_search)


# A ride starts on its branch, d = h(a), to round-off (a few 1e-16 of 1 + |d| + |ĝ(a)| on every
# example and hard-case scene), far below this bound. A jump of the radius (jump-in, snap-in,
# snap-out) that landed elsewhere would start the ride deeper or shallower at no cost in energy,
# creating or destroying it: such a ride ends the run with `off_branch`.
_ON_BRANCH = 1e-9
_MANY_TURNS = {WavyParaboloid: (64, 8192), Tabulated: (32, 4096)}


class Branch(eqx.Module):
    """Segments of one edge function on [0, x_top] with their inversion tables."""

    coefficient: jax.Array  # λ of this edge function
    nodes: jax.Array  # [S+1] segment ends: 0, turning points, x_top (padded with x_top)
    levels: jax.Array  # [S+1] h at the nodes
    increasing: jax.Array  # [S] whether h increases on the segment
    table: jax.Array | None  # [S, M] x at u_i = i/(M−1) on increasing segments, if kept
    overflow: jax.Array  # more turning points than the branch holds

    def level(self, law: ContactLaw, x):
        return law.edge(x, self.coefficient)

    def misses(self, law: ContactLaw, radius, indentation):
        """Whether d = h(a) fails by more than round-off (`_ON_BRANCH` of 1 + |d| + |ĝ(a)|): a
        ride that starts there is off its edge function."""
        scale = 1.0 + jnp.abs(indentation) + jnp.abs(law.g(radius))
        return jnp.abs(self.level(law, radius) - indentation) > _ON_BRANCH * scale

    def radius(self, law: ContactLaw, indentation, segment):
        """Root of h(x) = d on an increasing segment (clamped to the segment)."""
        if self.table is None:
            return self._solve(law, indentation, self.nodes[segment], self.nodes[segment + 1])
        low_level, high_level = self.levels[segment], self.levels[segment + 1]
        span = jnp.where(high_level > low_level, high_level - low_level, 1.0)
        u = jnp.sqrt(jnp.clip((indentation - low_level) / span, 0.0, 1.0))
        size = self.table.shape[1]
        position = u * (size - 1)
        index = jnp.clip(jnp.floor(position).astype(int), 0, size - 2)
        lower = self.table[segment, index]
        upper = self.table[segment, index + 1]
        start = lower + (position - index) * (upper - lower)

        # In the first cell the root may lie any number of decades above the segment's start p
        # (a tip, p = 0 with h ∝ x^k, possibly of infinite slope; or a turning point far below
        # the cell, as for a tiny Δγa): there Newton runs on log(h − h(p)) against log(x − p),
        # a nearly straight line.
        base = self.nodes[segment]
        from_base = (index == 0) & (indentation > low_level)
        base_start = self._power_start(law, base, low_level, upper, indentation)
        start = jnp.where(from_base, base_start, start)

        def newton(x):
            log_step, _ = self._log_newton(law, base, low_level, x, indentation)
            return jnp.where(from_base, log_step, self._newton(law, x, indentation))

        refined = jax.lax.stop_gradient(
            jax.lax.fori_loop(0, _NEWTON_STEPS, lambda _, x: jnp.clip(newton(x), lower, upper), start)
        )
        return jnp.clip(newton(refined), lower, upper)

    def _rise(self, law: ContactLaw, base, base_level, x):
        """(h(x) − h(p), its local exponent d log(h − h(p)) / d log(x − p)) above p = base."""
        rise = self.level(law, x) - base_level
        exponent = (x - base) * law.edge_slope(x, self.coefficient) / jnp.where(rise > 0.0, rise, 1.0)
        return rise, exponent

    def _power_start(self, law: ContactLaw, base, base_level, node, indentation):
        """Root of h = d between `base` and `node` if h − h(base) ∝ (x − base)^k with the local
        exponent k at the node."""
        rise, exponent = self._rise(law, base, base_level, node)
        usable = (rise > 0.0) & (exponent > 0.0)
        ratio = (indentation - base_level) / jnp.where(rise > 0.0, rise, 1.0)
        return base + (node - base) * jnp.where(usable, ratio ** (1.0 / jnp.where(usable, exponent, 1.0)), 0.0)

    def _log_newton(self, law: ContactLaw, base, base_level, x, indentation):
        """One Newton step on log(h − h(base)) = log(d − h(base)) in the variable log(x − base),
        and whether it was one: (x', usable). Not usable (x' = x) where h − h(base) has no
        positive rise or local exponent at x — below the round-off of h just above a turning
        point, where the rise of a quadratic minimum underflows."""
        offset = jnp.maximum(x - base, _SMALLEST_RADIUS)
        rise, exponent = self._rise(law, base, base_level, base + offset)
        target = indentation - base_level
        usable = (rise > 0.0) & (exponent > 0.0) & (target > 0.0)
        log_step = (jnp.log(jnp.where(usable, rise, 1.0)) - jnp.log(jnp.where(usable, target, 1.0))) / jnp.where(
            usable, exponent, 1.0
        )
        return jnp.where(usable, base + offset * jnp.exp(-log_step), x), usable

    def _newton(self, law: ContactLaw, x, indentation):
        slope = law.edge_slope(x, self.coefficient)
        usable = slope > 0.0
        step = (self.level(law, x) - indentation) / jnp.where(usable, slope, 1.0)
        return x - jnp.where(usable, step, 0.0)

    def _solve(self, law: ContactLaw, indentation, lower, upper):
        """Newton's method on log(h − h(lower)) against log(x − lower) (see `radius`),
        safeguarded by bisection in log(x − lower) on [lower, upper], until the iterate
        settles (at most _SAFEGUARDED_STEPS steps; a level outside the segment's range has no
        root inside: the segment's end, at once)."""
        # The search runs on values without derivatives (a while loop has no reverse mode);
        # the final Newton step below carries them.
        branch, frozen, target, low_end, high_end = jax.lax.stop_gradient((self, law, indentation, lower, upper))
        base_level = branch.level(frozen, low_end)
        span = high_end - low_end
        top_level = branch.level(frozen, high_end)
        inside_range = (target > base_level) & (target < top_level)

        def running(state):
            count, _, _, _, settled = state
            return (count < _SAFEGUARDED_STEPS) & ~settled

        def step(state):
            count, lo, hi, offset, _ = state  # offsets from `lower`
            below = branch.level(frozen, low_end + offset) < target
            lo, hi = jnp.where(below, offset, lo), jnp.where(below, hi, offset)
            guess, usable = branch._log_newton(frozen, low_end, base_level, low_end + offset, target)
            guess = guess - low_end
            inside = usable & (guess > lo) & (guess < hi)
            # Settled once Newton moves the iterate by round-off (its step may then leave the
            # bracket by an ulp: the iterate is kept) or the bracket has closed on it. A step
            # that is no step (no usable rise at the iterate: h − h(lower) lost in round-off
            # just above a turning point) settles nothing: it bisects.
            settled = (usable & (jnp.abs(guess - offset) <= _SETTLED * offset)) | (hi - lo <= _SETTLED * hi)
            new = jnp.where(inside, guess, jnp.sqrt(lo) * jnp.sqrt(hi))
            return count + 1, lo, hi, jnp.where(settled, offset, new), settled

        first = branch._power_start(frozen, low_end, base_level, high_end, target) - low_end
        # Where the segment ends at a turning point (h' = 0 there: no local exponent, and the
        # power start is `lower` itself) the search starts from the segment's middle.
        _, top_exponent = branch._rise(frozen, low_end, base_level, high_end)
        first = jnp.where(top_exponent > 0.0, first, 0.5 * span)
        first = jnp.where(inside_range, first, jnp.where(target >= top_level, span, _SMALLEST_RADIUS))
        start = (0, jnp.asarray(_SMALLEST_RADIUS), span, jnp.clip(first, _SMALLEST_RADIUS, span), ~inside_range)
        _, _, _, offset, _ = jax.lax.while_loop(running, step, start)
        return jnp.clip(self._newton(law, lower + offset, indentation), lower, upper)

    def cascade_out(self, law: ContactLaw, start, indentation):
        """First x ≥ start with h(x) > d: where an outward (attach) cascade stops.

        Returns (radius, segment, blocked); blocked means no such x below x_top (the
        contact reaches the body's wall, or the table's top).
        """
        segment, blocked = next_rising(self.nodes, self.levels, self.increasing, start, indentation)
        radius = jnp.maximum(self.radius(law, indentation, segment), start)
        return jnp.where(blocked, self.nodes[-1], radius), segment, blocked

    def cascade_in(self, law: ContactLaw, start, indentation):
        """Largest x ≤ start with h(x) < d: where an inward (detach) cascade stops.

        Returns (radius, segment, separated); separated means no spring holds: a = 0.
        """
        segment, separated = previous_rising(self.nodes, self.levels, self.increasing, start, indentation)
        radius = jnp.minimum(self.radius(law, indentation, segment), start)
        return jnp.where(separated, 0.0, radius), segment, separated


def next_rising(nodes, levels, increasing, start, level):
    """The first rising segment ending beyond `start` above `level`: (segment, none found)."""
    candidate = increasing & (nodes[1:] > start) & (levels[1:] > level)
    return jnp.argmax(candidate), ~jnp.any(candidate)


def previous_rising(nodes, levels, increasing, start, level):
    """The last rising segment beginning before `start` below `level`: (segment, none found)."""
    candidate = increasing & (nodes[:-1] < start) & (levels[:-1] < level)
    return candidate.shape[0] - 1 - jnp.argmax(candidate[::-1]), ~jnp.any(candidate)


def build_branch(law: ContactLaw, coefficient, top, tabulation: Tabulation, table_size: int) -> Branch:
    """Find the turning points of h on (0, top] (in closed form for a power-law ĝ, else by a
    search); tabulate its increasing segments if `table_size` > 0."""
    max_turns = tabulation.max_turns

    def slope(x):
        return law.edge_slope(x, coefficient)

    if law.power_form() is None:
        turns, valid, count = _searched_turns(law, coefficient, top, tabulation)
    else:
        turns, valid, count = _power_law_turns(law, coefficient, top, max_turns)
    turns = jnp.where(valid, turns, top)
    nodes = jnp.concatenate([jnp.zeros(1), jnp.sort(turns), jnp.full(1, top)])
    levels = law.edge(nodes, coefficient)
    middles = 0.5 * (nodes[:-1] + nodes[1:])
    increasing = (slope(middles) > 0.0) & (nodes[1:] > nodes[:-1])
    return Branch(
        coefficient=jnp.asarray(coefficient, dtype=nodes.dtype),
        nodes=nodes,
        levels=levels,
        increasing=increasing,
        table=_tabulate(law, coefficient, nodes, levels, increasing, table_size) if table_size else None,
        overflow=count > max_turns,
    )


def _power_law_turns(law: ContactLaw, coefficient, top, max_turns: int):
    """The turning point of h = Â·x̂ⁿ − λ·√x̂ in closed form, where h' = 0:
    x̂^(n−½) = λ/(2nÂ) (one turn for λ > 0 and n ≠ ½; none without adhesion); as
    `sign_changes` returns it: (points [max_turns], valid [max_turns], count)."""
    scale, exponent = law.power_form()
    usable = law.adhesive & (coefficient > 0.0) & (exponent != 0.5) & (scale > 0.0)
    turn = half_power_root(coefficient / (2.0 * exponent * scale), exponent, usable)
    valid = usable & (turn > 0.0) & (turn < top)
    turns = jnp.zeros(max_turns).at[0].set(jnp.where(valid, turn, top))
    flags = jnp.zeros(max_turns, bool).at[0].set(valid)
    return turns, flags, jnp.sum(flags)


def _searched_turns(law: ContactLaw, coefficient, top, tabulation: Tabulation):
    """The turning points of h on (0, top], searched on a grid a third logarithmic, two thirds
    uniform; with `tabulation.tip_search` it also brackets a turn from falling to rising below
    the grid (an attach edge with 0 < Δγa ≪ Δγ turns at its own jump-in radius, any number of
    decades down)."""
    max_turns, grid_size, tip_search = tabulation.max_turns, tabulation.turn_grid, tabulation.tip_search

    def slope(x):
        return law.edge_slope(x, coefficient)

    logarithmic = grid_size // 3
    lowest = jnp.minimum(_GRID_LOWEST, top * 10.0**-_GRID_DECADES)
    grid = jnp.sort(
        jnp.concatenate(
            [
                jnp.stack(_tip_turn_bracket(slope, _SMALLEST_RADIUS / jnp.minimum(law.scales.radial, 1.0), lowest))
                if tip_search
                else jnp.zeros(0),
                jnp.logspace(jnp.log10(lowest), jnp.log10(top), logarithmic),
                top * jnp.linspace(0.0, 1.0, grid_size - logarithmic + 1)[1:],
            ]
        )
    )
    return sign_changes(slope, grid, slope(grid) > 0.0, max_turns)


def sign_changes(slope, grid, rising, max_turns: int, steps: int = _BISECTION_STEPS, newton_steps: int = 0):
    """Where `slope` changes sign between neighbours of the sorted `grid` (`rising`: slope > 0
    there), bisected `steps` times (to round-off by default), then refined by `newton_steps`
    Newton steps on the slope (clamped to the bracket: for a smooth slope, fewer bisections
    reach round-off), and differentiated implicitly: (points [max_turns], valid [max_turns],
    count)."""
    change = (rising[1:] != rising[:-1]) & (grid[1:] > grid[:-1])
    changes_up_to = jnp.cumsum(change)
    count = changes_up_to[-1]
    # The cell of the k-th change: the first where the running count exceeds k (the last cell
    # for the k beyond the count).
    turn = jnp.arange(max_turns)
    first = jnp.argmax(changes_up_to[None, :] > turn[:, None], axis=1)
    index = jnp.where(turn < count, first, grid.shape[0] - 2)

    rising_below = rising[index]  # the lower end keeps its sign: bisect towards the other one
    lo, hi = bisect(lambda x: (slope(x) > 0.0) == rising_below, grid[index], grid[index + 1], steps)

    def newton(_, x):
        value, curvature = jax.jvp(slope, (x,), (jnp.ones_like(x),))
        usable = curvature != 0.0
        return jnp.clip(x - jnp.where(usable, value / jnp.where(usable, curvature, 1.0), 0.0), lo, hi)

    found = jax.lax.fori_loop(0, newton_steps, newton, 0.5 * (lo + hi))
    return implicit_root(slope, found), jnp.arange(max_turns) < count, count


def _tip_turn_bracket(slope, lower, upper):
    """Two radii around the turn of h' from falling (the Heß term) to rising in [lower, upper],
    bisected in log x; both at `upper` when h' does not fall at the lower end (h' = g' ≥ 0
    without that term) or rise at the upper. `lower` is the smallest radius whose SI value is
    a normal float: below it g' underflows."""
    turns = (slope(lower) < 0.0) & (slope(upper) > 0.0)
    lo, hi = bisect(lambda x: slope(x) <= 0.0, lower, upper, _TIP_BISECTION_STEPS, midpoint=_geometric_mean)
    return jnp.where(turns, lo, upper), jnp.where(turns, hi, upper)


def _geometric_mean(lower, upper):
    return jnp.sqrt(lower) * jnp.sqrt(upper)


def _tabulate(law: ContactLaw, coefficient, nodes, levels, increasing, table_size):
    """x at u_i = i/(M−1) on each increasing segment, by bisection."""
    u = jnp.linspace(0.0, 1.0, table_size)
    targets = levels[:-1, None] + u[None, :] ** 2 * (levels[1:] - levels[:-1])[:, None]

    lower = jnp.broadcast_to(nodes[:-1, None], targets.shape)
    upper = jnp.broadcast_to(nodes[1:, None], targets.shape)
    lo, hi = bisect(lambda x: law.edge(x, coefficient) < targets, lower, upper, _TABLE_BISECTION_STEPS)
    table = jnp.where(increasing[:, None], 0.5 * (lo + hi), lower)
    return table.at[:, 0].set(nodes[:-1]).at[:, -1].set(jnp.where(increasing, nodes[1:], nodes[:-1]))
