"""From SI parameters to the scaled problem the integrators solve."""

from dataclasses import dataclass

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np

from .._law.branches import Branch, build_branch
from .._law.law import ContactLaw
from ..profiles import Profile
from .._law.scales import Scales, adhesive_scales, energy_scales

# The branch tables reach this many times the bound on the largest contact radius.
_TOP_MARGIN = 4.0


@dataclass(frozen=True)
class Numerics:
    """Static choices of a run: what physics is switched on and how it is integrated.

    Changing any of these recompiles; parameter values (in `Physics`) do not.
    """

    adhesive: bool
    gravity: bool
    adhesion_model: str = "jkr"  # or "maugis_dugdale" (finite range, dugdale_impact)
    method: str = "dopri8"  # diffrax solver for the continuum law; "verlet": fixed-step springs
    dt: float | None = None  # time step (s) of method "verlet"
    rtol: float = 1e-10
    atol: float = 1e-12
    spring_array: bool = False  # the N springs of `Physics.spring_count` instead of the continuum law
    timed_loading: bool = True  # loading may start at a = 0 (no jump-in): compile its time path
    max_steps: int = 4096  # per phase
    max_bounces: int = 64
    max_turns: int = 4  # turning points of an edge function the branches hold
    turn_grid: int = 384  # points searched for turning points (more for wavy profiles)
    table_size: int = 65  # radius table per segment, kept only for timed loading
    tip_search: bool = True  # look for the attach edge's turn below the branch grid (0 < Δγa < Δγ)
    samples_per_phase: int = 0  # trajectory samples per phase; 0 keeps no trajectory

    @property
    def max_phases(self) -> int:
        """Phases a run may hold: four per bounce and every branch jump, plus flights."""
        return 4 * self.max_bounces + 2 * self.max_turns + 8


class Physics(eqx.Module):
    """SI parameters of one impact (traced: sweeps vary them without recompiling)."""

    profile: Profile
    E_star: jax.Array  # Pa
    mass: jax.Array  # kg
    velocity: jax.Array  # approach speed at the start (m/s)
    gap: jax.Array  # initial separation (m)
    work_of_adhesion: jax.Array  # Δγ (J/m²); unused without adhesion
    approach_work_of_adhesion: jax.Array  # Δγa ≤ Δγ (J/m²)
    adhesive_stress: jax.Array  # σ0 (Pa) of Maugis–Dugdale adhesion (range Δγ/σ0); unused by JKR
    gravity: jax.Array  # m/s²; unused without gravity
    time_limit: jax.Array  # s
    spring_length: jax.Array  # radius covered by a spring array (m); nan: the default
    spring_count: jax.Array  # N of a spring array (traced: one compilation serves every N); nan: continuum


class Problem(eqx.Module):
    """The scaled impact: contact law, its two branches and the initial state."""

    law: ContactLaw
    attach: Branch
    detach: Branch
    gravity: jax.Array  # scaled acceleration towards the surface
    start_indentation: jax.Array  # −gap (scaled)
    start_velocity: jax.Array  # scaled
    touch_speed: jax.Array  # scaled speed at the first touch
    bounded: jax.Array  # loading stores the impact energy at a finite contact radius (or a wall)
    time_limit: jax.Array  # scaled

    @property
    def scales(self) -> Scales:
        return self.law.scales

    @property
    def overflow(self):
        """The edge functions turn more often than the branches hold: nothing can be trusted."""
        return self.attach.overflow | self.detach.overflow


def touch_velocity(physics: Physics, numerics: Numerics):
    """Speed at first touch (m/s): the fall over the gap adds to v0 under gravity."""
    if not numerics.gravity:
        return physics.velocity
    return jnp.sqrt(physics.velocity**2 + 2.0 * physics.gravity * physics.gap)


