"""The continuum law (diffrax) over solvers × rtol (atol = rtol/100, scaled units): errors,
steps, the time of a single impact and per impact in a `jit(vmap)` batch, and compile times.

The tolerance is a traced argument, so one compile serves a whole rtol sweep; `solve` itself,
compiled with static tolerances, is timed beside it where the plan asks."""

import time
from collections.abc import Callable

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np

from .. import theory
from .._integrate.codes import RESULT_CODE
from .._integrate.continuum import Continuum
from .._run.parameters import options_for, physics_for
from .._run.programs import solve
from .._scene.scene import Scene, load_scene
from .cases import Case, case_scene, restitution, sticking_velocity
from .plans import BATCH_RANGE, E_STAR, MASS, RADIUS, WORK_OF_ADHESION, Plan
from .timing import best_time, compile_ahead


def bench_continuum(plan: Plan, cases: list[Case], log: Callable) -> dict:
    """Errors, steps, single and batched times and compile times of every solver × rtol."""
    names = [case.name for case in cases]
    results = {}
    for solver in plan.solvers:
        record, compiled_groups = _sweep_solver(plan, solver, cases)
        _summarise(record, names)
        in_batch = [i for i, case in enumerate(cases) if case.group == "tn"] or list(range(len(cases)))
        record.update(_batch(plan, solver, np.mean(record["time_single"][:, in_batch], axis=1), log))
        if plan.check_solve and "tn" in compiled_groups:
            record.update(_check_solve(plan, solver, compiled_groups["tn"]))
        results[solver] = record
        _log_solver(solver, record, log)
    return {"solvers": results, "cases": names, "rtols": np.asarray(plan.rtols)}


def _continuum(solver: str, rtol, max_steps: int) -> Continuum:
    """The continuum integrator with `solver` at rtol (atol = rtol/100, scaled units)."""
    return Continuum(method=solver, rtol=rtol, atol=rtol / 100.0, max_steps=max_steps)


def _single_impact(solver: str, scene: Scene) -> Callable:
    """(physics, rtol) → scaled outcome of one impact of the scene's kind, rtol traced."""
    options = options_for(scene, trajectory=False)
    max_steps = scene.solver.max_steps

    def single(physics, rtol):
        return _continuum(solver, rtol, max_steps).solve(physics, options)[1]

    return single


