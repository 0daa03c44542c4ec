"""What accuracy costs in time: a work-precision benchmark of every way `impact` integrates an impact.

`run(folder, quick=False)` measures, in one process on this machine, and writes `bench.h5`,
`work_precision.png` and `table.md`:

- **Continuum law** (diffrax, `impact.simulate.solve`) × solvers × rtol (atol = rtol/100,
  scaled units), on reference cases with closed-form restitution: Thornton–Ning paraboloids
  at v0/v_s ∈ {1.001, 1.05, 2, 30}, a cone and a power law n = 1.5 ((3.81–82)), and a
  paraboloid that attaches on touch (`theory.attach_on_touch_restitution`). Recorded: the
  error |e − e_ref| of each case and its max, steps (accepted, rejected), the time of a single
  impact (jitted, after compile, no trajectory), the time per impact in a `jit(vmap)` batch of
  10³ velocities of one case, and compile times. The tolerance is passed to `solve`'s code as
  a traced argument, so one compile serves a whole rtol sweep (a static rtol recompiles, about
  5 s each); the full run checks against `solve` itself, compiled with static tolerances.
- **Spring array** (Thornton–Ning at 2 v_s) × N: the exact event-driven stepper
  (`impact.springs`, whose error is the pure spatial error) and a fixed-step velocity Verlet
  (`impact.verlet`) over Δt, whose difference from the exact discrete model is the pure
  time-stepping error; fitted orders in N and in Δt. For N = 10 and 10⁶, the exact stepper's
  time per spring event and the memory of its compiled program (the same: nothing of size N).
- **Baseline a researcher would write**: the same contact law with `scipy.integrate.solve_ivp`
  (RK45, DOP853), state (d, v) in scaled units, the contact radius from the JKR branch by
  `brentq` inside the right-hand side, a terminal separation event; same cases, same run.

Times are the best of a few repeats (the machine is shared and noisy; ratios measured in one
run are what to read). The library does not enable float64: the caller does (the CLI does).
"""

from __future__ import annotations

import dataclasses
import math
import os
import platform
import time
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path
from typing import Callable

import equinox as eqx
import h5py
import jax
import jax.numpy as jnp
import numpy as np

from .. import theory
from .._core.package import __version__
from .._integrate import continuum, verlet
from .._io.run import atomic_path, write_text
from .._integrate.codes import RESULT_CODE
from .._scene.scene import load_scene
from .._integrate.problem import build_problem
from .._run.simulate import numerics_for, physics_for, solve

OUTPUTS = ("bench.h5", "work_precision.png", "table.md")

# The "micro" pair of the core tests: a 1 µm paraboloid on a stiff polymer.
RADIUS, E_STAR, WORK_OF_ADHESION, MASS = 1e-6, 1e9, 0.05, 1.0472e-14
CONE_ANGLE = 0.3  # slope angle (rad): f = r·tanθ, the power law n = 1, c = tanθ
POWER_N = 1.5
POWER_C = RADIUS ** (1.0 - POWER_N) / 2.0  # f = c·rⁿ through the paraboloid's f at r = R
TN_FACTORS = (1.001, 1.05, 2.0, 30.0)  # v0 / v_s of the Thornton–Ning cases
OTHER_FACTOR = 2.0  # v0 / v_s of the cone, power-law and attach-on-touch cases
BATCH_RANGE = (1.001, 30.0)  # v0 / v_s spanned by the batch

# Errors below this are round-off: they are drawn at it and left out of fits.
ERROR_FLOOR = 1e-15
TARGETS = (1e-3, 1e-4, 1e-6, 1e-8, 1e-10)  # errors at which the costs are compared


@dataclass(frozen=True)
class Plan:
    """What one benchmark run measures."""

    solvers: tuple[str, ...]
    rtols: tuple[float, ...]
    groups: tuple[str, ...]  # case groups (one compile each): tn, cone, power, attach
    batch_size: int
    batch_budget: float  # s: a batch expected to take longer is skipped
    spring_counts: tuple[int, ...]
    cost_counts: tuple[int, ...]  # N at which time per spring event and memory are compared
    verlet_counts: tuple[int, ...]
    verlet_steps: tuple[float, ...]  # Δt in scaled time units
    scipy_methods: tuple[str, ...]
    scipy_rtols: tuple[float, ...]
    check_solve: tuple[float, ...]  # rtols at which `solve` itself (static tolerances) is timed
    timing_budget: float  # s spent repeating one timing
    passes: int  # sweeps over the settings, each timing anew (the best is kept: load spikes pass)


def _decades(start: float, stop: float, per_decade: int) -> tuple[float, ...]:
    count = int(round(abs(math.log10(stop) - math.log10(start)) * per_decade)) + 1
    exponents = np.linspace(math.log10(start), math.log10(stop), count)
    return tuple(float(10.0**x) for x in np.round(exponents, 6))


def _counts(low_exponent: float, high_exponent: float, per_decade: int) -> tuple[int, ...]:
    exponents = np.arange(low_exponent, high_exponent + 1e-9, 1.0 / per_decade)
    return tuple(int(n) for n in np.unique(np.round(10.0**exponents).astype(int)))


FULL = Plan(
    solvers=("tsit5", "dopri5", "dopri8", "kvaerno5"),
    rtols=_decades(1e-3, 1e-12, 1),
    groups=("tn", "cone", "power", "attach"),
    batch_size=1000,
    batch_budget=20.0,
    spring_counts=_counts(2, 6, 4),
    cost_counts=(10, 1_000_000),
    verlet_counts=(1000, 10_000, 100_000),
    verlet_steps=_decades(1e-2, 1e-5, 4),
    scipy_methods=("RK45", "DOP853"),
    scipy_rtols=_decades(1e-3, 1e-12, 1),
    check_solve=(1e-8,),
    timing_budget=0.1,
    passes=3,
)

