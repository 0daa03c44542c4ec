"""A ride's horizon (`impact._integrate.base.AbstractAdaptiveIntegrator.ride`): a constant of the
program, so that XLA computes diffrax's bound 100 ulps below it once when compiling (no
`nextafter` left in the compiled program); a lane that is not in contact ends at once."""

import re

import diffrax as dfx
import jax
import jax.numpy as jnp
import numpy as np

from impact._core.runtime import float64
from impact._integrate.base import _IDLE_HORIZON, PHASE_HORIZON
from impact._integrate.continuum import Continuum


def decay(t, y, args):
    """y' = −y: y(t) = e^(−t) from y0 = 1."""
    return -y


def half_life(t, y, args, **kwargs):
    """Crosses zero upwards where y falls to `args` (1/2)."""
    return args - y[0]


@jax.jit
def ride(active):
    """(end time, end state, event found, steps) of a ride of y' = −y from y0 = 1 to y = 1/2."""
    solution = Continuum().ride(decay, half_life, jnp.ones(1), jnp.asarray(0.5), active, dense=False)
    found = solution.result == dfx.RESULTS.event_occurred
    return solution.ts[-1], solution.ys[-1], found, solution.stats["num_steps"]


@float64
def test_an_active_ride_ends_at_its_event_and_an_idle_one_at_once():
    """Active, the ride ends where y = 1/2, t = ln 2 (to 1e-9 relative at tsit5's rtol 1e-10);
    idle, at the pseudo-time `_IDLE_HORIZON` (located to 1e-14 relative) after one step. Its
    compiled program holds no `nextafter`: diffrax rounds a step that ends within 100 ulps of
    the horizon to it, and the horizon is a constant, so XLA folds that bound's 100 `nextafter`s
    (a traced horizon left them in the program)."""
    end, y_end, found, _ = ride(jnp.asarray(True))
    assert bool(found)
    np.testing.assert_allclose(float(end), np.log(2.0), rtol=1e-9)
    np.testing.assert_allclose(float(y_end[0]), 0.5, rtol=1e-9)
    end, _, found, steps = ride(jnp.asarray(False))
    assert bool(found) and int(steps) == 1
    np.testing.assert_allclose(float(end), _IDLE_HORIZON, rtol=1e-14)
    assert isinstance(PHASE_HORIZON, float)
    program = ride.lower(jnp.asarray(True)).compile().as_text()
    assert re.search(r'op_name="[^"]*nextafter', program) is None
