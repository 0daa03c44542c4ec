"""The figure of the documentation's page "Analysing results": a sweep over the impact velocity
and the work of adhesion, drawn from its `to_xarray()` dataset (axis labels and units read from
the dataset)."""

from typing import TYPE_CHECKING

from .. import theory

if TYPE_CHECKING:
    from matplotlib.figure import Figure

# The particle of configs/thornton_ning.yaml (tsit5 at rtol 1e-10: the quadrature method ends
# impacts far below the sticking velocity, v₀ ≲ 0.17 v_s, in solver_failure instead of captured).
_R, _MASS, _E_STAR = 1.0e-6, 1.0472e-14, 1.0e9
_SCENE = {
    "name": "thornton_ning",
    "body": {"profile": {"shape": "paraboloid", "R": _R}, "mass": _MASS},
    "material": {"E_star": _E_STAR},
    "initial": {"velocity": 0.6},
    "effects": {"adhesion": {"work_of_adhesion": 0.05}},
}
VELOCITY, WORK = "initial.velocity", "effects.adhesion.work_of_adhesion"


def restitution_map_figure(velocities=(0.05, 5.0, 100), works=(0.0025, 0.1, 40), shown=(0.01, 0.05, 0.1)) -> "Figure":
    """e(v₀, Δγ) of the Thornton–Ning particle on a grid of `velocities` (geomspace: start, stop,
    num; m/s) × `works` (linspace; J/m²): left, a map with the closed-form sticking velocity
    (3.51) over it; right, e(v₀) at the works of adhesion `shown`, selected from the dataset by
    value. The documentation's image:

        python -c "import impact; impact.configure(); from impact._plots.analysis import \\
            restitution_map_figure as f; f().savefig('docs/src/images/analysis_restitution.png', dpi=100)"
    """
    from matplotlib.figure import Figure

    from .._run.sweep import sweep

    axes_values = {VELOCITY: {"geomspace": list(velocities)}, WORK: {"linspace": list(works)}}
    ds = sweep(_SCENE, axes_values).to_xarray()
    figure = Figure(figsize=(10, 3.8), layout="constrained")
    landscape, cuts = figure.subplots(1, 2)
    v, work = ds[VELOCITY], ds[WORK]
    mesh = landscape.pcolormesh(v, work, ds.restitution.T, shading="nearest", cmap="viridis", vmin=0.0, vmax=1.0)
    figure.colorbar(mesh, ax=landscape, label="restitution e")
    sticking = theory.thornton_ning_sticking_velocity(_MASS, _R, _E_STAR, work.values)
    landscape.plot(sticking, work, "w--", lw=1.2, label="sticking velocity $v_s$ (3.51)")
    landscape.set_xlim(float(v[0]), float(v[-1]))
    landscape.legend(loc="upper left", fontsize="small")
    for k, value in enumerate(shown):
        cut = ds.restitution.sel({WORK: value}, method="nearest")  # the grid holds these values
        label = f"Δγ = {float(cut[WORK]):.3g} {cut[WORK].attrs['units']}"
        cuts.plot(v, cut, color=f"C{k}", label=label)
    cuts.set(ylabel=f"restitution e [{ds.restitution.attrs['units']}]", ylim=(-0.02, 1.02))
    cuts.legend(loc="lower right", fontsize="small")
    cuts.grid(alpha=0.3)
    landscape.set_ylabel(f"{WORK} [{work.attrs['units']}]")
    for axes in (landscape, cuts):
        axes.set_xscale("log")
        axes.set_xlabel(f"{VELOCITY} [{v.attrs['units']}]")
    figure.suptitle(f"Thornton–Ning particle: {ds.restitution.size} impacts, plotted from SweepResult.to_xarray()")
    return figure
