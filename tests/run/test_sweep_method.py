"""The method a sweep runs (issue #42, item 3): the one its scene names, else the quadrature where
every point allows it, else the scene's default ODE solver; each with its reason in the spec, the
sweep file, the sweep's summary and `impact validate`. A point equals a single run of its scene
with the sweep's method named, bitwise; a single run keeps what its scene says."""

import h5py
import numpy as np
import pytest
import yaml

import impact
from impact._io.sweep import read_sweep
from impact._scene.paths import with_values
from impact._scene.sweep import make_spec
from impact._scene.sweep_method import CHOSEN, FASTER, NAMED
from tests.command import invoke
from tests.run.bitwise import assert_bitwise, named_method
from tests.scenes import CONFIGS

VELOCITIES = [0.25, 0.6, 2.0]  # m/s; v_s = 0.3032 m/s: one captured point, two separated
# Results a point gives as the single run of its scene with the sweep's method named, to the bit;
# the single run's program (with its event log) contracts a few multiply–adds of the force
# otherwise, so the force extremes and ∮F dd agree to a few ulps (as in test_batch_independence).
SINGLE_RUN = ("restitution", "stuck", "contact_time", "bounces", "touch_velocity", "separation_velocity")
CLOSE = {"max_indentation": 1e-14, "max_force": 1e-14, "min_force": 1e-14, "dissipated_energy": 1e-12}


def unnamed(config: str = "thornton_ning.yaml", **solver) -> impact.Scene:
    """The config with its solver section replaced by `solver` (no method unless it names one)."""
    data = yaml.safe_load((CONFIGS / config).read_text())
    data["solver"] = solver
    return impact.load_scene(data)


def single_runs(scene: impact.Scene, velocities) -> dict:
    """`impact.simulate` of the scene at each velocity, as the sweep's columns of `SINGLE_RUN` and `CLOSE`."""
    runs = [impact.simulate(with_values(scene, {"initial.velocity": v}), trajectory=False) for v in velocities]
    return {name: np.asarray([getattr(run, name) for run in runs]) for name in (*SINGLE_RUN, *CLOSE)}


@pytest.mark.slow
def test_a_scene_without_a_method_is_swept_with_the_quadrature_and_equals_its_named_single_run():
    scene = unnamed()
    assert scene.solver.method == "tsit5"  # what a single run of it takes
    swept = impact.sweep(scene, {"initial.velocity": VELOCITIES}, order="given")
    assert (swept.spec.method, swept.spec.method_choice) == ("quadrature", CHOSEN)
    assert np.all(swept.steps == 0)  # no ODE step
    assert 0 < np.count_nonzero(swept.stuck) < len(VELOCITIES)
    single = single_runs(named_method(scene, "quadrature"), VELOCITIES)
    mine = {name: swept.results[name] for name in SINGLE_RUN}
    assert_bitwise(mine, {name: single[name] for name in SINGLE_RUN}, "quadrature named")
    for name, rtol in CLOSE.items():
        np.testing.assert_allclose(swept.results[name], single[name], rtol=rtol, err_msg=name)
    # the single run of the scene as written keeps its ODE solve
    ode = impact.simulate(scene, trajectory=False)
    assert ode.stats["steps"] > 0
    assert abs(ode.restitution - swept.restitution[1]) <= 1e-8 * swept.restitution[1]


def test_a_scene_that_names_its_method_keeps_it():
    spec = make_spec(CONFIGS / "thornton_ning.yaml", {"initial.velocity": VELOCITIES})  # names tsit5
    assert (spec.method, spec.method_choice) == ("tsit5", NAMED + FASTER)
    assert yaml.safe_load(spec.definition())["scene"]["solver"]["method"] == "tsit5"
    named = make_spec(unnamed(method="dopri8"), {"initial.velocity": VELOCITIES})
    assert (named.method, named.method_choice) == ("dopri8", NAMED + FASTER)


def test_the_quadrature_is_chosen_only_where_every_point_allows_it():
    """A point the quadrature refuses keeps the whole sweep on the scene's default, saying why;
    so do an axis of the ODE solve's settings and a scene the quadrature cannot run at all."""
    power_law = unnamed("power_law.yaml")
    assert make_spec(power_law, {"body.profile.n": [1.5, 2.0]}).method == "quadrature"
    mixed = make_spec(power_law, {"body.profile.n": [0.8, 1.5]})
    assert mixed.method == "tsit5"
    assert mixed.method_choice.startswith("the default: the scene names no method and 'quadrature' does not run")
    assert "value 0.8 makes the scene invalid" in mixed.method_choice and "n >= 1" in mixed.method_choice
    tolerances = make_spec(unnamed(), {"solver.rtol": [1e-8, 1e-10]})
    assert tolerances.method == "tsit5"
    assert "would leave the axis solver.rtol without effect" in tolerances.method_choice
    damped = make_spec(CONFIGS / "rubber_ball_viscoelastic.yaml", {"initial.velocity": [1.0, 2.0]})
    assert damped.method == "tsit5"
    assert damped.method_choice == (
        "the default: the scene names no method and 'quadrature' not with effects.damping: "
        "a damped phase does not keep its energy"
    )


def test_validate_says_which_method_a_sweep_runs():
    facts = " ".join(invoke("validate", CONFIGS / "power_law.yaml").output.replace("│", " ").split())
    assert "solver tsit5, rtol 1e-10" in facts
    assert "in a sweep quadrature: the scene names no method and 'quadrature' runs it" in facts
    named = " ".join(invoke("validate", CONFIGS / "thornton_ning.yaml").output.replace("│", " ").split())
    assert "in a sweep tsit5: named by the scene (solver.method); 'quadrature' would run it" in named


@pytest.mark.slow
def test_the_sweep_file_and_summary_record_the_method(tmp_path):
    sweep_file = tmp_path / "unnamed.yaml"
    scene = yaml.safe_load((CONFIGS / "thornton_ning.yaml").read_text())
    del scene["solver"]
    data = {"scene": scene, "axes": {"initial.velocity": VELOCITIES}}
    sweep_file.write_text(yaml.safe_dump(data))
    result = invoke("sweep", sweep_file, "-o", tmp_path / "out")
    assert result.exit_code == 0, result.output
    said = " ".join(result.output.replace("│", " ").split())
    assert f"method quadrature: {CHOSEN}" in said
    with h5py.File(tmp_path / "out" / "sweep.h5") as file:
        assert file["sweep"].attrs["method"] == "quadrature" and file["sweep"].attrs["method_choice"] == CHOSEN
    stored = read_sweep(tmp_path / "out" / "sweep.h5")
    assert (stored.spec.method, stored.spec.method_choice) == ("quadrature", CHOSEN)
