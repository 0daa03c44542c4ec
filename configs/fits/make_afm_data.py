"""Make afm_curve.csv: a synthetic AFM force curve of the scene in afm_curve.yaml (a 50 nm
paraboloid tip, reversible JKR adhesion, displacement control).

40 approach points at indentations from −2.5 to 3 nm, then 40 retract points back from 3 to
−2.5 nm; the force from the JKR curve (3.44) at E* = 0.8 GPa, Δγ = 0.1 J/m²: on approach 0 until
first touch (d = 0), where the contact jumps in (to a₀³ = 2πΔγR²/E*), on retract along the
branch down to the displacement-controlled critical point d_c (ξ = 1, (3.45)) and 0 below it.
The contact radius at each d is the root of d = a²/R − √(2πaΔγ/E*) beyond a_c (scipy's
brentq: independent of the fit's model). Gaussian noise σ = 0.5 nN on the force. Seed 15.
Run from anywhere: python configs/fits/make_afm_data.py
"""

from pathlib import Path

import numpy as np
from scipy.optimize import brentq

from impact import theory

SEED = 15
POINTS = 40  # per branch
RADIUS, E_STAR, WORK_OF_ADHESION = 5.0e-8, 0.8e9, 0.1  # m, Pa, J/m²: E* and Δγ are what the fit should find
FORCE_SIGMA = 0.5e-9  # N
LOWEST, DEEPEST = -2.5e-9, 3.0e-9  # m


def jkr_curve_force(indentation: float, retract: bool, radius=RADIUS, E_star=E_STAR, work=WORK_OF_ADHESION) -> float:
    """The force (N) of the quasi-static displacement-controlled JKR test at one indentation."""
    a_c, d_c, _ = (float(value) for value in theory.paraboloid_critical(radius, E_star, work, 1))
    if indentation < (d_c if retract else 0.0):
        return 0.0
    a = brentq(
        lambda x: float(theory.jkr_indentation(x, radius, E_star, work)) - indentation,
        a_c,
        1e3 * a_c,
        xtol=1e-30,
        rtol=1e-15,
    )
    return float(theory.jkr_force(a, radius, E_star, work))


def afm_data(seed: int = SEED) -> dict[str, np.ndarray]:
    """The columns of one synthetic curve: indentation (m), force (N), branch (labels)."""
    approach = np.linspace(LOWEST, DEEPEST, POINTS)
    indentation = np.concatenate([approach, approach[::-1]])
    retract = np.arange(2 * POINTS) >= POINTS
    exact = np.array([jkr_curve_force(d, back) for d, back in zip(indentation, retract, strict=True)])
    noise = np.random.default_rng(seed).standard_normal(2 * POINTS)
    return {
        "indentation": indentation,
        "force": exact + FORCE_SIGMA * noise,
        "branch": np.where(retract, "retract", "approach"),
    }


def main() -> None:
    columns = afm_data()
    header = (
        f"# Synthetic AFM curve of afm_curve.yaml made by make_afm_data.py (seed {SEED}): the quasi-static\n"
        f"# JKR curve of a paraboloid, R = {RADIUS:g} m, at E_star = {E_STAR:g} Pa, work_of_adhesion =\n"
        f"# {WORK_OF_ADHESION} J/m², displacement control; Gaussian noise sigma {FORCE_SIGMA:g} N on the force.\n"
        "# indentation in m, force in N.\n"
    )
    rows = [",".join(columns)] + [
        f"{d:.10g},{force:.10g},{branch}"
        for d, force, branch in zip(columns["indentation"], columns["force"], columns["branch"], strict=True)
    ]
    (Path(__file__).parent / "afm_curve.csv").write_text(header + "\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
