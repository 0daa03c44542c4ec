"""Derivatives of impacts (`impact.as_function`) against the derivatives of the chapter's closed
forms, and against central finite differences of the simulation itself where there is none."""

import jax
import jax.numpy as jnp
import numpy as np
import pytest

import impact
from impact import theory
from tests.scenes import CONFIGS, E_STAR, MASS, WORK, R

TN_INPUTS = [
    "effects.adhesion.work_of_adhesion",
    "initial.velocity",
    "material.E_star",
    "body.profile.R",
    "body.mass",
]
TN_POINT = np.array([WORK, 0.6, E_STAR, R, MASS])  # configs/thornton_ning.yaml


@pytest.fixture(scope="module")
def thornton_ning():
    """f(Δγ, v0, E*, R, m) = (restitution, max_force) of configs/thornton_ning.yaml; one per
    module, so that its tests share the compiled programs."""
    return impact.as_function(CONFIGS / "thornton_ning.yaml", TN_INPUTS, ["restitution", "max_force"])


def tn_restitution(x):
    work, velocity, E_star, R, mass = x
    return theory.thornton_ning_restitution(velocity, mass, R, E_star, work)


def jkr_max_force(x):
    """Largest force of the reversible JKR impact of a paraboloid, by the energy balance: the
    body jumps in at first touch to a0³ = 2πΔγR²/E* (d = 0) and loads along the JKR branch
    d = a²/R − √(2πaΔγ/E*), F = 4E*a³/(3R) − √(8πΔγE*a³) (3.44) until ∫F dd = ½mv0²;
    F_max = F(a_max). The polynomial work integral is written out; a_max by Newton."""
    work, velocity, E_star, R, mass = x
    A, B = 4.0 * E_star / (3.0 * R), jnp.sqrt(8.0 * jnp.pi * work * E_star)
    C, D = 2.0 / R, 0.5 * jnp.sqrt(2.0 * jnp.pi * work / E_star)

    def stored(a):  # ∫ F(s)·d'(s) ds from 0: F·d' = AC s⁴ − (AD + BC) s^(5/2) + BD s
        return A * C * a**5 / 5.0 - (A * D + B * C) * a**3.5 / 3.5 + B * D * a**2 / 2.0

    jump_in = jnp.cbrt(2.0 * jnp.pi * work * R**2 / E_star)
    energy = 0.5 * mass * velocity**2 + stored(jump_in)

    def newton(a):
        return a - (stored(a) - energy) / jax.grad(stored)(a)

    a = jax.lax.stop_gradient(jax.lax.fori_loop(0, 60, lambda _, a: newton(a), 3.0 * jump_in))
    a = newton(a)  # one differentiable step: the implicit derivative of the root
    return A * a**3 - B * a**1.5


@pytest.mark.slow
def test_derivatives_match_thornton_ning(thornton_ning):
    """e and F_max and their derivatives w.r.t. (Δγ, v0, E*, R, m): values against (3.50–51)
    and the energy balance to 1e-8; jax.jacfwd and jax.grad against those closed forms
    differentiated with jax, ≤ 1e-6 relative (measured 2.5e-8; the issue's finite differences
    gave −4.931 m²/J and 0.4931 s/m). One test: the programs compile once."""
    f = thornton_ning
    point = jnp.asarray(TN_POINT)
    restitution, max_force = np.asarray(f(TN_POINT))
    assert restitution == pytest.approx(float(tn_restitution(point)), rel=1e-8, abs=0.0)
    assert max_force == pytest.approx(float(jkr_max_force(point)), rel=1e-8, abs=0.0)
    exact = np.asarray(jax.grad(tn_restitution)(point))
    jacobian = np.asarray(jax.jacfwd(f)(TN_POINT))
    np.testing.assert_allclose(jacobian[0], exact, rtol=1e-6)
    assert jacobian[0, :2] == pytest.approx([-4.931, 0.4931], rel=1e-3, abs=0.0)
    np.testing.assert_allclose(jacobian[1], np.asarray(jax.grad(jkr_max_force)(point)), rtol=1e-6)
    np.testing.assert_allclose(np.asarray(jax.grad(lambda x: f(x)[0])(TN_POINT)), exact, rtol=1e-6)
    np.testing.assert_allclose(np.asarray(jax.jacrev(f)(TN_POINT)), jacobian, rtol=1e-12)

    # With JAX's 64-bit flag off f still computes in float64 (on the host, with the same
    # programs) and hands back float32.
    jax.config.update("jax_enable_x64", False)
    try:
        single = jnp.asarray(TN_POINT)
        value = jax.jit(f)(single)
        gradient = jax.grad(lambda x: f(x)[0])(single)
        assert single.dtype == value.dtype == gradient.dtype == jnp.float32
    finally:
        jax.config.update("jax_enable_x64", True)
    assert float(value[0]) == pytest.approx(restitution, rel=2e-6, abs=0.0)
    np.testing.assert_allclose(np.asarray(gradient, np.float64), exact, rtol=1e-5)


@pytest.mark.slow
def test_vmap_and_jit_equal_single_calls(thornton_ning):
    """jax.vmap(f) over 8 velocities equals 8 calls of f (to round-off); jax.jit(f) equals f.
    f of the test above: its single calls reuse the compiled value."""
    f = thornton_ning
    points = np.tile(TN_POINT, (8, 1))
    points[:, 1] = np.linspace(0.4, 1.2, 8)
    batched = np.asarray(jax.vmap(f)(points))[:, 0]
    single = np.array([float(f(point)[0]) for point in points])
    np.testing.assert_allclose(batched, single, rtol=1e-12)
    assert float(jax.jit(f)(points[3])[0]) == single[3]
    e_theory = [float(tn_restitution(jnp.asarray(point))) for point in points]
    np.testing.assert_allclose(single, e_theory, rtol=1e-8)


