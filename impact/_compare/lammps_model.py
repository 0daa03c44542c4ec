"""A scene as LAMMPS's granular contact model sees it: the normal model, the materials, the
surface energy, the damping and the yield stress that reproduce the scene's E*, Δγ, damping and
plasticity, with what LAMMPS leaves out in words; or the reason it cannot represent the scene.

LAMMPS's conventions (pair_style granular, fix wall/gran granular; release 2025.7.22):
- hertz/material, jkr, dmt: F = (4/3)E_mix√R δ^(3/2) (+ adhesion), E_mix = 1/((1 − ν₁²)/E₁ +
  (1 − ν₂²)/E₂) between two particles; a wall takes the particle's own E and ν, E_mix =
  E/(2(1 − ν²)).
- jkr: F = 4E_mix a³/(3R) − 2πa²√(4γE_mix/(πa)), pull-off 3πγR: γ = Δγ/2 gives JKR's (3/2)πRΔγ.
- dmt: Hertz − 4πγR while the spheres overlap: γ = Δγ/2 gives the DMT pull-off 2πRΔγ.
- mdr (Zunker & Kamrin, J. Mech. Phys. Solids 183 (2024) 105492): a pair contact is split at a
  rigid flat into two sphere–flat contacts of modulus E/(1 − ν²), each with the rule of Heß
  Δl = √(2πaγ(1 − ν²)/E); γ = Δγ/2 makes their sum the pair's √(2πaΔγ/E*). It yields where the
  mean Hertz pressure 4E_eff a/(3πR) reaches Y(1.75 e^(−4.4δ/R) + 1).
- damping: F = −η v_n with η = η₀ (velocity), η₀ m_eff (mass_velocity), η₀ a m_eff
  (viscoelastic); tsuji and coeff_restitution take a restitution coefficient, not with adhesion.
"""

import math
from dataclasses import dataclass

from .._scene.errors import SceneError
from .._scene.profiles import ParaboloidSpec, SphereSpec
from .._scene.scene import Scene

MODELS = ("jkr", "dmt", "hertz/material", "mdr")
ADHESIVE_MODELS = ("jkr", "dmt")
DAMPINGS = {
    "jkr": ("velocity", "mass_velocity", "viscoelastic"),
    "dmt": ("velocity", "mass_velocity", "viscoelastic"),
    "hertz/material": ("velocity", "mass_velocity", "viscoelastic", "tsuji", "coeff_restitution"),
    "mdr": ("mdr",),
}
RESTITUTION_DAMPINGS = ("tsuji", "coeff_restitution")  # their value is a coefficient of restitution
SPHERES = ("paraboloid", "sphere")
# Poisson's ratio passed where the scene gives E* alone: no normal force of these models depends on
# it at a given E* (it sets LAMMPS's tangential stiffness, switched off here, and mdr's plastic flow).
DEFAULT_POISSON = 0.3


class CompareError(SceneError):
    """A scene or option LAMMPS cannot represent; `problems` lists (field or option, reason) pairs."""


@dataclass(frozen=True)
class Material:
    """Young's modulus (Pa) and Poisson's ratio passed to LAMMPS for one particle type."""

    E: float
    nu: float


@dataclass(frozen=True)
class Damping:
    """LAMMPS's damping model, its coefficient η₀ (or restitution) and where it comes from."""

    model: str
    coefficient: float
    origin: str


