"""Spring arrays of a scene: the compiled size of an array, and whether a Maugis–Dugdale array
can resolve its adhesive zone, decided from a scene's values before it runs
(`_law.dugdale_springs.ZONE_SPRINGS` springs across the zone's width)."""

import math
from typing import TYPE_CHECKING

import jax
import numpy as np

from .. import theory
from .._law.dugdale_springs import LENGTH_MARGIN, ZONE_SPRINGS
from .profiles import ProfileSpec

if TYPE_CHECKING:
    from .adhesion.maugis_dugdale import MaugisDugdaleAdhesion

# Springs of a Maugis–Dugdale array: each spring event is a ride (and a quasi-static piece) of its own.
DUGDALE_MAX_SPRINGS = 2048


def spring_capacity(count: int) -> int:
    """Slots of the compiled spring array: the next power of two (at least 64), so that arrays
    of similar size share one compilation (the count itself is traced)."""
    return max(64, 1 << (int(count) - 1).bit_length())


def unresolved_zone(
    profile: ProfileSpec, E_star: float, adhesion: "MaugisDugdaleAdhesion", length: float | None, springs: int
):
    """Why `springs` Maugis–Dugdale springs over `length` (m; None: the default) cannot resolve
    the adhesive zone, or None: the array needs `ZONE_SPRINGS` springs across the zone's width
    s = (π/4)E*Δγ/σ0² (`theory.dugdale_zone_width`) over the length, or over the least default
    length, `LENGTH_MARGIN` jump-in radii (a default that reaches further, with the impact's
    energy or the program's peak, is checked in the run: status `unresolved_zone`)."""
    width = float(theory.dugdale_zone_width(E_star, adhesion.work_of_adhesion, adhesion.adhesive_stress))
    if length is None:
        length = LENGTH_MARGIN * jump_in_radius(profile, E_star, adhesion.work_of_adhesion)
        over = f"the default contact.length (at least {LENGTH_MARGIN:g} jump-in radii, {length:.3g} m)"
        more = " (more where the impact reaches further)"
    else:
        over, more = f"contact.length {length:.3g} m", ""
    needed = ZONE_SPRINGS * length / width
    if not math.isfinite(needed) or springs >= needed:  # (a scale beyond float64: `_representable`)
        return None
    least = math.ceil(needed)
    kind = ""
    if profile.shape == "paraboloid":
        tabor = theory.tabor_parameter(profile.R, adhesion.adhesive_stress, adhesion.adhesion_range, E_star)
        kind = f" (Tabor parameter Λ = {float(tabor):.4g})"
    if least <= DUGDALE_MAX_SPRINGS:
        advice = f"give at least {least} springs{more}, or 'continuum'"
    else:
        advice = (
            f"that needs {least} springs, more than the {DUGDALE_MAX_SPRINGS} allowed: give a shorter "
            "contact.length (just beyond the largest contact radius), or 'continuum'"
        )
    return (
        f"{springs} springs over {over} do not resolve the Maugis–Dugdale adhesive zone{kind}: its width "
        f"(π/4)E*Δγ/σ0² = {width:.3g} m needs {ZONE_SPRINGS:g} springs across it (else the array dissipates "
        f"like an attach-on-touch JKR contact); {advice}"
    )


def jump_in_radius(profile: ProfileSpec, E_star: float, work_of_adhesion: float) -> float:
    """a₀ (m) of the JKR jump-in, g(a₀) = √(2πa₀Δγ/E*), of a body with g = A·xⁿ (the power laws
    of Maugis–Dugdale): a₀ = (2πΔγ/(E*A²))^(1/(2n − 1))."""
    with jax.enable_x64(True):
        form = profile.build().power_form()
        assert form is not None, "validated: maugis_dugdale bodies are power laws"
        prefactor, exponent = (float(value) for value in form)
    with np.errstate(all="ignore"):  # a scale beyond float64 comes out inf or 0
        ratio = 2 * np.pi * work_of_adhesion / (E_star * np.float64(prefactor) ** 2)
        return float(ratio ** (1 / (2 * exponent - 1)))
