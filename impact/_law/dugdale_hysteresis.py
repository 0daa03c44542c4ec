"""Maugis–Dugdale adhesion with approach hysteresis, Δγa ≤ Δγ: this project's derivation (§3.8 of
the chapter has none), in the scaled units of `dugdale.DugdaleLaw` (E* = 1).

- Approach: the Maugis–Dugdale curve with the same σ0 and the range ha = Δγa/σ0: a point starts
  to attract once its gap falls below ha.
- Frozen zone: a point that has been within ha keeps attracting with σ0 until its gap reaches
  h = Δγ/σ0. The zone radius b grows monotonically along the curve (checked on every search
  grid: paraboloid, cone, n = 1.5 and 3, σ0 = 1e6…1e9 Pa), so the zone's outer edge stays at b_f,
  its largest radius so far, while ha ≤ gap(b_f) ≤ h. The contact edge keeps K = 0: (3.154) and
  (3.156) with b = b_f fixed, d = g(a) − 2σ·√(b_f² − a²); the range condition (3.152) becomes the
  gap at b_f, bⁿ·P(p) + b·Q(p) (`DugdaleLaw.range_gap`). Along it dF = 2a·dd (the zone's terms
  cancel): d and F rise with a, stable under both controls. At a = 0 the zone without contact
  keeps F = −π·σ·b_f² while d falls, its gap f(b_f) − d − (4σ/π)·b_f (3.162).
- Detach: where the gap at b_f reaches h, (3.152) holds with h: the state lies on the ordinary
  curve of range h and rides it down (b shrinks along it; the points it leaves are beyond h).
- Reloading returns along the frozen zone to the approach curve, where the gap at b_f falls back
  to ha: the state (a, b_f) there solves the approach curve's three equations.

At both switches the state is the same (a, b, d) seen from two families, so the path is
continuous there as the JKR hold at a_max is between its attach and detach edges; ha = h leaves
no frozen zone (the reversible law), and Λ → ∞ tends to the JKR law with Δγa (the zone's width
b − a → 0 pins a near a_max). The frozen zone is parametrised by φ: p = (b − a)/b = e^(−φ) in
contact (φ ≥ 0), d = −2σ·b_f + φ without contact (φ < 0; a kink at φ = 0, where the contact
closes, as at the curves' junction b_J).

`HysteresisCurve` is the path a state rides from the memory b_f, one parameter s over three
parts: the detach curve (s ≤ s1, its own parameter), the frozen zone (s1 ≤ s ≤ s2, φ = φ_d + s −
s1) and the approach curve (s ≥ s2). With b_f = 0 (apart) the frozen zone is the free approach
from d = −h to −ha at F = 0.
"""

from typing import ClassVar

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.derivatives import implicit_root
from .._core.search import bisect
from .curve import AbstractCurve, force_turns
from .dugdale import DugdaleCurve, DugdaleLaw
from .scales import Scales

# The frozen zone's switches, φ ∈ [0, 64] in contact (p ≥ 1.6e-28, beyond every curve's top):
# bisection to 64/2^36 ≈ 1e-9, then Newton steps (clamped to the bracket), each squaring the error.
_LARGEST_SHARE_LOG = 64.0
_SWITCH_STEPS = 36
_SWITCH_NEWTON_STEPS = 2


class HystereticLaw(eqx.Module):
    """A Maugis–Dugdale law that attaches over the range ha ≤ h and detaches over h."""

    detach: DugdaleLaw  # range ĥ = Δγ/σ0
    approach_range: jax.Array  # ĥa = Δγa/σ0

    @property
    def approach(self) -> DugdaleLaw:
        """The law of the approach curve: the range ĥa."""
        return eqx.tree_at(lambda law: law.range, self.detach, self.approach_range)

    @property
    def scales(self) -> Scales:
        return self.detach.scales

    @property
    def onset(self):
        """d where the interaction starts: the tip within the approach range, −ĥa."""
        return -self.approach_range