QUICK = Plan(
    solvers=("tsit5",),
    rtols=_decades(1e-3, 1e-11, 0.5),
    groups=("tn",),
    batch_size=1000,
    batch_budget=5.0,
    spring_counts=_counts(2, 4.5, 4),
    cost_counts=(10, 1_000_000),
    verlet_counts=(1000,),
    verlet_steps=_decades(1e-2, 1e-4, 2),
    scipy_methods=("RK45", "DOP853"),
    scipy_rtols=(1e-3, 1e-6, 1e-9),
    check_solve=(),
    timing_budget=0.05,
    passes=2,
)


# --- reference cases ------------------------------------------------------------------------


@dataclass(frozen=True)
class Case:
    """A reference impact: its scene, closed-form restitution and the data of the baseline."""

    name: str
    group: str
    scene: dict
    reference: float
    n: float  # power-law exponent of g (for the baseline: g = aⁿ in JKR units)
    c: float  # f = c·rⁿ (m^(1−n))
    attach_on_touch: bool

    @property
    def velocity(self) -> float:
        return float(self.scene["initial"]["velocity"])


def _scene(name: str, profile: dict, velocity: float, approach: float | None = None) -> dict:
    adhesion = {"work_of_adhesion": WORK_OF_ADHESION}
    if approach is not None:
        adhesion["approach_work_of_adhesion"] = approach
    return dict(
        name=name,
        body=dict(profile=profile, mass=MASS),
        material=dict(E_star=E_STAR),
        initial=dict(velocity=velocity),
        effects=dict(adhesion=adhesion),
    )


def sticking_velocity() -> float:
    """Thornton–Ning sticking velocity of the benchmark paraboloid (m/s)."""
    return float(theory.thornton_ning_sticking_velocity(MASS, RADIUS, E_STAR, WORK_OF_ADHESION))


def reference_cases(groups=("tn", "cone", "power", "attach")) -> list[Case]:
    """The reference impacts of the named groups, each with its closed-form restitution."""
    v_s = sticking_velocity()
    paraboloid = dict(shape="paraboloid", R=RADIUS)
    cases = []
    if "tn" in groups:
        for factor in TN_FACTORS:
            velocity = factor * v_s
            cases.append(Case(
                f"thornton_ning_{factor:g}", "tn", _scene("tn", paraboloid, velocity),
                float(theory.thornton_ning_restitution(velocity, MASS, RADIUS, E_STAR, WORK_OF_ADHESION)),
                2.0, 0.5 / RADIUS, False,
            ))
    for group, name, profile, n, c in (
        ("cone", "cone", dict(shape="cone", theta=CONE_ANGLE), 1.0, math.tan(CONE_ANGLE)),
        ("power", "power_law_1.5", dict(shape="power_law", n=POWER_N, c=POWER_C), POWER_N, POWER_C),
    ):
        if group in groups:
            v_n = float(theory.power_law_sticking_velocity(MASS, n, c, E_STAR, WORK_OF_ADHESION))
            velocity = OTHER_FACTOR * v_n
            cases.append(Case(
                name, group, _scene(name, profile, velocity),
                float(theory.power_law_restitution(velocity, MASS, n, c, E_STAR, WORK_OF_ADHESION)),
                n, c, False,
            ))
    if "attach" in groups:
        velocity = OTHER_FACTOR * v_s
        cases.append(Case(
            "attach_on_touch", "attach", _scene("attach", paraboloid, velocity, approach=0.0),
            float(theory.attach_on_touch_restitution(velocity, MASS, RADIUS, E_STAR, WORK_OF_ADHESION)),
            2.0, 0.5 / RADIUS, True,
        ))
    return cases


def restitution(outcome) -> float:
    """e of a scaled outcome (nan unless the body separated)."""
    if int(outcome.status) != RESULT_CODE["separated"]:
        return float("nan")
    return float(outcome.separation_velocity) / float(outcome.touch_velocity)


# --- timing ---------------------------------------------------------------------------------


def best_time(call: Callable, budget: float, repeats: int = 7, once: float = 1.0):
    """(best wall time in s, last result) of `call()`, repeated while within `budget` (at least
    twice, unless one call takes more than `once` seconds)."""
    times, start = [], time.perf_counter()
    result = None
    while len(times) < repeats:
        t0 = time.perf_counter()
        result = jax.block_until_ready(call())
        times.append(time.perf_counter() - t0)
        if times[-1] > once or (len(times) >= 2 and time.perf_counter() - start > budget):
            break
    return min(times), result


def _compile(function, *args):
    """(compiled executable, seconds to trace, lower and compile)."""
    start = time.perf_counter()
    compiled = jax.jit(function).lower(*args).compile()
    return compiled, time.perf_counter() - start


def _with_tolerance(numerics, rtol):
    return dataclasses.replace(numerics, rtol=rtol, atol=rtol / 100.0)


# --- continuum law --------------------------------------------------------------------------


