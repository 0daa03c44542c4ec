"""The figure of one shear test: the tangential force against the displacement, program order,
beside the closed forms of Cattaneo–Mindlin and Mindlin–Deresiewicz for a paraboloid."""

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .. import theory
from .._run.shear import ShearResult
from .figures import si_prefix, write_figures

if TYPE_CHECKING:
    from matplotlib.figure import Figure

FIGURES = ("shear.png",)


def save_shear_figures(result: ShearResult, folder: str | Path) -> list[Path]:
    """Write `shear.png` into `folder` (atomically); return its path."""
    return write_figures(folder, zip(FIGURES, (shear_figure(result),), strict=True))


def closed_form(result: ShearResult) -> np.ndarray | None:
    """Q (N) of each point after Cattaneo–Mindlin and Mindlin–Deresiewicz (Masing) for a
    paraboloid at the held normal force, under per-spring friction; None for other scenes."""
    scene = result.scene
    friction = scene.effects.friction
    if scene.body.profile.shape != "paraboloid" or friction is None or friction.limit != "per_spring":
        return None
    modulus, shear_modulus = scene.material.effective_modulus, scene.material.tangential_modulus
    normal = result.normal_force
    radius = np.cbrt(3.0 * normal * scene.body.profile.R / (4.0 * modulus))  # Hertz
    return theory.masing_program_force(
        result.displacement, result.leg, normal, radius, friction.coefficient, shear_modulus
    )


def shear_figure(result: ShearResult) -> "Figure":
    """Q against δ in program order, with the closed forms where they hold."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(7, 5), layout="constrained")
    axes = figure.subplots()
    shift_factor, shift_prefix = si_prefix(np.max(np.abs(result.displacement), initial=0.0))
    force_factor, force_prefix = si_prefix(np.max(np.abs(result.force), initial=0.0))
    axes.plot(result.displacement * shift_factor, result.force * force_factor, "C0-", label="spring array")
    reference = closed_form(result)
    if reference is not None:
        axes.plot(result.displacement * shift_factor, reference * force_factor, "k:", label="Cattaneo–Mindlin, Masing")
    axes.set_xlabel(f"tangential displacement δ ({shift_prefix}m)")
    axes.set_ylabel(f"tangential force Q ({force_prefix}N)")
    friction = result.scene.effects.friction
    mu = "" if friction is None else f", μ = {friction.coefficient:g}"
    axes.set_title(f"{result.scene.name}: F_n = {result.normal_force:.4g} N{mu}")
    axes.legend()
    axes.grid(alpha=0.3)
    return figure
