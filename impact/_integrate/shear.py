"""A quasi-static shear test on the spring array: the normal springs pressed to a constant load,
then the tangential springs driven through a program of displacements or forces.

At a constant indentation each spring's friction limit is constant, and its displacement after
a monotone shift s from a turning point (u_t, δ_t) of the program is the projection of
u_t + s (`_law.tangential`): exact whatever the shift, so every point of a leg follows from
the leg's turning state alone. Under force control the shift that gives the force Q is the
root of the increasing piecewise-linear Q(s), found exactly (`tangential.bracketed_newton`).
The answer differs from the continuum MDR (Cattaneo–Mindlin, Mindlin–Deresiewicz) only by the
springs' discretisation. Values are SI.
"""

import equinox as eqx
import jax
import jax.numpy as jnp
import numpy as np

from .._law.tangential import AbstractFrictionLimit, Projection, stick_radius
from .tangential import bracketed_newton


class NormalState(eqx.Module):
    """The normal springs at the held load: indentation d (m), springs in contact (the k
    lowest), force F_n (N); `overflow` where the load needs more springs than the array has."""

    indentation: jax.Array
    count: jax.Array
    force: jax.Array
    overflow: jax.Array


def normal_state(heights: np.ndarray, spacing: float, E_star: float, force_control: bool, peak: float) -> NormalState:
    """The springs (heights g_i, m, increasing) pressed to the force `peak` (N) or the
    indentation `peak` (m): F = 2E*Δx·Σ_{g_i<d}(d − g_i), solved exactly for d under force
    control (linear between two springs' heights)."""
    count = len(heights)
    sums = np.cumsum(heights)
    springs = np.arange(1, count + 1)
    if force_control:
        # With the k lowest springs in contact d = (F/(2E*Δx) + S_k)/k; the right k has d between g_k and g_k+1.
        candidates = (peak / (2.0 * E_star * spacing) + sums) / springs
        above = np.append(heights[1:], np.inf)
        valid = (candidates >= heights) & (candidates < above)
        k = int(np.argmax(valid)) + 1 if valid.any() else count
        d = candidates[k - 1]
    else:
        d = peak
        k = int(np.searchsorted(heights, d, side="left"))
    force = 2.0 * E_star * spacing * (k * d - (sums[k - 1] if k else 0.0))
    overflow = k >= count
    return NormalState(jnp.asarray(d), jnp.asarray(k), jnp.asarray(force), jnp.asarray(overflow))


class ShearCurve(eqx.Module):
    """The program's points in order (SI): tangential displacement δ (m), force Q (N), the
    inner radius c of the slip zone (m) and the leg of each (0 the first loading)."""

    displacement: jax.Array
    force: jax.Array
    stick_radius: jax.Array
    leg: jax.Array


def shear_curve(
    limit: AbstractFrictionLimit,
    heights,
    spacing,
    state: NormalState,
    force_control: bool,
    turning: tuple[float, ...],
    samples: int,
) -> ShearCurve:
    """The program from rest through the `turning` values (m, or N under force control),
    `samples` points a leg, on the springs at x_i = (i + ½)·`spacing` with the heights g_i."""
    attached = jnp.arange(heights.shape[0]) < state.count
    d, normal = state.indentation, state.force
    bound = limit.bound(attached, d, heights, normal)

    def shifted(start, shift) -> Projection:
        return limit.project(jnp.where(attached, start + shift, 0.0), attached, d, heights, normal)

    def shift_for(start, target):
        """The shift from `start` at which the force is `target`: Q(shift) rises from −bound to bound."""
        reach = (bound + jnp.abs(target)) / limit.stiffness + jnp.max(jnp.abs(start))

        def residual(shift):
            projection = shifted(start, shift)
            return limit.force(projection.displacement) - target, projection.force_slope

        return bracketed_newton(residual, jnp.zeros(()), -reach, reach, reach)

    pieces = []
    start, position, value = jnp.zeros_like(heights), jnp.zeros(()), jnp.zeros(())
    for leg, end in enumerate(turning):
        targets = value + jnp.linspace(0.0, 1.0, samples) * (end - value)

        def point(target, start=start, position=position):
            """(shift, force, stick radius) of one point of the leg: one at a time, O(N) memory."""
            shift = shift_for(start, target) if force_control else target - position
            projection = shifted(start, shift)
            return shift, limit.force(projection.displacement), stick_radius(projection, attached, spacing)

        shifts, forces, radii = jax.lax.map(point, targets)
        pieces.append(ShearCurve(position + shifts, forces, radii, jnp.full(samples, leg)))
        start = shifted(start, shifts[-1]).displacement
        position, value = position + shifts[-1], jnp.asarray(end)
    return jax.tree.map(lambda *parts: jnp.concatenate(parts), *pieces)
