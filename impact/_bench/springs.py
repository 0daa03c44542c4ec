"""The spring array on the Thornton–Ning case at 2·v_s: the exact event-driven stepper over N
(its error against the closed form is the pure spatial error) and a fixed-step velocity Verlet
over (N, Δt) (its difference from the exact discrete model is the pure time-stepping error)."""

from collections.abc import Callable
from functools import partial

import equinox as eqx
import jax.numpy as jnp
import numpy as np

from .. import theory
from .._integrate.problem import Options, Physics
from .._integrate.springs import SpringArray
from .._integrate.verlet import Verlet
from .._run.parameters import options_for, physics_for
from .._scene.scene import load_scene
from .cases import case_scene, restitution, sticking_velocity
from .plans import E_STAR, MASS, RADIUS, WORK_OF_ADHESION, Plan
from .timing import best_time, compile_ahead

_EXACT = SpringArray()  # the exact event-driven stepper


def bench_springs(plan: Plan, log: Callable) -> dict:
    """Exact stepper over N and velocity Verlet over (N, Δt), Thornton–Ning at 2·v_s."""
    velocity = 2.0 * sticking_velocity()
    reference = float(theory.thornton_ning_restitution(velocity, MASS, RADIUS, E_STAR, WORK_OF_ADHESION))
    scene = load_scene(case_scene("springs", dict(shape="paraboloid", R=RADIUS), velocity))
    physics, options = physics_for(scene), options_for(scene, trajectory=False)
    exact, time_unit = _exact_runs(plan, physics, options, reference, log)
    cost = _cost_per_event(plan, physics, options, log)
    verlet = {}
    for count in plan.verlet_counts:
        row = _verlet_runs(plan, with_count(physics, count), options)
        exact_e = exact["restitution"][list(exact["N"]).index(count)]
        verlet[count] = _with_errors(row, exact_e, reference, time_unit)
        log(
            f"springs Verlet N = {count}: order in Δt {row['order']:.2f}, |e − e_exact| ≤ {row['bound']:.2g}·Δt, "
            f"{row['time'][-1] / row['steps'][-1] * 1e9:.0f} ns/step at Δt = {row['dt'][-1]:.0e}"
        )
    return {"reference": reference, "exact": exact, "cost": cost, "verlet": verlet, "time_unit": time_unit}


def with_count(physics: Physics, count: int) -> Physics:
    """`physics` with N = `count` springs (traced: one compile serves every N)."""
    return eqx.tree_at(lambda p: p.spring_count, physics, jnp.asarray(float(count)))


def _exact_runs(plan: Plan, physics: Physics, options: Options, reference: float, log: Callable):
    """The exact stepper at every N of the plan: (e, time, events, compile time, ∮F dd, the
    signed error against the closed form and its fitted order in N; the time unit in s)."""
    counts = sorted(set(plan.spring_counts) | set(plan.verlet_counts))
    exact: dict = {"N": np.asarray(counts), "restitution": [], "time": [], "events": [], "compile": [], "work": []}
    time_unit = float("nan")
    for count in counts:
        arrayed = with_count(physics, count)
        compiled, seconds = compile_ahead(partial(_EXACT.solve, options=options), arrayed)
        run_time, (scales, outcome) = best_time(compiled, (arrayed,), plan.timing_budget)
        exact["restitution"].append(restitution(outcome))
        exact["time"].append(run_time)
        exact["events"].append(int(outcome.steps))
        exact["compile"].append(seconds)
        exact["work"].append(float(outcome.first_contact_work))
        time_unit = float(scales.time)
    exact = {key: np.asarray(value) for key, value in exact.items()}
    exact["error"] = exact["restitution"] - reference  # signed: the spatial error
    in_plan = np.isin(exact["N"], plan.spring_counts)
    exact["order"] = fitted_order(exact["N"][in_plan], exact["error"][in_plan])
    log(
        f"springs exact: N {counts[0]}–{counts[-1]}, order in N {exact['order']:.2f}, "
        f"error at N = {counts[-1]}: {exact['error'][-1]:.1e} in {exact['time'][-1] * 1e3:.1f} ms"
    )
    return exact, time_unit


