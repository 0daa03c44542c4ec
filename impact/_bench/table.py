"""table.md of a benchmark run: what each digit of accuracy costs, then every measurement."""

import numpy as np


def table_markdown(data: dict) -> str:
    """table.md: the cost of each digit, then every measurement (times in s, µs or ms)."""
    lines = _summary(data) + _continuum(data) + _spring_array(data["springs"]) + _verlet(data["springs"])
    lines += _scipy(data["scipy"])
    return "\n".join(lines) + "\n"


def _ms(seconds: float) -> str:
    if not np.isfinite(seconds):
        return "—"
    if seconds >= 1.0:
        return f"{seconds:.2f} s"
    if seconds >= 1e-3:
        return f"{seconds * 1e3:.3g} ms"
    return f"{seconds * 1e6:.3g} µs"


def header(*columns: str) -> list[str]:
    """The two lines that open a Markdown table of `columns`."""
    return ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]


def row(*cells: object) -> str:
    """One line of a Markdown table."""
    return "| " + " | ".join(str(cell) for cell in cells) + " |"


def _err(value: float) -> str:
    return "failed" if not np.isfinite(value) else f"{value:.1e}"


def _ratio(numerator: float, denominator: float) -> str:
    if not (np.isfinite(numerator) and np.isfinite(denominator)) or denominator <= 0:
        return "—"
    return f"{numerator / denominator:.0f}×" if numerator / denominator >= 10 else f"{numerator / denominator:.1f}×"


def _summary(data: dict) -> list[str]:
    """The title, the provenance and the cheapest setting of each method at each target error."""
    p, cases = data["provenance"], data["cases"]
    return [
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
        *cheapest_table(data),
    ]


def cheapest_table(data: dict) -> list[str]:
    """The cheapest setting of each method at each target error, as Markdown table rows."""
    equal = data["equal"]
    lines = header(
        "error ≤",
        "continuum, single",
        "continuum, batched (per impact)",
        "scipy solve_ivp",
        "springs, exact",
        "springs, Verlet",
        "scipy ÷ single",
        "scipy ÷ batched",
    )
    cost = equal["cost"]
    for t, target in enumerate(equal["targets"]):
        single = cost["continuum, single"][t]
        batched = cost["continuum, batched"][t]
        base = cost.get("scipy solve_ivp", np.full(len(equal["targets"]), np.nan))[t]
        solver = equal["best_solver"][float(target)]
        lines.append(
            row(
                f"{target:.0e}",
                _ms(single) + (f" ({solver})" if solver else ""),
                _ms(batched),
                _ms(base),
                _ms(cost["springs, exact"][t]),
                _ms(cost["springs, Verlet"][t]),
                _ratio(base, single),
                _ratio(base, batched),
            )
        )
    return lines


def _continuum(data: dict) -> list[str]:
    """Every solver × rtol of the continuum law, its compile times and the check against `solve`."""
    cont = data["continuum"]
    lines = ["", "## Continuum law (diffrax): solver × rtol (atol = rtol/100, scaled units)", ""]
    lines += continuum_table(cont)
    lines += ["", "Compile times (trace + XLA compile, once per solver for the whole rtol sweep):", ""]
    for solver, s in cont["solvers"].items():
        groups = ", ".join(f"{g} {t:.1f} s" for g, t in s["compile_single"].items())
        lines.append(
            f"- {solver}: single impact {groups}; batch of {data['plan'].batch_size} {s['compile_batch']:.1f} s"
        )
    return lines + _solve_check(cont)


def continuum_table(cont: dict, batch_error: bool = True) -> list[str]:
    """Every solver × rtol of the continuum law as Markdown table rows; `batch_error` adds the
    batch's own max error (table.md has it, the documentation's fragment leaves it out)."""
    columns = ["solver", "rtol", "max error", "steps per impact (accepted / rejected)", "single impact"]
    lines = header(*columns, "batched, per impact", *(["batch max error"] if batch_error else []))
    for solver, s in cont["solvers"].items():
        for r, rtol in enumerate(cont["rtols"]):
            failed = s["failures"][r]
            error = (
                _err(s["error_max"][r])
                if not failed
                else f"failed: {failed} ({s['error_max_solved'][r]:.1e} on the rest)"
            )
            steps = f"{np.mean(s['accepted'][r]):.0f} / {np.mean(s['rejected'][r]):.0f}"
            cells = [solver, f"{rtol:.0e}", error, steps, _ms(s["time_single_mean"][r]), _ms(s["time_batch"][r])]
            if batch_error:
                cells.append(_err(s["batch_error"][r]) if np.isfinite(s["time_batch"][r]) else "—")
            lines.append(row(*cells))
    return lines


