"""Results equal to the bit: what a point's independence of its batch is checked with."""

import numpy as np


def assert_bitwise(results: dict, reference: dict, label: str) -> None:
    """Every column of `results` equals `reference`'s to the bit (nan where it is nan)."""
    assert results.keys() == reference.keys(), label
    for name in reference:
        mine, theirs = np.asarray(results[name]), np.asarray(reference[name])
        differ = np.flatnonzero(~((mine == theirs) | (np.isnan(mine) & np.isnan(theirs))))
        assert differ.size == 0, f"{label}: {name} differs at points {differ.tolist()}"
