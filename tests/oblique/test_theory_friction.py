"""The closed forms of tangential contact and oblique impact (impact.theory): G*, Cattaneo–Mindlin
against its MDR derivation, the Masing branches of Mindlin–Deresiewicz, the rigid-body sliding
limit. Plain closed forms: no compile."""

import numpy as np
import pytest

from impact import theory

# A steel ball on steel: R = 5 mm, 10 N, μ = 0.3.
E, NU, R, FORCE, MU = 210e9, 0.3, 5e-3, 10.0, 0.3
E_STAR = 1.0 / (2.0 * (1.0 - NU**2) / E)
G_STAR = float(theory.effective_shear_modulus(E, NU, E, NU))
RADIUS = (3.0 * FORCE * R / (4.0 * E_STAR)) ** (1.0 / 3.0)  # Hertz
SLIP = float(theory.full_slip_displacement(FORCE, RADIUS, MU, G_STAR))


def test_shear_modulus_of_similar_materials_and_of_a_rigid_body():
    """G*/E* = 2(1 − ν)/(2 − ν) for similar bodies (1e-15); a rigid body adds no compliance:
    G* = 4G/(2 − ν), G = E/(2(1 + ν))."""
    assert G_STAR / E_STAR == pytest.approx(2.0 * (1.0 - NU) / (2.0 - NU), rel=1e-15, abs=0.0)
    shear = E / (2.0 * (1.0 + NU))
    assert float(theory.effective_shear_modulus(E, NU)) == pytest.approx(4.0 * shear / (2.0 - NU), rel=1e-15, abs=0.0)


def test_cattaneo_mindlin_is_the_sum_of_the_mdr_springs():
    """The MDR derivation: springs inside c stick at δ = λ(a² − c²)/R (λ = μE*/G*), those outside
    slip at λ(a² − x²)/R; Q = 2G*[cδ + ∫_c^a λ(a² − x²)/R dx] equals Johnson's μF_n(1 − c³/a³)
    with c = a(1 − Q/μF_n)^(1/3), and δ his (7.43): Q to 1e-13, δ to 1e-12, c to 1e-15·(a/c)³ (the
    cube root of 1 − Q/μF_n amplifies the round-off of Q by (a/c)³/3: 4e-12 at c = a/20)."""
    ratio = MU * E_STAR / G_STAR
    for fraction in (0.05, 0.3, 0.7, 0.99):
        c = RADIUS * fraction
        delta = ratio * (RADIUS**2 - c**2) / R
        slipping = ratio / R * (RADIUS**2 * (RADIUS - c) - (RADIUS**3 - c**3) / 3.0)
        force = 2.0 * G_STAR * (c * delta + slipping)
        assert float(theory.cattaneo_mindlin_force(delta, FORCE, RADIUS, MU, G_STAR)) == pytest.approx(
            force, rel=1e-13, abs=0.0
        )
        assert float(theory.cattaneo_mindlin_stick_radius(force, FORCE, RADIUS, MU)) == pytest.approx(
            c, rel=1e-15 / fraction**3, abs=0.0
        )
        assert float(theory.cattaneo_mindlin_displacement(force, FORCE, RADIUS, MU, G_STAR)) == pytest.approx(
            delta, rel=1e-12, abs=0.0
        )


def test_full_slip_and_the_initial_stiffness():
    """Q(δ_s) = μF_n, flat beyond; the initial slope is the no-slip stiffness 2G*a (rel 1e-6 at
    δ = 1e-9·δ_s: the curve's next term is O(δ²))."""
    assert float(theory.cattaneo_mindlin_force(SLIP, FORCE, RADIUS, MU, G_STAR)) == pytest.approx(
        MU * FORCE, rel=1e-15, abs=0.0
    )
    assert float(theory.cattaneo_mindlin_force(3.0 * SLIP, FORCE, RADIUS, MU, G_STAR)) == pytest.approx(
        MU * FORCE, rel=1e-6, abs=0.0
    )
    small = 1e-9 * SLIP
    slope = float(theory.cattaneo_mindlin_force(small, FORCE, RADIUS, MU, G_STAR)) / small
    assert slope == pytest.approx(2.0 * G_STAR * RADIUS, rel=1e-6, abs=0.0)