@dataclass(frozen=True)
class LammpsModel:
    """The granular model of one scene: the body (type 1) on a wall, or against a counterpart
    (type 2) when `pair`; SI units."""

    model: str
    pair: bool
    body_radius: float
    body_mass: float
    counterpart_radius: float
    counterpart_mass: float
    counterpart_velocity: float  # towards the body (m/s)
    materials: tuple[Material, Material]  # body, counterpart (a wall takes the body's)
    surface_energy: float  # γ (J/m²), 0 for hertz/material
    damping: Damping
    yield_stress: float  # Y (Pa) of mdr (0 for the other models)
    E_star: float  # the scene's effective modulus (Pa)
    notes: tuple[str, ...]  # how each parameter was mapped
    left_out: str  # what the LAMMPS model leaves out

    def normal_model(self, material: Material) -> str:
        """The normal-model words of LAMMPS's granular contact for one material."""
        E, nu, damp = f"{material.E:.17g}", f"{material.nu:.17g}", f"{self.damping.coefficient:.17g}"
        gamma = f"{self.surface_energy:.17g}"
        words = {
            "hertz/material": f"hertz/material {E} {damp} {nu}",
            "jkr": f"jkr {E} {damp} {nu} {gamma}",
            "dmt": f"dmt {E} {damp} {nu} {gamma}",
            "mdr": f"mdr {E} {nu} {self.yield_stress:.17g} {gamma} 0.0 {damp}",
        }[self.model]
        damping = "mdr 1" if self.model == "mdr" else self.damping.model
        return f"{words} damping {damping} tangential linear_nohistory 0.0 0.0"


def lammps_model(scene: Scene, model: str | None = None, damping: str | None = None) -> LammpsModel:
    """The LAMMPS granular model of an impact scene (`model`: jkr, dmt, hertz/material or mdr;
    default jkr with adhesion, hertz/material without; `damping`: "MODEL:VALUE" to replace the
    scene's damping in LAMMPS), or CompareError naming what LAMMPS cannot represent."""
    name = model or ("jkr" if scene.adhesive else "hertz/material")
    problems = _refusals(scene, name)
    chosen = None
    if damping is not None and name in MODELS:
        chosen, problem = _damping_option(damping, name)
        problems += problem
    if problems:
        raise CompareError(problems)
    counterpart = scene.counterpart
    pair = counterpart is not None
    body_radius = sphere_radius(scene)
    counterpart_radius = math.inf if counterpart is None or counterpart.radius is None else counterpart.radius
    materials, material_note = _materials(scene, name)
    gamma, adhesion_note = _surface_energy(scene, name)
    mapped, damping_note = _scene_damping(scene, name)
    if chosen is not None:
        replaced = damping_note.removeprefix("damping: ")
        mapped, damping_note = (
            chosen,
            f"damping: {chosen.model} {chosen.coefficient:g} (--damping; the scene's: {replaced})",
        )
    yield_stress, yield_note = _yield_stress(scene, name, materials[0])
    counterpart_mass = counterpart.resolved_mass if counterpart is not None else math.inf
    counterpart_velocity = counterpart.velocity if counterpart is not None else 0.0
    partner = (
        f"against a sphere of radius {counterpart_radius:.6g} m and mass {counterpart_mass:.6g} kg moving at "
        f"{counterpart_velocity:.6g} m/s towards it (pair_style granular)"
        if pair
        else "on a wall at rest (fix wall/gran granular, zplane)"
    )
    body = f"a sphere of radius {body_radius:.6g} m and mass {scene.body.resolved_mass:.6g} kg"
    geometry = f"particles: the body {body} {partner}"
    return LammpsModel(
        model=name,
        pair=pair,
        body_radius=body_radius,
        body_mass=scene.body.resolved_mass,
        counterpart_radius=counterpart_radius,
        counterpart_mass=counterpart_mass,
        counterpart_velocity=counterpart_velocity,
        materials=materials,
        surface_energy=gamma,
        damping=mapped,
        yield_stress=yield_stress,
        E_star=scene.material.effective_modulus,
        notes=tuple(note for note in (geometry, material_note, adhesion_note, damping_note, yield_note) if note),
        left_out=left_out(scene, name, mapped),
    )


def sphere_radius(scene: Scene) -> float:
    """The body's radius R (m): of its paraboloid or sphere (validated one of them)."""
    profile = scene.body.profile
    assert isinstance(profile, ParaboloidSpec | SphereSpec), "validated: the body is a paraboloid or sphere"
    return profile.R


