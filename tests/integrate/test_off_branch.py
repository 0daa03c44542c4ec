"""A ride of the continuum law starts on its edge function, d = h(a); one that does not (a jump of
the contact radius that landed elsewhere) ends the run with the status `off_branch` instead of a
restitution: before 828eadd the wavy paraboloid's cascades landed 0.08–0.2 (scaled) off and the
impact created energy (e = 1.77)."""

import jax
import pytest

from impact import simulate
from impact._integrate.codes import RESULT_CODE
from impact._law.branches import Branch
from impact._run.parameters import integrator_for, options_for, physics_for
from impact._scene.paths import with_values
from impact._scene.scene import load_scene
from tests.scenes import CONFIGS


def _status(scene) -> int:
    """The run's result code, traced afresh (a cached program would not see a patched branch)."""
    integrator, options = integrator_for(scene), options_for(scene, trajectory=False)
    _, outcome = jax.jit(lambda physics: integrator.solve(physics, options))(physics_for(scene))
    return int(outcome.status)


@pytest.mark.slow
@pytest.mark.parametrize(
    ("config", "changes"),
    [
        ("thornton_ning.yaml", {}),  # the energy's ends
        ("thornton_ning.yaml", {"solver.phase_ends": "integrated", "solver.rtol": 1e-8, "solver.atol": 1e-10}),
        ("rubber_ball_viscoelastic.yaml", {}),  # damped, no adhesion: the ride starts at the tip
        ("thornton_ning.yaml", {"solver.method": "quadrature"}),
    ],
)
def test_a_ride_that_starts_off_its_edge_function_ends_the_run(monkeypatch, config, changes):
    scene = with_values(load_scene(CONFIGS / config), changes)
    assert _status(scene) == RESULT_CODE[simulate(scene, trajectory=False).status] == RESULT_CODE["separated"]
    landed = Branch.cascade_out

    def off_by_a_little(self, law, start, indentation):  # the radius 1e-2 (scaled) beyond the root
        radius, segment, blocked = landed(self, law, start, indentation)
        return radius + 1e-2 * (1.0 + radius), segment, blocked

    monkeypatch.setattr(Branch, "cascade_out", off_by_a_little)
    assert _status(scene) == RESULT_CODE["off_branch"]
