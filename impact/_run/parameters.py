"""A scene's numbers as the integrators take them: its integrator, its static options and its
traced SI parameters."""

from typing import Any

import jax.numpy as jnp
import numpy as np

from .._core.concrete import on_device
from .._effects.damping import Damping
from .._effects.friction import Friction
from .._effects.gravity import Gravity
from .._integrate.base import AbstractIntegrator
from .._integrate.problem import Options, Physics
from .._law.branches import Tabulation
from .._scene.adhesion.base import loads_from_the_tip
from .._scene.scene import Scene
from ..profiles import Profile

_SAMPLES_PER_PHASE = 64


def integrator_for(scene: Scene) -> AbstractIntegrator:
    """The integrator a scene's law and solver settings name (`Scene.integrator`)."""
    return scene.integrator()


def options_for(scene: Scene, trajectory: bool = True) -> Options:
    """The static choices of a scene besides its integrator (changing them recompiles)."""
    adhesion = scene.active_adhesion
    profile = scene.contact_profile.build()
    return Options(
        adhesive=adhesion is not None,
        gravity=scene.effects.gravity is not None,
        max_bounces=scene.limits.max_bounces,
        tabulation=Tabulation.for_profile(profile, tip_search=adhesion is not None and adhesion.tip_search()),
        timed_loading=_loads_in_time(scene, profile),
        samples_per_phase=_SAMPLES_PER_PHASE if trajectory else 0,
        damped=scene.effects.damping is not None,
        curve_pieces=0 if adhesion is None else adhesion.curve_pieces(scene.contact.springs),
    )


def _loads_in_time(scene: Scene, profile: Profile) -> bool:
    """Whether a loading phase may have to be integrated in time (`Options.timed_loading`):
    where it starts from a = 0 on a tip its radius cannot ride (`profile`: the scene's contact
    profile, built); the adhesion model decides (`loads_in_time`), or without adhesion the
    profile (`loads_from_the_tip`)."""
    adhesion = scene.active_adhesion
    return loads_from_the_tip(profile) if adhesion is None else adhesion.loads_in_time(scene, profile)


def physics_for(scene: Scene, xp: Any = jnp, profile: Profile | None = None) -> Physics:
    """The traced SI parameters of a scene: its fields may hold arrays of a sweep's points (with
    `xp` numpy) or traced values (`xp` jax.numpy); `profile`: the body's, built (default: the
    scene's contact profile)."""
    springs = scene.contact.springs
    gravity, duration = scene.effects.gravity, scene.limits.duration
    damping, friction = scene.effects.damping, scene.effects.friction

    def value(number):
        return xp.asarray(number, dtype=xp.float64)

    return Physics(
        profile=scene.contact_profile.build() if profile is None else profile,
        E_star=value(scene.material.effective_modulus),
        mass=value(scene.reduced_mass),
        velocity=value(scene.approach_velocity),
        gap=value(scene.start.gap),
        law=scene.contact_law(xp),
        gravity=Gravity(value(0.0 if gravity is None else gravity.g)),
        damping=Damping(
            value(0.0 if damping is None else damping.viscoelastic_constant),
            value(0.0 if damping is None else damping.linear_coefficient),
        ),
        friction=Friction.none() if friction is None else friction.physics(scene, xp),
        time_limit=value(np.inf if duration is None else duration),
        spring_length=value(np.nan if scene.contact.length is None else scene.contact.length),
        spring_count=value(np.nan if isinstance(springs, str) else springs),
    )


def concrete_physics(scene: Scene) -> Physics:
    """`physics_for` a scene of concrete values as JAX arrays, computed in NumPy and copied
    (`on_device`): jax.numpy on concrete values compiles a program per operation."""
    return on_device(physics_for(scene, np))
