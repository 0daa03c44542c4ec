"""The work along the Maugis–Dugdale paraboloid's equilibrium curve in closed form: a potential
U(s) with dU/ds = F·dd/ds, so that ∫F dd from s₀ to s is U(s) − U(s₀) (scaled units of `Scales`).

Popov, Heß & Willert, Handbook of Contact Mechanics (Springer 2019), §3.8. On a contact (radius
a, zone radius b, c = √(b² − a²) = b·sin θ, a = b·cos θ), F = 2·(a·d − G(a)) − A with
A = σ·b²·(2θ − sin 2θ) (3.156) and d − g(a) = −2σ·c (3.154). By parts,
∫F dd = ∫₀ᵃ (d − g(x))² dx − A·d + ∫ω, with ω = (4σ²c² − 4σc·g(a))·da + 4σbθ·(g(a) − 2σc)·db
on the curve. ω alone is not exact, but the range condition R(a, b) = h (3.152) holds along the
curve (dR = 0), and ω − πσb²·dR is exact. For g = C_g·x² it all sums to

    U = (8/15)·C_g²·a⁵ − σ·C_g·b⁴·((5/3)·u³·sin θ + ½·u·sin θ + ½·θ) + (4/3)·σ²·(b³ − a³),

u = cos θ = 1 − p, b³ − a³ = b³·p·(3 − 3p + p²): every term without cancellation, even at the
JKR-like edge of a deep contact (p → 0). In the zone without contact (d = f(b) − (4σ/π)·b − h,
F = −πσb²) it is U = −(π/2)·σ·C_f·b⁴ + (4/3)·σ²·b³, which meets the contact's at the junction
(a = 0, θ = π/2, C_g = 2C_f).
"""

from collections.abc import Callable

import jax
import jax.numpy as jnp

from .dugdale import DugdaleCurve, DugdaleLaw, zone_angles


def closed_energy(law, curve) -> Callable[[jax.Array], jax.Array] | None:
    """s ↦ U(s) of `curve` where it is the Maugis–Dugdale paraboloid's (`curve_energy`); None
    for every other curve (static: known from the types)."""
    if isinstance(curve, DugdaleCurve) and isinstance(law, DugdaleLaw) and law.closed_degree == 2:
        return lambda s: curve_energy(law, curve, s)
    return None


def curve_energy(law: DugdaleLaw, curve: DugdaleCurve, s):
    """U at the curve parameter s (`DugdaleCurve`: s = b ≤ b_J in the zone, s = b_J − ln p in
    contact) of a paraboloid, scaled: the work ∫F dd along the curve is its difference."""
    assert law.closed_degree == 2, "the curve's energy is in closed form for the paraboloid only"
    stress, unit, junction = law.stress, law.g_unit(), curve.junction
    zone = jnp.minimum(s, junction)
    zone_energy = stress * zone**3 * (4.0 / 3.0 * stress - 0.5 * jnp.pi * law.f_unit() * zone)
    share = curve.share(s)
    angles = zone_angles(share)
    ratio, opening, angle = angles
    radius = law.zone_radius(share, angles)
    hertz = 8.0 / 15.0 * unit**2 * (ratio * radius) ** 5
    mixed = stress * unit * radius**4 * ((5.0 / 3.0 * ratio**2 + 0.5) * ratio * opening + 0.5 * angle)
    zone_stress = 4.0 / 3.0 * stress**2 * radius**3 * share * (3.0 - 3.0 * share + share**2)
    return jnp.where(s > junction, hertz - mixed + zone_stress, zone_energy)
