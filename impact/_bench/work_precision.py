"""What accuracy costs in time: a work-precision benchmark of every way `impact` integrates an impact.

`run(folder, quick=False)` measures, in one process on this machine, and writes `bench.h5`,
`work_precision.png` and `table.md`:

- **Continuum law** (diffrax, `Continuum` through `solve`) × solvers × rtol (atol = rtol/100,
  scaled units), on reference cases with closed-form restitution: Thornton–Ning paraboloids
  at v0/v_s ∈ {1.001, 1.05, 2, 30}, a cone and a power law n = 1.5 (Popov, Heß & Willert,
  Handbook of Contact Mechanics (Springer 2019), ch. 3, eqs. (3.81)–(3.82)), and a paraboloid
  that attaches on touch (`theory.attach_on_touch_restitution`). Recorded: the error
  |e − e_ref| of each case and its max, steps (accepted, rejected), the time of a single
  impact (jitted, after compile, no trajectory), the time per impact in a `jit(vmap)` batch of
  10³ velocities of one case, and compile times. The tolerance is passed to the integrator as
  a traced argument, so one compile serves a whole rtol sweep (a static rtol would recompile for
  each); the full run checks against `solve` itself, compiled with static tolerances.
- **Spring array** (Thornton–Ning at 2 v_s) × N: the exact event-driven stepper
  (`SpringArray`, whose error is the pure spatial error) and a fixed-step velocity Verlet
  (`Verlet`) over Δt, whose difference from the exact discrete model is the pure
  time-stepping error; fitted orders in N and in Δt. For N = 10 and 10⁶, the exact stepper's
  time per spring event and the memory of its compiled program (the same: nothing of size N).
- **Baseline a researcher would write**: the same contact law with `scipy.integrate.solve_ivp`
  (RK45, DOP853), state (d, v) in scaled units, the contact radius from the JKR branch by
  `brentq` inside the right-hand side, a terminal separation event; same cases, same run.

Times are the best of a few repeats (the machine is shared and noisy; ratios measured in one
run are what to read). The library does not enable float64: the caller does (the CLI does).
"""

import os
import platform
import time
from collections.abc import Callable
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import diffrax
import jax
import numpy as np
import scipy

from .._core.package import __version__
from .._io.bench import write_bench_h5
from .._io.files import write_text
from .._plots.bench import save_work_precision_figure
from .cases import reference_cases
from .comparison import equal_error
from .continuum import bench_continuum
from .plans import FULL, QUICK
from .scipy_baseline import bench_scipy
from .springs import bench_springs
from .table import table_markdown


def run(folder: str | Path, quick: bool = False, log: Callable[[str], None] = print) -> dict:
    """Measure everything, write bench.h5, work_precision.png and table.md into `folder`;
    return the measurements. Each line logged is prefixed with the seconds since the start.

    Needs float64 (`jax.config.update("jax_enable_x64", True)`; the CLI does it).
    """
    if not jax.config.read("jax_enable_x64"):
        raise RuntimeError("the benchmark needs float64: jax.config.update('jax_enable_x64', True) first")
    plan = QUICK if quick else FULL
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()

    def timed(line: str) -> None:
        log(f"[{time.perf_counter() - start:4.0f} s] {line}")

    cases = reference_cases(plan.groups)
    timed(
        f"{'quick' if quick else 'full'} benchmark: {len(cases)} cases, solvers {', '.join(plan.solvers)}, "
        f"rtol {plan.rtols[0]:.0e}…{plan.rtols[-1]:.0e}"
    )
    data: dict[str, Any] = {"plan": plan, "cases": cases, "provenance": provenance("quick" if quick else "full")}
    data["continuum"] = bench_continuum(plan, cases, timed)
    data["springs"] = bench_springs(plan, timed)
    data["scipy"] = bench_scipy(plan, cases, timed)
    data["equal"] = equal_error(data["continuum"], data["springs"], data["scipy"])
    data["provenance"]["wall_time"] = time.perf_counter() - start
    write_bench_h5(folder / "bench.h5", data)
    write_text(folder / "table.md", table_markdown(data))
    save_work_precision_figure(folder / "work_precision.png", data)
    timed(f"benchmark written to {folder} in {time.perf_counter() - start:.0f} s")
    return data


def provenance(plan_name: str) -> dict:
    """When, with which versions and on which machine a run measured."""
    machine = f"{platform.machine()}, {os.cpu_count()} cores, {platform.system()}"
    return {
        "date": datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC"),
        "impact": __version__,
        "jax": jax.__version__,
        "diffrax": diffrax.__version__,
        "scipy": scipy.__version__,
        "numpy": np.__version__,
        "python": platform.python_version(),
        "machine": f"{machine} (jax backend: {jax.default_backend()})",
        "plan": plan_name,
        "x64": bool(jax.config.read("jax_enable_x64")),
    }