def frozen_share(phi):
    """The zone share p = e^(−φ) of the frozen zone's contact at φ (1 without contact, φ < 0)."""
    return jnp.exp(-jnp.where(phi >= 0.0, phi, 0.0))


def frozen_state(law: DugdaleLaw, zone, phi, closed=None, contact=None):
    """(d, F, a, b) of the frozen zone of radius b = `zone` at φ (3.154, 3.156 with b fixed);
    `closed`: whether the contact's formula holds (default φ ≥ 0; given, it continues across the
    kink at φ = 0); `contact`: `law.contact(frozen_share(φ), zone)`, if already at hand."""
    closed = phi >= 0.0 if closed is None else closed
    depth, force, radius, _ = law.contact(frozen_share(phi), zone) if contact is None else contact
    open_depth = -2.0 * law.stress * zone + phi
    return (
        jnp.where(closed, depth, open_depth),
        jnp.where(closed, force, -jnp.pi * law.stress * zone**2),
        jnp.where(closed, radius, 0.0),
        jnp.broadcast_to(zone, jnp.shape(depth)),
    )


def _closing_gap(law: DugdaleLaw, zone):
    """The gap at b of the frozen zone at φ = 0 (a = 0, d = −2σb): f(b) + 2σ·(1 − 2/π)·b (3.164);
    without contact (φ < 0) it is f(b) − d − (4σ/π)·b = this − φ (3.162), in contact bⁿ·P + b·Q."""
    return law.f_unit() * zone**law.exponent + 2.0 * law.stress * (1.0 - 2.0 / jnp.pi) * zone


def frozen_switch(law: DugdaleLaw, zone, gap):
    """φ where the gap at b reaches `gap` (ĥ: onto the detach curve; ĥa: onto the approach curve):
    explicit without contact, bisected in φ in contact (the gap falls as φ grows), then Newton."""
    closing = _closing_gap(law, zone)
    safe = jnp.where(zone > 0.0, zone, 1.0)

    def excess(phi):
        return law.range_gap(jnp.exp(-phi), safe) - gap

    lower = jnp.zeros(jnp.broadcast_shapes(jnp.shape(zone), jnp.shape(gap)))
    lo, hi = bisect(lambda phi: excess(phi) > 0.0, lower, lower + _LARGEST_SHARE_LOG, _SWITCH_STEPS)

    def newton(_, phi):
        value, slope = jax.jvp(excess, (phi,), (jnp.ones_like(phi),))
        return jnp.clip(phi - jnp.where(slope < 0.0, value / jnp.where(slope < 0.0, slope, -1.0), 0.0), lo, hi)

    closed = implicit_root(excess, jax.lax.fori_loop(0, _SWITCH_NEWTON_STEPS, newton, 0.5 * (lo + hi)))
    return jnp.where(closing > gap, closed, closing - gap)


def curve_parameter(curve: DugdaleCurve, zone, phi):
    """s on a Maugis–Dugdale curve of the state with zone radius b at φ (of a switch, where the
    state is on the curve): b_J + φ in contact, b without."""
    return jnp.where(phi > 0.0, curve.junction + phi, zone)


