"""The search for the Dugdale zone's radius (`_law.outward_root.root_outward`): outward where the
function starts negative, inward where positive, nothing found where no sign change is within
reach, and the function traced once (one loop body: XLA compiles it once), as is the search in
a step of the zone array (`_law.viscoelastic_dugdale`)."""

import jax
import jax.numpy as jnp
import pytest

from impact._law.outward_root import root_outward
from impact._law.prony import PronyElement
from impact._law.viscoelastic_dugdale import DugdaleZoneArray, zone_array

SPACING, LENGTH = 0.05, 1.0  # Δx and the interval's end


def search(function, start, value=None):
    root, found, start_value = jax.jit(lambda x: root_outward(function, x, SPACING, LENGTH, value))(start)
    return float(root), bool(found), float(start_value)


def test_outward_from_a_negative_start():
    """x² − 0.09 from 0.1 (−0.08 there): the root 0.3, to the search's 1e-14 of max(c, Δx)."""
    root, found, start_value = search(lambda x: x**2 - 0.09, 0.1)
    assert found
    assert root == pytest.approx(0.3, rel=0, abs=1e-14)
    assert start_value == pytest.approx(-0.08, rel=1e-15)


def test_inward_from_a_positive_start():
    """x − 0.2 from 0.5: the root 0.2 inward."""
    root, found, _ = search(lambda x: x - 0.2, 0.5)
    assert found
    assert root == pytest.approx(0.2, rel=0, abs=1e-14)


def test_no_sign_change_within_reach_is_not_found():
    """x + 1 stays positive down to 0: not found, the start returned."""
    root, found, start_value = search(lambda x: x + 1.0, 0.5)
    assert not found
    assert root == 0.5
    assert start_value == 1.5


def test_a_given_start_value_sets_the_direction():
    """The value given at the start (−1: outward) is not evaluated: x − 0.7 from 0.1 finds 0.7."""
    root, found, start_value = search(lambda x: x - 0.7, 0.1, value=-1.0)
    assert found
    assert root == pytest.approx(0.7, rel=0, abs=1e-14)
    assert start_value == -1.0


def test_the_function_is_traced_once():
    """The start's value, the doubling steps and the regula falsi are iterations of one loop: the
    function appears once in the traced program."""
    traces = []

    def function(x):
        traces.append(x)
        return jnp.sin(x) - 0.5

    jax.make_jaxpr(lambda x: root_outward(function, x, SPACING, LENGTH))(0.1)
    assert len(traces) == 1


def test_a_step_of_the_zone_array_searches_the_radius_in_one_place(monkeypatch):
    """The zone's walk and the fold's bisection share one search of the zone's radius: tracing a
    step of the array traces `_zone_end` once."""
    element = PronyElement(jnp.asarray([3.0]), jnp.asarray([0.5]))
    array = zone_array(element, lambda x: 0.5 * x**2, 2.0, 100, 128, 0.3, 0.1)
    searches = []
    original = DugdaleZoneArray._zone_end

    def counted(self, *arguments):
        searches.append(arguments)
        return original(self, *arguments)

    monkeypatch.setattr(DugdaleZoneArray, "_zone_end", counted)
    jax.make_jaxpr(lambda d: array.advance(array.virgin(1), d, 1.0, 1e-3))(0.0)
    assert len(searches) == 1
