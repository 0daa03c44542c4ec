"""One conformance test over every contact law × integrator a scene can choose: each case's
impacts, a separated one and (where the law has it) a captured one, hold

- the energy balance: the kinetic energy the first contact took, ½μ(v_t² − v_s²) (v_s = 0 when
  captured), is its `dissipated_energy`, the integrator's ∮F dd, to the integrator's tolerance
  `balance` (relative to ½μv_t²; under gravity plus the work done against it between the touch
  and the separation, μg·(d_touch − d_sep): the contact lets go at d < 0); and ∮F dd of the
  trajectory samples by trapezoids is that work to `SAMPLED` of ½μv_t² (the samples resolve a
  phase, not the jumps of a spring array's force between them: `SAMPLED_STEPS`);
- passivity: no energy created: the plastic and viscous work ≥ −balance·½μv_t², and where the
  contact let go the adhesion hysteresis and the unrecovered elastic energy too (`BOUND`);
  0 ≤ e with e² ≤ 1 + balance; `assert_passive` on the trajectory;
- the expected outcome: separated or captured;

and, in the slow tier, batch independence: its points swept alone (calls of two, the point and
its copy) and together in one call give every result bitwise equal. The laws that
`test_batch_independence.py` and `test_quadrature.py` already sweep in batches of several sizes
are not swept again here.

The scenes are those other tests compile (the configs of `test_configs.py`, and scenes of
`test_jkr.py`, `test_energy_ends.py`, `test_quadrature.py`, `test_verlet.py`,
`test_dugdale_springs.py`): in a whole run a case costs the load of a compiled program, not a
compile. `balance` per integrator, from what it guarantees: round-off
where the phases end from the energy (tsit5's energy ends, quadrature) or the events advance in
closed form (the spring array); else the solver's tolerance as the ride amplifies it, about ten
times what these points measure: 9.7e-7 at rtol 1e-6 on the continuum law, 1.3e-9 along a
finite-range curve and 1.3e-7 on a Maugis–Dugdale array (rtol 1e-10), 5.5e-9 on Thornton's
plastic law (dopri8), 4e-10 on Thornton–Ning's, 5.3e-11 damped; Verlet's own discrete balance,
7.9e-7 at Δt = 1e-11 s.
"""

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import pytest

from impact import Result, Scene, load_scene, simulate, theory
from impact._integrate.dugdale import DugdaleSpringIntegrator
from impact._run.impacts import solve_scene
from impact._run.parameters import options_for
from impact._run.sweep import sweep
from impact._scene.paths import with_values
from tests.run.bitwise import assert_bitwise, named_method
from tests.run.passive import assert_passive
from tests.scenes import CONFIGS, E_STAR, MASS, WORK, R, micro_sphere

ROUND_OFF = 1e-12
SAMPLED = 1e-3
SAMPLED_STEPS = 1e-2
STICKING = float(theory.thornton_ning_sticking_velocity(MASS, R, E_STAR, WORK))  # m/s, the micro-sphere's
JKR = {"adhesion": {"work_of_adhesion": WORK}}
MAUGIS_DUGDALE = {
    "adhesion": {
        "model": "maugis_dugdale",
        "work_of_adhesion": WORK,
        "stress": float(theory.maugis_adhesive_stress(1.0, R, WORK, E_STAR)),  # Λ = 1
    }
}
# Losses that hold the adhesive bond's energy until the contact lets go: negative while a captured
# body is still bound (a captured Thornton–Ning particle's plastic work exceeds its ½μv_t²).
BOUND = ("adhesion_hysteresis", "unrecovered_elastic_energy")
SPRING_CAPACITY = 256  # the compiled capacity of test_dugdale_springs.py's impacts


@dataclass(frozen=True)
class Case:
    """A law on an integrator: its scene (loaded), the traced field its points set, the points
    (value, expected status), its balance tolerance, how it runs (`simulate` unless the program
    another test compiled needs its own integrator), whether its points are swept here."""

    scene: Callable[[], Scene]
    axis: str
    points: tuple[tuple[float, str], ...]
    balance: float
    run: Callable[[Scene], Result] = simulate
    swept: bool = True


def config(name: str, **changes) -> Callable[[], Scene]:
    return lambda: with_values(load_scene(CONFIGS / name), changes)


