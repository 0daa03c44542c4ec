"""How far an impact can push the contact: a bound on the largest contact radius."""

import jax.numpy as jnp
import numpy as np

from .._core.derivatives import implicit_root
from .._core.quadrature import ordered_sum
from .._core.search import bisect
from .law import ContactLaw

_BOUND_STEPS_PER_OCTAVE = 4
_BOUND_OCTAVES = (-12, 120)  # the grid 2^(k/4) reaches from 2^-12 to 2^120 (scaled)
_BOUND_NODES = 4
_BISECTION_STEPS = 60


def radius_bound(law: ContactLaw, coefficient, speed):
    """A radius beyond the largest contact radius an impact at scaled speed v reaches.

    Loading along the attach edge h stores W(a) = [a·h² − 2G·h − λ²a²/2] + ∫g² da from the
    adhesion scale a = 1 (integrate ∫F dh by parts with F = 2(a·h − G)); the bound is where W
    first exceeds ½v² + 1 with a > 1 (the +1 covers the adhesion scale). W is tabulated on
    a_k = 2^(k/4) (∫g² in closed form for a power law, else Gauss–Legendre on each step), then
    bisected inside the step. Capped by the body's extent. Returns (radius, found): an edge that
    never stores enough (n < 1/2, or n = 1/2 with a force attractive at every radius) pulls the
    contact open without limit.
    """
    energy = 0.5 * speed**2 + 1.0
    nodes, weights = (jnp.asarray(v) for v in np.polynomial.legendre.leggauss(_BOUND_NODES))

    def boundary(a):
        h = law.edge(a, coefficient)
        return a * h**2 - 2.0 * law.G(a) * h - coefficient**2 * a**2 / 2.0

    form = law.power_form()

    def squared_area(lo, hi):  # ∫_lo^hi g² da: in closed form for g = Â·aⁿ
        if form is not None:
            scale, exponent = form
            return scale**2 * (hi ** (2.0 * exponent + 1.0) - lo ** (2.0 * exponent + 1.0)) / (2.0 * exponent + 1.0)
        mid, half = 0.5 * (hi + lo), 0.5 * (hi - lo)
        points = mid[..., None] + half[..., None] * nodes
        return half * ordered_sum(weights * law.g(points) ** 2)

    low, high = _BOUND_OCTAVES
    grid = 2.0 ** (
        jnp.arange(low * _BOUND_STEPS_PER_OCTAVE, high * _BOUND_STEPS_PER_OCTAVE + 1) / _BOUND_STEPS_PER_OCTAVE
    )
    grid = jnp.minimum(grid, law.extent())
    if form is None:
        areas = jnp.concatenate([jnp.zeros(1), jnp.cumsum(squared_area(grid[:-1], grid[1:]))])
    else:
        areas = squared_area(grid[0], grid)
    one = -low * _BOUND_STEPS_PER_OCTAVE  # index of a = 1
    work = boundary(grid) - boundary(grid[one]) + areas - areas[one]
    enough = (work >= energy) & (grid > 1.0)
    index = jnp.where(jnp.any(enough), jnp.argmax(enough), grid.shape[0] - 1)
    start, start_work = grid[index - 1], work[index - 1]

    def excess(a):  # W(a) − (½v² + 1)
        return start_work + boundary(a) - boundary(start) + squared_area(start, a) - energy

    _, bound = bisect(lambda a: excess(a) < 0.0, start, grid[index], _BISECTION_STEPS)
    bound = implicit_root(excess, bound)  # a spring array's default length follows it
    return jnp.minimum(jnp.where(jnp.any(enough), bound, grid[-1]), law.extent()), jnp.any(enough)
