"""Tangential contact and oblique impact: the effective shear modulus, Cattaneo–Mindlin partial
slip of a paraboloid under a constant normal force, its Mindlin–Deresiewicz (Masing) branches,
and the rigid-body sliding limit of an oblique impact.

References: K. L. Johnson, *Contact Mechanics* (Cambridge 1985), §7.2 (Cattaneo–Mindlin)
and §7.4 (Mindlin–Deresiewicz); V. L. Popov and M. Heß, *Method of Dimensionality Reduction in
Contact Mechanics and Friction* (Springer 2015), the chapter on tangential contact (the same
results from the tangential MDR springs); N. Maw, J. R. Barber and J. N. Fawcett, Wear 38
(1976) 101, and E. Willert and V. L. Popov, ZAMM 96 (2016) 1089 (oblique impact).

In the MDR a paraboloid (g = x²/R) pressed to the contact radius a with the normal force
F_n = 4E*a³/(3R) and shifted tangentially by δ sticks inside c, where its tangential springs
(stiffness G*Δx) reach μ times their normal ones: μ(E*/G*)(a² − c²)/R = δ. Summing the springs,
Q = 2G*[cδ + ∫_c^a μ(E*/G*)(a² − x²)/R dx] = μF_n(1 − c³/a³), hence
c/a = (1 − Q/(μF_n))^(1/3) and δ = δ_s[1 − (1 − Q/(μF_n))^(2/3)], δ_s = 3μF_n/(4G*a) the
displacement at which the whole contact slides. This is Johnson's (7.43) with his
(2 − ν₁)/G₁ + (2 − ν₂)/G₂ = 4/G*.
"""

import math

import jax.numpy as jnp
import numpy as np

from .._core.runtime import float64
from ..profiles import Scalars


@float64
def effective_shear_modulus(E: Scalars, nu: Scalars, E_body: Scalars = math.inf, nu_body: Scalars = 0.0):
    """The effective shear modulus `G*` [Pa], `1/G* = (2 − ν)/(4G) + (2 − ν_b)/(4G_b)` with
    G = E/(2(1 + ν)) (Johnson (7.43)); a rigid body (E_body = inf, the default) adds nothing.
    For elastically similar bodies `G*/E* = 2(1 − ν)/(2 − ν)`."""
    # Arithmetic only: numbers stay numbers (a scene's), arrays arrays (a sweep's, traced values).
    return 1.0 / ((2.0 - nu) * (1.0 + nu) / (2.0 * E) + (2.0 - nu_body) * (1.0 + nu_body) / (2.0 * E_body))


@float64
def full_slip_displacement(normal_force: Scalars, contact_radius: Scalars, coefficient: Scalars, G_star: Scalars):
    """`δ_s = 3μF_n/(4G*a)` [m]: the tangential displacement at which the whole contact of a
    paraboloid slides (Cattaneo–Mindlin, Johnson (7.43) at Q = μF_n)."""
    return 3.0 * coefficient * normal_force / (4.0 * G_star * contact_radius)


@float64
def cattaneo_mindlin_force(
    displacement: Scalars, normal_force: Scalars, contact_radius: Scalars, coefficient: Scalars, G_star: Scalars
):
    """Tangential force Q [N] of a paraboloid shifted by δ [m] from rest at a constant normal
    force F_n [N] (contact radius a [m]): Q = μF_n[1 − (1 − |δ|/δ_s)^(3/2)]·sign δ, μF_n·sign δ
    beyond δ_s (inverse of Johnson (7.43))."""
    slip = full_slip_displacement(normal_force, contact_radius, coefficient, G_star)
    ratio = jnp.minimum(jnp.abs(displacement) / slip, 1.0)
    return jnp.sign(displacement) * coefficient * normal_force * (1.0 - (1.0 - ratio) ** 1.5)


@float64
def cattaneo_mindlin_displacement(
    force: Scalars, normal_force: Scalars, contact_radius: Scalars, coefficient: Scalars, G_star: Scalars
):
    """Tangential displacement δ [m] under a tangential force |Q| < μF_n [N] applied from rest
    at a constant normal force F_n: δ = δ_s[1 − (1 − |Q|/(μF_n))^(2/3)]·sign Q (Johnson (7.43))."""
    slip = full_slip_displacement(normal_force, contact_radius, coefficient, G_star)
    ratio = jnp.abs(force) / (coefficient * normal_force)
    return jnp.sign(force) * slip * (1.0 - (1.0 - ratio) ** (2.0 / 3.0))


