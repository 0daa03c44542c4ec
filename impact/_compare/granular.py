"""LAMMPS's granular contact models that a scene is mapped onto (pair_style granular, fix
wall/gran granular; release 2025.7.22): the normal models (`NormalModel`) and the damping models
(`DampingModel`), each with its keyword in LAMMPS's input and what the mapping needs of it.

A user names them by their keywords (`impact compare lammps --model jkr --damping tsuji:0.9`);
`NormalModel.named` and `DampingModel.named` turn the words into members, and from there on
every choice reads the member's data.
"""

import enum
from dataclasses import dataclass

from .._scene.errors import SceneError


class CompareError(SceneError):
    """A scene or option LAMMPS cannot represent; `problems` lists (field or option, reason) pairs."""


class DampingModel(enum.Enum):
    """LAMMPS's damping models of the normal force, F = −η v_n; the member's name is its keyword."""

    velocity = enum.auto()  # η = η₀
    mass_velocity = enum.auto()  # η = η₀ m_eff
    viscoelastic = enum.auto()  # η = η₀ a m_eff
    tsuji = enum.auto()  # from a coefficient of restitution
    coeff_restitution = enum.auto()  # from a coefficient of restitution
    mdr = enum.auto()  # mdr's own

    @classmethod
    def named(cls, keyword: str) -> "DampingModel | None":
        """The damping model of LAMMPS's `keyword`, None for another word."""
        return cls.__members__.get(keyword)

    @property
    def keyword(self) -> str:
        """Its keyword in LAMMPS's input."""
        return self.name

    @property
    def restitution(self) -> bool:
        """Whether its value is a coefficient of restitution (0 < e ≤ 1), not η₀ ≥ 0."""
        return self in (DampingModel.tsuji, DampingModel.coeff_restitution)

    @property
    def words(self) -> str:
        """What follows `damping` in LAMMPS's input: the keyword (mdr's with its flag, 1)."""
        return f"{self.keyword} 1" if self is DampingModel.mdr else self.keyword


_VISCOUS = (DampingModel.velocity, DampingModel.mass_velocity, DampingModel.viscoelastic)


@dataclass(frozen=True)
class NormalTraits:
    """What the mapping needs of one normal model."""

    # The words after its keyword: a format of E, nu, damping, gamma (γ) and yield_stress (Y).
    coefficients: str
    # The damping models it takes; the first is the scene's (none, or linear damping: η₀ = c).
    dampings: tuple[DampingModel, ...]
    # What it leaves out of the scene, in words.
    left_out: str
    # What LAMMPS's γ means for it, a format of its pull-off force `pull_off` (N); None: it takes no γ.
    adhesion: str | None = None
    # Its pull-off force over πγR (0 without one).
    pull_off_factor: float = 0.0
    # Its adhesion is what it models: refused without adhesion, or with approach hysteresis.
    needs_adhesion: bool = False
    # It yields (its own plasticity, with a yield stress Y); else it is elastic.
    plastic: bool = False
    # It runs on a wall (fix wall/gran), not only between two particles.
    on_walls: bool = True
    # It takes one material for both particles.
    one_material: bool = False
    # Its laws are those of the paraboloid f = r²/(2R).
    paraboloid: bool = True
    # Its atom style in LAMMPS's input.
    atom_style: str = "sphere"


def _adhesive_hertz(adhesion: str, pull_off_factor: float, left_out: str) -> NormalTraits:
    """A Hertz model with zero-range adhesion of LAMMPS's γ (jkr, dmt): its coefficients, the
    viscous dampings, and the adhesion it needs."""
    return NormalTraits(
        coefficients="{E} {damping} {nu} {gamma}",
        dampings=_VISCOUS,
        adhesion=adhesion,
        pull_off_factor=pull_off_factor,
        needs_adhesion=True,
        left_out=left_out,
    )


