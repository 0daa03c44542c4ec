"""Adhesive elastic–plastic impacts of a paraboloid: the limiting contact pressure of Thornton &
Ning (C. Thornton, Z. Ning, "A theoretical model for the stick/bounce behaviour of adhesive,
elastic-plastic spheres", Powder Technol. 99, 154 (1998)), written in the MDR with the rule of
Heß so that the elastic branches are exactly those of the JKR law (3.44) and the plastic ones
reduce to Thornton's (1997) law without adhesion.

JKR units (those of `thornton_ning_max_force`): radii in a0 = (2πΔγR²/E*)^(1/3), depths in
a0²/R, forces in E*·a0³/R, energies in E*·a0⁵/R², pressures in E*·a0/(πR). In them:

- elastic branch about a dent (curvature ratio ρ = R/R_p, residual depth d_p; virgin ρ = 1,
  d_p = 0): d = d_p + ρa² − √a, F = (4/3)ρa³ − 2a^(3/2);
- yield: the pressure at the centre of the JKR distribution, p_H − p_A = 2a − a^(−1/2) (the
  Hertzian 2E*a/(πR) less the adhesive √(2ΔγE*/(πa))), reaches P = πRp_y/(E*a0) at a_y;
- plastic loading (a > a_y, and beyond the largest radius a_m so far): the Hertzian part of the
  force grows with the limiting pressure over the new contact area, F_H = (4/3)a_y³ + P(a² −
  a_y²) (Thornton's dF = p_y·d(πa²), i.e. F = F_y + πp_yR(δ − δ_y) in the Hertzian depth
  δ = a²/R), while the geometry a² = Rδ and the adhesive terms stay those of the elastic law:
  d = a² − √a, F = F_H − 2a^(3/2);
- unloading and reloading below a_m: the elastic branch with the dent fixed by a_m, ρ = F_H(a_m)
  / ((4/3)a_m³) and d_p = (1 − ρ)a_m² (continuous in d and F at a_m: Thornton's R_p and δ_p);
- separation where the dent's branch turns (dd/da = 0, the displacement-controlled critical
  point: a_c = (4ρ)^(−2/3)).

The energy stored in a contact of radius a on a dent's branch (elastic springs less the surface
energy πa²Δγ) is U = A²a − (2/3)Aρa³ + ρ²a⁵/5 − a²/2 with A = ρa² − √a; it is the potential of
every elastic branch (dU = F dd), so the kinetic energy lost splits exactly into the adhesion
hysteresis, −U(1) at the jump-in plus U(a_c) at the snap-off, and the plastic work, the loading
work past a_y less the energy the dent stores.
"""

import jax
import jax.numpy as jnp

from .._core.runtime import float64
from .._core.search import bisect
from ..profiles import Scalars
from ._impact import _jkr_units, _jkr_work

# Bisection in ln a from the jump-in radius over 40 decades: 120 halvings reach the ulp.
_BISECTION_STEPS = 120
_LOG_SPAN = 92.0


def _yield_pressure(R, E_star, work_of_adhesion, yield_pressure):
    """P = πRp_y/(E*a0): p_y in the JKR pressure unit E*a0/(πR)."""
    a0, _, _ = _jkr_units(R, E_star, work_of_adhesion)
    return jnp.pi * R * yield_pressure / (E_star * a0)


def _search(stays_lower):
    """The radius a ≥ 1 where `stays_lower` stops holding (bisected in ln a)."""
    low, high = bisect(stays_lower, 0.0, _LOG_SPAN, _BISECTION_STEPS)
    return jnp.exp(0.5 * (low + high))


def _yield_radius(P):
    """a_y: 2a − a^(−1/2) = P (increasing in a; a_y > 1 where P > 1)."""
    return _search(lambda log_a: 2.0 * jnp.exp(log_a) - jnp.exp(-0.5 * log_a) < P)


def _hertzian_force(a, a_y, P):
    """F_H of the largest radius a: (4/3)a³ up to a_y, then (4/3)a_y³ + P(a² − a_y²)."""
    return jnp.where(a > a_y, 4.0 / 3.0 * a_y**3 + P * (a**2 - a_y**2), 4.0 / 3.0 * a**3)


def _curvature_ratio(a_m, a_y, P):
    """ρ = R/R_p of the dent left by the largest radius a_m (1 while elastic)."""
    return _hertzian_force(a_m, a_y, P) / (4.0 / 3.0 * a_m**3)