def bench_continuum(plan: Plan, cases: list[Case], log: Callable) -> dict:
    """Errors, steps, single and batched times and compile times of every solver × rtol."""
    names = [case.name for case in cases]
    rtols = np.asarray(plan.rtols)
    results = {}
    for solver in plan.solvers:
        shape = (len(rtols), len(cases))
        record = {
            "error": np.full(shape, np.nan),
            "restitution": np.full(shape, np.nan),
            "steps": np.zeros(shape, int),
            "accepted": np.zeros(shape, int),
            "rejected": np.zeros(shape, int),
            "time_single": np.full(shape, np.nan),
            "status": np.zeros(shape, int),
            "compile_single": {},
        }
        compiled_groups = {}
        for group in plan.groups:
            members = [i for i, case in enumerate(cases) if case.group == group]
            if not members:
                continue
            scenes = [load_scene(cases[i].scene) for i in members]
            numerics = dataclasses.replace(numerics_for(scenes[0], trajectory=False), method=solver)
            physics = [physics_for(scene) for scene in scenes]

            def single(physics, rtol, numerics=numerics):
                return solve.__wrapped__(physics, _with_tolerance(numerics, rtol))[1]

            compiled, seconds = _compile(single, physics[0], jnp.asarray(plan.rtols[0]))
            compiled_groups[group] = compiled
            record["compile_single"][group] = seconds
            for sweep in range(plan.passes):
                for r, rtol in enumerate(plan.rtols):
                    tolerance = jnp.asarray(rtol)
                    for i, p in zip(members, physics):
                        if sweep and record["time_single"][r, i] > 1.0:
                            continue
                        seconds, outcome = best_time(lambda: compiled(p, tolerance), plan.timing_budget, repeats=3)
                        record["time_single"][r, i] = np.fmin(record["time_single"][r, i], seconds)
                        if sweep:
                            continue
                        e = restitution(outcome)
                        record["restitution"][r, i] = e
                        record["error"][r, i] = abs(e - cases[i].reference)
                        record["steps"][r, i] = int(outcome.steps)
                        record["accepted"][r, i] = int(outcome.accepted_steps)
                        record["rejected"][r, i] = int(outcome.rejected_steps)
                        record["status"][r, i] = int(outcome.status)
        record["error_max"] = np.max(np.where(np.isnan(record["error"]), np.inf, record["error"]), axis=1)
        solved = np.isfinite(record["error"])
        record["error_max_solved"] = np.max(np.where(solved, record["error"], 0.0), axis=1)
        record["failures"] = [", ".join(names[i] for i in np.flatnonzero(~row)) for row in solved]
        record["time_single_mean"] = np.mean(record["time_single"], axis=1)
        in_batch = [i for i, case in enumerate(cases) if case.group == "tn"] or list(range(len(cases)))
        record.update(_batch(plan, solver, np.mean(record["time_single"][:, in_batch], axis=1), log))
        if plan.check_solve and "tn" in compiled_groups:
            record.update(_check_solve(plan, solver, compiled_groups["tn"]))
        results[solver] = record
        failed = sorted({name for row in record["failures"] for name in row.split(", ") if name})
        best = np.min(record["error_max_solved"])
        log(
            f"continuum {solver}: best max error {best:.1e}{f' (failed: {chr(44).join(failed)})' if failed else ''}, single {np.nanmin(record['time_single_mean']) * 1e3:.2f}–"
            f"{np.nanmax(record['time_single_mean']) * 1e3:.2f} ms, compile {sum(record['compile_single'].values()):.1f} s"
            f" + batch {record['compile_batch']:.1f} s"
        )
    return {"solvers": results, "cases": names, "rtols": rtols}


def _batch(plan: Plan, solver: str, single_times, log: Callable) -> dict:
    """Time per impact in a jit(vmap) batch over velocities of the Thornton–Ning case."""
    v_s = sticking_velocity()
    factors = np.geomspace(*BATCH_RANGE, plan.batch_size)
    velocities = jnp.asarray(factors * v_s)
    references = np.asarray(theory.thornton_ning_restitution(np.asarray(velocities), MASS, RADIUS, E_STAR, WORK_OF_ADHESION))
    scene = load_scene(_scene("tn", dict(shape="paraboloid", R=RADIUS), float(velocities[0])))
    physics = physics_for(scene)
    numerics = dataclasses.replace(numerics_for(scene, trajectory=False), method=solver)

    def one(velocity, rtol):
        tolerant = _with_tolerance(numerics, rtol)
        return continuum.integrate(build_problem(eqx.tree_at(lambda p: p.velocity, physics, velocity), tolerant), tolerant)

    compiled, seconds = _compile(jax.vmap(one, in_axes=(0, None)), velocities, jnp.asarray(plan.rtols[0]))
    per_impact = np.full(len(plan.rtols), np.nan)
    errors = np.full(len(plan.rtols), np.nan)
    for sweep in range(plan.passes):
        for r, rtol in enumerate(plan.rtols):
            if 0.5 * single_times[r] * plan.batch_size > plan.batch_budget:
                if not sweep:
                    log(f"  batch {solver} rtol {rtol:.0e}: skipped (about {0.5 * single_times[r] * plan.batch_size:.0f} s)")
                continue
            tolerance = jnp.asarray(rtol)
            total, outcome = best_time(lambda: compiled(velocities, tolerance), 0.0, repeats=2, once=0.5)
            per_impact[r] = np.fmin(per_impact[r], total / plan.batch_size)
            if sweep:
                continue
            separated = np.asarray(outcome.status) == RESULT_CODE["separated"]
            e = np.where(separated, np.asarray(outcome.separation_velocity) / np.asarray(outcome.touch_velocity), np.nan)
            errors[r] = np.max(np.where(np.isnan(e), np.inf, np.abs(e - references)))
    return {"compile_batch": seconds, "time_batch": per_impact, "batch_error": errors}


def _check_solve(plan: Plan, solver: str, traced) -> dict:
    """`impact.simulate.solve` itself (static tolerances, its own compile) beside the traced-rtol
    function the sweep times, interleaved, on the Thornton–Ning 2·v_s case."""
    scene = load_scene(_scene("tn", dict(shape="paraboloid", R=RADIUS), 2.0 * sticking_velocity()))
    physics = physics_for(scene)
    base = dataclasses.replace(numerics_for(scene, trajectory=False), method=solver)
    check = {"check_rtol": [], "check_compile": [], "check_time": [], "check_time_traced": [], "check_same": []}
    for rtol in plan.check_solve:
        numerics = _with_tolerance(base, rtol)
        start = time.perf_counter()
        jax.block_until_ready(solve(physics, numerics))
        first = time.perf_counter() - start
        tolerance = jnp.asarray(rtol)
        static_times, traced_times = [], []
        for _ in range(5):  # interleaved, so that both see the same load
            static_time, (_, outcome) = best_time(lambda: solve(physics, numerics), 0.0, repeats=2)
            traced_time, traced_outcome = best_time(lambda: traced(physics, tolerance), 0.0, repeats=2)
            static_times.append(static_time)
            traced_times.append(traced_time)
        check["check_rtol"].append(rtol)
        check["check_compile"].append(first - min(static_times))
        check["check_time"].append(min(static_times))
        check["check_time_traced"].append(min(traced_times))
        check["check_same"].append(float(restitution(outcome) == restitution(traced_outcome)))
    return {key: np.asarray(value) for key, value in check.items()}


# --- spring array ---------------------------------------------------------------------------