def maugis_dugdale_array(scene: Scene) -> Result:
    """The array's impact by test_dugdale_springs.py's program (no trajectory, 256 springs
    compiled, the scene's count traced)."""
    largest = with_values(scene, {"contact.springs": SPRING_CAPACITY})
    integrator = DugdaleSpringIntegrator(rtol=1e-10, atol=1e-12, capacity=SPRING_CAPACITY)
    return solve_scene(scene, integrator, options_for(largest, trajectory=False))


VELOCITY = "initial.velocity"
SEPARATED, CAPTURED = "separated", "captured"
CASES = {
    "Elastic · tsit5 · energy ends": Case(
        lambda: load_scene(micro_sphere(0.5, name="test")), VELOCITY, ((0.5, SEPARATED), (2.0, SEPARATED)), ROUND_OFF
    ),
    "JKR · tsit5 · energy ends": Case(
        config("thornton_ning.yaml"), VELOCITY, ((0.6, SEPARATED), (0.25, CAPTURED)), ROUND_OFF, swept=False
    ),
    "JKR · tsit5 · integrated ends (rtol 1e-6)": Case(
        config("thornton_ning.yaml", **{"solver.rtol": 1e-6, "solver.atol": 1e-8, "solver.phase_ends": "integrated"}),
        VELOCITY,
        ((0.6, SEPARATED), (0.25, CAPTURED)),
        1e-5,
    ),
    "JKR · quadrature": Case(
        config("thornton_ning.yaml", **{"solver.method": "quadrature"}),
        VELOCITY,
        ((0.6, SEPARATED), (0.25, CAPTURED)),
        ROUND_OFF,
        swept=False,
    ),
    "JKR · spring array (exact events)": Case(
        config("spring_array.yaml"), VELOCITY, ((0.6, SEPARATED), (0.25, CAPTURED)), ROUND_OFF, swept=False
    ),
    "JKR · spring array · Verlet": Case(
        lambda: load_scene(
            micro_sphere(
                2 * STICKING, JKR, name="verlet", contact={"springs": 300}, solver={"method": "verlet", "dt": 1e-11}
            )
        ),
        VELOCITY,
        ((2 * STICKING, SEPARATED), (0.5 * STICKING, CAPTURED)),
        5e-6,
    ),
    "JKR · attach on touch": Case(
        config("attach_on_touch.yaml"), VELOCITY, ((0.6, SEPARATED), (0.3, CAPTURED)), ROUND_OFF, swept=False
    ),
    "Maugis–Dugdale · continuum": Case(
        config("maugis_dugdale.yaml"), VELOCITY, ((0.6, SEPARATED), (0.05, CAPTURED)), 1e-8, swept=False
    ),
    "Maugis–Dugdale · continuum · approach hysteresis": Case(
        config("maugis_dugdale_hysteresis.yaml"), VELOCITY, ((0.6, SEPARATED), (0.05, CAPTURED)), 1e-8
    ),
    "Maugis–Dugdale · spring array": Case(
        lambda: load_scene(micro_sphere(0.6, MAUGIS_DUGDALE, name="md-springs", contact={"springs": 128})),
        VELOCITY,
        ((0.6, SEPARATED), (0.05, CAPTURED)),
        1e-6,
        run=maugis_dugdale_array,
    ),
    "Greenwood–Johnson": Case(
        config("greenwood_johnson.yaml"), VELOCITY, ((0.6, SEPARATED), (0.05, CAPTURED)), 1e-8, swept=False
    ),
    "Thornton (plastic) · dopri8": Case(
        config("plastic_steel.yaml"), VELOCITY, ((1.0, SEPARATED), (0.01, SEPARATED)), 5e-8
    ),
    "Thornton–Ning (adhesive plastic)": Case(
        config("wall_particle.yaml"), VELOCITY, ((20.0, SEPARATED), (0.5, CAPTURED)), 5e-9
    ),
    "viscoelastic damping": Case(
        config("rubber_ball_viscoelastic.yaml"), VELOCITY, ((2.0, SEPARATED), (0.2, SEPARATED)), 1e-9
    ),
    "viscoelastic half-space · midpoint": Case(
        config("viscoelastic_sphere.yaml"), VELOCITY, ((3.0, SEPARATED), (0.3, CAPTURED)), 1e-8, swept=False
    ),
    "oblique, Coulomb per spring": Case(
        config("oblique_kharaz.yaml"), VELOCITY, ((3.9, SEPARATED), (1.0, SEPARATED)), ROUND_OFF, swept=False
    ),
    "JKR · gravity bounces": Case(
        config("gravity_bounces.yaml"), "initial.gap", ((1.5e-7, CAPTURED), (6e-7, CAPTURED)), ROUND_OFF
    ),
    "JKR · two bodies": Case(config("two_spheres.yaml"), VELOCITY, ((0.1, SEPARATED), (0.01, SEPARATED)), ROUND_OFF),
}


