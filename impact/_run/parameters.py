"""A scene's numbers as the integrators take them: its integrator, its static options and its
traced SI parameters."""

from typing import Any

import jax
import jax.numpy as jnp
import numpy as np

from .._effects.adhesion import Adhesion
from .._effects.damping import Damping
from .._effects.gravity import Gravity
from .._effects.plasticity import Plasticity
from .._integrate.adhesive_plastic import AdhesivePlastic
from .._integrate.base import AbstractIntegrator
from .._integrate.continuum import Continuum
from .._integrate.double_hertz import GreenwoodJohnson
from .._integrate.dugdale import MaugisDugdale, MaugisDugdaleSprings
from .._integrate.plastic import Plastic
from .._integrate.problem import Options, Physics
from .._integrate.quadrature import Quadrature
from .._integrate.springs import SpringArray
from .._integrate.verlet import Verlet
from .._law.branches import Tabulation
from .._scene.profiles import PowerLawSpec
from .._scene.scene import Scene
from .._scene.sections import QUADRATURE
from ..profiles import Profile

_SAMPLES_PER_PHASE = 64


def integrator_for(scene: Scene) -> AbstractIntegrator:
    """The integrator a scene names: the continuum law with a diffrax solver, a spring array
    (exact, or stepped with Verlet), a finite-range law (Maugis–Dugdale, Greenwood–Johnson), or
    Thornton's plastic law (with adhesion, Thornton & Ning's)."""
    solver = scene.solver
    # The settings every adaptive (diffrax) integrator takes.
    adaptive: dict[str, Any] = {
        "method": solver.method,
        "rtol": solver.rtol,
        "atol": solver.atol,
        "max_steps": solver.max_steps,
    }
    adhesion = scene.active_adhesion
    if scene.effects.plasticity is not None and adhesion is not None:
        return AdhesivePlastic(**adaptive)
    if scene.effects.plasticity is not None:
        return Plastic(**adaptive)
    if adhesion is not None and adhesion.model == "maugis_dugdale" and scene.contact.springs != "continuum":
        return MaugisDugdaleSprings(**adaptive, capacity=spring_capacity(scene.contact.springs))
    if adhesion is not None and adhesion.model == "maugis_dugdale":
        return MaugisDugdale(**adaptive, hysteresis=adhesion.hysteretic)
    if adhesion is not None and adhesion.model == "greenwood_johnson":
        return GreenwoodJohnson(**adaptive)
    if scene.contact.springs == "continuum" and solver.method == QUADRATURE:
        return Quadrature()
    if scene.contact.springs == "continuum":
        return Continuum(**adaptive, phase_ends=scene.phase_ends)
    if solver.method == "verlet":
        assert solver.dt is not None, "validated: method 'verlet' takes dt"
        return Verlet(dt=solver.dt)
    return SpringArray()


def options_for(scene: Scene, trajectory: bool = True) -> Options:
    """The static choices of a scene besides its integrator (changing them recompiles)."""
    adhesion = scene.active_adhesion
    jkr = adhesion is not None and adhesion.model == "jkr"  # the edge tables below are the JKR law's
    partial_approach = adhesion is not None and jkr and adhesion.approach > 0.0 and adhesion.hysteretic
    profile = scene.contact_profile.build()
    return Options(
        adhesive=adhesion is not None,
        gravity=scene.effects.gravity is not None,
        max_bounces=scene.limits.max_bounces,
        # Only a partial approach work of adhesion puts the attach edge's turn decades below the
        # branch grid (Δγa = Δγ turns at the jump-in scale, Δγa = 0 does not turn).
        tabulation=Tabulation.for_profile(profile, tip_search=partial_approach),
        timed_loading=_loads_in_time(scene, profile),
        samples_per_phase=_SAMPLES_PER_PHASE if trajectory else 0,
        damped=scene.effects.damping is not None,
        curve_pieces=_spring_curve_pieces(scene),
    )


def spring_capacity(count: int) -> int:
    """Slots of the compiled spring array: the next power of two (at least 64), so that arrays
    of similar size share one compilation (the count itself is traced)."""
    return max(64, 1 << (int(count) - 1).bit_length())


