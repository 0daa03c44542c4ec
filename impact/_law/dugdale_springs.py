"""The spring array with Maugis–Dugdale adhesion (§3.8): N midpoint springs x_i = (i − ½)·Δx
under the Dugdale stress over the range, in the scaled units of a `DugdaleLaw`.

With the k inner springs in contact (a = k·Δx, each at d − g(x_i)) and the free springs of the
adhesive zone a < x ≤ b stretched by the line load −2σ̂·√(b² − x²) (3.148), the range condition
(3.152) with the contact's displacement taken over [0, a] is linear in d for a given zone radius
b: with θ = arccos(a/b) and, from ∫_a^b g(x)/√(b² − x²) dx = bⁿ·(π/2)·P(p) + θ·g(a) (P of
`DugdaleLaw.shape_term`, p = (b − a)/b),

    d_k(b) = g(a) + [(π/2)·(bⁿ·P(p) − h) − 2σ̂·(b − a)] / θ,
    F_k(b) = 2Δx·Σ_{i≤k} (d − g(x_i)) − σ̂·b²·(2θ − 2(a/b)·√(1 − a²/b²))   (3.156, the zone exact).

So only the contact is discretised (midpoint sums: second order in Δx), and at k = 0 this is
the zone without contact, d = f(b) − (4σ̂/π)·b − h. Where the continuum edge condition (3.154)
holds at a, d_k(b) is the continuum state. A spring at x is in contact while its contact force
(3.153), ∝ φ(x) = d − g(x) + 2σ̂·√(b² − x²), is not negative: spring k + 1 attaches as φ(x_{k+1})
rises through 0, spring k detaches as φ(x_k) falls through 0. Along the k-curve the state is
valid for b between β_k⁻ (φ(x_k) = 0; 0 for k = 0) and β_k⁺ (φ(x_{k+1}) = 0).

`DugdaleSpringCurve` strings the N + 1 valid pieces into one equilibrium curve (`AbstractCurve`)
of s: piece k is s ∈ [2k, 2k + 1] (b linear from β_k⁻ to β_k⁺), and s ∈ (2k + 1, 2k + 2) a
connector falling from its end to the start of piece k + 1 (an attach moves the zone outward,
so the next piece starts below: the connector falls and is never ridden). The curve riders
(`_integrate.curve`, the quasi-static `march_curve`) then ride the rising pieces and jump at
fixed d between them: an attach or a detach, or a cascade of them (snap-in, snap-out), by the
same rule as on the continuum curve.

The springs must resolve the adhesive zone, whose width s = (π/4)E*Δγ/σ0² (`theory.
dugdale_zone_width`; a_c/(2Λ²) for the paraboloid) shrinks towards JKR: where Δx ≳ s a spring
beyond the edge lies outside the narrow zone, attaches only when the surface reaches it and
still detaches by the Dugdale condition, and the array dissipates like an attach-on-touch JKR
contact (captured where the continuum bounces). `DugdaleSpringCurve.resolves` asks for
`ZONE_SPRINGS` springs across the zone.
"""

import jax
import jax.numpy as jnp

from .. import theory
from .._core.search import log_sign_change
from .branches import sign_changes
from .curve import TOP_MARGIN, AbstractCurve, Reach
from .dugdale import DugdaleLaw, reach_radius

# Grid points per piece searched for turning points of d inside a piece.
_PIECE_GRID = 8
# Piece ends: log bisection of b − a over [1e-30, 1e3]·(array length + 1), 80 halvings.
_GAP_DECADES = (-30.0, 3.0)
_END_STEPS = 80
# Springs an array needs across the adhesive zone (s/Δx): the restitution's error against the
# continuum (paraboloid, v0 = 0.6 m/s) is the same function of s/Δx at Λ = 1 and 3 (1.2e-2,
# 1.5e-3, 3.8e-4 at s/Δx = 1.2, 2.5, 5) and enters its N⁻² regime at s/Δx ≈ 2; below 1/2 the
# body is captured or e is off by up to 0.4. At Λ = 10 it is larger (9e-3 at 2, 1.6e-3 at 4).
ZONE_SPRINGS = 2.0
# The default array reaches this far beyond the contact radius an impact or a program reaches
# (the continuum curve, `TOP_MARGIN` times): springs beyond the largest contact are never used.
LENGTH_MARGIN = 1.25