def effective_radius(scene: Scene) -> float:
    """R (m) of the contact: R₁R₂/(R₁ + R₂) with a counterpart, else the body's."""
    return scene.effective_radius or sphere_radius(scene)


def _refusals(scene: Scene, model: str) -> list[tuple[str, str]]:
    """What LAMMPS's `model` cannot represent of the scene, as (field, reason) pairs."""
    if model not in MODELS:
        return [("--model", f"unknown model {model!r}; expected one of: {', '.join(MODELS)}")]
    if scene.kind != "impact":
        return [("kind", f"only impacts are compared with LAMMPS, not kind {scene.kind!r}")]
    problems = []
    shape = scene.body.profile.shape
    if shape not in SPHERES:
        problems.append(
            (
                "body.profile.shape",
                f"LAMMPS's granular particles are spheres: the body must be a paraboloid or sphere, not {shape!r}",
            )
        )
    if scene.counterpart is not None and scene.counterpart.radius is None:
        problems.append(
            (
                "counterpart.profile",
                "a flat counterpart of finite mass has no LAMMPS equivalent (its walls do not move freely): give the "
                "counterpart a paraboloid, or leave it out for a rigid flat at rest",
            )
        )
    if scene.effects.gravity is not None:
        problems.append(
            (
                "effects.gravity",
                "not mapped: the comparison is of the first contact without gravity (with LAMMPS's fix gravity the "
                "first rebound and the bounces after it would have to be told apart); leave gravity out",
            )
        )
    problems += _adhesion_refusals(scene, model)
    if scene.effects.plasticity is not None and model != "mdr":
        problems.append(
            ("effects.plasticity", f"LAMMPS's {model} is elastic: use --model mdr (its own plasticity) or leave it out")
        )
    if model == "mdr" and scene.counterpart is None:
        problems.append(
            (
                "--model",
                "mdr runs between two particles only (a scene with a counterpart): on a wall (fix wall/gran) LAMMPS "
                "2025.7.22 crashes the process, a segmentation fault in its mdr force",
            )
        )
    if model == "mdr" and scene.effects.damping is not None:
        problems.append(
            (
                "effects.damping",
                "LAMMPS's mdr takes only its own damping (damping mdr): leave effects.damping out, or pass "
                "--damping mdr:VALUE",
            )
        )
    return problems


def _adhesion_refusals(scene: Scene, model: str) -> list[tuple[str, str]]:
    adhesion = scene.active_adhesion
    if adhesion is None:
        if model in ADHESIVE_MODELS:
            why = f"{model} needs adhesion (effects.adhesion with work_of_adhesion > 0); without it use hertz/material"
            return [("--model", why)]
        return []
    if not adhesion.zero_range:
        return [
            (
                "effects.adhesion.model",
                f"LAMMPS's granular adhesion has zero range (jkr, dmt, mdr): {adhesion.name!r} has no equivalent there",
            )
        ]
    if adhesion.hysteretic and model in ADHESIVE_MODELS:
        return [
            (
                "effects.adhesion.approach_work_of_adhesion",
                f"{adhesion.approach:g} J/m² is below work_of_adhesion ({adhesion.work_of_adhesion:g} J/m²): LAMMPS's "
                f"{model} attaches at the touch with the whole work of adhesion (no approach hysteresis); leave it out",
            )
        ]
    return []


def _damping_option(text: str, model: str) -> tuple[Damping | None, list[tuple[str, str]]]:
    """--damping MODEL:VALUE, checked against the damping models LAMMPS allows with `model`."""
    allowed = DAMPINGS[model]
    kind, _, value = text.partition(":")
    try:
        coefficient = float(value)
    except ValueError:
        coefficient = math.nan
    restitution = kind in RESTITUTION_DAMPINGS
    valid = 0 < coefficient <= 1 if restitution else 0 <= coefficient < math.inf
    if kind not in allowed or not valid:
        restitutions = [name for name in allowed if name in RESTITUTION_DAMPINGS]
        bound = (
            f"VALUE >= 0 (0 < VALUE <= 1, a restitution, for {' and '.join(restitutions)})"
            if restitutions
            else "VALUE >= 0"
        )
        why = f"must be MODEL:VALUE with MODEL one of {', '.join(allowed)} for {model} and {bound}, got {text!r}"
        return None, [("--damping", why)]
    return Damping(kind, coefficient, "--damping"), []


