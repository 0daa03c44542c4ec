"""A point's result does not depend on its batch (issue #18, item 3): for each law, a sweep run
point by point (chunk 1), in calls of 6 (chunk 7), all at once (chunk 64 and the default) and in
reverse order gives every result bitwise equal, and equal to `impact.simulate` of the point.

XLA:CPU once vectorised the lanes of a batch, so that lanes in SIMD registers and lanes in the
scalar remainder rounded differently (restitutions apart by a few ulps, Maugis–Dugdale's step
counts by up to 20); `impact._core.runtime.COMPILER_OPTIONS` makes every lane run scalar code.
Twelve points make the batch wide enough to be vectorised without that option.

A Runge–Kutta step's sum of its stages is one matrix–vector product over every lane's state,
which XLA:CPU computes in tiles of 4 rows with fused multiply–adds and the rows left over
without: the last lane of a batch whose lanes hold 3 components in all not a multiple of 4 (a
batch of 3 or 7) rounded differently, by 3e-15 in the restitution of a power law n = 1.5. Rides
pad their state to 4 components (`impact._integrate.base`); the power law checks it with a
batch of 3.

Not yet for Maugis–Dugdale (its one-point program differs from its batched ones in the last
bits, and a batch of 7 splits into lanes 0–2 and 3–6: docs/src/sweeps.md), not checked here.
"""

from pathlib import Path

import numpy as np
import pytest

from impact import simulate
from impact._core.defaults import DEFAULT_CHUNK
from impact._run.sweep import sweep
from impact._scene.paths import with_values
from impact._scene.scene import load_scene

CONFIGS = Path(__file__).parents[2] / "configs"
POINTS = 12
# (scene, its changes, lowest and highest velocity in m/s): captured and separated points
LAWS = {
    "continuum JKR": ("thornton_ning.yaml", {}, 0.25, 5.0),
    "spring array": ("spring_array.yaml", {}, 0.3, 3.0),
    "attach hysteresis": ("attach_on_touch.yaml", {"effects.adhesion.approach_work_of_adhesion": 0.02}, 0.2, 3.0),
}
# Results `impact.simulate` gives bitwise on the continuum law; its program (with the event log)
# contracts a few multiply–adds of the force differently: the force extremes and ∮F dd agree to a
# few ulps, and on a spring array (whose events advance in closed form) these results too.
SIMULATED = ("restitution", "stuck", "contact_time", "bounces", "touch_velocity", "separation_velocity")
SIMULATED_CLOSE = {"spring array": 1e-14}
CLOSE = {
    "max_indentation": 1e-14,
    "max_force": 1e-14,
    "min_force": 1e-14,
    "dissipated_energy": 1e-12,  # ∮F dd cancels
    "adhesion_hysteresis": 1e-12,  # all of it here
}


def assert_bitwise(results: dict, reference: dict, label: str) -> None:
    assert results.keys() == reference.keys(), label
    for name in reference:
        mine, theirs = np.asarray(results[name]), np.asarray(reference[name])
        differ = np.flatnonzero(~((mine == theirs) | (np.isnan(mine) & np.isnan(theirs))))
        assert differ.size == 0, f"{label}: {name} differs at points {differ.tolist()}"


@pytest.mark.parametrize("law", LAWS)
def test_a_points_result_does_not_depend_on_its_batch(law):
    config, changes, low, high = LAWS[law]
    scene = with_values(load_scene(CONFIGS / config), changes)
    velocities = np.geomspace(low, high, POINTS)
    axes = {"initial.velocity": velocities.tolist()}
    alone = sweep(scene, axes, order="given", chunk=1)
    assert alone.stats["call_sizes"] == [1]
    assert 0 < np.count_nonzero(alone.stuck) < POINTS  # both outcomes: lanes that finish early
    for chunk, size in ((7, 6), (64, POINTS), (DEFAULT_CHUNK, POINTS)):
        batched = sweep(scene, axes, order="given", chunk=chunk)
        assert batched.stats["call_sizes"] == [size]
        assert_bitwise(batched.results, alone.results, f"chunk {chunk}")
    backwards = sweep(scene, {"initial.velocity": velocities[::-1].tolist()}, order="given", chunk=64)
    assert_bitwise({name: column[::-1] for name, column in backwards.results.items()}, alone.results, "reversed")
    for point in (0, POINTS // 2, POINTS - 1):
        single = simulate(with_values(scene, {"initial.velocity": float(velocities[point])}), trajectory=False)
        assert single.status == alone.status_names()[point]
        assert single.stats["steps"] == alone.steps[point]
        for name in SIMULATED:
            mine, theirs = getattr(single, name), alone.results[name][point]
            if law in SIMULATED_CLOSE:
                np.testing.assert_allclose(mine, theirs, rtol=SIMULATED_CLOSE[law], err_msg=name)
            else:
                assert np.array_equal(mine, theirs, equal_nan=True), (point, name)
        for name, rtol in CLOSE.items():
            np.testing.assert_allclose(getattr(single, name), alone.results[name][point], rtol=rtol, err_msg=name)


def test_a_power_law_point_does_not_depend_on_its_place_in_a_batch():
    """Three points, repeated in one call of 7 (7·3 state components: without the padding the
    last lane's time falls in the row left over from the 4-row tiles, and its restitution
    moved by 3e-15), and in reverse order: each point's results are bitwise the same wherever
    it sits. (One compiled program: a power law's takes ~20 s to compile.)"""
    scene = load_scene(CONFIGS / "power_law.yaml")
    velocities = np.array([0.12, 2.0, 0.3, 0.12, 2.0, 0.3, 0.3])  # m/s; v_s = 0.1315 m/s: 0.12 sticks
    batched = sweep(scene, {"initial.velocity": velocities.tolist()}, order="given", chunk=64)
    assert batched.stats["call_sizes"] == [7]
    assert 0 < np.count_nonzero(batched.stuck) < 7
    backwards = sweep(scene, {"initial.velocity": velocities[::-1].tolist()}, order="given", chunk=64)
    assert_bitwise({name: column[::-1] for name, column in backwards.results.items()}, batched.results, "reversed")
    first = {
        name: column[[np.flatnonzero(velocities == v)[0] for v in velocities]]
        for name, column in batched.results.items()
    }
    assert_bitwise(batched.results, first, "repeated points")
