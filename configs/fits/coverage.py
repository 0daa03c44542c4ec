"""Coverage of the error bars of the example fits: fit 100 synthetic data sets (seeds 0–99, model
'theory') and count how often the true values all lie within 3 (and 1) standard errors of the
fit. Expected for Gaussian errors: 99.7 % per parameter at 3σ, 68 % at 1σ.

    python configs/fits/coverage.py [drop_test|afm_curve|afm_maugis] [repetitions]

drop_test: the drop test of make_drop_data.py (work of adhesion and modulus from restitution
and largest force); afm_curve: the AFM curve of make_afm_data.py (modulus and work of adhesion
from the force on approach and retract); afm_maugis: the Maugis–Dugdale AFM curve of
make_maugis_data.py (modulus, work of adhesion and range).
"""

import sys
import time
from pathlib import Path

import numpy as np
import yaml

import impact

sys.path.insert(0, str(Path(__file__).parent))
import make_afm_data  # noqa: E402
import make_drop_data  # noqa: E402
import make_maugis_data  # noqa: E402

ADHESION, MODULUS, RANGE = "effects.adhesion.work_of_adhesion", "material.E_star", "effects.adhesion.range"
EXAMPLES = {  # fit file, data of a seed, true values
    "drop_test": (
        "drop_test.yaml",
        make_drop_data.drop_data,
        {ADHESION: make_drop_data.WORK_OF_ADHESION, MODULUS: make_drop_data.E_STAR},
    ),
    "afm_curve": (
        "afm_curve.yaml",
        make_afm_data.afm_data,
        {ADHESION: make_afm_data.WORK_OF_ADHESION, MODULUS: make_afm_data.E_STAR},
    ),
    "afm_maugis": (
        "afm_maugis.yaml",
        make_maugis_data.maugis_data,
        {
            MODULUS: make_maugis_data.E_STAR,
            ADHESION: make_maugis_data.WORK_OF_ADHESION,
            RANGE: make_maugis_data.RANGE,
        },
    ),
}


def pulls(example: str, seeds) -> tuple[np.ndarray, list[int]]:
    """(fitted − true)/standard error of every parameter [seeds, p], and the steps of each fit."""
    name, data_of, true = EXAMPLES[example]
    folder = Path(__file__).parent
    spec = yaml.safe_load((folder / name).read_text())
    scene = impact.load_scene(spec["scene"] if isinstance(spec["scene"], dict) else folder / spec["scene"])
    found, steps = [], []
    for seed in seeds:
        result = impact.fit(
            scene,
            data_of(seed),
            spec["parameters"],
            spec["observables"],
            spec.get("inputs", []),
            model="theory",
            branch=spec.get("branch"),
        )
        found.append([(result.values[path] - value) / result.standard_errors[path] for path, value in true.items()])
        steps.append(result.iterations)
    return np.array(found), steps


def main(example: str = "drop_test", repetitions: int = 100) -> None:
    impact.configure()
    start = time.perf_counter()
    found, steps = pulls(example, range(repetitions))
    seconds = time.perf_counter() - start
    magnitude = np.abs(found)
    print(f"{example}: {repetitions} fits in {seconds:.1f} s; steps: median {np.median(steps):.0f}, max {max(steps)}")
    print(f"all parameters within 3 standard errors: {np.all(magnitude < 3, axis=1).mean():.0%}")
    for index, path in enumerate(EXAMPLES[example][2]):
        within = (magnitude[:, index] < 3).mean(), (magnitude[:, index] < 1).mean()
        print(f"{path}: within 3σ {within[0]:.0%}, within 1σ {within[1]:.0%}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "drop_test", int(sys.argv[2]) if len(sys.argv) > 2 else 100)