class HysteresisCurve(AbstractCurve):
    """The path from the memory b_f: the detach curve up to s1, the frozen zone of b_f to s2, the
    approach curve beyond."""

    remembers: ClassVar[bool] = True

    approach: DugdaleCurve
    detach: DugdaleCurve
    approach_turns: jax.Array  # [T] turning points of F(s) on the approach curve ([0]: not needed)
    detach_turns: jax.Array  # [T] on the detach curve
    zone: jax.Array  # b_f
    lower: jax.Array  # s1 where the frozen zone meets the detach curve
    upper: jax.Array  # s2 where it meets the approach curve
    switches_at: jax.Array  # [2] φ of the two switches (detach, approach)
    start: jax.Array  # the approach curve's parameter at s2
    junction: jax.Array  # [3] where a contact closes: on the detach curve, frozen zone, approach curve (nan: none)
    nodes: jax.Array
    levels: jax.Array
    increasing: jax.Array
    overflow: jax.Array

    def state(self, law: HystereticLaw, s):
        """(d, F, a, b) at s."""
        return _on_part(self, law, s, s)

    def on_segment(self, law: HystereticLaw, s, segment):
        """(d, F, a, b) at s by the formula of the segment's part (continued across its ends: the
        parts meet at kinks, where a ride that starts at rest would see the wrong slope)."""
        return _on_part(self, law, s, 0.5 * (self.nodes[segment] + self.nodes[segment + 1]))

    def grid(self, law: HystereticLaw):
        """The detach curve's grid to s1, the frozen zone's ends, the approach curve's beyond s2."""
        detach = jnp.minimum(self.detach.grid(law.detach), self.lower)
        approach = self.upper + jnp.maximum(self.approach.grid(law.approach) - self.start, 0.0)
        return jnp.concatenate([detach, jnp.stack([self.lower, self.upper]), approach])

    def closes(self, s):
        return jnp.any(s == self.junction)

    def switches(self, s):
        """Whether s is a switch between the frozen zone and the detach or approach curve."""
        return (self.upper > self.lower) & ((s == self.lower) | (s == self.upper))

    def force_turns(self, law: HystereticLaw, top, max_turns: int):
        """The turning points of F(s) of the detach curve below s1 and of the approach curve above
        s2 (F rises with d on the frozen zone), each padded with the switch: [2T]."""
        detach = jnp.where(self.detach_turns < self.lower, self.detach_turns, self.lower)
        approach = self.upper + self.approach_turns - self.start
        approach = jnp.where(approach > self.upper, jnp.minimum(approach, top), self.upper)
        return jnp.concatenate([detach, approach]), jnp.asarray(False)

    def at(self, law: HystereticLaw, zone) -> "HysteresisCurve":
        """The path of the memory b_f = `zone`."""
        return hysteresis_curve(law, self.approach, self.detach, zone, self.approach_turns, self.detach_turns)

    def anchored(self, law: HystereticLaw, s, memory) -> tuple["HysteresisCurve", jax.Array, jax.Array]:
        """The path of a state at s that turns back, its memory (the zone radius there) and the
        state's place on it: the end of the frozen zone where it left the detach or approach
        curve, else s (on the frozen zone the path stays)."""
        zone = self.state(law, s)[3]
        curve = self.at(law, zone)
        return curve, zone, jnp.where(s <= self.lower, curve.lower, jnp.where(s >= self.upper, curve.upper, s))


# Traced once per shape of s and of the part's point, as `dugdale._state`: a ride evaluates the
# path in about 30 places.
@jax.jit
def _on_part(curve: HysteresisCurve, law: HystereticLaw, s, where_part):
    """(d, F, a, b) at s by the formula of the part (and the frozen zone's side of φ = 0)
    holding `where_part`."""
    part = jnp.where(where_part <= curve.lower, 0, jnp.where(where_part < curve.upper, 1, 2))
    # The two curves differ only in their range and junction: one evaluation, of the part's.
    # (`where`, not min/max, for the parameter: their derivative at a tie is halved.)
    detaching = part == 0
    along = jnp.where(
        detaching,
        jnp.where(s <= curve.lower, s, curve.lower),
        jnp.where(curve.start + s - curve.upper > 0.0, curve.start + s - curve.upper, 0.0),
    )
    range_ = jnp.where(detaching, law.detach.range, law.approach_range)
    outer_law = eqx.tree_at(lambda outer: outer.range, law.detach, range_)
    junction = jnp.where(detaching, curve.detach.junction, curve.approach.junction)
    outer_curve = eqx.tree_at(lambda detach: detach.junction, curve.detach, junction)
    frozen_phi = curve.switches_at[0] + s - curve.lower
    # The contact's formulas once, at the part's share and zone radius: the outer curve's b
    # from its range condition, the frozen zone's b_f (the laws differ only in the range).
    frozen = part == 1
    share = jnp.where(frozen, frozen_share(frozen_phi), outer_curve.share(along))
    contact = law.detach.contact(share, jnp.where(frozen, curve.zone, outer_law.zone_radius(share)))
    outer = outer_curve.joined(outer_law, along, contact)
    closed = curve.switches_at[0] + where_part - curve.lower >= 0.0
    frozen_part = frozen_state(law.detach, curve.zone, frozen_phi, closed, contact)
    return tuple(jnp.where(frozen, f, o) for o, f in zip(outer, frozen_part, strict=True))