def bench_springs(plan: Plan, log: Callable) -> dict:
    """Exact event-driven stepper over N and velocity Verlet over (N, Δt), Thornton–Ning at 2 v_s."""
    v_s = sticking_velocity()
    velocity = 2.0 * v_s
    reference = float(theory.thornton_ning_restitution(velocity, MASS, RADIUS, E_STAR, WORK_OF_ADHESION))
    scene = load_scene(_scene("springs", dict(shape="paraboloid", R=RADIUS), velocity))
    physics = physics_for(scene)
    numerics = dataclasses.replace(numerics_for(scene, trajectory=False), spring_array=True)

    def with_count(count):
        return eqx.tree_at(lambda p: p.spring_count, physics, jnp.asarray(float(count)))

    counts = sorted(set(plan.spring_counts) | set(plan.verlet_counts))
    exact = {"N": np.asarray(counts), "restitution": [], "time": [], "events": [], "compile": [], "work": []}
    for count in counts:
        arrayed = with_count(count)
        compiled, seconds = _compile(lambda p: solve.__wrapped__(p, numerics), arrayed)
        run_time, (scales, outcome) = best_time(lambda: compiled(arrayed), plan.timing_budget)
        exact["restitution"].append(restitution(outcome))
        exact["time"].append(run_time)
        exact["events"].append(int(outcome.steps))
        exact["compile"].append(seconds)
        exact["work"].append(float(outcome.first_contact_work))
    exact = {key: np.asarray(value) for key, value in exact.items()}
    exact["error"] = exact["restitution"] - reference  # signed: the spatial error
    in_plan = np.isin(exact["N"], plan.spring_counts)
    exact["order"] = fitted_order(exact["N"][in_plan], exact["error"][in_plan])
    log(f"springs exact: N {counts[0]}–{counts[-1]}, order in N {exact['order']:.2f}, "
        f"error at N = {counts[-1]}: {exact['error'][-1]:.1e} in {exact['time'][-1] * 1e3:.1f} ms")

    cost = {"N": np.asarray(plan.cost_counts), "time_per_event": [], "events": [], "memory": []}
    for count in plan.cost_counts:
        arrayed = with_count(count)
        compiled, _ = _compile(lambda p: solve.__wrapped__(p, numerics), arrayed)
        run_time, (_, outcome) = best_time(lambda: compiled(arrayed), plan.timing_budget)
        memory = compiled.memory_analysis()
        cost["events"].append(int(outcome.steps))
        cost["time_per_event"].append(run_time / int(outcome.steps))
        cost["memory"].append(memory.temp_size_in_bytes + memory.argument_size_in_bytes + memory.output_size_in_bytes)
        log(f"springs exact N = {count}: {cost['time_per_event'][-1] * 1e6:.2f} µs per spring event "
            f"({cost['events'][-1]} events), compiled program's buffers {cost['memory'][-1] / 1024:.1f} kB")
    cost = {key: np.asarray(value) for key, value in cost.items()}

    verlet_runs = {}
    stepping = dataclasses.replace(numerics, method="verlet")

    def stepped(p, step):
        return verlet.integrate(build_problem(p, stepping), stepping, p.spring_length, p.spring_count.astype(int), step=step)

    for count in plan.verlet_counts:
        arrayed = with_count(count)
        compiled, seconds = _compile(stepped, arrayed, jnp.asarray(plan.verlet_steps[0]))
        row = {"dt": np.asarray(plan.verlet_steps), "restitution": [], "time": [], "steps": [], "energy_lost": [], "work": []}
        for step in plan.verlet_steps:
            run_time, outcome = best_time(lambda: compiled(arrayed, jnp.asarray(step)), plan.timing_budget)
            row["restitution"].append(restitution(outcome))
            row["time"].append(run_time)
            row["steps"].append(int(outcome.steps))
            row["energy_lost"].append(0.5 * (float(outcome.touch_velocity) ** 2 - float(outcome.separation_velocity) ** 2))
            row["work"].append(float(outcome.first_contact_work))
        row = {key: np.asarray(value) for key, value in row.items()}
        exact_e = exact["restitution"][list(exact["N"]).index(count)]
        row["dt_si"] = row["dt"] * float(scales.time)
        row["time_error"] = row["restitution"] - exact_e  # against the exact discrete model
        row["total_error"] = row["restitution"] - reference
        row["spatial_error"] = exact_e - reference
        row["order"] = fitted_order(row["dt"], row["time_error"])
        row["bound"] = float(np.max(np.abs(row["time_error"]) / row["dt"]))  # |e − e_exact| ≤ C·Δt
        row["compile"] = seconds
        verlet_runs[count] = row
        log(f"springs Verlet N = {count}: order in Δt {row['order']:.2f}, |e − e_exact| ≤ {row['bound']:.2g}·Δt, "
            f"{row['time'][-1] / row['steps'][-1] * 1e9:.0f} ns/step at Δt = {row['dt'][-1]:.0e}")
    return {"reference": reference, "exact": exact, "cost": cost, "verlet": verlet_runs, "time_unit": float(scales.time)}


def fitted_order(x, error) -> float:
    """|slope| of log|error| against log x (x = N or Δt), least squares over the points above
    the round-off floor: p in |error| ≈ C·N^(−p) or C·Δt^p."""
    x, error = np.asarray(x, float), np.abs(np.asarray(error, float))
    keep = np.isfinite(error) & (error > 1e-13)
    if keep.sum() < 2:
        return float("nan")
    slope = np.polyfit(np.log(x[keep]), np.log(error[keep]), 1)[0]
    return float(abs(slope))


# --- the baseline: scipy.integrate.solve_ivp --------------------------------------------------


def jkr_units(case: Case):
    """(radial, normal, time) units of the baseline: the jump-in radius a0 with g(a0) = Δl(a0)."""
    a0 = float(theory.power_law_jump_in(case.n, case.c, E_STAR, WORK_OF_ADHESION)[0])
    normal = math.sqrt(2.0 * math.pi * a0 * WORK_OF_ADHESION / E_STAR)
    return a0, normal, math.sqrt(MASS / (E_STAR * a0))


