"""The closed forms a sweep compares with, where the theory gives them: the restitution of each
point (traced, inside the compiled batch), the sticking velocity of each point (numpy, to order
the points by cost) and the name of the closed form (Popov, Heß & Willert, Handbook of Contact
Mechanics (Springer 2019), ch. 3, eqs. (3.50–51), (3.81–82))."""

from typing import TYPE_CHECKING

import jax.numpy as jnp
import numpy as np

from ... import profiles, theory
from ..._integrate.adhesive_plastic import AdhesivePlastic
from ..._integrate.curve import AbstractCurveIntegrator, CurveIntegrator
from ..._integrate.plastic import Plastic
from ..._integrate.problem import Physics, touch_velocity
from ..._integrate.viscoelastic import ViscoelasticSprings
from ..._law.base import AbstractAdhesiveLaw, AbstractPlasticLaw
from ..._law.thornton import ThorntonNing
from ..._scene.scene import Scene

if TYPE_CHECKING:
    from .plan import StaticChoices


def closed_form_restitution(physics: Physics, choices: "StaticChoices"):
    """The chapter's restitution for one point (traced): Thornton–Ning for the paraboloid with
    Δγa = Δγ, (3.82) for power laws (n > 1/2) and cones (n = 1, c = tan θ) with Δγa = Δγ,
    attach on touch for the paraboloid with Δγa = 0, all without gravity; 1 without adhesion;
    NaN elsewhere (and for a viscoelastic half-space, which has none). Maugis–Dugdale and
    Greenwood–Johnson points get their JKR limit (Λ → ∞, k → ∞): no closed form has a finite
    range (nor Maugis–Dugdale's approach hysteresis).
    Thornton's (1997) closed form for plastic paraboloids without gravity, and Thornton & Ning's
    (1998) with adhesion (`theory.adhesive_plastic_restitution`)."""
    options, law = choices.options, physics.law
    if isinstance(choices.integrator, ViscoelasticSprings):
        return jnp.full((), jnp.nan)
    if isinstance(choices.integrator, AdhesivePlastic):
        profile, v = physics.profile, touch_velocity(physics, options)
        assert isinstance(profile, profiles.Paraboloid), "validated: plasticity takes paraboloids only"
        assert isinstance(law, ThorntonNing)
        adhesive = theory.adhesive_plastic_restitution(
            v, physics.mass, profile.R, physics.E_star, law.work_of_adhesion, law.yield_pressure
        )
        return jnp.where(options.gravity, jnp.nan, adhesive)
    if isinstance(choices.integrator, Plastic):
        profile, v = physics.profile, touch_velocity(physics, options)
        assert isinstance(profile, profiles.Paraboloid), "validated: plasticity takes paraboloids only"
        assert isinstance(law, AbstractPlasticLaw)
        yield_velocity = theory.thornton_yield_velocity(physics.mass, profile.R, physics.E_star, law.yield_pressure)
        return jnp.where(options.gravity, jnp.nan, theory.thornton_restitution(v, yield_velocity))
    nan = jnp.full((), jnp.nan)
    if options.damped:
        return nan if options.adhesive or options.gravity else _damped_restitution(physics, options)
    if not options.adhesive:
        return jnp.ones(())
    if options.gravity:
        return nan
    profile = physics.profile
    v, m, modulus = touch_velocity(physics, options), physics.mass, physics.E_star
    assert isinstance(law, AbstractAdhesiveLaw), "simulated adhesion has a work of adhesion"
    work = law.work_of_adhesion
    # A curve law without approach hysteresis is reversible: its JKR limit is the closed form.
    approach = getattr(law, "approach_work_of_adhesion", work)
    hysteretic = isinstance(choices.integrator, CurveIntegrator) and choices.integrator.hysteresis
    reversible = (approach == work) | (isinstance(choices.integrator, AbstractCurveIntegrator) and not hysteretic)
    if type(profile) is profiles.Paraboloid:
        jkr = theory.thornton_ning_restitution(v, m, profile.R, modulus, work)
        on_touch = theory.attach_on_touch_restitution(v, m, profile.R, modulus, work)
        return jnp.where(reversible, jkr, jnp.where(approach == 0, on_touch, nan))
    if type(profile) is profiles.PowerLaw:
        exponent = jnp.asarray(profile.n)
        n = jnp.where(exponent > 0.5, exponent, 2.0)
        power = theory.power_law_restitution(v, m, n, profile.c, modulus, work)
        return jnp.where(reversible & (exponent > 0.5), power, nan)
    if type(profile) is profiles.Cone:
        power = theory.power_law_restitution(v, m, 1.0, jnp.tan(profile.theta), modulus, work)
        return jnp.where(reversible, power, nan)
    return nan