def _stored_energy(a, ratio):
    """U on the branch of the dent with ρ = `ratio` at radius a (JKR units)."""
    excess = ratio * a**2 - jnp.sqrt(a)
    return excess**2 * a - 2.0 / 3.0 * excess * ratio * a**3 + ratio**2 * a**5 / 5.0 - a**2 / 2.0


def _plastic_antiderivative(a, a_y, P):
    """An antiderivative of F·dd/da along plastic loading: (c + Pa² − 2a^(3/2))(2a − a^(−1/2)/2)
    with c = (4/3)a_y³ − Pa_y²."""
    c = 4.0 / 3.0 * a_y**3 - P * a_y**2
    return c * a**2 - c * jnp.sqrt(a) + P / 2.0 * a**4 - P / 5.0 * a**2.5 - 8.0 / 7.0 * a**3.5 + a**2 / 2.0


def _loading_work(a, a_y, P):
    """∫F dd from the jump-in (a = 1, d = 0) to the radius a on first loading."""
    elastic = _jkr_work(jnp.minimum(a, a_y)) - _jkr_work(1.0)
    plastic = _plastic_antiderivative(a, a_y, P) - _plastic_antiderivative(a_y, a_y, P)
    return elastic + jnp.where(a > a_y, plastic, 0.0)


def _rebound_energy(a_m, a_y, P):
    """Kinetic energy at separation after turning at a_m: U(a_m) − U(a_c) on the dent's branch."""
    ratio = _curvature_ratio(a_m, a_y, P)
    return _stored_energy(a_m, ratio) - _stored_energy((4.0 * ratio) ** (-2.0 / 3.0), ratio)


def _max_radius(kinetic, a_y, P):
    """a_m where the loading work reaches `kinetic` (it falls from a = 1 to F = 0, then rises)."""
    return _search(lambda log_a: _loading_work(jnp.exp(log_a), a_y, P) < kinetic)


def _impact(velocity, mass, R, E_star, work_of_adhesion, yield_pressure):
    """(kinetic energy in JKR units, a_m, a_y, P) of an impact at `velocity`."""
    _, _, energy = _jkr_units(R, E_star, work_of_adhesion)
    P = _yield_pressure(R, E_star, work_of_adhesion, yield_pressure)
    a_y = _yield_radius(P)
    kinetic = 0.5 * mass * velocity**2 / energy
    return kinetic, _max_radius(kinetic, a_y, P), a_y, P


@float64
def adhesive_plastic_touch_pressure(R: Scalars, E_star: Scalars, work_of_adhesion: Scalars):
    """Pressure [Pa] at the centre of the JKR contact right after the jump-in (a = a0):
    `2E*a0/(πR) − √(2ΔγE*/(πa0)) = E*a0/(πR)`. A limiting pressure p_y at or below it would yield
    the contact as it forms: the model is defined for p_y above it only."""
    a0, _, _ = _jkr_units(R, E_star, work_of_adhesion)
    return E_star * a0 / (jnp.pi * R)


@float64
@jax.jit  # one compilation per shape (its bisection would recompile on each eager call)
def adhesive_plastic_yield_radius(R: Scalars, E_star: Scalars, work_of_adhesion: Scalars, yield_pressure: Scalars):
    """Contact radius a_y [m] where the JKR pressure at the centre reaches p_y:
    `2E*a/(πR) − √(2ΔγE*/(πa)) = p_y`."""
    a0, _, _ = _jkr_units(R, E_star, work_of_adhesion)
    return a0 * _yield_radius(_yield_pressure(R, E_star, work_of_adhesion, yield_pressure))


@float64
@jax.jit  # one compilation per shape (its bisection would recompile on each eager call)
def adhesive_plastic_yield_velocity(
    mass: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars, yield_pressure: Scalars
):
    """Impact velocity [m/s] whose loading just reaches a_y (0 where the attraction alone pulls
    the contact past a_y: every impact then yields)."""
    _, _, energy = _jkr_units(R, E_star, work_of_adhesion)
    P = _yield_pressure(R, E_star, work_of_adhesion, yield_pressure)
    a_y = _yield_radius(P)
    return jnp.sqrt(2.0 * jnp.maximum(_loading_work(a_y, a_y, P), 0.0) * energy / mass)


@float64
@jax.jit  # one compilation per shape (its bisection would recompile on each eager call)
def adhesive_plastic_max_radius(
    velocity: Scalars, mass: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars, yield_pressure: Scalars
):
    """Largest contact radius a_m [m] of an impact at `velocity` [m/s]: ½mv₀² = ∫F dd on loading."""
    a0, _, _ = _jkr_units(R, E_star, work_of_adhesion)
    return a0 * _impact(velocity, mass, R, E_star, work_of_adhesion, yield_pressure)[1]