def scipy_restitution(case: Case, method: str, rtol: float, atol: float):
    """e of one case as a researcher would write it with solve_ivp: (e, nfev, steps).

    JKR units (g = aⁿ, Δl = √a, F = 2(a·d − aⁿ⁺¹/(n+1)), mass 1), state (d, v). On the JKR
    branch d = aⁿ − √a the radius is a root found by brentq in every right-hand side call;
    the body separates at the branch's turning point d* (displacement control), a terminal
    event. Attach on touch: Hertzian loading a = d^(1/n) to the turnaround, a hold at a_max
    until d = h(a_max), then the JKR branch.
    """
    from scipy.integrate import solve_ivp
    from scipy.optimize import brentq

    n = case.n
    _, normal, unit_time = jkr_units(case)
    v0 = case.velocity / (normal / unit_time)
    a_star = (1.0 / (2.0 * n)) ** (1.0 / (n - 0.5))  # h'(a) = n·aⁿ⁻¹ − 1/(2√a) = 0
    d_star = a_star**n - math.sqrt(a_star)

    def h(a):
        return a**n - math.sqrt(a)

    def jkr_radius(d):
        if d <= d_star:
            return a_star
        high = max(1.0, 2.0 * a_star)
        while h(high) < d:
            high *= 2.0
        return brentq(lambda a: h(a) - d, a_star, high, xtol=1e-15, rtol=8.9e-16)

    def force(a, d):
        return 2.0 * (a * d - a ** (n + 1) / (n + 1))

    def jkr(t, y):
        return [y[1], -force(jkr_radius(y[0]), y[0])]

    def separation(t, y):
        return y[0] - d_star

    separation.terminal, separation.direction = True, -1
    options = dict(method=method, rtol=rtol, atol=atol)
    span = (0.0, 1e4)
    if not case.attach_on_touch:
        sol = solve_ivp(jkr, span, [0.0, v0], events=separation, **options)
        return abs(sol.y_events[0][0][1]) / v0, sol.nfev, sol.t.size - 1

    def hertz(t, y):
        return [y[1], -force(max(y[0], 0.0) ** (1.0 / n), y[0])]

    def turned(t, y):
        return y[1]

    turned.terminal, turned.direction = True, -1
    loading = solve_ivp(hertz, span, [0.0, v0], events=turned, **options)
    deepest = loading.y_events[0][0][0]
    held = deepest ** (1.0 / n)

    def hold(t, y):
        return [y[1], -force(held, y[0])]

    def unhold(t, y):
        return y[0] - h(held)

    unhold.terminal, unhold.direction = True, -1
    holding = solve_ivp(hold, span, [deepest, 0.0], events=unhold, **options)
    unloading = solve_ivp(jkr, span, holding.y_events[0][0], events=separation, **options)
    parts = (loading, holding, unloading)
    return (
        abs(unloading.y_events[0][0][1]) / v0,
        sum(part.nfev for part in parts),
        sum(part.t.size - 1 for part in parts),
    )


def bench_scipy(plan: Plan, cases: list[Case], log: Callable) -> dict:
    """The baseline on every case × method × rtol."""
    results = {}
    for method in plan.scipy_methods:  # first calls import and set up scipy's machinery
        scipy_restitution(cases[0], method, 1e-3, 1e-5)
    for method in plan.scipy_methods:
        shape = (len(plan.scipy_rtols), len(cases))
        record = {key: np.full(shape, np.nan) for key in ("error", "time", "nfev", "steps")}
        for r, rtol in enumerate(plan.scipy_rtols):
            for i, case in enumerate(cases):
                seconds, (e, nfev, steps) = _best_python_time(
                    lambda: scipy_restitution(case, method, rtol, rtol / 100.0), plan.timing_budget
                )
                record["error"][r, i] = abs(e - case.reference)
                record["time"][r, i] = seconds
                record["nfev"][r, i] = nfev
                record["steps"][r, i] = steps
        record["error_max"] = np.max(record["error"], axis=1)
        record["time_mean"] = np.mean(record["time"], axis=1)
        record["rtols"] = np.asarray(plan.scipy_rtols)
        results[method] = record
        log(f"scipy {method}: best max error {np.min(record['error_max']):.1e}, "
            f"{np.min(record['time_mean']) * 1e3:.1f}–{np.max(record['time_mean']) * 1e3:.1f} ms per impact")
    return results


def _best_python_time(call: Callable, budget: float, repeats: int = 5):
    times, start, result = [], time.perf_counter(), None
    while len(times) < repeats:
        t0 = time.perf_counter()
        result = call()
        times.append(time.perf_counter() - t0)
        if len(times) >= 2 and time.perf_counter() - start > budget:
            break
    return min(times), result


# --- comparison at equal error --------------------------------------------------------------


def reliable(errors) -> np.ndarray:
    """Errors of settings ordered from loose to tight, raised to the worst of every tighter
    setting: a setting reaches ε reliably when it and all tighter ones do (errors that zigzag,
    like Verlet's over Δt or the array's over N, are not credited with a lucky point)."""
    errors = np.where(np.isnan(np.asarray(errors, float)), np.inf, np.asarray(errors, float))
    return np.maximum.accumulate(errors[::-1])[::-1]


def cheapest(sequences, target: float) -> float:
    """Least time among the settings that reliably reach `target` (nan if none does).

    `sequences`: (errors, times) pairs, each a method's settings from loose to tight."""
    best = float("nan")
    for errors, times in sequences:
        times = np.asarray(times, float)
        ok = np.isfinite(times) & (reliable(errors) <= target)
        if ok.any() and not (np.min(times[ok]) >= best):
            best = float(np.min(times[ok]))
    return best


def families(continuum_results: dict, springs: dict, scipy_results: dict) -> dict:
    """The (errors, times) sequences (loose to tight) of each way to get e."""
    solvers = continuum_results["solvers"].values()
    out = {
        "continuum, single": [(s["error_max"], s["time_single_mean"]) for s in solvers],
        "continuum, batched": [(s["error_max"], s["time_batch"]) for s in solvers],
    }
    if scipy_results:
        out["scipy solve_ivp"] = [(s["error_max"], s["time_mean"]) for s in scipy_results.values()]
    out["springs, exact"] = [(np.abs(springs["exact"]["error"]), springs["exact"]["time"])]
    out["springs, Verlet"] = [(np.abs(r["total_error"]), r["time"]) for r in springs["verlet"].values()]
    return out