def _materials(scene: Scene, model: str) -> tuple[tuple[Material, Material], str]:
    """The materials of body and counterpart, and how they give the scene's E*."""
    given = scene.material
    E_star = given.effective_modulus
    if scene.counterpart is not None and model != "mdr" and given.E_body is not None:
        assert given.E is not None and given.nu is not None and given.nu_body is not None, "validated together"
        body, other = Material(given.E_body, given.nu_body), Material(given.E, given.nu)
        return (body, other), (
            f"materials: the body E = {body.E:.6g} Pa, ν = {body.nu:g}, the counterpart E = {other.E:.6g} Pa, "
            f"ν = {other.nu:g}, as the scene gives them: LAMMPS mixes them into E* = {E_star:.6g} Pa"
        )
    nu = next((value for value in (given.nu_body, given.nu) if value is not None), DEFAULT_POISSON)
    shared = Material(2.0 * (1.0 - nu**2) * E_star, nu)
    whose = "the wall takes the particle's E and ν" if scene.counterpart is None else "both particles take one material"
    origin = (
        f"{DEFAULT_POISSON:g} (the scene gives E* alone; at a given E* ν enters none of these normal forces)"
        if given.E_star is not None
        else f"{nu:g}, the scene's"
    )
    return (shared, shared), (
        f"materials: E = 2(1 − ν²)E* = {shared.E:.6g} Pa with ν = {origin}: {whose}, so that LAMMPS's "
        f"E* = E/(2(1 − ν²)) = {E_star:.6g} Pa, the scene's"
    )


def _surface_energy(scene: Scene, model: str) -> tuple[float, str]:
    """LAMMPS's γ (J/m²) and how it follows from Δγ."""
    adhesion = scene.active_adhesion
    if adhesion is None:
        return 0.0, "adhesion: none"
    work = adhesion.work_of_adhesion
    if model == "hertz/material":
        return 0.0, f"adhesion: none (hertz/material has none; the scene's Δγ = {work:g} J/m² is left out)"
    gamma = work / 2
    radius = effective_radius(scene)
    meaning = {
        "jkr": f"LAMMPS's pull-off 3πγR = (3/2)πRΔγ = {3 * math.pi * gamma * radius:.6g} N, JKR's",
        "dmt": f"LAMMPS's pull-off 4πγR = 2πRΔγ = {4 * math.pi * gamma * radius:.6g} N, DMT's",
        "mdr": "each side of the contact plane detaches by the rule of Heß with γ, together with Δγ",
    }[model]
    return gamma, f"adhesion: γ = Δγ/2 = {gamma:g} J/m² (Δγ the Dupré work of adhesion): {meaning}"


def _scene_damping(scene: Scene, model: str) -> tuple[Damping, str]:
    """The scene's damping as LAMMPS's: linear c → velocity η₀ = c; viscoelastic A → viscoelastic
    η₀ = 2E*A/m_eff (F = 2E*aA·v_n, Brilliantov et al.); none → η₀ = 0."""
    damping = scene.effects.damping
    lammps_name = "mdr" if model == "mdr" else "velocity"
    if damping is None:
        return Damping(lammps_name, 0.0, "scene"), f"damping: none ({lammps_name} with η₀ = 0)"
    if not damping.viscoelastic:
        c = damping.linear_coefficient
        return Damping("velocity", c, "scene"), f"damping: velocity η₀ = c = {c:g} N·s/m, the scene's linear damping"
    eta = 2.0 * scene.material.effective_modulus * damping.viscoelastic_constant / scene.reduced_mass
    return Damping("viscoelastic", eta, "scene"), (
        f"damping: viscoelastic η₀ = 2E*A/m_eff = {eta:.6g} 1/(m·s): LAMMPS's η₀·a·m_eff·v_n is the scene's "
        f"2E*·a·A·ḋ (A = {damping.viscoelastic_constant:g} s)"
    )


