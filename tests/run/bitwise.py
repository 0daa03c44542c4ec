"""Results equal to the bit: what a point's independence of its batch is checked with."""

import numpy as np

from impact._run.sweep import sweep
from impact._scene.paths import with_values
from impact._scene.scene import Scene

# The columns a sweep's batch-independence check compares.
COMPARED = ("restitution", "contact_time", "max_force", "min_force", "status")


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


def assert_chunks_agree(scene: Scene, axes: dict, chunks: tuple[int, ...]) -> None:
    """A sweep of `scene` over `axes` gives the same `COMPARED` columns, to the bit, in one call
    as in calls of each of `chunks` points."""
    whole = sweep(scene, axes, order="given").results
    for chunk in chunks:
        parts = sweep(scene, axes, order="given", chunk=chunk).results
        for name in COMPARED:
            assert np.array_equal(np.asarray(parts[name]), np.asarray(whole[name]), equal_nan=True), (chunk, name)