def hysteresis_curve(
    law: HystereticLaw, approach: DugdaleCurve, detach: DugdaleCurve, zone, approach_turns=None, detach_turns=None
) -> HysteresisCurve:
    """The path from the memory b_f = `zone` (0: apart) over the two built curves, split at their
    nodes, the frozen zone's ends and its junction; the curves' turning points of F(s), where a
    quasi-static march needs them."""
    zone = jnp.asarray(zone, float)
    switches = frozen_switch(law.detach, zone, jnp.stack([law.detach.range, law.approach_range]))
    # Equal ranges (Δγa = Δγ) leave no frozen zone: one root for both (two lanes may round apart).
    switches = switches.at[1].set(jnp.where(law.approach_range < law.detach.range, switches[1], switches[0]))
    lower = curve_parameter(detach, zone, switches[0])
    upper = lower + (switches[1] - switches[0])
    start = curve_parameter(approach, zone, switches[1])
    nan = jnp.full((), jnp.nan)
    junction = jnp.stack(
        [
            jnp.where(detach.junction < lower, detach.junction, nan),
            jnp.where((switches[0] < 0.0) & (switches[1] > 0.0), lower - switches[0], nan),
            jnp.where(approach.junction > start, upper + approach.junction - start, nan),
        ]
    )
    nodes = jnp.concatenate(
        [
            jnp.minimum(detach.nodes, lower),
            jnp.stack([lower, jnp.clip(lower - switches[0], lower, upper), upper]),
            upper + jnp.maximum(approach.nodes - start, 0.0),
        ]
    )
    empty = jnp.zeros(0)
    partial = HysteresisCurve(
        approach=approach,
        detach=detach,
        approach_turns=empty if approach_turns is None else approach_turns,
        detach_turns=empty if detach_turns is None else detach_turns,
        zone=zone,
        lower=lower,
        upper=upper,
        switches_at=switches,
        start=start,
        junction=junction,
        nodes=nodes,
        levels=jnp.zeros_like(nodes),
        increasing=jnp.zeros(nodes.shape[0] - 1, bool),
        overflow=approach.overflow | detach.overflow,
    )
    split = partial.split_at(law, nodes, partial.overflow)
    # Apart (b_f = 0) the frozen zone is the free approach at F = 0: flown, not ridden.
    free = (zone == 0.0) & (nodes[:-1] >= lower) & (nodes[1:] <= upper)
    return eqx.tree_at(lambda c: c.increasing, split, split.increasing & ~free)


def with_force_turns(
    law: HystereticLaw, approach: DugdaleCurve, detach: DugdaleCurve, max_turns: int
) -> HysteresisCurve:
    """The path apart (b_f = 0) over the two built curves with their turning points of F(s) (for a
    quasi-static march); it `overflow`s where either turns more often than `max_turns`."""
    approach_turns, approach_overflow = force_turns(law.approach, approach, approach.nodes[-1], max_turns)
    detach_turns, detach_overflow = force_turns(law.detach, detach, detach.nodes[-1], max_turns)
    turned = hysteresis_curve(law, approach, detach, 0.0, approach_turns, detach_turns)
    return eqx.tree_at(lambda c: c.overflow, turned, turned.overflow | approach_overflow | detach_overflow)
