"""Closed-form curves along the velocity axis of a sweep, its series, and the sticking velocity
estimated from the simulated points."""

import math
from collections.abc import Mapping

import jax
import numpy as np

from ..._core.runtime import compiler_options
from ..._core.stored import compile_stored
from ..._integrate.codes import RESULT_CODE
from ..._scene.paths import with_values
from ..._scene.sweep_spec import SweepSpec
from .closed_forms import closed_form_name, closed_form_restitution
from .plan import batch_physics, static_choices
from .result import SweepResult

VELOCITY = "initial.velocity"


_CURVE_POINTS = 512
_CURVES: dict = {}


def theory_curve(spec: SweepSpec, fixed: Mapping[str, object], path: str, values: np.ndarray) -> np.ndarray:
    """The closed-form restitution along `path` = values (other swept fields at `fixed`)."""
    values = np.asarray(values, dtype=np.float64)
    count = len(values)
    size = _CURVE_POINTS * max(1, -(-count // _CURVE_POINTS))
    padded = np.concatenate([values, np.full(size - count, values[-1])])
    params = {p: np.full(size, v) for p, v in fixed.items() if p != path}
    params[path] = padded
    physics = batch_physics(spec.scene, params, size)
    point = with_values(spec.scene, {p: params[p][0].item() for p in params})
    choices = static_choices(point)
    leaves, treedef = jax.tree.flatten(physics)
    key = (choices, treedef, tuple(leaf.shape for leaf in leaves))
    if key not in _CURVES:
        _CURVES[key] = compile_stored(
            jax.vmap(lambda p: closed_form_restitution(p, choices)),
            f"{__name__}.theory_curve {choices!r}",
            jax.tree.map(lambda leaf: jax.ShapeDtypeStruct(leaf.shape, leaf.dtype), physics),
            compiler_options(),
        )
    return np.asarray(_CURVES[key](physics))[:count]


def x_axis(spec: SweepSpec) -> str:
    """The axis figures and sticking estimates run along: the velocity if swept, else the first."""
    return VELOCITY if VELOCITY in spec.paths else spec.paths[0]


def series_along_x(result: SweepResult):
    """(x path, x [N], [(fixed values of the other axes, point indices sorted by x)])."""
    spec = result.spec
    path = x_axis(spec)
    flat = {p: v.reshape(-1) for p, v in result.params.items()}
    x = flat[path]
    others = [p for p in spec.paths if p != path]
    if not others:
        return path, x, [({}, np.argsort(x, kind="stable"))]
    columns = np.stack([flat[p].astype(np.float64) for p in others], axis=1)
    combos, first, inverse = np.unique(columns, axis=0, return_index=True, return_inverse=True)
    inverse = inverse.reshape(-1)
    series = []
    for combo in np.argsort(first):
        members = np.flatnonzero(inverse == combo)
        fixed = {p: flat[p][members[0]].item() for p in others}
        series.append((fixed, members[np.argsort(x[members], kind="stable")]))
    return path, x, series


def theory_dense(spec: SweepSpec, fixed: dict, path: str, low: float, high: float):
    """(x, e_theory) on a dense grid from low to high, refined three times (uniformly, 512
    points each) in the interval where e_theory leaves 0, which brackets the closed-form
    sticking velocity to ~1e-8 of the interval."""
    logarithmic = low > 0 and high / low > 10
    grid = np.geomspace(low, high, _CURVE_POINTS) if logarithmic else np.linspace(low, high, _CURVE_POINTS)
    values = theory_curve(spec, fixed, path, grid)
    for _ in range(3):
        crossing = np.flatnonzero((values[:-1] == 0) & (values[1:] > 0))
        if not crossing.size:
            break
        refined = np.linspace(grid[crossing[0]], grid[crossing[0] + 1], _CURVE_POINTS)[1:-1]
        grid = np.concatenate([grid, refined])
        values = np.concatenate([values, theory_curve(spec, fixed, path, refined)])
        order = np.argsort(grid, kind="stable")
        grid, values = grid[order], values[order]
    return grid, values


def closed_form_names(result: SweepResult) -> list[str]:
    """The closed forms the sweep's series are compared with."""
    _, _, series = series_along_x(result)
    theory_e = result.theory_restitution.reshape(-1)
    names = []
    for fixed, members in series:
        name = closed_form_name(with_values(result.scene, fixed))
        if np.isfinite(theory_e[members]).any() and name not in names:
            names.append(name)
    return names


def sticking_estimates(result: SweepResult) -> list[dict]:
    """Per combination of the other axes, along the velocity axis: the bracket of the sticking
    velocity (largest captured v, smallest separated v above it), an estimate from the first
    separated points (e² = 1 − (v_s/v)², exact for an energy loss independent of v), the
    closed-form v_s (where e_theory leaves 0) and max |e − e_theory|."""
    if VELOCITY not in result.spec.paths:
        return []
    path, x, series = series_along_x(result)
    e = result.restitution.reshape(-1)
    status = result.status.reshape(-1)
    theory_e = result.theory_restitution.reshape(-1)
    rows = []
    for fixed, members in series:
        ok = members[(status[members] == RESULT_CODE["separated"]) | (status[members] == RESULT_CODE["captured"])]
        v, ev = x[ok], e[ok]
        captured = status[ok] == RESULT_CODE["captured"]
        row = {
            "fixed": fixed,
            "low": math.nan,
            "high": math.nan,
            "estimate": math.nan,
            "theory": math.nan,
            "max_error": math.nan,
            "points": len(members),
            "failed": len(members) - len(ok),
        }
        if captured.any():
            row["low"] = float(v[captured].max())
        above = ~captured & (v > (row["low"] if captured.any() else -math.inf))
        if above.any():
            first = np.flatnonzero(above)[:2]
            row["high"] = float(v[first[0]])
            squares = 1.0 - ev[first] ** 2
            estimates = v[first] * np.sqrt(np.clip(squares, 0.0, None))
            if len(first) == 2 and v[first[1]] != v[first[0]]:
                # e² = A − B/v² through the two points: v_s = √(B/A)
                inv = 1.0 / v[first] ** 2
                slope = (ev[first[1]] ** 2 - ev[first[0]] ** 2) / (inv[1] - inv[0])
                intercept = ev[first[0]] ** 2 - slope * inv[0]
                if slope < 0 and intercept > 0:
                    estimates = np.array([math.sqrt(-slope / intercept)])
            estimate = float(estimates[0])
            if captured.any():
                estimate = min(max(estimate, row["low"]), row["high"])
            row["estimate"] = estimate if captured.any() else min(estimate, row["high"])
        th = theory_e[members]
        usable = np.isin(members, ok) & np.isfinite(th)
        if usable.any():
            row["max_error"] = float(np.max(np.abs(e[members][usable] - th[usable])))
            dense_v, dense_e = theory_dense(
                result.spec, fixed, path, float(x[members].min()) / 4, float(x[members].max())
            )
            positive = np.flatnonzero(dense_e > 0)
            if positive.size and positive[0] > 0:
                row["theory"] = float(0.5 * (dense_v[positive[0] - 1] + dense_v[positive[0]]))
        rows.append(row)
    return rows