def test_masing_branches_close_the_loop():
    """After loading to δ*, the unloading branch Q* − 2Q_CM((δ* − δ)/2) reaches −Q* at −δ*, and the
    reloading branch from there returns to Q* at δ* (1e-13): a closed hysteresis loop."""
    turning = 0.7 * SLIP
    top = float(theory.cattaneo_mindlin_force(turning, FORCE, RADIUS, MU, G_STAR))
    bottom = float(theory.mindlin_deresiewicz_force(-turning, turning, top, FORCE, RADIUS, MU, G_STAR))
    assert bottom == pytest.approx(-top, rel=1e-13, abs=0.0)
    back = float(theory.mindlin_deresiewicz_force(turning, -turning, bottom, FORCE, RADIUS, MU, G_STAR))
    assert back == pytest.approx(top, rel=1e-13, abs=0.0)


def test_a_program_of_legs_follows_its_turning_points():
    """`masing_program_force` over load to δ*, unload to −δ*, reload to δ*: Cattaneo–Mindlin on
    the first leg, each later leg a Masing branch from the previous leg's last point, so the loop
    closes (−Q* at −δ*, Q* again at δ*, 1e-13) and the legs meet where they turn."""
    turning = 0.7 * SLIP
    ramp = np.linspace(0.0, 1.0, 11)
    displacement = np.concatenate([turning * ramp, turning * (1.0 - 2.0 * ramp[1:]), turning * (2.0 * ramp[1:] - 1.0)])
    leg = np.repeat([0, 1, 2], [11, 10, 10])
    forces = theory.masing_program_force(displacement, leg, FORCE, RADIUS, MU, G_STAR)
    top = float(theory.cattaneo_mindlin_force(turning, FORCE, RADIUS, MU, G_STAR))
    loading = np.asarray(theory.cattaneo_mindlin_force(displacement[:11], FORCE, RADIUS, MU, G_STAR))
    assert forces[:11] == pytest.approx(loading, rel=1e-15, abs=0.0)
    assert forces[20] == pytest.approx(-top, rel=1e-13, abs=0.0)
    assert forces[-1] == pytest.approx(top, rel=1e-13, abs=0.0)
    unloading = theory.mindlin_deresiewicz_force(displacement[11:21], turning, top, FORCE, RADIUS, MU, G_STAR)
    assert forces[11:21] == pytest.approx(np.asarray(unloading), rel=1e-15, abs=0.0)


@pytest.mark.parametrize("restitution", [1.0, 0.6])
def test_rigid_sliding_of_a_solid_sphere(restitution):
    """v_t′ = v_t − μ(1 + e)v_n, ω′ = μ(1 + e)v_n/(k²R) with k² = 2/5, and the gross-sliding
    threshold (7/2)μ(1 + e) (1e-14)."""
    mass, speed, angle = 1e-3, 2.0, 1.2
    inertia = 0.4 * mass * R**2
    normal, tangential = speed * np.cos(angle), speed * np.sin(angle)
    after, spin = (
        float(value) for value in theory.sliding_impact(normal, tangential, 0.0, restitution, MU, mass, R, inertia)
    )
    assert after == pytest.approx(tangential - MU * (1 + restitution) * normal, rel=1e-14, abs=0.0)
    assert spin == pytest.approx(MU * (1 + restitution) * normal / (0.4 * R), rel=1e-14, abs=0.0)
    threshold = float(theory.gross_sliding_tangent(restitution, MU, mass, R, inertia))
    assert threshold == pytest.approx(3.5 * MU * (1 + restitution), rel=1e-14, abs=0.0)


def test_the_compliant_gross_sliding_limit_is_maw_barber_fawcetts():
    """With e = 1 and similar materials, tan θ = μ[(1 + 1/k²)·2 − E*/G*] is Maw, Barber & Fawcett's
    ψ₁ = 4χ − 1, ψ₁ = (G*/E*)·tan θ/μ and χ = (1 − ν)/(2 − ν)·(1 + 1/k²) (1e-14)."""
    mass, inertia = 1e-3, 0.4 * 1e-3 * R**2
    ratio = E_STAR / G_STAR
    tangent = float(theory.gross_sliding_tangent(1.0, MU, mass, R, inertia, ratio))
    chi = (1.0 - NU) / (2.0 - NU) * (1.0 + mass * R**2 / inertia)
    assert tangent / (MU * ratio) == pytest.approx(4.0 * chi - 1.0, rel=1e-14, abs=0.0)