@pytest.mark.slow
def test_power_law_derivatives_match_the_closed_form():
    """de/d(n, c, v0) of a power-law body against (3.81–82) differentiated with jax: ≤ 1e-6
    relative (measured 3.5e-9)."""
    inputs = ["body.profile.n", "body.profile.c", "initial.velocity"]
    f = impact.as_function(CONFIGS / "power_law.yaml", inputs, "restitution")
    point = np.array([1.5, 300.0, 0.3])
    gradient = np.asarray(jax.jacfwd(f)(point))

    def exact(x):
        n, c, velocity = x
        return theory.power_law_restitution(velocity, MASS, n, c, E_STAR, WORK)

    np.testing.assert_allclose(gradient, np.asarray(jax.grad(exact)(jnp.asarray(point))), rtol=1e-6)


def central_differences(f, point, step):
    """Jacobian by central differences with relative steps `step`: [outputs, inputs]."""
    columns = []
    for index in range(len(point)):
        up, down = point.copy(), point.copy()
        up[index] *= 1.0 + step
        down[index] *= 1.0 - step
        columns.append((np.asarray(f(up)) - np.asarray(f(down))) / (2.0 * step * point[index]))
    return np.stack(columns, axis=-1)


FINITE_DIFFERENCE_CASES = {
    # scene, changes, inputs, outputs, relative step
    "spring_array": (
        "spring_array.yaml",
        {"contact": {"springs": 200}},
        ["effects.adhesion.work_of_adhesion", "initial.velocity"],
        ["restitution", "max_force", "contact_time"],
        1e-4,
    ),
    "maugis_dugdale": (
        "maugis_dugdale.yaml",
        {},
        ["effects.adhesion.work_of_adhesion", "initial.velocity", "effects.adhesion.stress"],
        ["restitution", "max_force", "contact_time"],
        1e-4,
    ),
    "attach_on_touch_gravity": (  # attach on touch (Δγa = 0) and gravity, several bounces
        "gravity_bounces.yaml",
        {"effects": {"adhesion": {"work_of_adhesion": 0.1, "approach_work_of_adhesion": 0.0}}},
        ["effects.adhesion.work_of_adhesion", "initial.gap", "effects.gravity.g"],
        ["restitution", "max_force", "contact_time"],
        1e-4,
    ),
}


@pytest.mark.slow
@pytest.mark.parametrize("case", sorted(FINITE_DIFFERENCE_CASES))
def test_jacfwd_matches_finite_differences(case):
    """jax.jacfwd against central differences of the simulation (relative step 1e-4: the
    differences of steps 1e-4 and 1e-3 agree to ~1e-6, the truncation of 1e-3), ≤ 1e-5
    relative (measured ≤ 1e-7)."""
    file, changes, inputs, outputs, step = FINITE_DIFFERENCE_CASES[case]
    scene = impact.load_scene(CONFIGS / file).model_dump()
    for section, values in changes.items():
        scene[section].update(values)
    f = impact.as_function(scene, inputs, outputs)
    loaded = impact.load_scene(scene)
    point = np.array([_value(loaded, path) for path in inputs])
    np.testing.assert_allclose(np.asarray(jax.jacfwd(f)(point)), central_differences(f, point, step), rtol=1e-5)


def _value(scene, path):
    node = scene
    for key in path.split("."):
        node = getattr(node, key)
    return float(node)


def test_a_static_input_is_refused():
    with pytest.raises(impact.SceneError) as error:
        impact.as_function(CONFIGS / "thornton_ning.yaml", ["solver.rtol", "initial.velocity"], "restitution")
    assert str(error.value) == (
        "solver.rtol: selects the compiled program (a static choice of the solver, the limits, the "
        "contact or the effects): it cannot be an input; inputs are traced values such as velocities, "
        "moduli, works of adhesion, masses and profile parameters"
    )


def test_an_unknown_output_is_refused():
    with pytest.raises(impact.SceneError) as error:
        impact.as_function(CONFIGS / "thornton_ning.yaml", ["initial.velocity"], ["restitution", "bounciness"])
    assert str(error.value) == (
        "output: unknown output 'bounciness'; known: restitution, contact_time, max_indentation, "
        "max_force, min_force, touch_velocity, separation_velocity, dissipated_energy, "
        "tangential_velocity_after, spin_after, tangential_restitution, "
        "contact_point_tangential_restitution, rebound_angle, friction_work"
    )


def test_an_unknown_path_and_a_fixed_step_array_are_refused():
    scene = impact.load_scene(CONFIGS / "spring_array.yaml").model_dump()
    scene["solver"] = {"method": "verlet", "dt": 1e-10}
    with pytest.raises(impact.SceneError) as error:
        impact.as_function(scene, ["initial.speed"], "restitution")
    assert [path for path, _ in error.value.problems] == ["solver.method", "initial.speed"]
    assert "have no derivative" in error.value.problems[0][1]
    assert error.value.problems[1][1].startswith("no field 'initial.speed' in the scene; initial takes:")


def test_an_indentation_scene_is_refused():
    with pytest.raises(impact.SceneError) as error:
        impact.as_function(CONFIGS / "indentation_paraboloid.yaml", ["material.E_star"], "max_force")
    assert str(error.value) == "kind: as_function runs impacts; the scene is of kind 'indentation'"
