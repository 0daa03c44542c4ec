"""Maugis–Dugdale adhesion in the MDR picture (3.143–3.157), scaled units of `Scales`.

A constant adhesive stress σ0 acts wherever the gap is below the range h (Δγ = σ0·h, (3.4)).
In the 1-D model it is the line load q = −2σ0·√(b² − x²) on |x| ≤ b (3.148), b ≥ a the radius
of the adhesive zone. With σ̂ = σ0·ℓx/(E*·ℓz) and ĥ = h/ℓz (hats dropped below), for a body
f = C_f·rⁿ, g = C_g·xⁿ (paraboloid n = 2, cone n = 1, power law):

- zone without contact (a = 0, the centre gap open), b from 0 (gap h at the tip) upwards:
  d = f(b) − (4σ/π)·b − h,   F = −π·σ·b²  (gap h at r = b, (3.162) without its contact condition);
- contact of radius a = (1 − p)·b, p = (b − a)/b: the range condition (3.152) with (3.154)
  inserted is homogeneous in b,
      bⁿ·P(p) + b·Q(p) = h,   P = (2/π)·∫_0^θ (g(cos φ) − g(u)) dφ,   Q = (4σ/π)·(√(1 − u²)·θ − p),
  with u = a/b = 1 − p and θ = arccos u; then d = g(a) − 2σ·b·√(1 − u²) (3.154) and
  F = 2·(a·d − G(a)) − σ·b²·(2θ − 2u·√(1 − u²)) (3.156).

For each p the zone radius b is one monotone scalar root; no integral sits inside an iteration.
At p = 1 (a = 0) it is the junction b_J where the centre closes, f(b) + 2σ·(1 − 2/π)·b = h
(3.164), so one parameter runs along every equilibrium state: s = b ≤ b_J in the zone,
s = b_J − ln p in contact. `DugdaleCurve` splits s at the turning points of d(s): the body
rides the rising segments and jumps at fixed d at their ends, as the JKR branches do.

For the paraboloid and the cone P has a closed form, P = (C_g/2π)·S(2θ) (n = 2) and
P = (2C_g/π)·S(θ) (n = 1) with S(x) = sin x − x·cos x (its series where it cancels, x < 1/2),
and the range condition is a quadratic (n = 2) or linear (n = 1) equation in b: a state is a
few elementary functions. For other n P is Gauss–Legendre in φ for u ≥ 1/2, with
g(cos φ) − g(u) written without cancellation (u → 1 is the JKR-like edge of a deep contact);
for u < 1/2 it is f(1)·π/2 minus the part over y = cos φ ∈ [0, u], in y = u·t² (smooth for any
n), and b a Newton root.
"""

import math

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.derivatives import implicit_root
from .._core.lanes import computed_once
from .._core.quadrature import gauss_legendre, ordered_sum
from ..profiles import Cone, Paraboloid, PowerLaw, Profile
from .branches import sign_changes
from .curve import AbstractCurve, Reach
from .law import ContactLaw
from .scales import Scales

_QUADRATURE_NODES = 32
_RADIUS_NEWTON_STEPS = 12
# States searched for turning points: zones b/b_J from 1e-12 to 1 (half in log, half even),
# contacts with s − b_J = −ln p from 0 to the span, evenly. For the paraboloid d(s) and F(s)
# turn once each, at a minimum (found so for Λ from 1e-3 to 1e3 on a grid of 68 000 states):
# a coarse grid brackets them; other bodies are searched finely.
_CONTACT_LOG_SPAN = 40.0
_ZONE_POINTS, _CONTACT_POINTS = 192, 640
_PARABOLOID_ZONE_POINTS, _PARABOLOID_CONTACT_POINTS = 16, 32
# The paraboloid's grid of a spring array's default length (`reach_radius`): finer than its
# curve's (the reach is a grid point), and kept so that the default arrays stay as they are.
_LENGTH_ZONE_POINTS, _LENGTH_CONTACT_POINTS = 32, 128
# Turning points: bisection to 2^-8 of their grid cell, then Newton steps on dd/ds (clamped to
# the bracket): each squares the error, the third to round-off.
_TURN_BISECTION_STEPS = 8
_TURN_NEWTON_STEPS = 3


def degree_of(profile: Profile) -> jax.Array:
    """n of a body f = c·rⁿ: the paraboloid (n = 2), the cone (n = 1) or a power law."""
    if isinstance(profile, PowerLaw):
        return jnp.asarray(profile.n)
    if isinstance(profile, Paraboloid):
        return jnp.asarray(2.0)
    if isinstance(profile, Cone):
        return jnp.asarray(1.0)
    raise ValueError(f"Maugis–Dugdale adhesion needs a power-law body, not {type(profile).__name__}")


