"""What a contact phase did, from its two ends: the work ∫F dd, the force range and the deepest
indentation, in closed form or by quadrature along the branch the radius rode."""

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core import derivatives
from .._core.quadrature import gauss_legendre, ordered_sum
from .._core.search import golden_section
from .._law.branches import Branch
from .._law.law import ContactLaw, half_power_root, power
from .codes import ADVANCE


class ContactSummary(eqx.Module):
    """What a stretch of contact did, in scaled units."""

    work: jax.Array  # ∫F dd of the elastic force along the stretch
    lowest_force: jax.Array
    highest_force: jax.Array
    deepest: jax.Array  # the largest indentation reached
    viscous_work: jax.Array | float = 0.0  # ∫F_visc ḋ dt: dissipated by damping (`_effects.damping`)


_QUADRATURE_NODES = 48
# The largest ln(a_high/a_low) one Gauss–Legendre panel in ln a takes at full accuracy; the rest
# of a longer ride, ≲ e^(−10·(p+1)) of the work for F·h' ∝ a^p, gets a panel of its own.
_LOG_PANEL = 10.0
_SCAN_POINTS = 33
# Golden sections from a bracket of two scan cells: 0.618^40 ≈ 4e-9 of it, where the value is
# settled to round-off (F − F* ∝ (s − s*)² ≲ 1e-17·F'' of the bracket²).
_GOLDEN_STEPS = 40

# With the located ends an undamped phase whose solver speed misses its energy balance,
# |v² − (v₀² − 2∫F dd + 2g·Δd)|, by more than this fraction of v₀² + v² + the touch speed² (its
# kinetic energies) ends the run with `energy_drift`: the speed then says nothing. Relative to the
# kinetic energies, not to the energy terms: where those terms nearly cancel (hard/08, n = 0.6:
# ~1e9 summing to ~0.3) an error relative to them is rtol-sized, as in any loose run. 1 lies
# between the drift of every config at its own tolerance (orders below) and that of the wrong
# answers it stops (of order 1 and above): docs/src/accuracy.md, "The located ends, checked".
_DRIFT = 1.0


def branch_force(law: ContactLaw, branch: Branch, radius):
    """Force while the contact radius rides the branch: d = h(a)."""
    return law.force(radius, branch.level(law, radius))


def branch_work(law: ContactLaw, branch: Branch, start_radius, end_radius):
    """∫F dd while a moves along the branch from start to end: ∫F(a)·h'(a) da.

    For ĝ = Â·aⁿ in closed form, the difference of the potential
    W(a) = 2n²Â²/((n+1)(2n+1))·a^(2n+1) − 2nλÂ/(n+1)·a^(n+3/2) + λ²a²/2 (F·h' with
    F = 2(Â·n/(n+1)·a^(n+1) − λ·a^(3/2)) and h' = nÂ·a^(n−1) − λ/(2√a), integrated term by
    term). Other profiles: Gauss–Legendre in u = ln a over the top e^10 of the radii, where
    power-law behaviour a^p becomes exponential (an interval [a0, 40·a0] is no harder than
    [a0, 2·a0]); below that (from a = 0, or from a jump-in radius decades further down), in s
    with a = a_low + (a_split − a_low)·s².
    """
    form = law.power_form()
    if form is not None:
        coefficient = branch.coefficient if law.adhesive else jnp.zeros(())
        potential = _power_law_potential
        return potential(form, coefficient, end_radius) - potential(form, coefficient, start_radius)
    nodes, weights = gauss_legendre(_QUADRATURE_NODES)

    def integrand(radii):
        return branch_force(law, branch, radii) * law.edge_slope(radii, branch.coefficient)

    low = jnp.minimum(start_radius, end_radius)
    high = jnp.maximum(start_radius, end_radius)
    sign = jnp.where(end_radius >= start_radius, 1.0, -1.0)
    positive = low > 0.0
    log_high = jnp.log(jnp.where(positive, high, 1.0))
    log_split = jnp.maximum(jnp.log(jnp.where(positive, low, 1.0)), log_high - _LOG_PANEL)
    log_span = log_high - log_split
    logarithmic = jnp.exp(log_split + log_span * nodes)
    top = jnp.where(positive, ordered_sum(weights * log_span * logarithmic * integrand(logarithmic)), 0.0)
    split = jnp.where(positive, jnp.exp(log_split), high)
    squared = low + (split - low) * nodes**2
    bottom = ordered_sum(weights * 2.0 * (split - low) * nodes * integrand(squared))
    return sign * (top + bottom)


def _power_law_potential(form, coefficient, radius):
    """W(a) of `branch_work` for ĝ = Â·aⁿ (W(0) = 0)."""
    scale, exponent = form
    return (
        2.0 * exponent**2 * scale**2 / ((exponent + 1.0) * (2.0 * exponent + 1.0)) * power(radius, 2.0 * exponent + 1.0)
        - 2.0 * exponent * coefficient * scale / (exponent + 1.0) * power(radius, exponent + 1.5)
        + 0.5 * coefficient**2 * radius**2
    )


