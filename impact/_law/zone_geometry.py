"""The Dugdale zone on a spring array's hat functions (φ_j: 1 at x_j = (j − ½)·Δx, 0 at its
neighbours, flat on [0, x_1]; the springs' values interpolated linearly): the zone's line load
on each spring and each spring's weight in the Abel transform at the zone's edge, both in closed
form (V. L. Popov, M. Heß, E. Willert, Handbook of Contact Mechanics, Springer 2019, §3.8,
(3.148), (3.152)). Scaled lengths; `zone` is the zone's radius c (0: no zone)."""

import jax.numpy as jnp


def _hat_weights(spacing, slots: int, zone, constant, linear):
    """Σ over [0, c] of each spring's hat function against a kernel k(x), from the kernel's
    integrals `constant`(lo, hi) = ∫k and `linear`(lo, hi) = ∫x·k over [lo, hi] ⊂ [0, c]."""
    left = (jnp.arange(slots) + 0.5) * spacing  # x_i: the pieces [x_i, x_i+1]
    lower, upper = jnp.minimum(left, zone), jnp.minimum(left + spacing, zone)
    plain, moment = constant(lower, upper), linear(lower, upper)
    to_left = ((left + spacing) * plain - moment) / spacing
    to_right = (moment - left * plain) / spacing
    head = constant(jnp.zeros(()), jnp.minimum(0.5 * spacing, zone))
    weights = to_left + jnp.concatenate([jnp.zeros(1), to_right[:-1]])
    return weights.at[0].add(head)


def zone_loads(spacing, slots: int, stress, zone):
    """f_j(c) [slots]: the zone's line load −2σ̂·√(c² − x²) (3.148) on the springs' hat
    functions, per width Δx = `spacing` (they add up to the whole load); σ̂ = `stress`."""
    safe = jnp.where(zone > 0.0, zone, 1.0)

    def constant(lo, hi):  # ∫ √(c² − x²) dx
        def primitive(x):
            angle = jnp.arcsin(jnp.clip(x / safe, 0.0, 1.0))
            return 0.5 * (x * jnp.sqrt(jnp.maximum(safe**2 - x**2, 0.0)) + safe**2 * angle)

        return primitive(hi) - primitive(lo)

    def linear(lo, hi):  # ∫ x·√(c² − x²) dx
        return (jnp.maximum(safe**2 - lo**2, 0.0) ** 1.5 - jnp.maximum(safe**2 - hi**2, 0.0) ** 1.5) / 3.0

    area = _hat_weights(spacing, slots, jnp.where(zone > 0.0, zone, 0.0), constant, linear)
    return jnp.where(zone > 0.0, -2.0 * stress * area / spacing, 0.0)


def zone_kernel(spacing, slots: int, zone):
    """K_j(c) [slots]: the springs' hat functions against 1/√(c² − x²) over [0, c] (they add up
    to π/2): (2/π)·Σ K_j·s_j is the Abel transform at r = c of the linearly interpolated s_j."""
    safe = jnp.where(zone > 0.0, zone, 1.0)

    def constant(lo, hi):  # ∫ dx/√(c² − x²)
        return jnp.arcsin(jnp.clip(hi / safe, 0.0, 1.0)) - jnp.arcsin(jnp.clip(lo / safe, 0.0, 1.0))

    def linear(lo, hi):  # ∫ x dx/√(c² − x²)
        return jnp.sqrt(jnp.maximum(safe**2 - lo**2, 0.0)) - jnp.sqrt(jnp.maximum(safe**2 - hi**2, 0.0))

    weights = _hat_weights(spacing, slots, jnp.where(zone > 0.0, zone, 0.0), constant, linear)
    return jnp.where(zone > 0.0, weights, 0.0)
