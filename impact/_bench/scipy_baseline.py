"""The baseline a researcher would write: the same contact law with `scipy.integrate.solve_ivp`
(RK45, DOP853), state (d, v) in JKR units, the contact radius from the JKR branch by `brentq`
inside the right-hand side, a terminal separation event; the same cases as the continuum law."""

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from .. import theory
from .cases import Case
from .plans import E_STAR, MASS, WORK_OF_ADHESION, Plan
from .timing import best_python_time

_SPAN = (0.0, 1e4)  # time span of every solve_ivp call (JKR units): ended by its event


def jkr_units(case: Case) -> tuple[float, float, float]:
    """(radial (m), normal (m), time (s)) units of the baseline: the jump-in radius a0 with
    g(a0) = Δl(a0)."""
    a0 = float(theory.power_law_jump_in(case.n, case.c, E_STAR, WORK_OF_ADHESION)[0])
    normal = math.sqrt(2.0 * math.pi * a0 * WORK_OF_ADHESION / E_STAR)
    return a0, normal, math.sqrt(MASS / (E_STAR * a0))


class JkrLaw(NamedTuple):
    """The contact law in JKR units (g = aⁿ, Δl = √a, mass 1), as plain Python functions."""

    h: Callable  # the JKR branch d = h(a) = aⁿ − √a
    force: Callable  # F(a, d) = 2(a·d − aⁿ⁺¹/(n+1))
    jkr: Callable  # right-hand side (t, (d, v)) on the JKR branch, a(d) by brentq
    separation: Callable  # terminal event: d falls through the branch's turning point d*


def jkr_law(n: float) -> JkrLaw:
    """The law of exponent n; the body separates at the turning point d* of the branch
    (displacement control)."""
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

    separation.terminal, separation.direction = True, -1  # type: ignore[attr-defined]
    return JkrLaw(h, force, jkr, separation)


def scipy_restitution(case: Case, method: str, rtol: float, atol: float) -> tuple[float, int, int]:
    """e of one case as a researcher would write it with solve_ivp: (e, right-hand sides, steps).

    On the JKR branch the radius is a root found by brentq in every right-hand side call; the
    body separates at the branch's turning point d*, a terminal event.
    """
    _, normal, unit_time = jkr_units(case)
    v0 = case.velocity / (normal / unit_time)
    law = jkr_law(case.n)
    options = dict(method=method, rtol=rtol, atol=atol)
    if case.attach_on_touch:
        return _attach_on_touch(law, case.n, v0, options)
    sol = solve_ivp(law.jkr, _SPAN, [0.0, v0], events=law.separation, **options)
    return abs(sol.y_events[0][0][1]) / v0, sol.nfev, sol.t.size - 1


def _attach_on_touch(law: JkrLaw, n: float, v0: float, options: dict) -> tuple[float, int, int]:
    """Attach on touch: Hertzian loading a = d^(1/n) to the turnaround, a hold at a_max until
    d = h(a_max), then the JKR branch to separation."""
    force = law.force

    def hertz(t, y):
        return [y[1], -force(max(y[0], 0.0) ** (1.0 / n), y[0])]

    def turned(t, y):
        return y[1]

    turned.terminal, turned.direction = True, -1  # type: ignore[attr-defined]
    loading = solve_ivp(hertz, _SPAN, [0.0, v0], events=turned, **options)
    deepest = loading.y_events[0][0][0]
    held = deepest ** (1.0 / n)

    def hold(t, y):
        return [y[1], -force(held, y[0])]

    def unhold(t, y):
        return y[0] - law.h(held)

    unhold.terminal, unhold.direction = True, -1  # type: ignore[attr-defined]
    holding = solve_ivp(hold, _SPAN, [deepest, 0.0], events=unhold, **options)
    unloading = solve_ivp(law.jkr, _SPAN, holding.y_events[0][0], events=law.separation, **options)
    parts = (loading, holding, unloading)
    return (
        abs(unloading.y_events[0][0][1]) / v0,
        sum(part.nfev for part in parts),
        sum(part.t.size - 1 for part in parts),
    )


def bench_scipy(plan: Plan, cases: list[Case], log: Callable) -> dict:
    """The baseline on every case × method × rtol (atol = rtol/100): errors, times (s),
    right-hand sides and steps per impact."""
    results = {}
    for method in plan.scipy_methods:  # first calls import and set up scipy's machinery
        scipy_restitution(cases[0], method, 1e-3, 1e-5)
    for method in plan.scipy_methods:
        shape = (len(plan.scipy_rtols), len(cases))
        record = {key: np.full(shape, np.nan) for key in ("error", "time", "nfev", "steps")}
        for r, rtol in enumerate(plan.scipy_rtols):
            for i, case in enumerate(cases):
                seconds, (e, nfev, steps) = best_python_time(
                    scipy_restitution, (case, method, rtol, rtol / 100.0), plan.timing_budget
                )
                record["error"][r, i] = abs(e - case.reference)
                record["time"][r, i] = seconds
                record["nfev"][r, i] = nfev
                record["steps"][r, i] = steps
        record["error_max"] = np.max(record["error"], axis=1)
        record["time_mean"] = np.mean(record["time"], axis=1)
        record["rtols"] = np.asarray(plan.scipy_rtols)
        results[method] = record
        log(
            f"scipy {method}: best max error {np.min(record['error_max']):.1e}, "
            f"{np.min(record['time_mean']) * 1e3:.1f}–{np.max(record['time_mean']) * 1e3:.1f} ms per impact"
        )
    return results