def squared_speed(start, work, gravity, depth):
    """v² (scaled, unit mass) at the end of a stretch of contact from its energy balance,
    v₀² − 2∫F dd + 2g·(d − d₀): `start` is (d₀, v₀), `work` ∫F dd along it, `depth` d at its end."""
    start_depth, start_speed = start
    return start_speed**2 - 2.0 * work + 2.0 * gravity * (depth - start_depth)


def drifts(start, end, work, gravity, touch_speed):
    """Whether the speed at the end of an undamped stretch of contact (`end` = (d, v)) misses its
    energy balance from `start` = (d₀, v₀) by more than `_DRIFT` of v₀² + v² + touch_speed²."""
    v_end = end[1]
    balance = squared_speed(start, work, gravity, end[0])
    return jnp.abs(v_end**2 - balance) > _DRIFT * (start[1] ** 2 + v_end**2 + touch_speed**2)


def hold_work(law: ContactLaw, radius, start, end):
    """∫F dd at a fixed contact radius: F = 2(a·d − G(a)) is linear in d."""
    return radius * (end**2 - start**2) - 2.0 * law.G(radius) * (end - start)


def extremes(function, lower, upper):
    """(min, max) of a scalar function between two points: a scan, then golden sections."""
    lower, upper = jnp.minimum(lower, upper), jnp.maximum(lower, upper)
    grid = jnp.linspace(0.0, 1.0, _SCAN_POINTS)
    points = lower + (upper - lower) * grid
    values = function(points)
    step = (upper - lower) / (_SCAN_POINTS - 1)

    def refine(sign):
        best = jnp.argmin(sign * values)
        lo = jnp.maximum(points[best] - step, lower)
        hi = jnp.minimum(points[best] + step, upper)
        a, b = golden_section(lambda x: sign * function(x), lo, hi, _GOLDEN_STEPS)
        return sign * jnp.minimum(sign * function(0.5 * (a + b)), sign * values[best])

    low, high = jax.vmap(refine)(jnp.array([1.0, -1.0]))
    return low, high


def branch_force_range(law: ContactLaw, branch: Branch, start_radius, end_radius):
    """(min, max) of the force while the radius rides the branch between two radii.

    For ĝ = Â·aⁿ the force on the branch, F = 2(a·h − Ĝ) = 2(Â·n/(n+1)·a^(n+1) − λ·a^(3/2)),
    has one stationary point, a^(n−½) = 3λ/(2nÂ): the range is that of F at the two ends and
    there, if it lies between them. Other profiles: `extremes` (a scan and golden sections).
    """
    form = law.power_form()
    if form is None:
        return extremes(lambda a: branch_force(law, branch, a), start_radius, end_radius)
    scale, exponent = form
    coefficient = branch.coefficient if law.adhesive else jnp.zeros(())
    usable = (coefficient > 0.0) & (exponent != 0.5) & (scale > 0.0)
    stationary = half_power_root(1.5 * coefficient / (exponent * jnp.where(usable, scale, 1.0)), exponent, usable)
    low, high = jnp.minimum(start_radius, end_radius), jnp.maximum(start_radius, end_radius)
    between = usable & (stationary > low) & (stationary < high)
    forces = branch_force(law, branch, jnp.stack([low, high, jnp.where(between, stationary, low)]))
    return jnp.min(forces), jnp.max(forces)


def phase_summary(law: ContactLaw, branch: Branch, riding, radii, gravity, start, end) -> ContactSummary:
    """Work ∫F dd, the force range and the deepest indentation of one contact phase.

    `riding`: the radius follows the branch (else it is held fixed at radii[0]);
    `radii` are the contact radii and `start`, `end` the (d, v) at the two ends of the phase.
    """
    a_start, a_end = radii
    d_start, v_start = start
    d_end, _ = end

    work_riding = branch_work(law, branch, a_start, a_end)
    low_riding, high_riding = branch_force_range(law, branch, a_start, a_end)

    # Hold: a harmonic arc about d_eq; if it starts inward it turns at d_eq + amplitude.
    stiffness = 2.0 * jnp.maximum(a_start, 1e-300)
    balance = (2.0 * law.G(a_start) + gravity) / stiffness
    turn = balance + derivatives.sqrt((d_start - balance) ** 2 + v_start**2 / stiffness)
    deepest_hold = jnp.where(v_start > 0.0, jnp.maximum(turn, d_start), jnp.maximum(d_start, d_end))
    forces_hold = law.force(a_start, jnp.stack([jnp.minimum(d_start, d_end), deepest_hold]))
    work_hold = hold_work(law, a_start, d_start, d_end)

    return ContactSummary(
        work=jnp.where(riding, work_riding, work_hold),
        lowest_force=jnp.where(riding, low_riding, forces_hold[0]),
        highest_force=jnp.where(riding, high_riding, forces_hold[1]),
        deepest=jnp.where(riding, jnp.maximum(d_start, d_end), deepest_hold),
    )


def active_branch(mode, attach: Branch, detach: Branch) -> Branch:
    """Loading rides the attach branch; hold and unloading answer to the detach branch."""
    return jax.tree.map(lambda a, d: jnp.where(mode == ADVANCE, a, d), attach, detach)


def segment_end(branch: Branch, mode, segment):
    """The radius where the phase's segment of the branch ends: its upper node while advancing,
    else its lower one."""
    return jnp.where(mode == ADVANCE, branch.nodes[segment + 1], branch.nodes[segment])
