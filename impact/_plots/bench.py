"""The work-precision figure of a benchmark run: the error against the time per impact, log–log,
one line per method (continuum law single and batched, the scipy baseline, the spring array
exact over N and with velocity Verlet over Δt)."""

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .._core.convergence import ERROR_FLOOR, reliable
from .._io.files import atomic_path

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

SOLVER_COLORS = {
    "tsit5": "#1f77b4",
    "dopri5": "#2ca02c",
    "dopri8": "#d62728",
    "kvaerno5": "#9467bd",
    "bosh3": "#8c564b",
    "heun": "#e377c2",
    "kvaerno3": "#7f7f7f",
}
_VERLET_SHADES = ("#8fd3dc", "#17becf", "#0b6c75", "#063a40")  # light to dark: small to large N


def save_work_precision_figure(path: str | Path, data: dict) -> Path:
    """Write the work-precision figure to `path` (PNG, 130 dpi), atomically."""
    path = Path(path)
    with atomic_path(path) as temporary:
        work_precision_figure(data).savefig(temporary, dpi=130, format="png")
    return path


def work_precision_figure(data: dict) -> "Figure":
    """Error (max |e − e_ref| over the reference cases) against time per impact (s), log–log."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(10.0, 7.5), layout="constrained")
    axes = figure.add_subplot()
    lowest = [1.0]  # the smallest error drawn (sets the lower limit)
    handles = _continuum_lines(axes, data, lowest) + _scipy_lines(axes, data, lowest)
    handles += _spring_lines(axes, data, lowest)
    _label_axes(axes, data, lowest)
    axes.legend(handles=handles, fontsize=7.5, loc="upper right", framealpha=0.92)
    return figure


def _draw(axes: "Axes", lowest: list, times, errors, labels=(), offset=(5, 2), **style) -> None:
    """A line of (time, error) points, errors below the round-off floor drawn at it, each
    non-empty label annotated beside its point."""
    times, errors = np.asarray(times, float), np.asarray(errors, float)
    ok = np.isfinite(times) & np.isfinite(errors)
    y = np.maximum(errors[ok], ERROR_FLOOR)
    if y.size:
        lowest.append(float(y.min()))
    axes.plot(times[ok], y, **style)
    texts = np.asarray(list(labels) or [""] * len(ok), dtype=object)[ok]
    for x, value, text in zip(times[ok], y, texts, strict=True):
        if text:
            axes.annotate(
                text,
                (x, value),
                textcoords="offset points",
                xytext=offset,
                fontsize=7.5,
                color=style.get("color"),
                ha="right" if offset[0] < 0 else "left",
                va="center",
            )


def _continuum_lines(axes: "Axes", data: dict, lowest: list) -> list:
    """One solid (single impact) and one dashed (per impact in a batch) line per solver."""
    from matplotlib.lines import Line2D

    handles = []
    cont = data["continuum"]
    for solver, s in cont["solvers"].items():
        color = SOLVER_COLORS.get(solver, "black")
        failed = sorted({name for names in s["failures"] for name in names.split(", ") if name})
        errors = s["error_max_solved"] if failed else s["error_max"]
        labels = [f"rtol {r:.0e}" if solver == "tsit5" and k % 3 == 0 else "" for k, r in enumerate(cont["rtols"])]
        _draw(axes, lowest, s["time_single_mean"], errors, color=color, marker="o", ms=4.5, lw=1.8)
        dashed = dict(color=color, marker="o", ms=4, lw=1.3, ls="--", mfc="white")
        _draw(axes, lowest, s["time_batch"], errors, labels, offset=(-6, 0), **dashed)
        note = f"\n(failed runs, left out: {', '.join(failed)})" if failed else ""
        handles.append(Line2D([], [], color=color, marker="o", lw=1.8, label=f"continuum, diffrax {solver}{note}"))
    handles.append(Line2D([], [], color="grey", lw=1.8, label="    solid: one impact (jit)"))
    batch = f"    dashed: per impact in a jit(vmap) batch of {data['plan'].batch_size}"
    handles.append(Line2D([], [], color="grey", lw=1.3, ls="--", marker="o", mfc="white", label=batch))
    return handles


def _scipy_lines(axes: "Axes", data: dict, lowest: list) -> list:
    """One black line per solve_ivp method of the baseline."""
    from matplotlib.lines import Line2D

    handles = []
    for method, s in data["scipy"].items():
        rk45 = method == "RK45"
        style: dict[str, Any] = dict(
            color="black", marker="s" if rk45 else "D", ms=4.5, lw=1.3, ls="-." if rk45 else ":"
        )
        labels = [f"rtol {r:.0e}" if method == "DOP853" and k % 3 == 0 else "" for k, r in enumerate(s["rtols"])]
        _draw(axes, lowest, s["time_mean"], s["error_max"], labels, **style)
        handles.append(Line2D([], [], **style, label=f"baseline: scipy solve_ivp {method}, a(d) by brentq"))
    return handles


def _spring_lines(axes: "Axes", data: dict, lowest: list) -> list:
    """The exact stepper over N (labelled at powers of ten), and per N Verlet's points over Δt
    with the error that every smaller Δt stays below."""
    from matplotlib.lines import Line2D

    springs = data["springs"]
    exact = springs["exact"]
    decades = np.log10(exact["N"])
    labels = [f"N = $10^{int(round(x))}$" if abs(x - round(x)) < 1e-9 else "" for x in decades]
    style: dict[str, Any] = dict(color="#ff7f0e", marker="^", ms=5, lw=1.5)
    _draw(axes, lowest, exact["time"], np.abs(exact["error"]), labels, **style)
    handles = [Line2D([], [], **style, label="spring array, exact event-driven (over N)")]
    verlet = springs["verlet"]
    for (count, row), shade in zip(verlet.items(), _VERLET_SHADES[-len(verlet) :], strict=False):
        errors = np.abs(row["total_error"])
        _draw(axes, lowest, row["time"], errors, color=shade, marker="v", ms=3.5, lw=0, alpha=0.7)
        _draw(axes, lowest, row["time"], reliable(errors), color=shade, lw=1.4)
        label = f"spring array N = {count}, velocity Verlet (over Δt)"
        handles.append(Line2D([], [], color=shade, marker="v", lw=1.4, label=label))
    return handles


def _label_axes(axes: "Axes", data: dict, lowest: list) -> None:
    """Log scales, labels, the provenance in the title, grids, limits and the note on the springs."""
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
    axes.set_ylim(bottom=max(min(lowest) / 3.0, ERROR_FLOOR / 3.0))
    axes.margins(x=0.06)
    axes.text(
        0.01,
        0.01,
        "spring array: Thornton–Ning at 2·v_s only. Verlet markers: each Δt; its line: the error\n"
        "that every smaller Δt stays below (Verlet's error zigzags with Δt, so does the array's with N)",
        transform=axes.transAxes,
        ha="left",
        va="bottom",
        fontsize=7.5,
        color="dimgrey",
    )


def save_speed_figure(path: str | Path, rows: list[dict]) -> Path:
    """Write the figure of `impact bench speed` to `path` (PNG, 110 dpi), atomically."""
    path = Path(path)
    with atomic_path(path) as temporary:
        speed_figure(rows).savefig(temporary, dpi=110, format="png")
    return path


def speed_figure(rows: list[dict]) -> "Figure":
    """µs per impact against the points of a sweep (log–log, one line per workload, the bar
    from the fastest to the slowest run); beside it, the spring array's µs per impact against
    its number of springs N at the smallest points count measured."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(11.0, 4.8), layout="constrained")
    by_points, by_springs = figure.subplots(1, 2, width_ratios=(1.6, 1.0))
    workloads = list(dict.fromkeys(row["workload"] for row in rows))
    for workload in workloads:
        mine = sorted((row for row in rows if row["workload"] == workload), key=lambda row: row["points"])
        if mine[0]["springs"] and len(mine) < 2 and len(workloads) > 1:
            continue  # a point of the scan over N: drawn on the right
        points = np.asarray([row["points"] for row in mine], float)
        median = np.asarray([row["us_per_impact_median"] for row in mine])
        spread = [median - [row["us_min"] for row in mine], [row["us_max"] for row in mine] - median]
        by_points.errorbar(points, median, yerr=spread, marker="o", ms=4, capsize=2, label=workload)
    by_points.set(xscale="log", yscale="log", xlabel="points in the sweep", ylabel="µs per impact (median)")
    by_points.set_title("Cost per impact after compile", fontsize=10)
    by_points.legend(fontsize=7.5, ncols=2)
    by_points.grid(True, which="both", alpha=0.3)
    springs = [row for row in rows if row["springs"]]
    if springs:
        smallest = min(row["points"] for row in springs)
        scan = sorted((row for row in springs if row["points"] == smallest), key=lambda row: row["springs"])
        counts = np.asarray([row["springs"] for row in scan], float)
        cost = np.asarray([row["us_per_impact_median"] for row in scan])
        by_springs.plot(counts, cost, "o-", color="#17becf", label=f"spring array, {smallest} points")
        by_springs.plot(counts, cost[-1] * counts / counts[-1], ":", color="0.5", label="∝ N")
        by_springs.legend(fontsize=7.5)
    by_springs.set(xscale="log", yscale="log", xlabel="springs N", ylabel="µs per impact (median)")
    by_springs.set_title("Spring array: cost against N", fontsize=10)
    by_springs.grid(True, which="both", alpha=0.3)
    return figure
