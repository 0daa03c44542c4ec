"""What no impact of a passive body can do, checked on every example and hard-case scene."""

import numpy as np


def assert_passive(result) -> None:
    """Time never runs back; a jump of the contact (two samples at one time) moves neither the
    depth nor the speed (only the radius and the force jump); and the first contact's loop ∮F dd
    is not negative where it closed: a body leaves no faster than it came (to 1e-9 of the touch
    energy)."""
    assert np.all(np.diff(result.t) >= 0.0)
    still = np.flatnonzero(np.diff(result.t) == 0.0)
    for series in (result.indentation, result.velocity):
        scale = np.max(np.abs(series))
        assert np.all(np.abs(series[still + 1] - series[still]) <= 1e-9 * scale)
    if np.isfinite(result.contact_time):  # the first contact's loop closed
        touch_energy = 0.5 * result.scene.reduced_mass * result.touch_velocity**2
        assert result.dissipated_energy >= -1e-9 * touch_energy
