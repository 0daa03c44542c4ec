"""How a phase of the continuum law (`continuum`) is integrated: its arguments (the branch, the
state variable, where the phase ends), the contact radius of a phase integrated in time, and the
viscous and total force of a state."""

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.types import Parameter
from .._law.branches import Branch
from .._law.law import ContactLaw
from .carry import Carry
from .codes import ADVANCE, HOLD, RECEDE
from .problem import Motion, Options, Problem
from .ride import AbstractPhaseArgs, speed_scale
from .work import active_branch, segment_end

# Radii (scaled) at which the edge slope is compared to tell a steep tip.
_TIP_NEAR, _TIP_FAR = 1e-9, 1e-6


class PhaseArgs(AbstractPhaseArgs):
    """What the vector field and the event conditions of one phase need."""

    law: ContactLaw
    branch: Branch
    riding: jax.Array  # state is (a, v, t) in pseudo-time; else (d, v, t) in time
    mode: jax.Array
    segment: jax.Array
    radius: jax.Array  # held radius (HOLD)
    motion: Motion
    velocity_sign: jax.Array  # turnaround: sign·v crosses zero upwards
    level_sign: jax.Array  # branch end: sign·(distance to the end) crosses zero upwards
    level: jax.Array  # the end in the state's variable: a segment end (riding) or a depth d
    speed_scale: jax.Array  # 1 + the speeds of the phase start and of the touch
    damping: tuple[Parameter, Parameter]  # (η_a, η_0) of the viscous force (η_a·a + η_0)·v
    releases: jax.Array  # the contact ends where the total force returns to zero (damped, no adhesion)
    # Loading may be integrated in time (`Options.timed_loading`); else a timed phase is a hold.
    timed_loading: bool = eqx.field(static=True)


def timed_radius(d, args: PhaseArgs):
    """Contact radius of a time-parametrized phase: held, or the branch root at d (only where
    loading is integrated in time: otherwise every timed phase is a hold)."""
    if not args.timed_loading:
        return args.radius
    riding = args.branch.radius(args.law, d, args.segment)
    return jnp.where(args.mode == HOLD, args.radius, riding)


def viscous_force(radius, velocity, args: PhaseArgs):
    """F_v = (η_a·a + η_0)·v of the springs in contact (scaled)."""
    per_radius, constant = args.damping
    return (per_radius * radius + constant) * velocity


def total_force(y, args: PhaseArgs):
    """The elastic and the viscous force of the state y (riding: y[0] = a; timed: y[0] = d)."""
    x, v = y[0], y[1]
    law, branch = args.law, args.branch
    radius = jnp.where(args.riding, jnp.maximum(x, 0.0), timed_radius(x, args))
    depth = jnp.where(args.riding, branch.level(law, radius), x)
    return law.force(radius, depth) + viscous_force(radius, v, args)


def phase_args(problem: Problem, options: Options, c: Carry) -> PhaseArgs:
    """How the phase starting from the carry is integrated and where it ends."""
    law = problem.law
    branch = active_branch(c.mode, problem.attach, problem.detach)
    # A segment rising from (or within 1e-6 of) a steep tip (h' → ∞ at a = 0, power laws
    # n < 1) is integrated in time: in a, the pace q would never let a get there. Where the
    # scene never loads in time, no tip is steep (and a rounded slope of ĝ = Â·a must not say so).
    steep = (
        (branch.nodes[c.segment] < _TIP_FAR)
        & (law.edge_slope(_TIP_NEAR, branch.coefficient) > law.edge_slope(_TIP_FAR, branch.coefficient))
        if options.timed_loading
        else jnp.asarray(False)
    )
    riding = ((c.mode == RECEDE) | (c.mode == ADVANCE)) & ~steep
    # Ends of the phase: the branch's segment end (in a when riding, in d when timed), or the
    # detach edge of the held radius.
    node = segment_end(branch, c.mode, c.segment)
    level = jnp.where(
        riding,
        node,
        jnp.where(c.mode == HOLD, problem.detach.level(law, c.radius), branch.level(law, node)),
    )
    return PhaseArgs(
        law=law,
        branch=branch,
        riding=riding,
        mode=c.mode,
        segment=c.segment,
        radius=c.radius,
        motion=problem.motion,
        velocity_sign=jnp.where(c.mode == ADVANCE, -1.0, 1.0),
        level_sign=jnp.where(c.mode == ADVANCE, 1.0, -1.0),
        level=level,
        speed_scale=speed_scale(problem, c),
        damping=(problem.damping_per_radius, problem.damping_constant),
        releases=(c.mode != ADVANCE) & ~law.adhesive,
        timed_loading=options.timed_loading,
    )