class DugdaleLaw(eqx.Module):
    """A power-law body in the scaled spring foundation with a Dugdale adhesive zone."""

    law: ContactLaw  # profile and scales (its JKR edge terms are unused)
    degree: jax.Array  # n
    stress: jax.Array  # σ̂ = σ0·ℓx/(E*·ℓz)
    range: jax.Array  # ĥ = h/ℓz

    @staticmethod
    def scaled(profile: Profile, scales: Scales, E_star, adhesive_stress, adhesion_range) -> "DugdaleLaw":
        """The law of a power-law body with the stress σ0 (Pa) up to the range h (m), in the units
        of `scales`."""
        zero = jnp.zeros(())
        return DugdaleLaw(
            law=ContactLaw(profile, scales, zero, zero, False),
            degree=degree_of(profile),
            stress=adhesive_stress * scales.radial / (E_star * scales.normal),
            range=adhesion_range / scales.normal,
        )

    @property
    def closed_degree(self) -> int | None:
        """n of a paraboloid (2) or a cone (1), whose P and b have closed forms (static: known
        from the body's type); None for a power law (n traced)."""
        return _CLOSED_DEGREES.get(type(self.law.profile))

    @property
    def exponent(self):
        """n: a Python number where it is known statically (integer powers), else traced."""
        closed = self.closed_degree
        return self.degree if closed is None else closed

    def g_unit(self):
        """C_g = ĝ(1)."""
        return self.law.g(jnp.ones(()))

    def f_unit(self):
        """C_f = f̂(1)."""
        scales = self.law.scales
        return self.law.profile.f(scales.radial) / scales.normal

    @property
    def scales(self) -> Scales:
        return self.law.scales

    @property
    def onset(self):
        """d where the interaction starts: the tip within the range, −h."""
        return -self.range

    def zone(self, zone, junction=None):
        """(d, F) of an adhesive zone of radius b without contact. Given the junction b_J, d is
        written from there, d = −2σ·b_J + f(b) − f(b_J) − (4σ/π)·(b − b_J) (the same with
        (3.164)), so that it meets the contact's d = −2σ·b_J at p = 1 exactly: a round-off step
        between the two would be a spurious jump where the curve runs flat past the junction."""
        n, stress, unit = self.exponent, self.stress, self.f_unit()
        force = -jnp.pi * stress * zone**2
        if junction is None:
            return unit * zone**n - 4.0 * stress * zone / jnp.pi - self.range, force
        rise = unit * (zone**n - junction**n) - 4.0 * stress * (zone - junction) / jnp.pi
        return rise - 2.0 * stress * junction, force

    def shape_term(self, share, angles=None):
        """P(p) of the range condition (`angles`: `zone_angles(share)`, if already at hand)."""
        ratio, opening, angle = zone_angles(share) if angles is None else angles
        closed = self.closed_degree
        if closed == 2:  # S(2θ): sin 2θ = 2uv, cos 2θ = (u − v)(u + v), v = sin θ
            excess = _sine_excess(2.0 * angle, 2.0 * ratio * opening, (ratio - opening) * (ratio + opening))
            return self.g_unit() / (2.0 * jnp.pi) * excess
        if closed == 1:
            return 2.0 * self.g_unit() / jnp.pi * _sine_excess(angle, opening, ratio)
        n, unit = self.degree, self.g_unit()
        nodes, weights = gauss_legendre(_QUADRATURE_NODES)
        phi = angle[..., None] * nodes
        # g(cos φ) − g(u) = C_g·uⁿ·expm1(n·log1p((cos φ − cos θ)/u)), cos φ − cos θ = 2 sin·sin
        safe_ratio = jnp.maximum(ratio, 0.25)[..., None]
        gap = 2.0 * jnp.sin(0.5 * (angle[..., None] + phi)) * jnp.sin(0.5 * (angle[..., None] - phi))
        excess = unit * safe_ratio**n * jnp.expm1(n * jnp.log1p(gap / safe_ratio))
        direct = angle * ordered_sum(weights * excess)
        # ∫_0^θ g(cos φ) dφ = (π/2)·f(1) − ∫_0^u g(y)/√(1 − y²) dy, y = u·t²
        inner = ratio[..., None] * nodes**2
        near = ordered_sum(weights * unit * inner**n * 2.0 * ratio[..., None] * nodes / jnp.sqrt(1.0 - inner**2))
        complement = 0.5 * jnp.pi * self.f_unit() - near - angle * unit * ratio**n
        return 2.0 / jnp.pi * jnp.where(ratio >= 0.5, direct, complement)

    def adhesive_term(self, share, angles=None):
        """Q(p) of the range condition (`angles` as for `shape_term`)."""
        _, opening, angle = zone_angles(share) if angles is None else angles
        return 4.0 * self.stress / jnp.pi * (opening * angle - share)

    def zone_radius(self, share, angles=None):
        """b solving bⁿ·P + b·Q = h: Newton on ln(bⁿP + bQ) = ln h (convex in ln b) from the
        smaller one-term root, which lies above; one last step outside the loop, from the root
        differentiated implicitly, carries the derivatives of b (the curve's slope dd/ds is
        itself one: its derivative needs the second)."""
        angles = zone_angles(share) if angles is None else angles
        shape, adhesive = self.shape_term(share, angles), self.adhesive_term(share, angles)
        if self.closed_degree == 2:  # b²P + bQ = h, P, Q ≥ 0: the positive root, without cancellation
            return 2.0 * self.range / (adhesive + jnp.sqrt(adhesive**2 + 4.0 * shape * self.range))
        if self.closed_degree == 1:
            return self.range / (shape + adhesive)
        n, log_range = self.degree, jnp.log(self.range)

        def residual(log_zone):
            return jnp.logaddexp(n * log_zone + jnp.log(shape), log_zone + jnp.log(adhesive)) - log_range

        def newton(log_zone):
            value, slope = jax.jvp(residual, (log_zone,), (jnp.ones_like(log_zone),))
            return log_zone - value / slope

        start = jnp.minimum((log_range - jnp.log(shape)) / n, log_range - jnp.log(adhesive))
        settled = jax.lax.fori_loop(0, _RADIUS_NEWTON_STEPS, lambda _, x: newton(x), jax.lax.stop_gradient(start))
        return jnp.exp(newton(implicit_root(residual, settled)))

    def contact(self, share, zone=None):
        """(d, F, a, b) of the contact with zone share p = (b − a)/b: d from (3.154), F from
        (3.156). Given the zone radius b (`zone`), of that b: its range condition need not hold
        (`range_gap`)."""
        n, unit = self.exponent, self.g_unit()
        angles = zone_angles(share)
        ratio, opening, angle = angles
        zone = self.zone_radius(share, angles) if zone is None else zone
        radius = ratio * zone
        depth = unit * radius**n - 2.0 * self.stress * zone * opening
        elastic = 2.0 * (unit * radius ** (n + 1) * n / (n + 1) - 2.0 * self.stress * radius * zone * opening)
        force = elastic - self.stress * zone**2 * (2.0 * angle - 2.0 * ratio * opening)
        return depth, force, radius, zone

    def range_gap(self, share, zone):
        """The gap at r = b of the contact with zone share p and zone radius b, bⁿ·P(p) + b·Q(p)
        (the left side of the range condition (3.152) with (3.154) inserted): h on the curve."""
        angles = zone_angles(share)
        return zone**self.exponent * self.shape_term(share, angles) + zone * self.adhesive_term(share, angles)


