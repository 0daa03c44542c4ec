"""The tables of a benchmark run as Markdown fragments that the documentation includes verbatim
(`--markdown FILE`; docs/src/accuracy.md includes docs/snippets/*.md): a line saying when, where
and by which command they were measured, then the table."""

import math

from .table import cheapest_table, continuum_table
from .workloads import workloads


def work_precision_fragment(data: dict, command: str) -> str:
    """The cheapest setting for each error and every solver × rtol of the continuum law."""
    lines = [
        _measured(data["provenance"], command),
        "",
        "**The cheapest setting for each error** (a setting counts when it and every tighter setting of its "
        "method reach the error):",
        "",
        *cheapest_table(data),
        "",
        "**The continuum law, every solver and tolerance** (atol = rtol/100, scaled units):",
        "",
        *continuum_table(data["continuum"], batch_error=False),
    ]
    return "\n".join(lines) + "\n"


def speed_fragment(rows: list[dict], provenance: dict, command: str) -> str:
    """One row per workload × points count of `impact bench speed`; the device's peak memory
    only where a device kept one (GPUs)."""
    names = {workload.key: workload.name for workload in workloads()}
    device = any(math.isfinite(row["device_peak_mb"]) for row in rows)
    lines = [
        _measured(provenance, command) + (f" Sweeps on {rows[0]['device']}." if rows else ""),
        "",
        "| workload (`--only`) | method | points | µs per impact, median (min–max) | max error (against) | steps "
        "| compile | build / integrate / post, µs | peak RSS |" + (" device peak |" if device else ""),
        "|---|---|---|---|---|---|---|---|---|" + ("---|" if device else ""),
    ]
    for row in rows:
        line = (
            f"| {names.get(row['workload'], row['workload'])} (`{row['workload']}`) | {row['method']} "
            f"| {row['points']} "
            f"| {microseconds(row['us_per_impact_median'])} ({microseconds(row['us_min'])}–"
            f"{microseconds(row['us_max'])}) | {row['max_error']:.1e} ({row['error_reference']}) "
            f"| {row['steps_mean']:.0f} | {row['compile_s']:.1f} s | {microseconds(row['build_us'])} / "
            f"{microseconds(row['integrate_us'])} / {microseconds(row['post_us'])} | {row['peak_rss_mb']:.0f} MB |"
        )
        lines.append(line + (f" {row['device_peak_mb']:.0f} MB |" if device else ""))
    return "\n".join(lines) + "\n"


def _measured(provenance: dict, command: str) -> str:
    p = provenance
    return (
        f"Measured {p['date']} by `{command}` on {p['machine']}; impact {p['impact']}, jax {p['jax']}, "
        f"diffrax {p['diffrax']}, Python {p['python']}, float64."
    )


def microseconds(value: float) -> str:
    """A time in µs to a tenth above 10 µs, else to three digits (a GPU's fraction of a µs)."""
    return f"{value:.1f}" if value >= 10 else f"{value:.3g}"
