"""Make afm_maugis.csv: a synthetic AFM force curve of the scene in afm_maugis.yaml (a 20 nm
paraboloid tip, Maugis–Dugdale adhesion of finite range, displacement control).

40 approach points at indentations from 0 to 2 nm (in contact: the snap-in at d = −h moves
with the fitted range, and a row it passes jumps from 0 to the adhesive branch, which a
least-squares step cannot see), then 40 retract points back from 2 to −1.6 nm, through the
pull-off near −1 nm; the force from the Maugis–Dugdale curve of the paraboloid (3.171) at E* = 1 GPa,
Δγ = 0.1 J/m² and the range h = 0.5 nm (σ0 = Δγ/h = 0.2 GPa, Tabor parameter Λ = 1.15 (3.172)).
At this Λ the curve d̃(κ) (κ = b/a the zone over the contact radius) has one minimum, the
displacement-controlled critical point, and the zone without contact (3.176) only falls: on
approach the force is 0 until the tip comes within the range (d = −h), where the contact snaps
onto the rising branch beyond the minimum (κ closer to 1); on retract it follows that branch
down to the minimum and lets go below it (F = 0). The state at each d is the root in ln(κ − 1)
of d̃(κ) = d/|d_c| (scipy's brentq on `theory.maugis_paraboloid`: independent of the fit's
model, which rides the law's curve). Gaussian noise σ = 0.1 nN on the force. Seed 16.
Run from anywhere: python configs/fits/make_maugis_data.py
"""

import math
from pathlib import Path

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from impact import theory

SEED = 16
POINTS = 40  # per branch
RADIUS, E_STAR, WORK_OF_ADHESION, RANGE = 2.0e-8, 1.0e9, 0.1, 5.0e-10  # m, Pa, J/m², m
FORCE_SIGMA = 1.0e-10  # N
LOWEST, DEEPEST = -1.6e-9, 2.0e-9  # m: the retract ends at LOWEST, the approach starts at 0
LOG_EXCESS = (-30.0, 10.0)  # ln(κ − 1) searched


def jkr_units(radius=RADIUS, E_star=E_STAR, work=WORK_OF_ADHESION) -> tuple[float, float]:
    """|d_c| (m) and F_A (N) of the normalization (3.170)."""
    a_c = (9.0 * math.pi * radius**2 * work / (8.0 * E_star)) ** (1.0 / 3.0)
    return a_c**2 / (3.0 * radius), 1.5 * math.pi * radius * work


def tabor(radius=RADIUS, E_star=E_STAR, work=WORK_OF_ADHESION, adhesion_range=RANGE) -> float:
    return float(theory.tabor_parameter(radius, work / adhesion_range, adhesion_range, E_star))


def _normalized(log_excess: float, tabor_parameter: float) -> tuple[float, float]:
    _, depth, force = theory.maugis_paraboloid(1.0 + math.exp(log_excess), tabor_parameter)
    return float(depth), float(force)


def critical_log_excess(tabor_parameter: float) -> float:
    """ln(κ − 1) at the minimum of d̃ (3.171): the displacement-controlled pull-off."""
    found = minimize_scalar(
        lambda x: _normalized(x, tabor_parameter)[0], bounds=LOG_EXCESS, method="bounded", options={"xatol": 1e-12}
    )
    return float(found.x)


def maugis_curve_force(indentation: float, retract: bool) -> float:
    """The force (N) of the quasi-static displacement-controlled test at one indentation."""
    unit_depth, unit_force = jkr_units()
    parameter = tabor()
    turn = critical_log_excess(parameter)
    depth = indentation / unit_depth
    lowest = _normalized(turn, parameter)[0]
    if depth < (lowest if retract else -RANGE / unit_depth):
        return 0.0
    log_excess = brentq(lambda x: _normalized(x, parameter)[0] - depth, LOG_EXCESS[0], turn, xtol=1e-14, rtol=1e-15)
    return _normalized(log_excess, parameter)[1] * unit_force


def maugis_data(seed: int = SEED) -> dict[str, np.ndarray]:
    """The columns of one synthetic curve: indentation (m), force (N), branch (labels)."""
    approach = np.linspace(0.0, DEEPEST, POINTS)
    indentation = np.concatenate([approach, np.linspace(DEEPEST, LOWEST, POINTS)])
    retract = np.arange(2 * POINTS) >= POINTS
    exact = np.array([maugis_curve_force(d, back) for d, back in zip(indentation, retract, strict=True)])
    noise = np.random.default_rng(seed).standard_normal(2 * POINTS)
    return {
        "indentation": indentation,
        "force": exact + FORCE_SIGMA * noise,
        "branch": np.where(retract, "retract", "approach"),
    }


def main() -> None:
    columns = maugis_data()
    header = (
        f"# Synthetic AFM curve of afm_maugis.yaml made by make_maugis_data.py (seed {SEED}): the quasi-static\n"
        f"# Maugis-Dugdale curve of a paraboloid, R = {RADIUS:g} m, at E_star = {E_STAR:g} Pa, work_of_adhesion =\n"
        f"# {WORK_OF_ADHESION} J/m², range = {RANGE:g} m (Tabor parameter {tabor():.4f}), displacement control;\n"
        f"# Gaussian noise sigma {FORCE_SIGMA:g} N on the force. indentation in m, force in N.\n"
    )
    rows = [",".join(columns)] + [
        f"{d:.10g},{force:.10g},{branch}"
        for d, force, branch in zip(columns["indentation"], columns["force"], columns["branch"], strict=True)
    ]
    (Path(__file__).parent / "afm_maugis.csv").write_text(header + "\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