_CLOSED_DEGREES: dict[type, int] = {Paraboloid: 2, Cone: 1}
# Below this x, S(x) = sin x − x·cos x from its series Σ (−1)^(k+1)·2k·x^(2k+1)/(2k+1)!
# (8 terms: the first left out is below 1e-17 relative); above it the direct form loses at
# most a digit.
_SERIES_BELOW = 0.5
_SERIES = tuple((-1.0) ** (k + 1) * 2 * k / math.factorial(2 * k + 1) for k in range(1, 9))


def zone_angles(share):
    """(u, sin θ, θ) of the zone share p = 1 − u, u = a/b = cos θ: the one inverse trigonometric
    function of a state (sin θ = √(p(2 − p)) without cancellation at small p)."""
    ratio = 1.0 - share
    opening = jnp.sqrt(share * (2.0 - share))
    return ratio, opening, jnp.arctan2(opening, ratio)


def _sine_excess(x, sine, cosine):
    """S(x) = sin x − x·cos x = ∫_0^x φ·sin φ dφ from sin x and cos x, without cancellation at
    small x."""
    square = x * x
    series = jnp.full_like(x, _SERIES[-1])  # Horner's rule from its last coefficient: 0·x² + c, one step less
    for coefficient in reversed(_SERIES[:-1]):
        series = series * square + coefficient
    return jnp.where(x < _SERIES_BELOW, x * square * series, sine - x * cosine)