class NormalModel(enum.Enum):
    """LAMMPS's granular normal models; the member's name is its keyword (hertz/material's with
    its slash). Conventions: hertz/material, jkr, dmt: F = (4/3)E_mix√R δ^(3/2) (+ adhesion),
    E_mix = 1/((1 − ν₁²)/E₁ + (1 − ν₂²)/E₂) between two particles, E/(2(1 − ν²)) on a wall; jkr:
    F = 4E_mix a³/(3R) − 2πa²√(4γE_mix/(πa)), pull-off 3πγR; dmt: Hertz − 4πγR while the spheres
    overlap; mdr (Zunker & Kamrin, J. Mech. Phys. Solids 183 (2024) 105492): a pair contact split at
    a rigid flat into two sphere–flat contacts of modulus E/(1 − ν²), each with the rule of Heß
    Δl = √(2πaγ(1 − ν²)/E), yielding where the mean Hertz pressure 4E_eff a/(3πR) reaches
    Y(1.75 e^(−4.4δ/R) + 1)."""

    jkr = _adhesive_hertz(
        adhesion="LAMMPS's pull-off 3πγR = (3/2)πRΔγ = {pull_off:.6g} N, JKR's",
        pull_off_factor=3.0,
        left_out=(
            "LAMMPS's jkr attaches at the touch with the JKR jump-in (no approach hysteresis, Δγa = Δγ) and "
            "releases the contact at the force-controlled pull-off δ_f, where F = −(3/2)πRΔγ: it cuts the JKR "
            "branch there, while a free body follows the branch on to its displacement-controlled end (ξ = 1) "
            "and snaps off at −(5/9) of that force. Undamped it loses "
            "theory.force_release_energy_loss = 0.4939 of the Thornton–Ning energy at every speed, and its "
            "sticking velocity is √0.4939 = 0.7028 of theirs."
        ),
    )
    dmt = _adhesive_hertz(
        adhesion="LAMMPS's pull-off 4πγR = 2πRΔγ = {pull_off:.6g} N, DMT's",
        pull_off_factor=4.0,
        left_out=(
            "LAMMPS's dmt adds a constant attraction 2πRΔγ (the DMT pull-off) while the spheres overlap and none "
            "outside: no range, no jump-in, no snap-off; undamped it returns all the energy (e = 1)."
        ),
    )
    hertz_material = NormalTraits(
        coefficients="{E} {damping} {nu}",
        dampings=(*_VISCOUS, DampingModel.tsuji, DampingModel.coeff_restitution),
        left_out="LAMMPS's hertz/material is Hertz's law without adhesion.",
    )
    mdr = NormalTraits(
        coefficients="{E} {nu} {yield_stress} {gamma} 0.0 {damping}",
        dampings=(DampingModel.mdr,),
        adhesion="each side of the contact plane detaches by the rule of Heß with γ, together with Δγ",
        plastic=True,
        on_walls=False,
        one_material=True,
        paraboloid=False,
        atom_style="sphere 1",
        left_out=(
            "LAMMPS's mdr (Zunker & Kamrin 2024) is a law of its own: an elliptical 1-D indenter in place of the "
            "sphere's MDR profile, its own plasticity (yield where the mean Hertz pressure reaches "
            "Y(1.75e^(−4.4δ/R) + 1), a flattened radius after it), adhesion by tensile springs once unloading "
            "begins (no jump-in at the touch), each side of a pair against a rigid flat at the contact plane."
        ),
    )

    @classmethod
    def named(cls, keyword: str) -> "NormalModel":
        """The model of LAMMPS's `keyword` (the option --model); CompareError for another word."""
        found = {model.keyword: model for model in cls}.get(keyword)
        if found is None:
            known = ", ".join(model.keyword for model in cls)
            raise CompareError([("--model", f"unknown model {keyword!r}; expected one of: {known}")])
        return found

    @classmethod
    def default(cls, adhesive: bool) -> "NormalModel":
        """The model of a scene without --model: jkr with adhesion, hertz/material without."""
        return cls.jkr if adhesive else cls.hertz_material

    @property
    def keyword(self) -> str:
        """Its keyword in LAMMPS's input."""
        return self.name.replace("_", "/")

    @property
    def traits(self) -> NormalTraits:
        """What the mapping needs of it."""
        return self.value

    def words(self, E: float, nu: float, damping: float, gamma: float, yield_stress: float) -> str:
        """Its keyword and coefficients in LAMMPS's input (SI, to 17 digits)."""
        values = {"E": E, "nu": nu, "damping": damping, "gamma": gamma, "yield_stress": yield_stress}
        return f"{self.keyword} " + self.traits.coefficients.format(**{k: f"{v:.17g}" for k, v in values.items()})
