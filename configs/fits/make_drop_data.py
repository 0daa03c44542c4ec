"""Make drops.csv: a synthetic drop test of the Thornton–Ning scene (configs/thornton_ning.yaml).

30 impact velocities, geometric from 0.35 to 3 m/s (the sticking velocity is 0.3032 m/s); the
restitution and the largest force from the closed forms (3.50)–(3.51) and
`impact.theory.thornton_ning_max_force` at Δγ = 0.05 J/m², E* = 1 GPa, with Gaussian noise:
σ = 0.01 on the restitution (absolute, also written per row as restitution_sigma) and 2 % on
the largest force (relative). Seed 15. Run from anywhere: python configs/fits/make_drop_data.py
"""

from pathlib import Path

import numpy as np

import impact
from impact import theory

SEED = 15
ROWS = 30
WORK_OF_ADHESION, E_STAR = 0.05, 1.0e9  # J/m², Pa: the values the fit should find
RESTITUTION_SIGMA, FORCE_RELATIVE_SIGMA = 0.01, 0.02


def drop_data(seed: int = SEED) -> dict[str, np.ndarray]:
    """The columns of a synthetic drop test (velocity, restitution ± σ, max_force) of one seed."""
    scene = impact.load_scene(Path(__file__).parents[1] / "thornton_ning.yaml")
    mass, radius = scene.body.resolved_mass, scene.body.profile.R
    velocity = np.geomspace(0.35, 3.0, ROWS)
    arguments = (velocity, mass, radius, E_STAR, WORK_OF_ADHESION)
    noise = np.random.default_rng(seed).standard_normal((2, ROWS))
    restitution = np.asarray(theory.thornton_ning_restitution(*arguments)) + RESTITUTION_SIGMA * noise[0]
    max_force = np.asarray(theory.thornton_ning_max_force(*arguments)) * (1 + FORCE_RELATIVE_SIGMA * noise[1])
    return {
        "initial.velocity": velocity,
        "restitution": restitution,
        "restitution_sigma": np.full(ROWS, RESTITUTION_SIGMA),
        "max_force": max_force,
    }


def main() -> None:
    columns = drop_data()
    header = (
        f"# Synthetic drop test of configs/thornton_ning.yaml made by make_drop_data.py (seed {SEED}):\n"
        f"# closed forms at work_of_adhesion = {WORK_OF_ADHESION} J/m², E_star = {E_STAR:g} Pa, with Gaussian noise\n"
        f"# sigma {RESTITUTION_SIGMA} on restitution, {FORCE_RELATIVE_SIGMA:.0%} (relative) on max_force (N).\n"
    )
    table = np.stack(list(columns.values()), axis=1)
    rows = [",".join(columns)] + [",".join(f"{value:.10g}" for value in row) for row in table]
    (Path(__file__).parent / "drops.csv").write_text(header + "\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
