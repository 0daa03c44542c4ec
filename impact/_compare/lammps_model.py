"""A scene as LAMMPS's granular contact model sees it: the normal model, the materials, the
surface energy, the damping and the yield stress that reproduce the scene's E*, Δγ, damping and
plasticity, with what LAMMPS leaves out in words; or the reason it cannot represent the scene.

The models and their conventions are `granular.NormalModel` and `granular.DampingModel`. The
mapping: a wall takes the particle's own E and ν (E_mix = E/(2(1 − ν²))); γ = Δγ/2 gives jkr's
pull-off 3πγR = JKR's (3/2)πRΔγ, dmt's 4πγR = the DMT pull-off 2πRΔγ, and makes the sum of mdr's
two sides the pair's √(2πaΔγ/E*); damping F = −η v_n with η = η₀ (velocity), η₀ m_eff
(mass_velocity), η₀ a m_eff (viscoelastic); tsuji and coeff_restitution take a restitution
coefficient, not with adhesion.
"""

import math
from dataclasses import dataclass

from .._scene.profiles import ParaboloidSpec, SphereSpec
from .._scene.scene import Scene
from .granular import CompareError, DampingModel, NormalModel

SPHERES = ("paraboloid", "sphere")
# Poisson's ratio passed where the scene gives E* alone: no normal force of these models depends on
# it at a given E* (it sets LAMMPS's tangential stiffness, switched off here, and mdr's plastic flow).
DEFAULT_POISSON = 0.3


@dataclass(frozen=True)
class Material:
    """Young's modulus (Pa) and Poisson's ratio passed to LAMMPS for one particle type."""

    E: float
    nu: float


@dataclass(frozen=True)
class Damping:
    """LAMMPS's damping model, its coefficient η₀ (or restitution) and where it comes from."""

    model: DampingModel
    coefficient: float
    origin: str


@dataclass(frozen=True)
class Particles:
    """The particles of one speed: the body (type 1) on a wall, or against a counterpart (type 2)
    when `pair`; SI units."""

    body_radius: float  # m
    body_mass: float  # kg
    counterpart_radius: float  # m; inf: a wall
    counterpart_mass: float  # kg; inf: a wall
    counterpart_velocity: float  # towards the body (m/s)

    @property
    def pair(self) -> bool:
        """Whether the body meets a counterpart particle (pair_style granular), not a wall."""
        return math.isfinite(self.counterpart_radius)

    def describe(self) -> str:
        """The particles in words (the mapping's first note)."""
        body = f"a sphere of radius {self.body_radius:.6g} m and mass {self.body_mass:.6g} kg"
        partner = (
            f"against a sphere of radius {self.counterpart_radius:.6g} m and mass {self.counterpart_mass:.6g} kg "
            f"moving at {self.counterpart_velocity:.6g} m/s towards it (pair_style granular)"
            if self.pair
            else "on a wall at rest (fix wall/gran granular, zplane)"
        )
        return f"particles: the body {body} {partner}"


@dataclass(frozen=True)
class LammpsModel:
    """The granular model of one scene: its normal model, particles, materials, adhesion, damping
    and yield stress; SI units."""

    model: NormalModel
    particles: Particles
    materials: tuple[Material, Material]  # body, counterpart (a wall takes the body's)
    surface_energy: float  # γ (J/m²), 0 for hertz/material
    damping: Damping
    yield_stress: float  # Y (Pa) of mdr (0 for the other models)
    E_star: float  # the scene's effective modulus (Pa)
    notes: tuple[str, ...]  # how each parameter was mapped
    left_out: str  # what the LAMMPS model leaves out

    def normal_model(self, material: Material) -> str:
        """The normal-model words of LAMMPS's granular contact for one material."""
        words = self.model.words(
            material.E, material.nu, self.damping.coefficient, self.surface_energy, self.yield_stress
        )
        return f"{words} damping {self.damping.model.words} tangential linear_nohistory 0.0 0.0"