def spring_turns(max_turns: int, capacity: int) -> int:
    """Turning points of d or F a spring curve of `capacity` pieces may hold inside them, for a
    law whose continuum curve has `max_turns`: towards JKR (Λ ≳ 3) d and F each turn inside
    every piece (the narrow zone grows unstably before the next spring touches), and near a
    turning point of the continuum curve the slopes of a few pieces in a row alternate in sign."""
    return 2 * capacity + 4 * max_turns + 16


def default_length(law: DugdaleLaw, reach: Reach):
    """The array's default length (scaled): `LENGTH_MARGIN` times the contact radius that the
    impact or the program reaches (`reach`), where the continuum curve reaches `TOP_MARGIN` times."""
    return reach_radius(law, reach) * (LENGTH_MARGIN / TOP_MARGIN)


def zone_springs(law: DugdaleLaw, spacing):
    """Springs across the adhesive zone, s/Δx: s of `theory.dugdale_zone_width` in the law's units
    (E* = 1, Δγ = σ̂·ĥ: s = (π/4)·ĥ/σ̂)."""
    return theory.dugdale_zone_width(1.0, law.stress * law.range, law.stress) / spacing


def piece_state(law: DugdaleLaw, spacing, prefix, k, zone):
    """(d, F, a) on the k-curve at zone radius b (`prefix`[k] = Σ_{i≤k} g(x_i), scaled)."""
    n, stress = law.exponent, law.stress
    radius = k * spacing
    ratio = radius / jnp.where(zone > 0.0, zone, 1.0)  # a/b (0 for the zone born at b = 0)
    share = jnp.clip(1.0 - ratio, 0.0, 1.0)
    opening = jnp.sqrt(share * (2.0 - share))  # √(1 − a²/b²)
    angle = jnp.arctan2(opening, ratio)  # θ = arccos(a/b)
    rise = 0.5 * jnp.pi * (zone**n * law.shape_term(share) - law.range) - 2.0 * stress * (zone - radius)
    depth = law.law.g(radius) + rise / angle
    force = 2.0 * spacing * (k * depth - prefix[k]) - stress * zone**2 * (2.0 * angle - 2.0 * ratio * opening)
    return depth, force, radius


def contact_margin(law: DugdaleLaw, depth, zone, x):
    """φ(x) = d − g(x) + 2σ̂·√(b² − x²): the contact force of a spring at x over E*·Δx (3.153)."""
    return depth - law.law.g(x) + 2.0 * law.stress * jnp.sqrt(jnp.maximum((zone - x) * (zone + x), 0.0))


