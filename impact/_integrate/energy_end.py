"""The end of an undamped phase of the continuum law from its energy balance (`Continuum` with
`phase_ends="energy"`): the speed at a segment end, the radius of a turnaround, the speed at the
end of a hold, exact to round-off at any tolerance of the solver."""

import jax
import jax.numpy as jnp

from .._core import derivatives
from .carry import Carry
from .codes import ADVANCE, HOLD, RECEDE
from .continuum_args import PhaseArgs, timed_radius
from .problem import Problem
from .work import branch_work, hold_work, segment_end, squared_speed

# Newton steps from the located turnaround radius (within ~rtol of the root) to round-off.
_TURNAROUND_NEWTON = 3
# |v²| after Newton's steps, relative to v₀² + |v²| at the segment's end + 1 (the phase's
# energies), below which they found a root of v² (a turnaround), above which there is none near.
_CONVERGED = 1e-9


def energy_end(problem: Problem, args: PhaseArgs, c: Carry, located, ended, turned):
    """(x, v, turned) at the end of an undamped phase from its energy balance,
    v² = v₀² − 2∫F dd + 2g·Δd (unit mass in the scaled units); `located` = (x, v) from the solver's
    dense output, kept where the phase did not end at a located event (`ended`).

    Along a branch (ridden in a, or timed in d from a steep tip): at a segment end (the radius is
    the node) v has the phase's direction; at a turnaround v = 0 and the radius is the root of
    v² = 0, by Newton from the located one (within the solver's tolerance of it), with
    d(v²)/da = 2(g − F)·h'(a), kept inside the segment; a timed phase's x is then the depth h(a).
    Where the body only just reaches the segment's end, or only just fails to, the solver's event
    may be the wrong one at a loose tolerance, and the energy decides: a turnaround near which
    Newton finds no root of v², while the body reaches the segment's end with v² > 0, is that
    end; a segment end reached with v² < 0 is a turnaround before it, where Newton from the end
    finds v² = 0.
    A hold ends at its detach depth (x, the depth, is `args.level`); a turnaround there is a
    capture, left as located.
    """
    x_located, v_located = located
    law, branch, gravity = problem.law, args.branch, problem.motion.gravity

    def ridden_squared_speed(radius):
        ridden = branch_work(law, branch, c.radius, radius)
        return squared_speed((c.d, c.v), ridden, gravity, branch.level(law, radius))

    def newton(radius, _):
        force = law.force(radius, branch.level(law, radius))
        slope = 2.0 * (gravity - force) * law.edge_slope(radius, branch.coefficient)
        step = ridden_squared_speed(radius) / jnp.where(slope != 0.0, slope, 1.0)
        return jnp.clip(radius - step, branch.nodes[c.segment], branch.nodes[c.segment + 1]), None

    def speed(squared, sign):  # no nan derivative where it is unused at 0
        return sign * derivatives.sqrt(jnp.maximum(squared, 0.0))

    # The radius where the phase ended: riding, the state itself; timed along a branch, the
    # segment's end, or at a turnaround the branch root at the located depth.
    node = segment_end(branch, args.mode, args.segment)
    if args.timed_loading:
        timed = ((args.mode == ADVANCE) | (args.mode == RECEDE)) & ~args.riding
        radius_located = jnp.where(args.riding, x_located, jnp.where(turned, timed_radius(x_located, args), node))
    else:  # every timed phase is a hold
        timed = jnp.asarray(False)
        radius_located = x_located
    root, _ = jax.lax.scan(newton, radius_located, None, length=_TURNAROUND_NEWTON)
    riding = ended & (args.riding | timed)
    # The energy's verdict where it and the solver's event disagree (see above).
    at_node = ridden_squared_speed(node)
    converged = jnp.abs(ridden_squared_speed(root)) <= _CONVERGED * (c.v**2 + jnp.abs(at_node) + 1.0)
    reaches = riding & turned & ~converged & (at_node > 0.0)
    falls_short = riding & ~turned & converged & (at_node < 0.0)
    turned = (turned & ~reaches) | falls_short
    end_radius = jnp.where(turned, root, node)  # riding and not turned: the segment's end
    riding_speed = speed(ridden_squared_speed(end_radius), -args.velocity_sign)  # while riding, sign·v < 0
    depth = args.level
    held_speed = speed(
        squared_speed((c.d, c.v), hold_work(law, c.radius, c.d, depth), gravity, depth), jnp.sign(v_located)
    )
    holding = ended & (args.mode == HOLD) & ~turned  # a hold never rides
    x_along = jnp.where(timed, branch.level(law, end_radius), end_radius)
    x_end = jnp.where(riding, x_along, jnp.where(holding, depth, x_located))
    v_end = jnp.where(riding, jnp.where(turned, 0.0, riding_speed), jnp.where(holding, held_speed, v_located))
    return x_end, v_end, turned
