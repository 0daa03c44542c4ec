"""Coverage of the drop test's error bars: fit 100 synthetic drop tests (make_drop_data.py, seeds
0–99, model 'theory') and count how often the true work of adhesion and modulus both lie within
3 (and 1) standard errors of the fit. Expected for Gaussian errors: 99.7 % per parameter at 3σ,
68 % at 1σ. Run: python configs/fits/coverage.py [repetitions]
"""

import sys
import time
from pathlib import Path

import numpy as np
import yaml

import impact

sys.path.insert(0, str(Path(__file__).parent))
from make_drop_data import E_STAR, WORK_OF_ADHESION, drop_data  # noqa: E402

TRUE = {"effects.adhesion.work_of_adhesion": WORK_OF_ADHESION, "material.E_star": E_STAR}


def main(repetitions: int = 100) -> None:
    impact.configure()
    folder = Path(__file__).parent
    spec = yaml.safe_load((folder / "drop_test.yaml").read_text())
    scene = impact.load_scene(folder / spec["scene"])
    pulls, steps, start = [], [], time.perf_counter()
    for seed in range(repetitions):
        result = impact.fit(
            scene, drop_data(seed), spec["parameters"], spec["observables"], spec["inputs"], model="theory"
        )
        pulls.append([(result.values[path] - true) / result.standard_errors[path] for path, true in TRUE.items()])
        steps.append(result.iterations)
    pulls_array = np.abs(np.array(pulls))
    both = np.all(pulls_array < 3, axis=1).mean()
    seconds = time.perf_counter() - start
    print(f"{repetitions} fits in {seconds:.1f} s; steps: median {np.median(steps):.0f}, max {max(steps)}")
    print(f"both parameters within 3 standard errors: {both:.0%}")
    for index, path in enumerate(TRUE):
        within = (pulls_array[:, index] < 3).mean(), (pulls_array[:, index] < 1).mean()
        print(f"{path}: within 3σ {within[0]:.0%}, within 1σ {within[1]:.0%}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 100)
