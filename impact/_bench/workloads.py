"""What `impact bench speed` runs: the workloads (a scene built in code, swept over the initial
velocity), the point counts of the full and the quick plan, and the reference each error is
measured against."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import theory
from .._core.defaults import SPEED_REPEATS
from .._scene.adhesion import GreenwoodJohnsonAdhesion, MaugisDugdaleAdhesion
from .cases import case_scene, sticking_velocity
from .plans import BATCH_RANGE, CONE_ANGLE, E_STAR, MASS, POWER_C, RADIUS, WORK_OF_ADHESION

SPEED_OUTPUTS = ("speed.csv", "speed.png")
CLOSED_FORM = "closed form"  # error against the sweep's theory_restitution
TIGHTER = "rtol/100"  # error against the same points at rtol, atol / 100
TIGHTER_FACTOR = 100.0
TIGHTER_POINTS = 1000  # at most this many of the points (evenly strided) get the tighter run

# Maugis–Dugdale at Tabor parameter Λ = 1 on the benchmark paraboloid (configs/maugis_dugdale.yaml).
DUGDALE_STRESS = 3.7411019e7
# The glass bead of configs/gravity_bounces.yaml: dropped 0.15 µm, a few contacts, then captured.
BEAD = dict(R=1.0e-3, density=2500.0, E_star=1.0e10, work_of_adhesion=0.1, gap=1.5e-7, g=9.81)
POWER3_C = RADIUS**-2 / 2.0  # f = c·r³ through the paraboloid's f at r = R
BEAD_VELOCITIES = (1e-4, 2e-3)  # m/s at the start, 0.15 µm up: touch speeds 1.7–2.6 mm/s
ENERGY_RTOL = 1e-6  # rtol of the Thornton–Ning workload of a restitution table
# p_y (Pa) of the plastic workloads: 2.3× the pressure at the centre of the benchmark paraboloid's
# contact right after its jump-in (22 MPa), which Thornton & Ning's law needs p_y above.
YIELD_PRESSURE = 5.0e7


@dataclass(frozen=True)
class Workload:
    """A scene swept over `initial.velocity` from `velocities[0]` to `velocities[1]` (m/s),
    geometrically spaced, and the reference of its error."""

    key: str  # short name: the CSV's workload column, `--only`
    name: str
    scene: dict
    velocities: tuple[float, float]
    reference: str  # CLOSED_FORM or TIGHTER
    springs: int = 0  # spring count of a spring-array workload (0: continuum)

    def axis(self, points: int) -> dict:
        """The sweep's axes for `points` velocities."""
        return {"initial.velocity": np.geomspace(*self.velocities, points)}


def _range(sticking: float) -> tuple[float, float]:
    return (BATCH_RANGE[0] * sticking, BATCH_RANGE[1] * sticking)


def _power_law(key: str, name: str, n: float, c: float, profile: dict) -> Workload:
    v_n = float(theory.power_law_sticking_velocity(MASS, n, c, E_STAR, WORK_OF_ADHESION))
    return Workload(key, name, case_scene(key, profile, v_n), _range(v_n), CLOSED_FORM)


def spring_array(count: int) -> Workload:
    """The Thornton–Ning paraboloid on N = `count` springs, each contact computed whole from
    prefix sums (`solver.method: quadrature`, the fastest; the same results as the exact event
    loop to round-off); its error against Thornton–Ning is the spatial error of N springs."""
    v_s = sticking_velocity()
    scene = case_scene(f"springs_{count}", dict(shape="paraboloid", R=RADIUS), v_s)
    scene["contact"] = dict(springs=count)
    scene["solver"] = dict(method="quadrature")
    return Workload(f"springs{count}", f"spring array N={count}", scene, _range(v_s), CLOSED_FORM, springs=count)


def workloads(quick: bool = False) -> list[Workload]:
    """The workloads of issue #14 in table order, then the spring array's scan over N (the
    quick plan: the light ones, the scan at N = 64, 256, 1024)."""
    v_s = sticking_velocity()
    paraboloid = dict(shape="paraboloid", R=RADIUS)
    tn = Workload("tn", "Thornton–Ning", case_scene("tn", paraboloid, v_s), _range(v_s), CLOSED_FORM)
    power15 = _power_law("power1.5", "power law n=1.5", 1.5, POWER_C, dict(shape="power_law", n=1.5, c=POWER_C))
    power3 = _power_law("power3", "power law n=3", 3.0, POWER3_C, dict(shape="power_law", n=3.0, c=POWER3_C))
    cone = _power_law("cone", "cone", 1.0, float(np.tan(CONE_ANGLE)), dict(shape="cone", theta=CONE_ANGLE))
    light = [tn, power15, power3, cone, spring_array(256)]
    attach = Workload(
        "attach", "attach on touch", case_scene("attach", paraboloid, v_s, approach=0.0), _range(v_s), CLOSED_FORM
    )
    if quick:
        return [*light, attach, *(spring_array(n) for n in (64, 1024))]
    heavy = [spring_array(2048), _dugdale(v_s), attach, _bead(), _double_hertz(v_s)]
    loose = [_energy_ends(workload) for workload in (tn, power15, power3, cone)]
    timed = [_quadrature(workload) for workload in (tn, power15, power3, cone, *heavy[1:])]
    plastic = [_plastic(adhesive=False), _plastic(adhesive=True)]
    return [*light, *heavy, *loose, *timed, *plastic, *(spring_array(n) for n in SCAN_COUNTS if n not in (256, 2048))]