class DugdaleCurve(AbstractCurve):
    """The equilibrium states of one Dugdale law along s, split into monotone segments."""

    junction: jax.Array  # b_J
    nodes: jax.Array  # [S+1] segment ends in s: 0, turning points, b_J, s_top
    levels: jax.Array  # [S+1] d at the nodes
    increasing: jax.Array  # [S]
    overflow: jax.Array  # more turning points than the curve holds

    def state(self, law: DugdaleLaw, s):
        """(d, F, a, b) at s."""
        return _state(self, law, s)

    def share(self, s):
        """The zone share p = e^(b_J − s) of the contact at s (1 in the zone without contact)."""
        return jnp.exp(jnp.minimum(self.junction - s, 0.0))

    def joined(self, law: DugdaleLaw, s, contact):
        """(d, F, a, b) at s, given `contact`, the (d, F, a, b) of `law.contact` at `share(s)`."""
        closed = s > self.junction
        zone = jnp.minimum(s, self.junction)
        zone_depth, zone_force = law.zone(zone, self.junction)
        depth, force, radius, contact_zone = contact
        return (
            jnp.where(closed, depth, zone_depth),
            jnp.where(closed, force, zone_force),
            jnp.where(closed, radius, 0.0),
            jnp.where(closed, contact_zone, zone),
        )

    def grid(self, law: DugdaleLaw, points: tuple[int, int] | None = None):
        """Zones b/b_J from 1e-12 to 1 (log and even), then contacts with −ln p from 0 to 40
        (`points`: how many of each, if not the law's own)."""
        if points is None:
            points = (
                (_PARABOLOID_ZONE_POINTS, _PARABOLOID_CONTACT_POINTS)
                if law.closed_degree == 2
                else (_ZONE_POINTS, _CONTACT_POINTS)
            )
        zones, contacts = points
        unit = jnp.concatenate([jnp.logspace(-12.0, 0.0, zones // 2), jnp.linspace(0.0, 1.0, zones // 2)])
        contact = self.junction + jnp.linspace(0.0, _CONTACT_LOG_SPAN, contacts + 1)[1:]
        return jnp.concatenate([self.junction * jnp.sort(unit), contact])


# A ride's program evaluates the curve in about 30 places (its build, the vector field, the
# inversion, the work's extremes, …): as its own jitted function the states' formulas are traced
# once per shape of s (8 in an impact), and each place differentiates or batches that trace.
@jax.jit
def _state(curve: DugdaleCurve, law: DugdaleLaw, s):
    return curve.joined(law, s, law.contact(curve.share(s)))


def _unsplit(law: DugdaleLaw) -> DugdaleCurve:
    """The curve before it is bounded and split (its junction only)."""
    return DugdaleCurve(
        junction=law.zone_radius(jnp.ones(())),
        nodes=jnp.zeros(1),
        levels=jnp.zeros(1),
        increasing=jnp.zeros(0, bool),
        overflow=jnp.asarray(False),
    )


def reach_radius(law: DugdaleLaw, reach: Reach):
    """The contact radius where the curve's reach lies on its search grid (scaled; the
    paraboloid's finer `_LENGTH_*` grid), from the grid alone: no turning point is found."""
    curve = _unsplit(law)
    grid = curve.grid(law, (_LENGTH_ZONE_POINTS, _LENGTH_CONTACT_POINTS) if law.closed_degree == 2 else None)
    depths, forces, radii, _ = curve.state(law, grid)
    return curve.state(law, reach(grid, depths, forces, radii))[2]


def _grid_states(law: DugdaleLaw, curve: DugdaleCurve, grid):
    """(d, F, dd/ds, a) at the points of `grid` (a multiple of 16 of them), each computed once
    (`computed_once`: the reach's cumulative sums and the search for turning points read them
    all)."""

    def at(s):  # the states and dd/ds by one forward derivative
        (depth, force, radius), (slope, _, _) = jax.jvp(lambda x: curve.state(law, x)[:3], (s,), (jnp.ones_like(s),))
        return depth, force, slope, radius

    return jax.tree.map(lambda values: values.reshape(grid.shape), computed_once(at, grid.reshape(-1, 16)))


def build_curve(law: DugdaleLaw, max_turns: int, reach: Reach) -> DugdaleCurve:
    """Bound the curve (`reach`: `top_of_reach` for an impact, `top_of_peak` for a quasi-static
    program) and split it there at the turning points of d(s)."""
    partial = _unsplit(law)
    junction, grid = partial.junction, partial.grid(law)
    depths, forces, slopes, radii = _grid_states(law, partial, grid)
    top = reach(grid, depths, forces, radii)

    nodes, overflow = _turning_points(law, partial, jnp.minimum(grid, top), slopes > 0.0, junction, top, max_turns)
    return partial.split_at(law, nodes, overflow)


def _turning_points(law: DugdaleLaw, curve: DugdaleCurve, grid, rising, junction, top, max_turns: int):
    """Nodes 0, the turning points of d(s), b_J and the top, sorted; padded with the top."""
    turns, valid, count = sign_changes(
        lambda s: curve.riding(law, s)[2], grid, rising, max_turns, _TURN_BISECTION_STEPS, _TURN_NEWTON_STEPS
    )
    # A sign change across the junction is the junction itself (a kink), already a node.
    turns = jnp.where(valid & (jnp.abs(turns - junction) > 1e-12 * junction), turns, top)
    nodes = jnp.sort(jnp.concatenate([jnp.zeros(1), turns, jnp.stack([junction, top])]))
    return nodes, count > max_turns