def equal_error(continuum_results: dict, springs: dict, scipy_results: dict) -> dict:
    """Cheapest time of each family at each target error, and the speed-ups over the baseline."""
    fams = families(continuum_results, springs, scipy_results)
    table = {name: np.asarray([cheapest(sequences, target) for target in TARGETS]) for name, sequences in fams.items()}
    best_solver = {}
    for target in TARGETS:
        costs = {
            name: cheapest([(s["error_max"], s["time_single_mean"])], target)
            for name, s in continuum_results["solvers"].items()
        }
        reachable = {k: v for k, v in costs.items() if np.isfinite(v)}
        best_solver[target] = min(reachable, key=reachable.get) if reachable else ""
    return {"targets": np.asarray(TARGETS), "cost": table, "best_solver": best_solver}


# --- outputs --------------------------------------------------------------------------------


def provenance(plan_name: str) -> dict:
    import diffrax
    import scipy

    return {
        "date": datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "impact": __version__,
        "jax": jax.__version__,
        "diffrax": diffrax.__version__,
        "scipy": scipy.__version__,
        "numpy": np.__version__,
        "python": platform.python_version(),
        "machine": f"{platform.machine()}, {os.cpu_count()} cores, {platform.system()} (jax backend: {jax.default_backend()})",
        "plan": plan_name,
        "x64": bool(jax.config.jax_enable_x64),
    }


def write_h5(path: Path, data: dict) -> None:
    """bench.h5: every measured number (SI seconds; Δt in scaled time and in s)."""

    def put(group, name, value):
        if isinstance(value, dict):
            sub = group.create_group(str(name))
            for key, item in value.items():
                put(sub, key, item)
        elif isinstance(value, str):
            group.attrs[name] = value
        elif isinstance(value, (list, tuple)) and value and isinstance(value[0], str):
            group.create_dataset(name, data=np.asarray(value, dtype=h5py.string_dtype()))
        else:
            group.create_dataset(name, data=np.asarray(value))

    with atomic_path(path) as temporary, h5py.File(temporary, "w") as file:
        for key, value in data["provenance"].items():
            file.attrs[key] = value
        continuum_group = file.create_group("continuum")
        put(continuum_group, "cases", data["continuum"]["cases"])
        put(continuum_group, "references", np.asarray([case.reference for case in data["cases"]]))
        put(continuum_group, "velocities", np.asarray([case.velocity for case in data["cases"]]))
        put(continuum_group, "rtol", data["continuum"]["rtols"])
        for solver, record in data["continuum"]["solvers"].items():
            put(continuum_group, solver, record)
        scipy_group = file.create_group("scipy")
        for method, record in data["scipy"].items():
            put(scipy_group, method, record)
        springs_group = file.create_group("springs")
        springs_group.attrs["reference"] = data["springs"]["reference"]
        springs_group.attrs["time_unit"] = data["springs"]["time_unit"]
        put(springs_group, "exact", data["springs"]["exact"])
        put(springs_group, "cost", data["springs"]["cost"])
        verlet_group = springs_group.create_group("verlet")
        for count, row in data["springs"]["verlet"].items():
            put(verlet_group, f"N{count}", row)
        summary = file.create_group("equal_error")
        put(summary, "targets", data["equal"]["targets"])
        for name, costs in data["equal"]["cost"].items():
            put(summary, name.replace(", ", "_").replace(" ", "_"), costs)


def _ms(seconds: float) -> str:
    if not np.isfinite(seconds):
        return "—"
    if seconds >= 1.0:
        return f"{seconds:.2f} s"
    if seconds >= 1e-3:
        return f"{seconds * 1e3:.3g} ms"
    return f"{seconds * 1e6:.3g} µs"


def _err(value: float) -> str:
    return "failed" if not np.isfinite(value) else f"{value:.1e}"