def _dugdale(v_s: float) -> Workload:
    scene = case_scene(MaugisDugdaleAdhesion.model_name(), dict(shape="paraboloid", R=RADIUS), v_s)
    scene["effects"]["adhesion"] = MaugisDugdaleAdhesion.section(
        work_of_adhesion=WORK_OF_ADHESION, stress=DUGDALE_STRESS
    )
    return Workload("md", "Maugis–Dugdale Λ=1", scene, _range(v_s), TIGHTER)


def _double_hertz(v_s: float) -> Workload:
    """Greenwood–Johnson at k = 10 (configs/greenwood_johnson.yaml): its goal is the JKR law's cost."""
    scene = case_scene(GreenwoodJohnsonAdhesion.model_name(), dict(shape="paraboloid", R=RADIUS), v_s)
    scene["effects"]["adhesion"] = GreenwoodJohnsonAdhesion.section(work_of_adhesion=WORK_OF_ADHESION, k=10.0)
    return Workload("gj", "Greenwood–Johnson k=10", scene, _range(v_s), TIGHTER)


def _energy_ends(workload: Workload) -> Workload:
    """A continuum workload as a restitution table with an ODE solver takes it: each phase's end
    from its energy balance (the default) makes the restitution exact at any rtol, so rtol
    ENERGY_RTOL serves (the contact time then good to about 1e-6)."""
    scene = {**workload.scene, "name": f"{workload.scene['name']}_energy"}
    scene["solver"] = dict(rtol=ENERGY_RTOL, atol=ENERGY_RTOL / 100.0, phase_ends="energy")
    name = f"{workload.name}, rtol {ENERGY_RTOL:g}"
    return Workload(f"{workload.key}_energy", name, scene, workload.velocities, workload.reference)


def _quadrature(workload: Workload) -> Workload:
    """A continuum workload without an ODE solve (`solver.method: quadrature`): each phase ended
    by its energy balance and timed by Gauss quadrature (the contact time good to about 1e-8);
    its error against the ODE solver's tighter run where it has no closed form (`tighter_error`)."""
    scene = {**workload.scene, "name": f"{workload.scene['name']}_quadrature"}
    scene["solver"] = dict(method="quadrature")
    return Workload(
        f"{workload.key}_quadrature", f"{workload.name}, quadrature", scene, workload.velocities, workload.reference
    )


def _plastic(adhesive: bool) -> Workload:
    """The benchmark paraboloid yielding at p_y = YIELD_PRESSURE (Thornton's law, or with adhesion
    Thornton & Ning's) by quadrature, its fastest method, from 1.001 to 30 times its yield velocity
    (with adhesion its sticking velocity)."""
    if adhesive:
        key, name = "tn_plastic_quadrature", "Thornton–Ning plastic, quadrature"
        scene = case_scene(key, dict(shape="paraboloid", R=RADIUS), 1.0)
        low = theory.adhesive_plastic_sticking_velocity(MASS, RADIUS, E_STAR, WORK_OF_ADHESION, YIELD_PRESSURE)
    else:
        key, name = "plastic_quadrature", "Thornton plastic, quadrature"
        scene = {**case_scene(key, dict(shape="paraboloid", R=RADIUS), 1.0), "effects": {}}
        low = theory.thornton_yield_velocity(MASS, RADIUS, E_STAR, YIELD_PRESSURE)
    scene["effects"]["plasticity"] = dict(yield_pressure=YIELD_PRESSURE)
    scene["solver"] = dict(method="quadrature")
    return Workload(key, name, scene, _range(float(low)), CLOSED_FORM)


def _bead() -> Workload:
    scene = dict(
        name="gravity_bounces",
        body=dict(profile=dict(shape="paraboloid", R=BEAD["R"]), density=BEAD["density"]),
        material=dict(E_star=BEAD["E_star"]),
        initial=dict(velocity=BEAD_VELOCITIES[0], gap=BEAD["gap"]),
        effects=dict(adhesion=dict(work_of_adhesion=BEAD["work_of_adhesion"]), gravity=dict(g=BEAD["g"])),
        limits=dict(max_bounces=64),
    )
    return Workload("gravity", "gravity bounces", scene, BEAD_VELOCITIES, TIGHTER)


SCAN_COUNTS = (64, 128, 256, 512, 1024, 2048, 4096)  # N of the spring array's cost-vs-N scan


@dataclass(frozen=True)
class SpeedPlan:
    """What one `impact bench speed` run measures: (workload, points counts) in order."""

    plan: tuple[tuple[Workload, tuple[int, ...]], ...]
    repeats: int = SPEED_REPEATS
    chunk: int | None = None  # points per compiled call (None: the sweep's default)

    def runs(self) -> tuple[tuple[Workload, tuple[int, ...]], ...]:
        return self.plan


def speed_plan(
    quick: bool = False,
    points: tuple[int, ...] = (),
    only: tuple[str, ...] = (),
    repeats: int = SPEED_REPEATS,
    chunk: int | None = None,
) -> SpeedPlan:
    """The full plan (every workload at 10², 10³, 10⁴ points, but the spring arrays at 10², 10³
    and the scan over N at 10²), or the quick one (the light workloads at 10², the scan at N = 64,
    256, 1024); `points` replaces every count, `only` keeps the workloads of those keys."""
    runs = []
    for workload in workloads(quick):
        if only and workload.key not in only:
            continue
        if quick:
            counts: tuple[int, ...] = (100,)
        elif workload.springs:
            counts = (100, 1000) if workload.springs in (256, 2048) else (100,)
        else:
            counts = (100, 1000, 10000)
        runs.append((workload, tuple(points) or counts))
    return SpeedPlan(tuple(runs), repeats, chunk)
