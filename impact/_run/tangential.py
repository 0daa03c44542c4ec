"""The tangential results of an impact in SI units: the body's sliding and spin after the first
contact, the tangential restitutions, the rebound angle and the friction work, for `Result` and
for a sweep's points alike.

Signs: x runs along the body's sliding before the impact (v_t ≥ 0); ω > 0 rolls the body along
+x; the contact point slides with w = v_t − Rω. Without `effects.friction` nothing tangential is
computed: the body slides on unchanged and keeps its spin.
"""

from typing import Any

import numpy as np

# The tangential scalar results (`Result` fields, a sweep's columns with friction): name → (unit,
# description).
TANGENTIAL_RESULTS = {
    "tangential_velocity_after": ("m s-1", "velocity of the centre along the surface after the first contact"),
    "spin_after": ("rad s-1", "spin after the first contact, > 0 rolling along the sliding"),
    "tangential_restitution": ("", "|v_t′|/v_t of the centre (nan without tangential velocity)"),
    "contact_point_tangential_restitution": (
        "",
        "−w′/w of the contact point, w = v_t − Rω: −1 sliding on unchanged, +1 reversed (nan where w = 0)",
    ),
    "rebound_angle": ("rad", "angle of the rebound from the surface normal, atan(v_t′/v_n′)"),
    "friction_work": ("J", "energy lost to friction in the first contact (0 without friction)"),
}
# The tangential time series (`Result` fields sampled at `Result.t`): name → (unit, description).
TANGENTIAL_SERIES = {
    "tangential_force": ("N", "tangential force on the body, against its sliding > 0"),
    "stick_radius": ("m", "inner radius c of the slip zone (the contact radius where no spring slips)"),
}


def tangential_results(
    before: tuple[Any, Any], after: tuple[Any, Any], lever_arm, rebound_speed, friction_work, xp: Any = np
) -> dict[str, Any]:
    """The scalars of `TANGENTIAL_RESULTS` from (v_t, ω) `before` and `after` the first contact
    (m/s, rad/s), the lever arm R (m), the normal rebound speed (m/s; nan without one) and the
    friction work (J); numbers, or arrays of `xp` (a sweep's points, traced)."""
    (velocity, spin), (velocity_after, spin_after) = before, after
    slip, slip_after = velocity - lever_arm * spin, velocity_after - lever_arm * spin_after
    return {
        "tangential_velocity_after": velocity_after,
        "spin_after": spin_after,
        "tangential_restitution": _ratio(xp.abs(velocity_after), velocity, xp),
        "contact_point_tangential_restitution": _ratio(-slip_after, slip, xp),
        "rebound_angle": xp.arctan2(velocity_after, rebound_speed),
        "friction_work": friction_work,
    }


def _ratio(numerator, denominator, xp: Any):
    """numerator/denominator, nan where the denominator is 0."""
    given = denominator != 0
    return xp.where(given, numerator / xp.where(given, denominator, 1.0), xp.nan)