def _cost_per_event(plan: Plan, physics: Physics, options: Options, log: Callable) -> dict:
    """Time per spring event (s) and the buffers of the compiled program (bytes) at the N of
    `plan.cost_counts`: the same buffers at every N (nothing of size N is kept)."""
    cost: dict = {"N": np.asarray(plan.cost_counts), "time_per_event": [], "events": [], "memory": []}
    for count in plan.cost_counts:
        arrayed = with_count(physics, count)
        compiled, _ = compile_ahead(partial(_EXACT.solve, options=options), arrayed)
        run_time, (_, outcome) = best_time(compiled, (arrayed,), plan.timing_budget)
        memory = compiled.memory_analysis()
        cost["events"].append(int(outcome.steps))
        cost["time_per_event"].append(run_time / int(outcome.steps))
        cost["memory"].append(memory.temp_size_in_bytes + memory.argument_size_in_bytes + memory.output_size_in_bytes)
        log(
            f"springs exact N = {count}: {cost['time_per_event'][-1] * 1e6:.2f} µs per spring event "
            f"({cost['events'][-1]} events), compiled program's buffers {cost['memory'][-1] / 1024:.1f} kB"
        )
    return {key: np.asarray(value) for key, value in cost.items()}


def _solve_verlet(physics: Physics, step, options: Options):
    """Velocity Verlet with the step Δt given in scaled time units."""
    problem = _EXACT.build(physics, options)
    return Verlet(dt=step * problem.scales.time).integrate(problem, options)


def _verlet_runs(plan: Plan, arrayed: Physics, options: Options) -> dict:
    """Velocity Verlet over the plan's Δt at one N: e, time (s), steps, and the kinetic energy
    lost and ∮F dd of the first contact (scaled)."""
    compiled, seconds = compile_ahead(
        partial(_solve_verlet, options=options), arrayed, jnp.asarray(plan.verlet_steps[0])
    )
    row: dict = {"dt": np.asarray(plan.verlet_steps), "restitution": [], "time": [], "steps": []}
    row |= {"energy_lost": [], "work": []}
    for step in plan.verlet_steps:
        run_time, outcome = best_time(compiled, (arrayed, jnp.asarray(step)), plan.timing_budget)
        row["restitution"].append(restitution(outcome))
        row["time"].append(run_time)
        row["steps"].append(int(outcome.steps))
        row["energy_lost"].append(0.5 * (float(outcome.touch_velocity) ** 2 - float(outcome.separation_velocity) ** 2))
        row["work"].append(float(outcome.first_contact_work))
    row = {key: np.asarray(value) for key, value in row.items()}
    row["compile"] = seconds
    return row


def _with_errors(row: dict, exact_e: float, reference: float, time_unit: float) -> dict:
    """Verlet's errors: against the exact discrete model (time stepping), of that model against
    the closed form (spatial) and in all; its order in Δt and the bound C in |e − e_exact| ≤ C·Δt."""
    row["dt_si"] = row["dt"] * time_unit
    row["time_error"] = row["restitution"] - exact_e
    row["total_error"] = row["restitution"] - reference
    row["spatial_error"] = exact_e - reference
    row["order"] = fitted_order(row["dt"], row["time_error"])
    row["bound"] = float(np.max(np.abs(row["time_error"]) / row["dt"]))
    return row


def fitted_order(x, error) -> float:
    """|slope| of log|error| against log x (x = N or Δt), least squares over the points above
    the round-off floor: p in |error| ≈ C·N^(−p) or C·Δt^p."""
    x, error = np.asarray(x, float), np.abs(np.asarray(error, float))
    keep = np.isfinite(error) & (error > 1e-13)
    if keep.sum() < 2:
        return float("nan")
    slope = np.polyfit(np.log(x[keep]), np.log(error[keep]), 1)[0]
    return float(abs(slope))