def _solve_check(cont: dict) -> list[str]:
    """`solve` with static tolerances beside the traced-rtol sweep (only where it was run)."""
    checks = [(solver, s) for solver, s in cont["solvers"].items() if "check_rtol" in s]
    if not checks:
        return []
    lines = [
        "",
        "Check against `impact._run.impacts.solve` itself (static tolerances, own compile), Thornton–Ning 2·v_s:",
        "",
        *header("solver", "rtol", "solve: compile", "solve: run", "traced-rtol run", "same e"),
    ]
    for solver, s in checks:
        for k, rtol in enumerate(s["check_rtol"]):
            compile_time, same = f"{s['check_compile'][k]:.1f} s", "yes" if s["check_same"][k] else "no"
            lines.append(
                row(solver, f"{rtol:.0e}", compile_time, _ms(s["check_time"][k]), _ms(s["check_time_traced"][k]), same)
            )
    return lines


def _spring_array(springs: dict) -> list[str]:
    """The exact event-driven stepper over N, and its time per spring event and memory."""
    exact, cost = springs["exact"], springs["cost"]
    lines = [
        "",
        f"## Spring array, exact event-driven stepper (spatial error; fitted order in N: {exact['order']:.2f})",
        "",
        *header("N", "e − e_TN", "events", "time", "compile"),
    ]
    for k, count in enumerate(exact["N"]):
        error, compile_time = f"{exact['error'][k]:+.2e}", f"{exact['compile'][k]:.1f} s"
        lines.append(row(count, error, exact["events"][k], _ms(exact["time"][k]), compile_time))
    lines += [
        "",
        "Time per spring event (a run's time over its events, fixed costs included) and the buffers of the "
        "compiled program:",
        "",
    ]
    for k, count in enumerate(cost["N"]):
        lines.append(
            f"- N = {count}: {cost['time_per_event'][k] * 1e6:.2f} µs per event ({cost['events'][k]} events), "
            f"{cost['memory'][k] / 1024:.1f} kB"
        )
    return lines


def _verlet(springs: dict) -> list[str]:
    """Velocity Verlet over (N, Δt): its spatial and time-stepping errors and energy identity."""
    lines = ["", "## Spring array, velocity Verlet (error = spatial part + time-stepping part)", ""]
    for count, fit in springs["verlet"].items():
        lines.append(
            f"- N = {count}: spatial part e_exact − e_TN = {fit['spatial_error']:+.2e}; time-stepping part "
            f"|e − e_exact| fitted order in Δt {fit['order']:.2f}, bounded by {fit['bound']:.2g}·Δt (scaled Δt)"
        )
    lines += [
        "",
        *header(
            "N",
            "Δt (scaled)",
            "Δt",
            "steps",
            "time",
            "e − e_exact (time stepping)",
            "e − e_TN (total)",
            "KE lost − ∮F dd, relative (= ⅛Δt²a₀²: Verlet's identity)",
        ),
    ]
    for count, run in springs["verlet"].items():
        for k, step in enumerate(run["dt"]):
            mismatch = (run["energy_lost"][k] - run["work"][k]) / run["energy_lost"][k]
            errors = f"{run['time_error'][k]:+.2e}", f"{run['total_error'][k]:+.2e}", f"{mismatch:+.1e}"
            lines.append(
                row(count, f"{step:.2e}", f"{run['dt_si'][k]:.2e} s", run["steps"][k], _ms(run["time"][k]), *errors)
            )
    return lines


def _scipy(scipy_results: dict) -> list[str]:
    """The solve_ivp baseline over method × rtol (absent when it was not run)."""
    if not scipy_results:
        return []
    lines = [
        "",
        "## Baseline: scipy.integrate.solve_ivp, (d, v) in JKR units, a(d) by brentq in the right-hand side",
        "",
        *header("method", "rtol", "max error", "right-hand sides per impact", "steps per impact", "time per impact"),
    ]
    for method, s in scipy_results.items():
        for r, rtol in enumerate(s["rtols"]):
            calls, steps = f"{np.mean(s['nfev'][r]):.0f}", f"{np.mean(s['steps'][r]):.0f}"
            lines.append(row(method, f"{rtol:.0e}", _err(s["error_max"][r]), calls, steps, _ms(s["time_mean"][r])))
    return lines