def lammps_model(scene: Scene, model: NormalModel | None = None, damping: str | None = None) -> LammpsModel:
    """The LAMMPS granular model of an impact scene (`model`: default jkr with adhesion,
    hertz/material without; `damping`: the option "MODEL:VALUE" to replace the scene's damping in
    LAMMPS), or CompareError naming what LAMMPS cannot represent."""
    name = model or NormalModel.default(scene.adhesive)
    problems = _refusals(scene, name)
    chosen = None
    if damping is not None:
        chosen, problem = _damping_option(damping, name)
        problems += problem
    if problems:
        raise CompareError(problems)
    materials, material_note = _materials(scene, name)
    gamma, adhesion_note = _surface_energy(scene, name)
    mapped, damping_note = _scene_damping(scene, name)
    if chosen is not None:
        replaced = damping_note.removeprefix("damping: ")
        mapped, damping_note = (
            chosen,
            f"damping: {chosen.model.keyword} {chosen.coefficient:g} (--damping; the scene's: {replaced})",
        )
    yield_stress, yield_note = _yield_stress(scene, name, materials[0])
    particles = _particles(scene)
    notes = (particles.describe(), material_note, adhesion_note, damping_note, yield_note)
    return LammpsModel(
        model=name,
        particles=particles,
        materials=materials,
        surface_energy=gamma,
        damping=mapped,
        yield_stress=yield_stress,
        E_star=scene.material.effective_modulus,
        notes=tuple(note for note in notes if note),
        left_out=left_out(scene, name, mapped),
    )


def _particles(scene: Scene) -> Particles:
    """The body and its counterpart (a wall at rest where the scene has none)."""
    counterpart = scene.counterpart
    return Particles(
        body_radius=sphere_radius(scene),
        body_mass=scene.body.resolved_mass,
        counterpart_radius=math.inf if counterpart is None or counterpart.radius is None else counterpart.radius,
        counterpart_mass=math.inf if counterpart is None else counterpart.resolved_mass,
        counterpart_velocity=0.0 if counterpart is None else counterpart.velocity,
    )


def sphere_radius(scene: Scene) -> float:
    """The body's radius R (m): of its paraboloid or sphere (validated one of them)."""
    profile = scene.body.profile
    assert isinstance(profile, ParaboloidSpec | SphereSpec), "validated: the body is a paraboloid or sphere"
    return profile.R


def effective_radius(scene: Scene) -> float:
    """R (m) of the contact: R₁R₂/(R₁ + R₂) with a counterpart, else the body's."""
    return scene.effective_radius or sphere_radius(scene)


def _refusals(scene: Scene, model: NormalModel) -> list[tuple[str, str]]:
    """What LAMMPS's `model` cannot represent of the scene, as (field, reason) pairs."""
    traits, keyword = model.traits, model.keyword
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
    if scene.effects.plasticity is not None and not traits.plastic:
        problems.append(
            (
                "effects.plasticity",
                f"LAMMPS's {keyword} is elastic: use --model mdr (its own plasticity) or leave it out",
            )
        )
    if not traits.on_walls and scene.counterpart is None:
        problems.append(
            (
                "--model",
                f"{keyword} runs between two particles only (a scene with a counterpart): on a wall (fix wall/gran) "
                f"LAMMPS 2025.7.22 crashes the process, a segmentation fault in its {keyword} force",
            )
        )
    own = traits.dampings[0]
    # The scene's damping maps to LAMMPS's velocity or viscoelastic damping (`_scene_damping`).
    if scene.effects.damping is not None and not {DampingModel.velocity, DampingModel.viscoelastic} & set(
        traits.dampings
    ):
        problems.append(
            (
                "effects.damping",
                f"LAMMPS's {keyword} takes only its own damping (damping {own.keyword}): leave effects.damping out, "
                f"or pass --damping {own.keyword}:VALUE",
            )
        )
    return problems


def _adhesion_refusals(scene: Scene, model: NormalModel) -> list[tuple[str, str]]:
    adhesion = scene.active_adhesion
    if adhesion is None:
        if model.traits.needs_adhesion:
            why = (
                f"{model.keyword} needs adhesion (effects.adhesion with work_of_adhesion > 0); without it use "
                "hertz/material"
            )
            return [("--model", why)]
        return []
    if not adhesion.zero_range:
        return [
            (
                "effects.adhesion.model",
                f"LAMMPS's granular adhesion has zero range (jkr, dmt, mdr): {adhesion.name!r} has no equivalent there",
            )
        ]
    if adhesion.hysteretic and model.traits.needs_adhesion:
        return [
            (
                "effects.adhesion.approach_work_of_adhesion",
                f"{adhesion.approach:g} J/m² is below work_of_adhesion ({adhesion.work_of_adhesion:g} J/m²): LAMMPS's "
                f"{model.keyword} attaches at the touch with the whole work of adhesion (no approach hysteresis); "
                "leave it out",
            )
        ]
    return []


