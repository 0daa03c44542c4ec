"""What an integrator is given: the SI parameters of an impact (`Physics`, traced), the static
choices of the run (`Options`), and the scaled problem built from them (`Problem`)."""

import abc
from dataclasses import dataclass, field

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.types import Parameter
from .._effects.damping import Damping
from .._effects.friction import Friction
from .._effects.gravity import Gravity
from .._law.base import AbstractContactLaw, AbstractEdgeLaw
from .._law.branches import Branch, Tabulation, build_branch
from .._law.law import ContactLaw
from .._law.reach import radius_bound
from .._law.scales import Scales, energy_scales
from ..profiles import Profile

# The branch tables reach this many times the bound on the largest contact radius.
_TOP_MARGIN = 4.0
# Radius table per increasing segment, kept where loading is integrated in time.
_TABLE_SIZE = 65


@dataclass(frozen=True)
class Options:
    """Static choices of a run besides its integrator: which effects compile, how the law is
    tabulated, how many bounces and trajectory samples the run holds. Changing any of them
    recompiles; parameter values (in `Physics`) do not."""

    adhesive: bool  # adhesion compiles (named, with Δγ > 0)
    gravity: bool  # gravity compiles
    max_bounces: int = 64
    tabulation: Tabulation = field(default_factory=Tabulation)
    timed_loading: bool = True  # loading may start at a = 0 (no jump-in): compile its time path
    damped: bool = False  # damping compiles: a viscous force and its work (a fourth state)
    samples_per_phase: int = 0  # trajectory samples per phase; 0 keeps no trajectory
    curve_pieces: int = 0  # pieces of a spring curve (Maugis–Dugdale spring array), each a ride

    @property
    def max_phases(self) -> int:
        """Phases a run may hold: four per bounce and every branch jump, plus flights; on a spring
        curve, every piece ridden in and out in two contacts."""
        return 4 * self.max_bounces + 2 * self.tabulation.max_turns + 8 + 4 * self.curve_pieces


class Physics(eqx.Module):
    """SI parameters of one impact (traced: sweeps vary them without recompiling)."""

    profile: Profile
    E_star: Parameter  # Pa
    mass: Parameter  # kg
    velocity: Parameter  # approach speed at the start (m/s)
    gap: Parameter  # initial separation (m)
    law: AbstractContactLaw  # the contact law the scene names, with its parameters
    gravity: Gravity  # unused unless `Options.gravity`
    damping: Damping  # unused unless `Options.damped`
    friction: Friction  # unused unless the integrator is an oblique one
    time_limit: Parameter  # s
    spring_length: Parameter  # radius covered by a spring array (m); nan: the default
    spring_count: Parameter  # N of a spring array (traced: one compilation serves every N); nan: continuum


def touch_velocity(physics: Physics, options: Options) -> Parameter:
    """Speed at first touch (m/s): the fall over the gap adds to v0 under gravity."""
    if not options.gravity:
        return physics.velocity
    return physics.gravity.touch_velocity(physics.velocity, physics.gap)


def scaled_time_limit(physics: Physics, scales: Scales) -> jax.Array:
    """The time limit in units of `scales` (an infinite one kept out of the division, whose
    derivative would be nan)."""
    limit = physics.time_limit
    return jnp.where(jnp.isfinite(limit), limit / scales.time, jnp.inf)


class Motion(eqx.Module):
    """How the body moves besides the contact law (scaled): where and how fast it starts, its
    speed at the first touch, the pull towards the surface and the time limit."""

    start_indentation: Parameter  # where the body starts (−gap, or less where the interaction starts before the touch)
    start_velocity: Parameter
    touch_speed: Parameter  # speed at the first touch (where the interaction starts)
    gravity: Parameter  # acceleration towards the surface
    time_limit: Parameter


def motion_of(physics: Physics, options: Options, scales: Scales, start_indentation, touch_speed) -> Motion:
    """The scene's motion in the units of `scales`, from `start_indentation` (scaled) with the
    scaled speed `touch_speed` at the first touch."""
    return Motion(
        start_indentation=start_indentation,
        start_velocity=physics.velocity / scales.velocity,
        touch_speed=touch_speed,
        gravity=physics.gravity.scaled(scales) if options.gravity else jnp.zeros(()),
        time_limit=scaled_time_limit(physics, scales),
    )


class AbstractProblem(eqx.Module):
    """The scaled impact an integrator runs: its units, the body's motion and what bounds it."""

    motion: eqx.AbstractVar[Motion]
    bounded: eqx.AbstractVar[Parameter]  # loading stores the impact energy at a finite contact radius

    @property
    @abc.abstractmethod
    def scales(self) -> Scales:
        """The SI values of the units."""

    @property
    @abc.abstractmethod
    def overflow(self) -> jax.Array:
        """The law's tables cannot hold the impact: nothing can be trusted."""


class Problem(AbstractProblem):
    """The scaled impact of the continuum (and spring-array) law: the law, its two branches and
    the initial state."""

    law: ContactLaw
    attach: Branch
    detach: Branch
    motion: Motion
    bounded: Parameter  # loading stores the impact energy at a finite contact radius (or a wall)
    damping_per_radius: Parameter  # η_a of the scaled viscous force (η_a·â + η_0)·v̂ (`Damping.scaled`)
    damping_constant: Parameter  # η_0

    @property
    def scales(self) -> Scales:
        return self.law.scales

    def viscous_force(self, radius, velocity):
        """F̂_visc = (η_a·â + η_0)·v̂ while in contact (scaled)."""
        return (self.damping_per_radius * radius + self.damping_constant) * velocity

    @property
    def overflow(self):
        """The edge functions turn more often than the branches hold: nothing can be trusted."""
        return self.attach.overflow | self.detach.overflow


def build_problem(physics: Physics, options: Options) -> Problem:
    """Scale the physics, tabulate the branches and state the initial condition."""
    profile, law = physics.profile, physics.law
    assert isinstance(law, AbstractEdgeLaw), f"the continuum MDR rides an edge law, not {type(law).__name__}"
    speed = touch_velocity(physics, options)
    if options.adhesive:
        scales = law.scales(profile, physics.E_star, physics.mass, speed)
        detach_coefficient, attach_coefficient = law.hess_coefficients(scales, physics.E_star)
    else:
        scales = energy_scales(profile, physics.E_star, physics.mass, speed)
        detach_coefficient = attach_coefficient = jnp.zeros(())
    contact = ContactLaw(profile, scales, detach_coefficient, attach_coefficient, options.adhesive)

    per_radius, constant = physics.damping.scaled(scales) if options.damped else (jnp.zeros(()), jnp.zeros(()))
    touch_speed = speed / scales.velocity
    reach, bounded = radius_bound(contact, attach_coefficient, touch_speed)
    top = jnp.minimum(contact.extent(), _TOP_MARGIN * reach)
    table = _TABLE_SIZE if options.timed_loading else 0

    def branch(coefficient):
        return build_branch(contact, coefficient, top, options.tabulation, table)

    both = jax.vmap(branch)(jnp.stack([attach_coefficient, detach_coefficient]))
    attach = jax.tree.map(lambda leaf: leaf[0], both)
    detach = jax.tree.map(lambda leaf: leaf[1], both)
    return Problem(
        law=contact,
        attach=attach,
        detach=detach,
        motion=motion_of(physics, options, scales, -physics.gap / scales.normal, touch_speed),
        bounded=bounded | jnp.isfinite(contact.extent()),
        damping_per_radius=per_radius,
        damping_constant=constant,
    )