@float64
def cattaneo_mindlin_stick_radius(force: Scalars, normal_force: Scalars, contact_radius: Scalars, coefficient: Scalars):
    """Radius c [m] of the stick zone under |Q| ≤ μF_n applied from rest: c = a(1 − |Q|/(μF_n))^(1/3)
    (Johnson §7.2)."""
    return contact_radius * jnp.cbrt(1.0 - jnp.abs(force) / (coefficient * normal_force))


@float64
def mindlin_deresiewicz_force(
    displacement: Scalars,
    turning_displacement: Scalars,
    turning_force: Scalars,
    normal_force: Scalars,
    contact_radius: Scalars,
    coefficient: Scalars,
    G_star: Scalars,
):
    """Tangential force Q [N] after the last reversal of the displacement at (δ_t [m], Q_t [N]),
    at a constant normal force: the loading curve scaled by two about the turning point
    (Masing's rule; Mindlin and Deresiewicz, Johnson §7.4), Q = Q_t + 2·Q_CM((δ − δ_t)/2), valid
    until the branch meets the previous turning point."""
    shift = 0.5 * (displacement - turning_displacement)
    return turning_force + 2.0 * cattaneo_mindlin_force(shift, normal_force, contact_radius, coefficient, G_star)


def masing_program_force(
    displacement: np.ndarray,
    leg: np.ndarray,
    normal_force: float,
    contact_radius: float,
    coefficient: float,
    G_star: float,
) -> np.ndarray:
    """Tangential force Q [N] at each point of a shear program from rest at a constant normal
    force: Cattaneo–Mindlin on the first leg, then Mindlin–Deresiewicz (Masing) from the last point
    of the previous leg on each later one. `displacement` [m] and the integer `leg` of each point
    (0, 1, …, in program order) are arrays of one length; valid while no branch meets an earlier
    turning point."""
    common = (normal_force, contact_radius, coefficient, G_star)
    forces = np.empty_like(displacement, dtype=np.float64)
    turning = None
    for number in np.unique(leg):
        points = leg == number
        shift = displacement[points]
        if turning is None:
            forces[points] = cattaneo_mindlin_force(shift, *common)
        else:
            forces[points] = mindlin_deresiewicz_force(shift, *turning, *common)
        turning = (shift[-1], forces[points][-1])
    return forces


@float64
def gross_sliding_tangent(
    restitution: Scalars,
    coefficient: Scalars,
    mass: Scalars,
    radius: Scalars,
    inertia: Scalars,
    modulus_ratio: Scalars = 0.0,
):
    """tan θ above which a sphere (radius R [m], mass m [kg], inertia I [kg·m²] about its centre)
    hitting without spin at the angle θ from the normal slides through the whole impact:
    `μ[(1 + mR²/I)(1 + e_n) − e_n·E*/G*]`, `modulus_ratio` = `E*/G*` (dimensionless).

    A rigid contact (`modulus_ratio` 0, the default) slides while the contact point does,
    w = v_t − Rω ≥ 0, to the end: (1 + mR²/I)μ(1 + e_n), 7μ(1 + e_n)/2 for a solid sphere. A
    compliant one slides on after w has reversed, as long as the friction limit λu_z of its
    springs (`λ = μE*/G*`) falls faster than the springs follow the contact point, |w| < λ|ḋ|:
    that binds at the end, where ḋ = −e_n·v_n, and takes `e_n·μE*/G*` off. For e_n = 1 and
    similar materials this is the limit ψ₁ = 4χ − 1 of Maw, Barber & Fawcett (1976)."""
    return coefficient * ((1.0 + mass * radius**2 / inertia) * (1.0 + restitution) - restitution * modulus_ratio)


@float64
def sliding_impact(
    normal_velocity: Scalars,
    tangential_velocity: Scalars,
    spin: Scalars,
    restitution: Scalars,
    coefficient: Scalars,
    mass: Scalars,
    radius: Scalars,
    inertia: Scalars,
):
    """(v_t′ [m/s], ω′ [rad/s]) after an impact that slides throughout (tan θ above
    `gross_sliding_tangent`): the tangential impulse is μ times the normal one, m(1 + e_n)v_n,
    so v_t′ = v_t − μ(1 + e_n)v_n and ω′ = ω + mRμ(1 + e_n)v_n/I (ω > 0 rolls the sphere along
    the sliding direction; μ(1 + e_n)v_n/(k²R) added for I = k²mR²)."""
    impulse = coefficient * (1.0 + restitution) * normal_velocity
    return tangential_velocity - impulse, spin + mass * radius * impulse / inertia
