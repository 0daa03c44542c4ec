"""The Struve functions' asymptotic series, evaluated as rows of one Horner's rule: the same
numbers as each series evaluated alone (`_odd_series`), to the bit, at the arguments of the
asymptotic branch (z > 30: w = 1/z below 1/30) and beyond it."""

import jax
import numpy as np
import pytest

from impact.profiles import _functions as functions

# w = 1/z of the asymptotic branch (z from 30 to 10⁶), a scalar and an array of them.
ARGUMENTS = {"array": 1.0 / np.geomspace(30.0, 1e6, 2001), "scalar": np.float64(1.0 / 31.7)}


@pytest.mark.parametrize("nu", [0, 1])
@pytest.mark.parametrize("shape", sorted(ARGUMENTS))
def test_rows_are_each_series_alone_to_the_bit(nu, shape):
    hankel = functions._hankel_coef(nu, 24) * (-1.0) ** (np.arange(24) // 2)
    alone = [(hankel[0::2], 0), (hankel[1::2], 1), (functions._struve_asym_coef(nu, 15), 1 - nu)]
    w = ARGUMENTS[shape]
    with jax.enable_x64(True):
        rows = jax.jit(
            lambda w: functions._odd_series_rows(w, functions._ASYMPTOTIC[nu], functions._ASYMPTOTIC_FIRSTS[nu])
        )(w)
        each = [jax.jit(lambda w, c=c, f=f: functions._odd_series(w, c, f))(w) for c, f in alone]
    assert len(rows) == 3
    for row, single in zip(rows, each, strict=True):
        assert np.array_equal(np.asarray(row), np.asarray(single))
