"""How far an impact can push the contact: a bound on the largest contact radius."""

import jax
import jax.numpy as jnp
import numpy as np

from .._core.derivatives import implicit_root
from .._core.quadrature import ordered_sum
from .._core.search import bisect
from .law import ContactLaw, half_power_root

_BOUND_STEPS_PER_OCTAVE = 4
_BOUND_OCTAVES = (-12, 120)  # the grid 2^(k/4) reaches from 2^-12 to 2^120 (scaled)
_BOUND_NODES = 4
_BISECTION_STEPS = 60
# The power-law bound: halvings of its bracket in log a (at most 120 octaves: to within 7e-6 of
# an octave), then Newton's steps kept inside the last bracket (to the last bit: from 5e-6
# relative, two of them square the error twice).
_POWER_BISECTION_STEPS = 24
_POWER_NEWTON_STEPS = 3


def radius_bound(law: ContactLaw, coefficient, speed):
    """A radius beyond the largest contact radius an impact at scaled speed v reaches.

    Loading along the attach edge h stores W(a) = [a·h² − 2G·h − λ²a²/2] + ∫g² da from the
    adhesion scale a = 1 (integrate ∫F dh by parts with F = 2(a·h − G)); the bound is where W
    first exceeds ½v² + 1 with a > 1 (the +1 covers the adhesion scale): for ĝ = Â·aⁿ found on
    the stretch where W rises (`power_law_bound`), else on a table of W (`tabulated_bound`).
    Capped by the body's extent. Returns (radius, found): an edge that never stores enough (n <
    1/2, or n = 1/2 with a force attractive at every radius) pulls the contact open without limit.
    """
    bound, found = (tabulated_bound if law.power_form() is None else power_law_bound)(law, coefficient, speed)
    return jnp.minimum(bound, law.extent()), found


def _stored_work(law: ContactLaw, coefficient):
    """(boundary term a·h² − 2G·h − λ²a²/2 of W, ∫_lo^hi g² da): closed form for ĝ = Â·aⁿ,
    else Gauss–Legendre on each interval."""

    def boundary(a):
        h = law.edge(a, coefficient)
        return a * h**2 - 2.0 * law.G(a) * h - coefficient**2 * a**2 / 2.0

    form = law.power_form()
    nodes, weights = (jnp.asarray(v) for v in np.polynomial.legendre.leggauss(_BOUND_NODES))

    def squared_area(lo, hi):
        if form is not None:
            scale, exponent = form
            return scale**2 * (hi ** (2.0 * exponent + 1.0) - lo ** (2.0 * exponent + 1.0)) / (2.0 * exponent + 1.0)
        mid, half = 0.5 * (hi + lo), 0.5 * (hi - lo)
        points = mid[..., None] + half[..., None] * nodes
        return half * ordered_sum(weights * law.g(points) ** 2)

    return boundary, squared_area


def tabulated_bound(law: ContactLaw, coefficient, speed):
    """`radius_bound` of any edge (before the extent cap): W tabulated on a_k = 2^(k/4), the
    first step where it reaches ½v² + 1 above a = 1 bisected."""
    energy = 0.5 * speed**2 + 1.0
    boundary, squared_area = _stored_work(law, coefficient)
    low, high = _BOUND_OCTAVES
    grid = 2.0 ** (
        jnp.arange(low * _BOUND_STEPS_PER_OCTAVE, high * _BOUND_STEPS_PER_OCTAVE + 1) / _BOUND_STEPS_PER_OCTAVE
    )
    grid = jnp.minimum(grid, law.extent())
    areas = jnp.concatenate([jnp.zeros(1), jnp.cumsum(squared_area(grid[:-1], grid[1:]))])
    one = -low * _BOUND_STEPS_PER_OCTAVE  # index of a = 1
    work = boundary(grid) - boundary(grid[one]) + areas - areas[one]
    enough = (work >= energy) & (grid > 1.0)
    index = jnp.where(jnp.any(enough), jnp.argmax(enough), grid.shape[0] - 1)
    start, start_work = grid[index - 1], work[index - 1]

    def excess(a):  # W(a) − (½v² + 1)
        return start_work + boundary(a) - boundary(start) + squared_area(start, a) - energy

    _, bound = bisect(lambda a: excess(a) < 0.0, start, grid[index], _BISECTION_STEPS)
    bound = implicit_root(excess, bound)  # a spring array's default length follows it
    return jnp.where(jnp.any(enough), bound, grid[-1]), jnp.any(enough)


def power_law_bound(law: ContactLaw, coefficient, speed):
    """`radius_bound` for ĝ = Â·aⁿ without a table (before the extent cap). Here
    W(a) = 2n²Â²/((n+1)(2n+1))·a^(2n+1) − 2nλÂ/(n+1)·a^(n+3/2) + λ²a²/2 turns where
    u = a^(n−½) is λ/(2nÂ) or λ(n+1)/(nÂ) (W' = a·Q(u), Q quadratic in u), so its first crossing
    of ½v² + 1 above a = 1 lies where W rises: up to its local maximum if W there already reaches
    that energy, else beyond its local minimum. Bisected there in log a (24 halvings of at most
    120 octaves), then refined by Newton's steps inside the last bracket, to the last bit."""
    energy = 0.5 * speed**2 + 1.0
    boundary, squared_area = _stored_work(law, coefficient)
    scale, exponent = law.power_form()
    usable = (coefficient > 0.0) & (exponent != 0.5)
    largest = 2.0 ** _BOUND_OCTAVES[1]
    # u grows with a for n > ½: W peaks at the near root and bottoms at the far one; else the reverse.
    near = half_power_root(coefficient / (2.0 * exponent * scale), exponent, usable)
    far = half_power_root(coefficient * (exponent + 1.0) / (exponent * scale), exponent, usable)
    peak, trough = jnp.where(exponent > 0.5, near, far), jnp.where(exponent > 0.5, far, near)

    def excess(a):  # W(a) − W(1) − (½v² + 1)
        return boundary(a) - boundary(1.0) + squared_area(1.0, a) - energy

    rising_first = (peak > 1.0) & (excess(jnp.maximum(peak, 1.0)) >= 0.0)
    lower = jnp.where(rising_first, 1.0, jnp.maximum(trough, 1.0))
    upper = jnp.where(rising_first, peak, largest)
    found = rising_first | ~(excess(largest) < 0.0)  # W overflows (nan) only far above the energy
    low, high = bisect(lambda a: excess(a) < 0.0, lower, upper, _POWER_BISECTION_STEPS, midpoint=_geometric_mean)

    def newton(_, a):
        value, slope = jax.jvp(excess, (a,), (jnp.ones_like(a),))
        step = jnp.clip(a - value / jnp.where(slope != 0.0, slope, 1.0), low, high)
        return jnp.where(jnp.isfinite(step), step, a)

    bound = jax.lax.fori_loop(0, _POWER_NEWTON_STEPS, newton, high)
    return jnp.where(found, implicit_root(excess, bound), largest), found


def _geometric_mean(lower, upper):
    return jnp.sqrt(lower) * jnp.sqrt(upper)
