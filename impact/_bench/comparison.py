"""Costs compared at equal error: the least time at which each way of computing e reaches each
target error reliably (a setting counts when it and every tighter one of its method do)."""

import numpy as np

from .._core.convergence import reliable
from .plans import TARGETS


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
        best_solver[target] = min(reachable, key=reachable.__getitem__) if reachable else ""
    return {"targets": np.asarray(TARGETS), "cost": table, "best_solver": best_solver}