class DugdaleSpringCurve(AbstractCurve):
    """The equilibrium states of a Maugis–Dugdale spring array along s (pieces and connectors).
    The arrays hold a compiled capacity of pieces; the array's N (`count`, ≤ the capacity) may
    be traced, so one compilation serves every N."""

    spacing: jax.Array  # Δx
    count: jax.Array  # N
    prefix: jax.Array  # [capacity+2] Σ_{i≤k} g(x_i)
    lower: jax.Array  # [capacity+1] β_k⁻
    upper: jax.Array  # [capacity+1] β_k⁺
    junction: jax.Array  # s where the first spring attaches (the contact closes)
    nodes: jax.Array
    levels: jax.Array
    increasing: jax.Array
    overflow: jax.Array

    @property
    def capacity(self) -> int:
        return self.lower.shape[0] - 1

    @property
    def top(self):
        """s at the end of the last piece: spring N + 1, past the array, would attach."""
        return 2.0 * self.count + 1.0

    def resolves(self, law: DugdaleLaw):
        """Whether `ZONE_SPRINGS` springs or more lie across the adhesive zone (else the array's
        answer is wrong: `unresolved_zone`)."""
        return zone_springs(law, self.spacing) >= ZONE_SPRINGS

    def piece(self, law: DugdaleLaw, k, fraction):
        """(d, F, a, b) on piece k at the fraction of its way from β_k⁻ to β_k⁺."""
        zone = self.lower[k] + fraction * (self.upper[k] - self.lower[k])
        depth, force, radius = piece_state(law, self.spacing, self.prefix, k, zone)
        return depth, force, radius, zone

    def state(self, law: DugdaleLaw, s):
        """(d, F, a, b) at s: on piece k for s ∈ [2k, 2k + 1], else on the connector after it."""
        k = jnp.clip(jnp.floor(0.5 * s).astype(int), 0, self.count)
        offset = s - 2.0 * k
        on_piece = offset <= 1.0
        here = self.piece(law, k, jnp.clip(offset, 0.0, 1.0))
        following = self.piece(law, jnp.minimum(k + 1, self.count), jnp.zeros_like(s))
        weight = jnp.clip(offset - 1.0, 0.0, 1.0)
        return tuple(jnp.where(on_piece, h, h + weight * (f - h)) for h, f in zip(here, following, strict=True))

    def on_segment(self, law: DugdaleLaw, s, segment):
        """The piece holding `segment`, continued analytically past its ends (b linear in s),
        not into the connectors: a step that crosses a spring event sees no kink."""
        k = jnp.clip(jnp.floor(0.5 * self.nodes[segment]).astype(int), 0, self.count)
        return self.piece(law, k, s - 2.0 * k)

    def grid(self, law: DugdaleLaw):
        """`_PIECE_GRID` points on each piece, its ends included (none beyond the top)."""
        pieces = 2.0 * jnp.arange(self.capacity + 1)
        return jnp.minimum((pieces[:, None] + jnp.linspace(0.0, 1.0, _PIECE_GRID)[None, :]).ravel(), self.top)


def build_spring_curve(law: DugdaleLaw, count, capacity: int, length, max_turns: int) -> DugdaleSpringCurve:
    """The curve of `count` ≤ `capacity` midpoint springs on [0, L] (L = `length`, scaled), with
    up to `max_turns` turning points of d inside pieces (`overflow` where there are more, or more
    springs than the capacity)."""
    spacing = length / count
    k = jnp.arange(capacity + 1)
    positions = (k + 0.5) * spacing
    prefix = jnp.concatenate([jnp.zeros(1), jnp.cumsum(law.law.g(positions))])
    radius = k * spacing

    def margin_at(x):
        def excess(gap):
            depth, _, _ = piece_state(law, spacing, prefix, k, radius + gap)
            return contact_margin(law, depth, radius + gap, x)

        return excess

    low, high = (jnp.full(capacity + 1, 10.0**e) * (length + 1.0) for e in _GAP_DECADES)
    gaps_lower, _ = log_sign_change(margin_at(jnp.maximum(positions - spacing, 0.0)), low, high, _END_STEPS)
    gaps_upper, _ = log_sign_change(margin_at(positions), low, high, _END_STEPS)
    partial = DugdaleSpringCurve(
        spacing=spacing,
        count=jnp.asarray(count),
        prefix=prefix,
        lower=jnp.where(k == 0, 0.0, radius + gaps_lower),
        upper=radius + gaps_upper,
        junction=jnp.ones(()),
        nodes=jnp.zeros(1),
        levels=jnp.zeros(1),
        increasing=jnp.zeros(0, bool),
        overflow=jnp.asarray(False),
    )
    grid, top = partial.grid(law), partial.top

    def slope(s):
        return partial.slopes(law, s)[0]

    turns, valid, found = sign_changes(slope, grid, slope(grid) > 0.0, max_turns)
    ends = jnp.minimum(jnp.arange(2 * capacity + 2, dtype=grid.dtype), top)
    nodes = jnp.sort(jnp.concatenate([ends, jnp.where(valid, turns, top)]))
    # an array beyond its capacity is refused here
    return partial.split_at(law, nodes, (found > max_turns) | (count > capacity))
