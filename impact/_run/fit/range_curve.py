"""The curve of a displacement-controlled indentation test with adhesion of finite range
(Maugis–Dugdale, §3.8; Greenwood–Johnson, §3.9) as a model: the force and the contact radius at
a given indentation on the branch the test is on, differentiable in every scene value.

Every equilibrium of such a law lies on one curve s ↦ (d, F, a) (`_law.curve`; for the
paraboloid under Maugis–Dugdale the parametric form (3.171) with the range condition), split at
the turning points of d(s) into segments. The test rides the rising segments and jumps at fixed
d from the end of one to the next rising state at that level (`_integrate.quasistatic.curve`):

- approach: the stress zone is born at d = −h (the onset) and the state lands on the first
  rising segment above that level; at the end of each segment it jumps onward, so the segment
  holding a depth d is the one the chain of jumps reaches there;
- retract: from the state at the program's peak (the segment the approach reaches there) down
  the segments and the jumps inward to the last rising state below; where none is left the body
  leaves the range of the stress (pull-off) and the force is 0.

The state on its segment is the root s of d(s) = d by bisection, differentiated by the implicit
function theorem (the law's zone radius is itself such a root: nested implicit roots). The
curve is the one the quasi-static march builds (`finite_range_curve`): the model meets it to
the last bits of the bisection. The approach rows are the first loading, the retract rows the
last unloading from the peak (the program's `peak`, or the row's own depth beyond it).
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from ..._core.derivatives import implicit_root
from ..._core.search import bisect
from ..._integrate.quasistatic import finite_range_curve, finite_range_law
from ..._integrate.quasistatic.loading import BISECTION_STEPS
from ..._integrate.quasistatic.setup import loading_scales
from ..._law.branches import next_rising, previous_rising
from ..._law.curve import AbstractCurve
from ..._scene.scene import Scene
from ..indentation import indentation_loading, indentation_numerics


def finite_range_state(scene: Scene, values: Scene, depth, retract) -> dict[str, jax.Array]:
    """contact_radius, indentation and force (SI) of the displacement-controlled test of a
    finite-range scene at the indentation `depth` (m) on its branch (`retract`: the unloading);
    `values`: the scene with the (traced) values of the fit set."""
    adhesion = values.effects.adhesion
    assert adhesion is not None, "checked: a finite-range curve has adhesion"
    loading = eqx.tree_at(
        lambda test: (test.profile, test.E_star, test.law),
        indentation_loading(scene),
        (
            values.body.profile.build(),
            jnp.asarray(values.material.effective_modulus, jnp.float64),
            adhesion.law(jnp),
        ),
    )
    # The curve and its segments only place the state: built without derivatives (the state of
    # a row is the root below, differentiated through the law). The units carry E* and the
    # profile: differentiated.
    numerics = indentation_numerics(scene)
    _, _, fixed, curve = finite_range_curve(jax.lax.stop_gradient(loading), numerics)
    scales = loading_scales(loading, adhesive=True)
    law = finite_range_law(loading, numerics, scales)
    level = depth / scales.normal
    peak = jnp.maximum(loading.peak / scales.normal, level)
    approach, _ = approach_segment(curve, fixed.onset, level)
    top, _ = approach_segment(curve, fixed.onset, peak)
    back, released = retract_segment(curve, top, level)
    segment = jnp.where(retract, back, approach)
    attached = jnp.where(retract, ~released, level >= fixed.onset)
    s = curve_root(law, fixed, curve, segment, level, attached)
    _, force, radius, _ = curve.state(law, s)
    zero = jnp.zeros_like(force)
    return {
        "contact_radius": jnp.where(attached, radius * scales.radial, zero),
        "indentation": jnp.asarray(depth, force.dtype),
        "force": jnp.where(attached, force * scales.force, zero),
    }


def approach_segment(curve: AbstractCurve, onset, level) -> tuple[jax.Array, jax.Array]:
    """The rising segment holding the depth `level` on approach (scaled), and whether the chain
    of jumps ran off the top of the curve: the landing at the onset, then a jump onward at the
    end of each segment below `level`."""
    nodes, levels, rising = curve.nodes, curve.levels, curve.increasing
    first, blocked = next_rising(nodes, levels, rising, jnp.zeros(()), onset)

    def onward(_, carry):
        segment, blocked = carry
        end = levels[segment + 1]
        following, none = next_rising(nodes, levels, rising, nodes[segment + 1], end)
        jumps = (level > end) & ~blocked
        return jnp.where(jumps & ~none, following, segment), blocked | (jumps & none)

    return jax.lax.fori_loop(0, rising.shape[0], onward, (first, blocked))


def retract_segment(curve: AbstractCurve, top, level) -> tuple[jax.Array, jax.Array]:
    """The rising segment holding the depth `level` on the way back from the segment `top`
    (scaled), and whether the body has left the range (released) above that depth."""
    nodes, levels, rising = curve.nodes, curve.levels, curve.increasing

    def inward(_, carry):
        segment, released = carry
        start = levels[segment]
        previous, none = previous_rising(nodes, levels, rising, nodes[segment], start)
        jumps = (level < start) & ~released
        return jnp.where(jumps & ~none, previous, segment), released | (jumps & none)

    return jax.lax.fori_loop(0, rising.shape[0], inward, (top, jnp.asarray(False)))


def curve_root(law, fixed, curve: AbstractCurve, segment, level, attached) -> jax.Array:
    """s on the rising `segment` where d(s) = `level` (clamped to the segment), by bisection on
    the `fixed` law (the same, without derivatives) and differentiated implicitly through `law`;
    off contact, the middle of the segment (any regular point)."""
    lower, upper = curve.nodes[segment], curve.nodes[segment + 1]
    ends = curve.levels[segment], curve.levels[segment + 1]
    goal = jnp.where(attached, jnp.clip(level, *ends), curve.depth(fixed, 0.5 * (lower + upper)))
    lo, hi = bisect(lambda s: curve.depth(fixed, s) < goal, lower, upper, BISECTION_STEPS)
    return implicit_root(lambda s: curve.depth(law, s) - goal, 0.5 * (lo + hi))