def _damped_restitution(physics: Physics, options):
    """Damped, without adhesion and gravity: the exact linear spring–dashpot of a flat punch
    (k = 2E*a, c = 2E*a·A + c_linear), and Schwager–Pöschel's first order in βv₀^(1/5) for the
    viscoelastic paraboloid (its asymptote for small A, not a closed form); NaN elsewhere."""
    profile, damping, v = physics.profile, physics.damping, touch_velocity(physics, options)
    if type(profile) is profiles.FlatPunch:
        stiffness = 2.0 * physics.E_star * profile.radius
        coefficient = stiffness * damping.dissipative_constant + damping.coefficient
        return theory.dashpot_restitution(coefficient / (2.0 * jnp.sqrt(stiffness * physics.mass)))
    if type(profile) is profiles.Paraboloid:
        beta = theory.viscoelastic_beta(damping.dissipative_constant, physics.mass, profile.R, physics.E_star)
        first_order = theory.viscoelastic_restitution_first_order(v, beta)
        return jnp.where(damping.coefficient == 0.0, first_order, jnp.nan)
    return jnp.full((), jnp.nan)


def _damped_name(scene: Scene) -> str:
    damping = scene.effects.damping
    assert damping is not None
    if scene.active_adhesion is not None or scene.effects.gravity is not None:
        return "no closed form (damping with adhesion or gravity)"
    shape = scene.contact_profile.shape
    if shape == "flat_punch":
        return "linear spring–dashpot (theory.dashpot_restitution)"
    if shape == "paraboloid" and damping.viscoelastic:
        return "Schwager–Pöschel first order 1 − 1.1534βv₀^(1/5) (small A)"
    return "no closed form (damping)"


def closed_form_name(scene: Scene) -> str:
    """Which closed form `theory_restitution` holds for a scene (as the figure names it)."""
    adhesion = scene.effects.adhesion
    if scene.effects.viscoelasticity is not None:
        return "no closed form (viscoelastic half-space)"
    if scene.effects.damping is not None:
        return _damped_name(scene)
    if scene.effects.plasticity is not None:
        if scene.effects.gravity is not None:
            return "no closed form (gravity)"
        return "Thornton & Ning 1998 (adhesive plastic)" if scene.adhesive else "Thornton 1997 (plastic)"
    if adhesion is None or not adhesion.work_of_adhesion > 0:
        return "no adhesion: e = 1"
    if scene.effects.gravity is not None:
        return "no closed form (gravity)"
    return adhesion.closed_form_name(scene)


def sticking_velocity(scene: Scene, physics: Physics) -> np.ndarray:
    """Closed-form sticking velocity (m/s) of each point of a batched Physics, numpy; NaN where
    the chapter gives none (the same formulas as `theory.*_sticking_velocity`)."""
    profile, mass, modulus, law = physics.profile, physics.mass, physics.E_star, physics.law
    work = law.work_of_adhesion if isinstance(law, AbstractAdhesiveLaw) else np.zeros_like(mass)
    nan = np.full(np.shape(mass), np.nan)
    with np.errstate(all="ignore"):
        if isinstance(profile, profiles.Paraboloid):
            loss = np.cbrt(profile.R**4 * (np.pi * work) ** 5 / modulus**2) * (1 + np.cbrt(864.0)) / 10
            return np.where(work > 0, np.sqrt(2 * loss / mass), nan)
        if isinstance(profile, (profiles.PowerLaw, profiles.Cone)):
            if isinstance(profile, profiles.Cone):
                n, c = np.ones_like(mass), np.tan(profile.theta)
            else:
                n, c = np.asarray(profile.n), np.asarray(profile.c)
            kappa = np.asarray(profiles.kappa(n))
            p = 1 / (2 * n - 1)
            stiffness = modulus * (n * c * kappa) ** 2
            scale = ((np.pi * work / 2) ** (2 * n + 1) / stiffness**2) ** p
            shape = (8 * n - 4) / (2 * n**2 + 3 * n + 1) * (n + (n + 1) * (2 * n) ** (4 * p))
            return np.where((work > 0) & (n > 0.5), np.sqrt(scale * shape / mass), nan)
    return nan