def _damping_option(text: str, model: NormalModel) -> tuple[Damping | None, list[tuple[str, str]]]:
    """--damping MODEL:VALUE, checked against the damping models LAMMPS allows with `model`."""
    allowed = model.traits.dampings
    keyword, _, value = text.partition(":")
    kind = DampingModel.named(keyword)
    try:
        coefficient = float(value)
    except ValueError:
        coefficient = math.nan
    restitution = kind is not None and kind.restitution
    valid = 0 < coefficient <= 1 if restitution else 0 <= coefficient < math.inf
    if kind is None or kind not in allowed or not valid:
        restitutions = [name.keyword for name in allowed if name.restitution]
        bound = (
            f"VALUE >= 0 (0 < VALUE <= 1, a restitution, for {' and '.join(restitutions)})"
            if restitutions
            else "VALUE >= 0"
        )
        names = ", ".join(name.keyword for name in allowed)
        why = f"must be MODEL:VALUE with MODEL one of {names} for {model.keyword} and {bound}, got {text!r}"
        return None, [("--damping", why)]
    return Damping(model=kind, coefficient=coefficient, origin="--damping"), []


def _materials(scene: Scene, model: NormalModel) -> tuple[tuple[Material, Material], str]:
    """The materials of body and counterpart, and how they give the scene's E*."""
    given = scene.material
    E_star = given.effective_modulus
    if scene.counterpart is not None and not model.traits.one_material and given.E_body is not None:
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


def _surface_energy(scene: Scene, model: NormalModel) -> tuple[float, str]:
    """LAMMPS's γ (J/m²) and how it follows from Δγ."""
    adhesion = scene.active_adhesion
    if adhesion is None:
        return 0.0, "adhesion: none"
    work = adhesion.work_of_adhesion
    traits = model.traits
    if traits.adhesion is None:
        return 0.0, f"adhesion: none ({model.keyword} has none; the scene's Δγ = {work:g} J/m² is left out)"
    gamma = work / 2
    radius = effective_radius(scene)
    meaning = traits.adhesion.format(pull_off=traits.pull_off_factor * math.pi * gamma * radius)
    return gamma, f"adhesion: γ = Δγ/2 = {gamma:g} J/m² (Δγ the Dupré work of adhesion): {meaning}"


def _scene_damping(scene: Scene, model: NormalModel) -> tuple[Damping, str]:
    """The scene's damping as LAMMPS's: linear c → velocity η₀ = c; viscoelastic A → viscoelastic
    η₀ = 2E*A/m_eff (F = 2E*aA·v_n, Brilliantov et al.); none → η₀ = 0."""
    damping = scene.effects.damping
    if damping is None:
        own = model.traits.dampings[0]
        return Damping(model=own, coefficient=0.0, origin="scene"), f"damping: none ({own.keyword} with η₀ = 0)"
    if not damping.viscoelastic:
        c = damping.linear_coefficient
        return Damping(model=DampingModel.velocity, coefficient=c, origin="scene"), (
            f"damping: velocity η₀ = c = {c:g} N·s/m, the scene's linear damping"
        )
    eta = 2.0 * scene.material.effective_modulus * damping.viscoelastic_constant / scene.reduced_mass
    return Damping(model=DampingModel.viscoelastic, coefficient=eta, origin="scene"), (
        f"damping: viscoelastic η₀ = 2E*A/m_eff = {eta:.6g} 1/(m·s): LAMMPS's η₀·a·m_eff·v_n is the scene's "
        f"2E*·a·A·ḋ (A = {damping.viscoelastic_constant:g} s)"
    )


def _yield_stress(scene: Scene, model: NormalModel, material: Material) -> tuple[float, str]:
    """mdr's Y: where the scene yields (Thornton's peak pressure p_y = 2E*a/(πR), i.e. a mean pressure
    (2/3)p_y), mdr yields at the same contact radius; without plasticity Y = E, above any Hertz mean
    pressure 4E_eff/(3π) of mdr's overlaps (δ < R), so it never yields."""
    if not model.traits.plastic:
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


def left_out(scene: Scene, model: NormalModel, damping: Damping) -> str:
    """What LAMMPS's `model` (with `damping`) leaves out of the scene, in words."""
    traits = model.traits
    words = traits.left_out
    if traits.paraboloid and scene.body.profile.shape == "sphere":
        words += " Its laws are those of the paraboloid f = r²/(2R), the scene's sphere within O(a²/R²)."
    if damping.coefficient > 0 and not traits.needs_adhesion:
        words += (
            " Damped, it keeps the contact until the overlap ends, pulling the body back once the viscous force "
            "exceeds the elastic one; impact lets the body go where the total force returns to zero (Schwager & "
            "Pöschel, Granular Matter 9, 465 (2007))."
        )
    if damping.origin == "--damping":
        words += " Its damping is the one given by --damping, not the scene's."
    return words + " Velocity Verlet at a fixed step dt; contact times counted in whole steps."
