"""The named losses of an impact's first contact: how the kinetic energy it lost, ∮F dd
(`dissipated_energy`), splits into plastic work, viscous work, the adhesion hysteresis and the
elastic energy a damped contact leaves in the surface. They sum to `dissipated_energy`.

On SI values, floats or traced arrays: a sweep computes them inside its compiled batch with
the arithmetic `simulate` uses for one impact (a loss that cannot occur is the float 0, so that
`simulate` runs no JAX operation for it)."""

from collections.abc import Callable

from .. import theory
from .._integrate.adhesive_plastic import AdhesivePlastic
from .._integrate.base import AbstractIntegrator
from .._integrate.plastic import Plastic
from .._integrate.problem import Physics
from .._law.thornton import ThorntonNing
from .._scene.scene import Scene

# Each named loss, and whether a scene names the effect it belongs to (where it does not, the
# loss is 0 and the outputs leave it out).
NAMED_LOSSES: dict[str, Callable[[Scene], bool]] = {
    "plastic_work": lambda scene: scene.effects.plasticity is not None,
    "viscous_work": lambda scene: _viscous(scene),
    "adhesion_hysteresis": lambda scene: scene.effects.adhesion is not None,
    "unrecovered_elastic_energy": lambda scene: _viscous(scene),
}


def _viscous(scene: Scene) -> bool:
    """Whether the scene dissipates viscously: damping, or a viscoelastic medium."""
    return scene.effects.damping is not None or scene.effects.viscoelasticity is not None


def plastic_work(integrator: AbstractIntegrator, physics: Physics, max_indentation, dissipated):
    """J dissipated by plastic flow in the first contact that reached `max_indentation` (m) and
    lost `dissipated` (J): all of it without adhesion (Thornton 1997); with adhesion, Thornton &
    Ning's flow up to the deepest indentation (in closed form, `theory.adhesive_plastic_losses`:
    no later contact reaches that deep); 0 without plasticity."""
    if isinstance(integrator, AdhesivePlastic):
        law = physics.law
        assert isinstance(law, ThorntonNing), "the adhesive plastic integrator rides Thornton & Ning's law"
        return theory.adhesive_plastic_losses(
            max_indentation, physics.profile.radius_scale(), physics.E_star, law.work_of_adhesion, law.yield_pressure
        )[1]
    if isinstance(integrator, Plastic):
        return dissipated
    return 0.0


def adhesion_hysteresis(adhesive: bool, dissipated, plastic, viscous, stored=0.0):
    """J of the first contact's loss dissipated neither by plastic flow nor viscously, nor left
    in a viscoelastic medium (`stored`, J): the jump-in and the snap-off of the adhesive contact
    (0 where adhesion is not simulated)."""
    if not adhesive:
        return 0.0
    return dissipated - plastic - viscous - stored


def unrecovered_elastic_energy(adhesive: bool, damped: bool, dissipated, viscous, stored=0.0):
    """J of elastic energy the surface still holds when the contact lets go. A damped contact
    without adhesion ends where the total force returns to zero, at a finite indentation (the
    body leaves faster than the surface recovers: Schwager & Pöschel, Phys. Rev. E 78, 051304
    (2008)), so ∫F dd of the elastic force over the contact is not zero; the body's kinetic
    energy lost includes it (with adhesion the snap-off releases it: `adhesion_hysteresis`). A
    viscoelastic medium states it, `stored` (J), with or without adhesion. 0 otherwise."""
    if damped and not adhesive:
        return dissipated - viscous
    return stored