def _spring_curve_pieces(scene: Scene) -> int:
    """Pieces of the spring curve a Maugis–Dugdale spring array rides (0 for any other law)."""
    adhesion, springs = scene.active_adhesion, scene.contact.springs
    if adhesion is None or adhesion.model != "maugis_dugdale" or springs == "continuum":
        return 0
    return spring_capacity(springs) + 1


def _loads_in_time(scene: Scene, profile: Profile) -> bool:
    """Whether a loading phase may have to be integrated in time (`Options.timed_loading`):
    where it starts from a = 0 on a tip its radius cannot ride (`profile`: the scene's contact
    profile, built). Without adhesion or without an approach work (Δγa = 0) loading starts from
    the tip on ĝ itself; a body ĝ = Â·aⁿ with n ≥ 1 rises from there with a finite slope, so the
    radius rides and no radius table is built per point: the attach-on-touch paraboloid runs in
    0.13× the time, with the same steps and error.
    Other JKR bodies: see `_rises_from_the_tip`; the other laws never load in time."""
    adhesion = scene.active_adhesion
    if adhesion is not None and adhesion.model != "jkr":
        return False
    if adhesion is None or adhesion.approach == 0.0:
        form = profile.power_form()
        return form is None or float(form[1]) < 1.0
    return _rises_from_the_tip(scene)


def _rises_from_the_tip(scene: Scene) -> bool:
    """Whether loading of an adhesive power-law body may start from a = 0 and so needs the timed
    path (its radius table is built per point and its radius solved in every step: the slow
    path). For n ≤ 1/2 the attach edge h = g − λa·√x rises from the tip (no jump-in); above,
    the jump-in radius, ∝ λa^(1/(n − 1/2)) in units of the impact energy, may lie below the
    smallest float for n < 1 or a small approach work Δγa < Δγ (measured: Δγa/Δγ = 1e-100 at
    n = 1 is lost without the timed path). With n ≥ 1 and Δγa = Δγ (the closed form (3.81–82))
    the jump-in is found as for the paraboloid, and no step solves for a radius."""
    profile, adhesion = scene.contact_profile, scene.active_adhesion
    assert adhesion is not None
    return isinstance(profile, PowerLawSpec) and (profile.n < 1.0 or adhesion.hysteretic)


def physics_for(scene: Scene) -> Physics:
    """The traced SI parameters of a scene."""
    springs = scene.contact.springs
    gravity, plasticity = scene.effects.gravity, scene.effects.plasticity
    duration = scene.limits.duration
    return Physics(
        profile=scene.contact_profile.build(),
        E_star=_float64(scene.material.effective_modulus),
        mass=_float64(scene.reduced_mass),
        velocity=_float64(scene.approach_velocity),
        gap=_float64(scene.start.gap),
        adhesion=adhesion_for(scene),
        gravity=Gravity(_float64(gravity.g)) if gravity else Gravity.none(),
        plasticity=Plasticity(_float64(plasticity.yield_pressure)) if plasticity else Plasticity.none(),
        damping=damping_for(scene),
        time_limit=_float64(np.inf if duration is None else duration),
        spring_length=_float64(np.nan if scene.contact.length is None else scene.contact.length),
        spring_count=_float64(np.nan if springs == "continuum" else springs),
    )


def adhesion_for(scene: Scene) -> Adhesion:
    """The adhesion parameters of a scene (those of no adhesion where it names none)."""
    adhesion = scene.active_adhesion
    return Adhesion.none() if adhesion is None else adhesion_of(adhesion)


def adhesion_of(adhesion) -> Adhesion:
    """The parameters of an adhesion section (its values may be traced)."""
    dugdale = adhesion.model == "maugis_dugdale"
    return Adhesion(
        work_of_adhesion=_float64(adhesion.work_of_adhesion),
        approach_work_of_adhesion=_float64(adhesion.approach),
        adhesive_stress=_float64(adhesion.adhesive_stress if dugdale else np.nan),
        double_hertz_factor=_float64(np.nan if adhesion.k is None else adhesion.k),
    )


def damping_for(scene: Scene) -> Damping:
    """The damping parameters of a scene (zero where it names none)."""
    damping = scene.effects.damping
    if damping is None:
        return Damping.none()
    return Damping(_float64(damping.viscoelastic_constant), _float64(damping.linear_coefficient))


def _float64(value) -> jax.Array:
    return jnp.asarray(value, jnp.float64)
