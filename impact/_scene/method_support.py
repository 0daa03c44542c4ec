"""Which scenes the integrators that skip the ODE solve can run: phases ended by their energy
balance (`solver.phase_ends: energy`) and phases timed by quadrature (`solver.method:
quadrature`). Each refusal says why, in words a scene file's author can act on."""

from typing import TYPE_CHECKING

from .._law.base import AbstractCurveLaw
from .profiles import PowerLawSpec
from .sections import QUADRATURE_SHAPES

# Springs a spring array computed from prefix sums holds: each contact costs O(N) vector work and
# memory per point (a sweep's chunk holds them all at once).
SPRING_QUADRATURE_MAX_SPRINGS = 16384

if TYPE_CHECKING:
    from .scene import Scene


def energy_ends_refusal(scene: "Scene") -> str | None:
    """Why the scene's phases cannot end from their energy balance, or None where they can."""
    adhesion = scene.active_adhesion
    if scene.contact.springs != "continuum":
        return "for the continuum law only (contact.springs: continuum): a spring array's events advance exactly"
    if adhesion is not None and not adhesion.zero_range:
        return f"not with adhesion model {adhesion.name!r}: its phases end where the solver locates them"
    if scene.effects.plasticity is not None:
        return "not with effects.plasticity: its phases end where the solver locates them"
    if scene.effects.damping is not None:
        return "not with effects.damping: a damped phase does not keep its energy"
    return None


def quadrature_refusal(scene: "Scene") -> str | None:
    """Why the scene's contact phases cannot be timed by quadrature, or None where they can: a
    curve law's rides along its continuum curve, the phases of Thornton's plastic laws; else the
    phases must end from their energy balance, the work along a branch must have its closed form
    (ĝ = Â·xⁿ) and loading must start from a jump-in or a tip of finite slope."""
    if scene.kind != "impact":
        return "times the contact phases of an impact (kind: impact)"
    if scene.contact.springs != "continuum":
        return spring_quadrature_refusal(scene)
    curve = isinstance(scene.contact_law(), AbstractCurveLaw)
    plastic = scene.effects.plasticity is not None
    why = None if curve or plastic else energy_ends_refusal(scene)
    if why is not None:
        return why
    if scene.solver.phase_ends == "integrated":
        return "ends every phase from its energy balance: leave solver.phase_ends out (or set it to 'energy')"
    if scene.limits.duration is not None:
        return "does not stop a phase midway: leave limits.duration out"
    if curve or plastic:
        return None
    profile = scene.contact_profile
    if profile.shape not in QUADRATURE_SHAPES:
        return f"needs a profile of the form g = A·xⁿ ({', '.join(QUADRATURE_SHAPES)}), not {profile.shape!r}"
    adhesion = scene.active_adhesion
    partial = adhesion is not None and 0.0 < adhesion.approach < adhesion.work_of_adhesion
    if isinstance(profile, PowerLawSpec) and (profile.n < 1.0 or partial):
        return (
            f"needs a power law with n >= 1 (not {profile.n:g}) and, with adhesion, approach_work_of_adhesion "
            "equal to work_of_adhesion or 0: otherwise loading may start from a tip of infinite slope"
        )
    return None


def spring_quadrature_refusal(scene: "Scene") -> str | None:
    """Why the scene's spring array (contact.springs: N) cannot be computed contact by contact
    from prefix sums (`_integrate.spring_quadrature`), or None where it can: the array of the
    zero-range law (JKR, with or without approach hysteresis, or no adhesion), elastic and
    undamped, up to `SPRING_QUADRATURE_MAX_SPRINGS` springs, every contact run to its end."""
    adhesion = scene.active_adhesion
    if adhesion is not None and not adhesion.zero_range:
        return (
            f"computes the spring array of the zero-range (JKR) law only, not of adhesion model {adhesion.name!r}: "
            "leave solver.method out (its springs ride their curve), or use contact.springs: continuum"
        )
    effects = scene.effects
    for name, effect in (
        ("plasticity", effects.plasticity),
        ("damping", effects.damping),
        ("friction", effects.friction),
        ("viscoelasticity", effects.viscoelasticity),
    ):
        if effect is not None:
            return f"computes the elastic spring array only, not with effects.{name}"
    if scene.solver.phase_ends is not None:
        return "ends every contact from its energy balance: leave solver.phase_ends out"
    if scene.limits.duration is not None:
        return "does not stop a contact midway: leave limits.duration out"
    springs = scene.contact.springs
    if isinstance(springs, int) and springs > SPRING_QUADRATURE_MAX_SPRINGS:
        return (
            f"holds at most {SPRING_QUADRATURE_MAX_SPRINGS} springs (its work and memory grow with N at every "
            f"point), not {springs}: leave solver.method out (the exact event loop takes any N)"
        )
    return None