def table_markdown(data: dict) -> str:
    """table.md: the cost of each digit, then every measurement."""
    p = data["provenance"]
    cont, springs, scipy_results, equal = data["continuum"], data["springs"], data["scipy"], data["equal"]
    cases = data["cases"]
    lines = [
        f"# Work-precision benchmark ({p['plan']} run)",
        "",
        f"{p['date']}; impact {p['impact']}, jax {p['jax']}, diffrax {p['diffrax']}, scipy {p['scipy']}, "
        f"Python {p['python']}; {p['machine']}; float64. Times are the best of a few repeats.",
        "",
        f"Error: max |e − e_ref| over {len(cases)} reference cases ({', '.join(c.name for c in cases)}); "
        f"the spring array rows are Thornton–Ning at 2·v_s only.",
        "",
        "## What a digit costs: the cheapest setting that reaches each error",
        "",
        "A setting counts when it and every tighter setting of the same method reach the error "
        "(no credit for a lucky point of a zigzagging error).",
        "",
        "| error ≤ | continuum, single | continuum, batched (per impact) | scipy solve_ivp | springs, exact | springs, Verlet | scipy ÷ single | scipy ÷ batched |",
        "|---|---|---|---|---|---|---|---|",
    ]
    cost = equal["cost"]
    for t, target in enumerate(equal["targets"]):
        single = cost["continuum, single"][t]
        batched = cost["continuum, batched"][t]
        base = cost.get("scipy solve_ivp", np.full(len(equal["targets"]), np.nan))[t]
        solver = equal["best_solver"][float(target)]
        lines.append(
            f"| {target:.0e} | {_ms(single)}{f' ({solver})' if solver else ''} | {_ms(batched)} | {_ms(base)} | "
            f"{_ms(cost['springs, exact'][t])} | {_ms(cost['springs, Verlet'][t])} | "
            f"{_ratio(base, single)} | {_ratio(base, batched)} |"
        )
    lines += ["", "## Continuum law (diffrax): solver × rtol (atol = rtol/100, scaled units)", ""]
    lines += [
        "| solver | rtol | max error | steps per impact (accepted / rejected) | single impact | batched, per impact | batch max error |",
        "|---|---|---|---|---|---|---|",
    ]
    for solver, s in cont["solvers"].items():
        for r, rtol in enumerate(cont["rtols"]):
            failed = s["failures"][r]
            error = _err(s["error_max"][r]) if not failed else f"failed: {failed} ({s['error_max_solved'][r]:.1e} on the rest)"
            lines.append(
                f"| {solver} | {rtol:.0e} | {error} | "
                f"{np.mean(s['accepted'][r]):.0f} / {np.mean(s['rejected'][r]):.0f} | {_ms(s['time_single_mean'][r])} | "
                f"{_ms(s['time_batch'][r])} | {_err(s['batch_error'][r]) if np.isfinite(s['time_batch'][r]) else '—'} |"
            )
    lines += ["", "Compile times (trace + XLA compile, once per solver for the whole rtol sweep):", ""]
    for solver, s in cont["solvers"].items():
        groups = ", ".join(f"{g} {t:.1f} s" for g, t in s["compile_single"].items())
        lines.append(f"- {solver}: single impact {groups}; batch of {data['plan'].batch_size} {s['compile_batch']:.1f} s")
    checks = [(solver, s) for solver, s in cont["solvers"].items() if "check_rtol" in s]
    if checks:
        lines += [
            "",
            "Check against `impact.simulate.solve` itself (static tolerances, own compile), Thornton–Ning 2·v_s:",
            "",
            "| solver | rtol | solve: compile | solve: run | traced-rtol run | same e |",
            "|---|---|---|---|---|---|",
        ]
        for solver, s in checks:
            for k, rtol in enumerate(s["check_rtol"]):
                lines.append(
                    f"| {solver} | {rtol:.0e} | {s['check_compile'][k]:.1f} s | {_ms(s['check_time'][k])} | "
                    f"{_ms(s['check_time_traced'][k])} | {'yes' if s['check_same'][k] else 'no'} |"
                )
    exact = springs["exact"]
    lines += [
        "",
        f"## Spring array, exact event-driven stepper (spatial error; fitted order in N: {exact['order']:.2f})",
        "",
        "| N | e − e_TN | events | time | compile |",
        "|---|---|---|---|---|",
    ]
    for k, count in enumerate(exact["N"]):
        lines.append(
            f"| {count} | {exact['error'][k]:+.2e} | {exact['events'][k]} | {_ms(exact['time'][k])} | {exact['compile'][k]:.1f} s |"
        )
    cost = springs["cost"]
    lines += ["", "Time per spring event (a run's time over its events, fixed costs included) and the buffers of the compiled program:", ""]
    for k, count in enumerate(cost["N"]):
        lines.append(f"- N = {count}: {cost['time_per_event'][k] * 1e6:.2f} µs per event ({cost['events'][k]} events), "
                     f"{cost['memory'][k] / 1024:.1f} kB")
    lines += [
        "",
        "## Spring array, velocity Verlet (error = spatial part + time-stepping part)",
        "",
    ]
    for count, row in springs["verlet"].items():
        lines.append(
            f"- N = {count}: spatial part e_exact − e_TN = {row['spatial_error']:+.2e}; time-stepping part "
            f"|e − e_exact| fitted order in Δt {row['order']:.2f}, bounded by {row['bound']:.2g}·Δt (scaled Δt)"
        )
    lines += ["", "| N | Δt (scaled) | Δt | steps | time | e − e_exact (time stepping) | e − e_TN (total) | KE lost − ∮F dd, relative (= ⅛Δt²a₀²: Verlet's identity) |",
              "|---|---|---|---|---|---|---|---|"]
    for count, row in springs["verlet"].items():
        for k, step in enumerate(row["dt"]):
            mismatch = (row["energy_lost"][k] - row["work"][k]) / row["energy_lost"][k]
            lines.append(
                f"| {count} | {step:.2e} | {row['dt_si'][k]:.2e} s | {row['steps'][k]} | {_ms(row['time'][k])} | "
                f"{row['time_error'][k]:+.2e} | {row['total_error'][k]:+.2e} | {mismatch:+.1e} |"
            )
    if scipy_results:
        lines += [
            "",
            "## Baseline: scipy.integrate.solve_ivp, (d, v) in JKR units, a(d) by brentq in the right-hand side",
            "",
            "| method | rtol | max error | right-hand sides per impact | steps per impact | time per impact |",
            "|---|---|---|---|---|---|",
        ]
        for method, s in scipy_results.items():
            for r, rtol in enumerate(s["rtols"]):
                lines.append(
                    f"| {method} | {rtol:.0e} | {_err(s['error_max'][r])} | {np.mean(s['nfev'][r]):.0f} | "
                    f"{np.mean(s['steps'][r]):.0f} | {_ms(s['time_mean'][r])} |"
                )
    return "\n".join(lines) + "\n"


def _ratio(numerator: float, denominator: float) -> str:
    if not (np.isfinite(numerator) and np.isfinite(denominator)) or denominator <= 0:
        return "—"
    return f"{numerator / denominator:.0f}×" if numerator / denominator >= 10 else f"{numerator / denominator:.1f}×"


SOLVER_COLORS = {"tsit5": "#1f77b4", "dopri5": "#2ca02c", "dopri8": "#d62728", "kvaerno5": "#9467bd",
                 "bosh3": "#8c564b", "heun": "#e377c2", "kvaerno3": "#7f7f7f"}