def build_problem(physics: Physics, numerics: Numerics) -> Problem:
    """Scale the physics, tabulate the branches and state the initial condition."""
    profile = physics.profile
    if numerics.adhesive:
        scales = adhesive_scales(
            profile, physics.E_star, physics.approach_work_of_adhesion, physics.mass, touch_velocity(physics, numerics)
        )
        detach_coefficient = jnp.sqrt(
            2.0 * jnp.pi * scales.radial * physics.work_of_adhesion / physics.E_star
        ) / scales.normal
        attach_coefficient = detach_coefficient * jnp.sqrt(
            physics.approach_work_of_adhesion / physics.work_of_adhesion
        )
    else:
        scales = energy_scales(profile, physics.E_star, physics.mass, touch_velocity(physics, numerics))
        detach_coefficient = attach_coefficient = jnp.zeros(())
    law = ContactLaw(profile, scales, detach_coefficient, attach_coefficient, numerics.adhesive)

    gravity = physics.gravity * scales.time**2 / scales.normal if numerics.gravity else jnp.zeros(())
    start_velocity = physics.velocity / scales.velocity
    start_indentation = -physics.gap / scales.normal
    touch_speed = touch_velocity(physics, numerics) / scales.velocity
    reach, bounded = radius_bound(law, attach_coefficient, touch_speed)
    top = jnp.minimum(law.extent(), _TOP_MARGIN * reach)
    table = numerics.table_size if numerics.timed_loading else 0
    def branch(coefficient):
        return build_branch(law, coefficient, top, numerics.max_turns, numerics.turn_grid, table, numerics.tip_search)

    both = jax.vmap(branch)(jnp.stack([attach_coefficient, detach_coefficient]))
    attach, detach = (jax.tree.map(lambda leaf: leaf[i], both) for i in range(2))
    return Problem(
        law=law,
        attach=attach,
        detach=detach,
        gravity=gravity,
        start_indentation=start_indentation,
        start_velocity=start_velocity,
        touch_speed=touch_speed,
        bounded=bounded | jnp.isfinite(law.extent()),
        time_limit=physics.time_limit / scales.time,
    )


_BOUND_STEPS_PER_OCTAVE = 4
_BOUND_OCTAVES = (-12, 120)  # the grid 2^(k/4) reaches from 2^-12 to 2^120 (scaled)
_BOUND_NODES = 4


def radius_bound(law: ContactLaw, coefficient, speed):
    """A radius beyond the largest contact radius an impact at scaled speed v reaches.

    Loading along the attach edge h stores W(a) = [a·h² − 2G·h − λ²a²/2] + ∫g² da from the
    adhesion scale a = 1 (integrate ∫F dh by parts with F = 2(a·h − G)); the bound is where W
    first exceeds ½v² + 1 with a > 1 (the +1 covers the adhesion scale). W is tabulated on
    a_k = 2^(k/4) (Gauss–Legendre on each step), then bisected inside the step. Capped by the
    body's extent. Returns (radius, found): an edge that never stores enough (n < 1/2, or
    n = 1/2 with a force attractive at every radius) pulls the contact open without limit.
    """
    energy = 0.5 * speed**2 + 1.0
    nodes, weights = (jnp.asarray(v) for v in np.polynomial.legendre.leggauss(_BOUND_NODES))

    def boundary(a):
        h = law.edge(a, coefficient)
        return a * h**2 - 2.0 * law.G(a) * h - coefficient**2 * a**2 / 2.0

    def squared_area(lo, hi):  # ∫_lo^hi g² da
        mid, half = 0.5 * (hi + lo), 0.5 * (hi - lo)
        points = mid[..., None] + half[..., None] * nodes
        return half * jnp.sum(weights * law.g(points) ** 2, axis=-1)

    low, high = _BOUND_OCTAVES
    grid = 2.0 ** (jnp.arange(low * _BOUND_STEPS_PER_OCTAVE, high * _BOUND_STEPS_PER_OCTAVE + 1) / _BOUND_STEPS_PER_OCTAVE)
    grid = jnp.minimum(grid, law.extent())
    areas = jnp.concatenate([jnp.zeros(1), jnp.cumsum(squared_area(grid[:-1], grid[1:]))])
    one = -low * _BOUND_STEPS_PER_OCTAVE  # index of a = 1
    work = boundary(grid) - boundary(grid[one]) + areas - areas[one]
    enough = (work >= energy) & (grid > 1.0)
    index = jnp.where(jnp.any(enough), jnp.argmax(enough), grid.shape[0] - 1)
    start, start_work = grid[index - 1], work[index - 1]

    def short(a):
        return start_work + boundary(a) - boundary(start) + squared_area(start, a) < energy

    def bisect(_, bracket):
        lo, hi = bracket
        mid = 0.5 * (lo + hi)
        return jnp.where(short(mid), mid, lo), jnp.where(short(mid), hi, mid)

    _, bound = jax.lax.fori_loop(0, 60, bisect, (start, grid[index]))
    return jnp.minimum(jnp.where(jnp.any(enough), bound, grid[-1]), law.extent()), jnp.any(enough)
