"""What the tests share: the example files' folders, the micro-sphere most impacts strike (the one
of configs/thornton_ning.yaml), its JKR units, and scenes built on it.

Module-level constants, not fixtures: parametrize lists and other module constants are computed
from them at collection. `tests/conftest.py` holds the fixtures."""

import math
from pathlib import Path

import pytest
import yaml

import impact

ROOT = Path(__file__).resolve().parents[1]
CONFIGS = ROOT / "configs"
HARD = CONFIGS / "hard"
SWEEPS = CONFIGS / "sweeps"
FITS = CONFIGS / "fits"
THORNTON_NING = CONFIGS / "thornton_ning.yaml"

# The micro-sphere: a 1 µm paraboloid of 2500 kg/m³ on a stiff polymer (E* = 1 GPa) with
# Δγ = 0.05 J/m²; its sticking velocity is 0.3032 m/s (3.52).
R, E_STAR, WORK, MASS = 1.0e-6, 1.0e9, 0.05, 1.0472e-14  # m, Pa, J/m², kg
# Its JKR units (3.170): the contact radius, the depth |d_c| and the force of the
# force-controlled pull-off.
A_JKR = (9 * math.pi * R**2 * WORK / (8 * E_STAR)) ** (1 / 3)
D_JKR = A_JKR**2 / (3 * R)
F_JKR = 1.5 * math.pi * R * WORK

# Quasi-static indentation: the control and its ξ (3: force, 1: displacement).
CONTROLS = [("force", 3), ("displacement", 1)]


def micro_sphere(velocity: float, effects: dict | None = None, **sections) -> dict:
    """The micro-sphere's impact at `velocity` (m/s) on a rigid flat, with the scene's
    `effects` (none: no adhesion) and any further top-level sections (name, solver, contact,
    …)."""
    return {
        "body": {"profile": {"shape": "paraboloid", "R": R}, "mass": MASS},
        "material": {"E_star": E_STAR},
        "initial": {"velocity": velocity},
        "effects": {} if effects is None else effects,
        **sections,
    }


def indentation_scene(
    profile: dict,
    control: str,
    peak: float,
    work: float = WORK,
    approach: float | None = None,
    springs: "int | str" = "continuum",
    E_star: float = E_STAR,
    **program,
) -> dict:
    """A quasi-static indentation of `profile` under `control` up to `peak` (N or m) and back
    to pull-off (`program` adds cycles, unload_to), with JKR adhesion `work` (J/m², 0: none)
    and `approach` (Δγa), on the continuum law or `springs` springs."""
    effects = {}
    if work:
        effects["adhesion"] = {"work_of_adhesion": work}
        if approach is not None:
            effects["adhesion"]["approach_work_of_adhesion"] = approach
    return dict(
        name="test",
        kind="indentation",
        control=control,
        program=dict(peak=peak, **program),
        body=dict(profile=profile),
        material=dict(E_star=E_star),
        effects=effects,
        contact=dict(springs=springs),
    )


# Two glass spheres (configs/two_spheres.yaml's, the body stiffer) and their speeds in the lab.
R_BODY, R_OTHER = 10e-6, 20e-6  # m
DENSITY = 2500.0  # kg/m³
V_BODY, V_OTHER = 0.1, 0.05  # m/s, towards each other


def two_spheres(**counterpart) -> dict:
    """Glass spheres with JKR adhesion; the counterpart's fields override the defaults."""
    return {
        "body": {"profile": {"shape": "paraboloid", "R": R_BODY}, "density": DENSITY},
        "counterpart": {
            "profile": {"shape": "paraboloid", "R": R_OTHER},
            "density": DENSITY,
            "velocity": V_OTHER,
            **counterpart,
        },
        "material": {"E": 63e9, "nu": 0.2, "E_body": 70e9, "nu_body": 0.22},
        "initial": {"velocity": V_BODY},
        "effects": {"adhesion": {"work_of_adhesion": 0.1}},
    }


def quadrature_refusal(config: Path, change: dict) -> str:
    """The message `solver.method: quadrature` is refused with in the scene of `config` (a YAML
    file) with the top-level sections of `change` replaced."""
    data = {**yaml.safe_load(config.read_text()), **change, "solver": {"method": "quadrature"}}
    with pytest.raises(impact.SceneError) as error:
        impact.load_scene(data)
    return dict(error.value.problems)["solver.method"]
