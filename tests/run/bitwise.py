"""Results equal to the bit: what a point's independence of its batch is checked with."""

import numpy as np

from impact._scene.paths import with_values
from impact._scene.scene import Scene


def assert_bitwise(results: dict, reference: dict, label: str) -> None:
    """Every column of `results` equals `reference`'s to the bit (nan where it is nan)."""
    assert results.keys() == reference.keys(), label
    for name in reference:
        mine, theirs = np.asarray(results[name]), np.asarray(reference[name])
        differ = np.flatnonzero(~((mine == theirs) | (np.isnan(mine) & np.isnan(theirs))))
        assert differ.size == 0, f"{label}: {name} differs at points {differ.tolist()}"


def named_method(scene: Scene, method: str | None = None) -> Scene:
    """The scene with `method` named (None: the method a single run of it takes). A sweep runs the
    method its scene names, else the quadrature where every point allows it; a point of a sweep
    equals a single run of its scene with the sweep's method named."""
    return with_values(scene, {"solver.method": method or scene.solver.method})