def plot(path: Path, data: dict) -> None:
    """Error against time per impact, log–log: one line per method (a work-precision diagram)."""
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D

    figure = Figure(figsize=(10.0, 7.5), layout="constrained")
    axes = figure.add_subplot()
    floor = ERROR_FLOOR
    lowest = [1.0]

    def draw(times, errors, labels=(), offset=(5, 2), **style):
        times, errors = np.asarray(times, float), np.asarray(errors, float)
        ok = np.isfinite(times) & np.isfinite(errors)
        y = np.maximum(errors[ok], floor)
        if y.size:
            lowest.append(float(y.min()))
        axes.plot(times[ok], y, **style)
        for x, value, text in zip(times[ok], y, np.asarray(list(labels) or [""] * len(ok), dtype=object)[ok]):
            if text:
                axes.annotate(text, (x, value), textcoords="offset points", xytext=offset, fontsize=7.5,
                              color=style.get("color"), ha="right" if offset[0] < 0 else "left", va="center")

    handles = []
    cont = data["continuum"]
    for solver, s in cont["solvers"].items():
        color = SOLVER_COLORS.get(solver, "black")
        failed = sorted({name for names in s["failures"] for name in names.split(", ") if name})
        errors = s["error_max_solved"] if failed else s["error_max"]
        labels = [f"rtol {r:.0e}" if solver == "tsit5" and k % 3 == 0 else "" for k, r in enumerate(cont["rtols"])]
        draw(s["time_single_mean"], errors, color=color, marker="o", ms=4.5, lw=1.8)
        draw(s["time_batch"], errors, labels, offset=(-6, 0), color=color, marker="o", ms=4, lw=1.3, ls="--", mfc="white")
        note = f"\n(failed runs, left out: {', '.join(failed)})" if failed else ""
        handles.append(Line2D([], [], color=color, marker="o", lw=1.8, label=f"continuum, diffrax {solver}{note}"))
    handles.append(Line2D([], [], color="grey", lw=1.8, label="    solid: one impact (jit)"))
    handles.append(Line2D([], [], color="grey", lw=1.3, ls="--", marker="o", mfc="white",
                          label=f"    dashed: per impact in a jit(vmap) batch of {data['plan'].batch_size}"))
    for method, s in data["scipy"].items():
        style = dict(color="black", marker="s" if method == "RK45" else "D", ms=4.5, lw=1.3, ls="-." if method == "RK45" else ":")
        labels = [f"rtol {r:.0e}" if method == "DOP853" and k % 3 == 0 else "" for k, r in enumerate(s["rtols"])]
        draw(s["time_mean"], s["error_max"], labels, **style)
        handles.append(Line2D([], [], **style, label=f"baseline: scipy solve_ivp {method}, a(d) by brentq"))
    springs = data["springs"]
    exact = springs["exact"]
    labels = [f"N = $10^{int(round(np.log10(n)))}$" if abs(np.log10(n) - round(np.log10(n))) < 1e-9 else "" for n in exact["N"]]
    style = dict(color="#ff7f0e", marker="^", ms=5, lw=1.5)
    draw(exact["time"], np.abs(exact["error"]), labels, **style)
    handles.append(Line2D([], [], **style, label="spring array, exact event-driven (over N)"))
    shades = ["#8fd3dc", "#17becf", "#0b6c75", "#063a40"]
    for (count, row), shade in zip(springs["verlet"].items(), shades[-len(springs["verlet"]):]):
        errors = np.abs(row["total_error"])
        draw(row["time"], errors, color=shade, marker="v", ms=3.5, lw=0, alpha=0.7)
        draw(row["time"], reliable(errors), color=shade, lw=1.4)
        handles.append(Line2D([], [], color=shade, marker="v", lw=1.4, label=f"spring array N = {count}, velocity Verlet (over Δt)"))
    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.set_xlabel("time per impact (s), after compile")
    axes.set_ylabel(f"error: max |e − e_ref| over {len(data['cases'])} reference cases")
    p = data["provenance"]
    axes.set_title(
        f"What accuracy costs: impact {p['impact']}, {p['date'][:10]}, {p['machine'].split(' (')[0]}, "
        f"jax {p['jax']}, diffrax {p['diffrax']}",
        fontsize=10,
    )
    axes.grid(True, which="major", alpha=0.4)
    axes.grid(True, which="minor", alpha=0.12)
    axes.set_ylim(bottom=max(min(lowest) / 3.0, floor / 3.0))
    axes.margins(x=0.06)
    axes.text(
        0.01, 0.01,
        "spring array: Thornton–Ning at 2·v_s only. Verlet markers: each Δt; its line: the error\n"
        "that every smaller Δt stays below (Verlet's error zigzags with Δt, so does the array's with N)",
        transform=axes.transAxes, ha="left", va="bottom", fontsize=7.5, color="dimgrey",
    )
    axes.legend(handles=handles, fontsize=7.5, loc="upper right", framealpha=0.92)
    with atomic_path(path) as temporary:
        figure.savefig(temporary, dpi=130, format="png")


# --- the run ----------------------------------------------------------------------------------


def run(folder: str | Path, quick: bool = False, log: Callable[[str], None] = print) -> dict:
    """Measure everything, write bench.h5, work_precision.png and table.md into `folder`.

    Needs float64 (`jax.config.update("jax_enable_x64", True)`; the CLI does it).
    """
    if not jax.config.jax_enable_x64:
        raise RuntimeError("the benchmark needs float64: jax.config.update('jax_enable_x64', True) first")
    plan = QUICK if quick else FULL
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    say = log
    log = lambda line: say(f"[{time.perf_counter() - start:4.0f} s] {line}")  # noqa: E731
    cases = reference_cases(plan.groups)
    log(f"{'quick' if quick else 'full'} benchmark: {len(cases)} cases, solvers {', '.join(plan.solvers)}, "
        f"rtol {plan.rtols[0]:.0e}…{plan.rtols[-1]:.0e}")
    data = {"plan": plan, "cases": cases, "provenance": provenance("quick" if quick else "full")}
    data["continuum"] = bench_continuum(plan, cases, log)
    data["springs"] = bench_springs(plan, log)
    data["scipy"] = bench_scipy(plan, cases, log)
    data["equal"] = equal_error(data["continuum"], data["springs"], data["scipy"])
    data["provenance"]["wall_time"] = time.perf_counter() - start
    write_h5(folder / "bench.h5", data)
    write_text(folder / "table.md", table_markdown(data))
    plot(folder / "work_precision.png", data)
    log(f"benchmark written to {folder} in {time.perf_counter() - start:.0f} s")
    return data