@float64
@jax.jit  # one compilation per shape (its bisection would recompile on each eager call)
def adhesive_plastic_dent(
    max_radius: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars, yield_pressure: Scalars
):
    """(R_p [m], δ_p [m]) of the dent left by the largest contact radius a_m [m]: R_p = R/ρ with
    `ρ = F_H(a_m)/((4/3)E*a_m³/R)`, `δ_p = (1 − ρ)a_m²/R`; (R, 0) while a_m ≤ a_y."""
    a0, depth, _ = _jkr_units(R, E_star, work_of_adhesion)
    P = _yield_pressure(R, E_star, work_of_adhesion, yield_pressure)
    a_m = max_radius / a0
    ratio = _curvature_ratio(a_m, _yield_radius(P), P)
    return R / ratio, (1.0 - ratio) * a_m**2 * depth


@float64
@jax.jit  # one compilation per shape (its bisection would recompile on each eager call)
def adhesive_plastic_max_indentation(
    velocity: Scalars, mass: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars, yield_pressure: Scalars
):
    """Deepest indentation δ_max [m] of an impact at `velocity` [m/s]: a_m²/R − Δl(a_m) (the
    geometry of first loading, elastic or plastic)."""
    _, depth, _ = _jkr_units(R, E_star, work_of_adhesion)
    a_m = _impact(velocity, mass, R, E_star, work_of_adhesion, yield_pressure)[1]
    return (a_m**2 - jnp.sqrt(a_m)) * depth


@float64
@jax.jit  # one compilation per shape (its bisection would recompile on each eager call)
def adhesive_plastic_losses(
    max_indentation: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars, yield_pressure: Scalars
):
    """(adhesion hysteresis [J], plastic work [J]) of a contact that reached the depth δ_max [m]
    and separated: −U(a0) at the jump-in plus U(a_c) at the snap-off, and the loading work past
    a_y less the energy the dent stores, U(a_m) − U(a_y). Their sum is the kinetic energy lost."""
    _, depth, energy = _jkr_units(R, E_star, work_of_adhesion)
    P = _yield_pressure(R, E_star, work_of_adhesion, yield_pressure)
    a_y = _yield_radius(P)
    a_m = _search(lambda log_a: jnp.exp(2.0 * log_a) - jnp.exp(0.5 * log_a) < max_indentation / depth)
    ratio = _curvature_ratio(a_m, a_y, P)
    hysteresis = _stored_energy((4.0 * ratio) ** (-2.0 / 3.0), ratio) - _jkr_work(1.0)
    flow = _loading_work(a_m, a_y, P) - _loading_work(jnp.minimum(a_m, a_y), a_y, P)
    plastic = flow - (_stored_energy(a_m, ratio) - _jkr_work(jnp.minimum(a_m, a_y)))
    return hysteresis * energy, jnp.where(a_m > a_y, plastic, 0.0) * energy  # exactly 0 below yield


@float64
@jax.jit  # one compilation per shape (its bisection would recompile on each eager call)
def adhesive_plastic_restitution(
    velocity: Scalars, mass: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars, yield_pressure: Scalars
):
    """Restitution of the adhesive elastic–plastic impact at `velocity` [m/s]:
    e² = (U(a_m) − U(a_c))/(½mv₀²), 0 where the contact cannot separate (captured). Below the
    yield velocity it is Thornton–Ning's (3.50); at high speed it tends to Thornton's (1997)."""
    kinetic, a_m, a_y, P = _impact(velocity, mass, R, E_star, work_of_adhesion, yield_pressure)
    return jnp.sqrt(jnp.maximum(_rebound_energy(a_m, a_y, P), 0.0) / kinetic)


@float64
@jax.jit  # one compilation per shape (its bisection would recompile on each eager call)
def adhesive_plastic_sticking_velocity(
    mass: Scalars, R: Scalars, E_star: Scalars, work_of_adhesion: Scalars, yield_pressure: Scalars
):
    """Impact velocity [m/s] below which the body is captured: the largest radius a_m at which
    the dent's branch gives back no kinetic energy, U(a_m) = U(a_c), and ½mv_s² its loading work."""
    _, _, energy = _jkr_units(R, E_star, work_of_adhesion)
    P = _yield_pressure(R, E_star, work_of_adhesion, yield_pressure)
    a_y = _yield_radius(P)
    a_s = _search(lambda log_a: _rebound_energy(jnp.exp(log_a), a_y, P) < 0.0)
    return jnp.sqrt(2.0 * _loading_work(a_s, a_y, P) * energy / mass)