def _yield_stress(scene: Scene, model: str, material: Material) -> tuple[float, str]:
    """mdr's Y: where the scene yields (Thornton's peak pressure p_y = 2E*a/(πR), i.e. a mean pressure
    (2/3)p_y), mdr yields at the same contact radius; without plasticity Y = E, above any Hertz mean
    pressure 4E_eff/(3π) of mdr's overlaps (δ < R), so it never yields."""
    if model != "mdr":
        return 0.0, ""
    plasticity = scene.effects.plasticity
    if plasticity is None:
        return material.E, f"yield stress: Y = E = {material.E:.6g} Pa: the contact never yields"
    E_star, radius = scene.material.effective_modulus, sphere_radius(scene)
    contact_radius = math.pi * plasticity.yield_pressure * effective_radius(scene) / (2 * E_star)
    Y = (2 / 3) * plasticity.yield_pressure / (1.75 * math.exp(-4.4 * contact_radius**2 / radius**2) + 1)
    return Y, (
        f"yield stress: Y = {Y:.6g} Pa, so that mdr yields at the scene's yield radius {contact_radius:.6g} m "
        f"(mean pressure (2/3)p_y, p_y = {plasticity.yield_pressure:g} Pa)"
    )


def left_out(scene: Scene, model: str, damping: Damping) -> str:
    """What LAMMPS's `model` (with `damping`) leaves out of the scene, in words."""
    words = {
        "jkr": (
            "LAMMPS's jkr attaches at the touch with the JKR jump-in (no approach hysteresis, Δγa = Δγ) and "
            "releases the contact at the force-controlled pull-off δ_f, where F = −(3/2)πRΔγ: it cuts the JKR "
            "branch there, while a free body follows the branch on to its displacement-controlled end (ξ = 1) "
            "and snaps off at −(5/9) of that force. Undamped it loses "
            "theory.force_release_energy_loss = 0.4939 of the Thornton–Ning energy at every speed, and its "
            "sticking velocity is √0.4939 = 0.7028 of theirs."
        ),
        "dmt": (
            "LAMMPS's dmt adds a constant attraction 2πRΔγ (the DMT pull-off) while the spheres overlap and none "
            "outside: no range, no jump-in, no snap-off; undamped it returns all the energy (e = 1)."
        ),
        "hertz/material": "LAMMPS's hertz/material is Hertz's law without adhesion.",
        "mdr": (
            "LAMMPS's mdr (Zunker & Kamrin 2024) is a law of its own: an elliptical 1-D indenter in place of the "
            "sphere's MDR profile, its own plasticity (yield where the mean Hertz pressure reaches "
            "Y(1.75e^(−4.4δ/R) + 1), a flattened radius after it), adhesion by tensile springs once unloading "
            "begins (no jump-in at the touch), each side of a pair against a rigid flat at the contact plane."
        ),
    }[model]
    if model != "mdr" and scene.body.profile.shape == "sphere":
        words += " Its laws are those of the paraboloid f = r²/(2R), the scene's sphere within O(a²/R²)."
    if damping.coefficient > 0 and model not in ADHESIVE_MODELS:
        words += (
            " Damped, it keeps the contact until the overlap ends, pulling the body back once the viscous force "
            "exceeds the elastic one; impact lets the body go where the total force returns to zero (Schwager & "
            "Pöschel, Granular Matter 9, 465 (2007))."
        )
    if damping.origin == "--damping":
        words += " Its damping is the one given by --damping, not the scene's."
    return words + " Velocity Verlet at a fixed step dt; contact times counted in whole steps."
