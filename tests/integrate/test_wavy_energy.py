"""The wavy paraboloid (3.132), whose edge function h = g − λ·√x turns dozens of times: every
jump of its contact keeps the indentation, and an impact never gains energy.

Before the root search of a segment that ends at a turning point was fixed (`Branch._solve`:
the power start there is the segment's lower end, where h − h(lower) rounds to zero, so its
log-Newton step was no step and counted as settled), every cascade landed on the top of its
segment: at touch the contact jumped to a = 42.5 nm, where h = 12.5 nm, not 0, and each snap-in
moved the body deeper at no cost; the case 11_wavy_strong rebounded with e = 1.77 (∮F dd =
−4.47e-12 J against 2.09e-12 J at touch).
"""

import jax.numpy as jnp
import numpy as np
import pytest
import yaml

from impact import simulate
from impact._integrate import transitions
from impact._integrate.problem import build_problem
from impact._run.parameters import options_for, physics_for
from impact._scene.scene import load_scene
from tests.scenes import HARD

CASE = HARD / "11_wavy_strong.yaml"


def wavy_scene(velocity: float, approach: float | None = None) -> dict:
    scene = yaml.safe_load(CASE.read_text())
    scene["initial"]["velocity"] = velocity
    if approach is not None:
        scene["effects"]["adhesion"]["approach_work_of_adhesion"] = approach
    return scene


@pytest.mark.slow
def test_every_rising_segment_of_the_wavy_edge_has_its_root():
    """h(a) = d on each rising segment, also those that end at a turning point (all but the
    last), at levels across the segment; and the jump-in at touch lands where h = 0."""
    scene = load_scene(CASE)
    problem = build_problem(physics_for(scene), options_for(scene, trajectory=False))
    law, attach = problem.law, problem.attach
    assert attach.table is None  # the search (`Branch._solve`), not a table
    rising = [int(s) for s in np.flatnonzero(np.asarray(attach.increasing))]
    assert len(rising) >= 8
    for segment in rising[:8]:
        low, high = float(attach.levels[segment]), float(attach.levels[segment + 1])
        for fraction in (1e-6, 0.1, 0.5, 0.9):
            level = jnp.asarray(low + fraction * (high - low))
            radius = attach.radius(law, level, segment)
            assert attach.nodes[segment] <= radius <= attach.nodes[segment + 1]
            assert abs(float(attach.level(law, radius) - level)) <= 1e-12 * (1.0 + abs(high))
    touch = transitions.touch(problem)
    assert abs(float(attach.level(law, touch.radius))) <= 1e-12
    assert float(touch.radius) < float(attach.nodes[touch.segment + 1])  # not the segment's top


@pytest.mark.slow
@pytest.mark.parametrize("approach", [None, 0.025, 0.0])
@pytest.mark.parametrize("velocity", [0.5, 2.0, 5.0, 20.0])
def test_a_wavy_impact_never_gains_energy_and_jumps_at_constant_depth(velocity, approach):
    result = simulate(wavy_scene(velocity, approach))
    assert result.status == "separated" or result.stuck
    assert result.restitution <= 1.0
    assert result.dissipated_energy >= 0.0
    # A jump of the contact (two samples at one time) keeps the indentation and the speed.
    t, d, v = result.t, result.indentation, result.velocity
    jumps = np.flatnonzero(np.diff(t) == 0)
    assert jumps.size >= 1
    scale = float(np.max(np.abs(d)))
    assert np.max(np.abs(d[jumps + 1] - d[jumps])) <= 1e-9 * scale
    assert np.max(np.abs(v[jumps + 1] - v[jumps])) <= 1e-9 * velocity