def _sweep_solver(plan: Plan, solver: str, cases: list[Case]) -> tuple[dict, dict]:
    """Every case × rtol with one solver: (the record, the compiled single impact of each group)."""
    shape = (len(plan.rtols), len(cases))
    record: dict = {
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
        if members:
            compiled, seconds = _sweep_group(plan, solver, [cases[i] for i in members], members, record)
            compiled_groups[group] = compiled
            record["compile_single"][group] = seconds
    return record, compiled_groups


def _sweep_group(plan: Plan, solver: str, group: list[Case], columns: list[int], record: dict):
    """Compile one group's single impact once and time it over the rtol sweep, best of
    `plan.passes` sweeps; fills `record` at `columns`. Returns (compiled, compile time in s)."""
    scenes = [load_scene(case.scene) for case in group]
    physics = [physics_for(scene) for scene in scenes]
    compiled, seconds = compile_ahead(_single_impact(solver, scenes[0]), physics[0], jnp.asarray(plan.rtols[0]))
    for sweep in range(plan.passes):
        for r, rtol in enumerate(plan.rtols):
            tolerance = jnp.asarray(rtol)
            for case, i, p in zip(group, columns, physics, strict=True):
                if sweep and record["time_single"][r, i] > 1.0:
                    continue
                run_time, outcome = best_time(compiled, (p, tolerance), plan.timing_budget, repeats=3)
                record["time_single"][r, i] = np.fmin(record["time_single"][r, i], run_time)
                if not sweep:
                    _record_outcome(record, (r, i), outcome, case.reference)
    return compiled, seconds


def _record_outcome(record: dict, at: tuple[int, int], outcome, reference: float) -> None:
    e = restitution(outcome)
    record["restitution"][at] = e
    record["error"][at] = abs(e - reference)
    record["steps"][at] = int(outcome.steps)
    record["accepted"][at] = int(outcome.accepted_steps)
    record["rejected"][at] = int(outcome.rejected_steps)
    record["status"][at] = int(outcome.status)


def _summarise(record: dict, names: list[str]) -> None:
    """Per rtol: the max error (inf where a case failed), the max over the solved cases, the
    failed cases' names and the mean single-impact time."""
    record["error_max"] = np.max(np.where(np.isnan(record["error"]), np.inf, record["error"]), axis=1)
    solved = np.isfinite(record["error"])
    record["error_max_solved"] = np.max(np.where(solved, record["error"], 0.0), axis=1)
    record["failures"] = [", ".join(names[i] for i in np.flatnonzero(~row)) for row in solved]
    record["time_single_mean"] = np.mean(record["time_single"], axis=1)


def _log_solver(solver: str, record: dict, log: Callable) -> None:
    failed = sorted({name for row in record["failures"] for name in row.split(", ") if name})
    failures = f" (failed: {','.join(failed)})" if failed else ""
    single = record["time_single_mean"]
    log(
        f"continuum {solver}: best max error {np.min(record['error_max_solved']):.1e}{failures}, "
        f"single {np.nanmin(single) * 1e3:.2f}–{np.nanmax(single) * 1e3:.2f} ms, "
        f"compile {sum(record['compile_single'].values()):.1f} s + batch {record['compile_batch']:.1f} s"
    )


def _impact_at_velocity(solver: str, scene: Scene) -> Callable:
    """(velocity in m/s, rtol) → scaled outcome of the scene's impact at that velocity."""
    physics = physics_for(scene)
    single = _single_impact(solver, scene)

    def one(velocity, rtol):
        return single(eqx.tree_at(lambda p: p.velocity, physics, velocity), rtol)

    return one


def _batch(plan: Plan, solver: str, single_times, log: Callable) -> dict:
    """Time per impact (s) in a jit(vmap) batch over velocities of the Thornton–Ning case, and
    the batch's max error; an rtol whose batch would exceed `plan.batch_budget` is skipped."""
    velocities = jnp.asarray(np.geomspace(*BATCH_RANGE, plan.batch_size) * sticking_velocity())
    references = np.asarray(
        theory.thornton_ning_restitution(np.asarray(velocities), MASS, RADIUS, E_STAR, WORK_OF_ADHESION)
    )
    scene = load_scene(case_scene("tn", dict(shape="paraboloid", R=RADIUS), float(velocities[0])))
    batched = jax.vmap(_impact_at_velocity(solver, scene), in_axes=(0, None))
    compiled, seconds = compile_ahead(batched, velocities, jnp.asarray(plan.rtols[0]))
    per_impact = np.full(len(plan.rtols), np.nan)
    errors = np.full(len(plan.rtols), np.nan)
    for sweep in range(plan.passes):
        for r, rtol in enumerate(plan.rtols):
            expected = 0.5 * single_times[r] * plan.batch_size
            if expected > plan.batch_budget:
                if not sweep:
                    log(f"  batch {solver} rtol {rtol:.0e}: skipped (about {expected:.0f} s)")
                continue
            total, outcome = best_time(compiled, (velocities, jnp.asarray(rtol)), 0.0, repeats=2, once=0.5)
            per_impact[r] = np.fmin(per_impact[r], total / plan.batch_size)
            if not sweep:
                separated = np.asarray(outcome.status) == RESULT_CODE["separated"]
                e = np.where(
                    separated, np.asarray(outcome.separation_velocity) / np.asarray(outcome.touch_velocity), np.nan
                )
                errors[r] = np.max(np.where(np.isnan(e), np.inf, np.abs(e - references)))
    return {"compile_batch": seconds, "time_batch": per_impact, "batch_error": errors}


def _check_solve(plan: Plan, solver: str, traced) -> dict:
    """`solve` of `impact._run.impacts` itself (static tolerances, its own compile) beside the
    traced-rtol function the sweep times, interleaved, on the Thornton–Ning 2·v_s case."""
    scene = load_scene(case_scene("tn", dict(shape="paraboloid", R=RADIUS), 2.0 * sticking_velocity()))
    physics = physics_for(scene)
    options = options_for(scene, trajectory=False)
    max_steps = scene.solver.max_steps
    check: dict = {"check_rtol": [], "check_compile": [], "check_time": [], "check_time_traced": [], "check_same": []}
    for rtol in plan.check_solve:
        integrator = _continuum(solver, rtol, max_steps)  # Python floats: static, compiled per rtol
        start = time.perf_counter()
        jax.block_until_ready(solve(integrator, physics, options))
        first = time.perf_counter() - start
        tolerance = jnp.asarray(rtol)
        static_times, traced_times = [], []
        for _ in range(5):  # interleaved, so that both see the same load
            static_time, (_, outcome) = best_time(solve, (integrator, physics, options), 0.0, repeats=2)
            traced_time, traced_outcome = best_time(traced, (physics, tolerance), 0.0, repeats=2)
            static_times.append(static_time)
            traced_times.append(traced_time)
        check["check_rtol"].append(rtol)
        check["check_compile"].append(first - min(static_times))
        check["check_time"].append(min(static_times))
        check["check_time_traced"].append(min(traced_times))
        check["check_same"].append(float(restitution(outcome) == restitution(traced_outcome)))
    return {key: np.asarray(value) for key, value in check.items()}