def first_contact_ends(result: Result) -> tuple[float, float] | None:
    """The indentations (m) at the first touch and where the first contact let go; None if it
    never did."""
    kinds = [kind for _, kind in result.events]
    if "separation" not in kinds:
        return None
    touch, separation = (result.events[kinds.index(kind)][0] for kind in ("touch", "separation"))
    at = np.searchsorted(result.t, [touch, separation])
    return float(result.indentation[at[0]]), float(result.indentation[at[1]])


def sampled_loop_work(result: Result) -> float:
    """∮F dd over the first contact (J), by trapezoids between the trajectory samples."""
    kinds = [kind for _, kind in result.events]
    touch, separation = (result.events[kinds.index(kind)][0] for kind in ("touch", "separation"))
    inside = (result.t >= touch) & (result.t <= separation)
    depth, force = result.indentation[inside], result.force[inside]
    return float(np.sum(0.5 * (force[1:] + force[:-1]) * np.diff(depth)))


def assert_conforms(case: Case, result: Result, status: str) -> None:
    assert result.status == status, result.status
    mass = result.scene.reduced_mass
    touch = 0.5 * mass * result.touch_velocity**2
    lost = touch - 0.5 * mass * result.separation_velocity**2
    ends = first_contact_ends(result) if len(result.t) else None
    gravity = result.scene.effects.gravity
    if gravity is not None and ends is not None:
        lost -= mass * gravity.g * (ends[0] - ends[1])  # work against gravity, out of the kinetic energy
    assert abs(lost - result.dissipated_energy) <= case.balance * touch, (lost - result.dissipated_energy) / touch
    for loss in ("plastic_work", "viscous_work", *(() if result.stuck else BOUND)):
        assert getattr(result, loss) >= -case.balance * touch, loss
    assert result.restitution >= 0.0 and result.restitution**2 <= 1.0 + case.balance
    assert (result.restitution == 0.0) == (result.separation_velocity == 0.0)
    if len(result.t):
        assert_passive(result)
        if ends is not None:
            steps = result.scene.contact.springs != "continuum"
            tolerance = SAMPLED_STEPS if steps else SAMPLED
            assert abs(sampled_loop_work(result) - result.dissipated_energy) <= tolerance * touch


# The cases of the fast tier (`pytest -m "not slow"`): programs its other tests compile too.
FAST = ("JKR · tsit5 · energy ends", "JKR · quadrature")


@pytest.mark.parametrize("name", [pytest.param(name, marks=() if name in FAST else pytest.mark.slow) for name in CASES])
def test_every_law_on_every_integrator_balances_its_energy_and_creates_none(name):
    case = CASES[name]
    scene = case.scene()
    for value, status in case.points:
        assert_conforms(case, case.run(with_values(scene, {case.axis: value})), status)


@pytest.mark.slow
@pytest.mark.parametrize("name", [name for name, case in CASES.items() if case.swept])
def test_a_points_result_does_not_depend_on_its_batch_on_any_law(name):
    case = CASES[name]
    values = [value for value, _ in case.points]
    axes = {case.axis: [values[0], *values]}  # the first point twice: a lane beside its own copy
    scene = named_method(case.scene())  # the case's integrator, which a sweep keeps where it is named
    alone = sweep(scene, axes, order="given", chunk=1)
    together = sweep(scene, axes, order="given", chunk=64)
    assert alone.stats["call_sizes"] == [2] and together.stats["call_sizes"] == [len(values) + 1]
    assert_bitwise(together.results, alone.results, name)
    assert list(alone.status_names()[1:]) == [status for _, status in case.points]
