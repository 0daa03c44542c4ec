"""`run_phases` with `landed_contact` (a flight, the contact it lands in and the flight that
contact ends in, a turn; without gravity the approach, the contact's phases and the flight away)
runs the phases that a flight and the contact it lands in a turn run, up to the phase bound
(which does not bound a contact after a flight): the same outcome, for runs that end by
themselves and runs that the bound cuts off."""

import functools
from types import SimpleNamespace

import jax
import jax.numpy as jnp
import pytest

from impact._core.pytree import replace
from impact._integrate.carry import finish, initial_carry, run_phases
from impact._integrate.codes import ADVANCE, DONE, FLIGHT, RECEDE

BOUNCES = 3  # contacts before the body leaves for good


def _flight(c, bounces=BOUNCES):
    """A flight that lands (a contact starts) until `bounces` contacts are over, then ends the run."""
    lands = c.contacts < bounces
    return replace(
        c,
        mode=jnp.where(lands, ADVANCE, DONE),
        phases=c.phases + 1,
        contacts=c.contacts + lands.astype(int),
        t=c.t + 1.0,
    )


def _contact(c):
    """Loading turns into unloading, which ends in a flight; each a phase."""
    return replace(c, mode=jnp.where(c.mode == ADVANCE, RECEDE, FLIGHT), phases=c.phases + 1, t=2.0 * c.t + 1.0)


_PROBLEM = SimpleNamespace(
    motion=SimpleNamespace(start_indentation=-1.0, start_velocity=1.0),
    overflow=jnp.asarray(False),
    bounded=jnp.asarray(True),
)


def _landed_turns(options, flight=_flight, contact=_contact):
    """The loop of a flight and the contact it lands in a turn."""

    def turn(c):
        c = jax.lax.cond(c.mode == FLIGHT, flight, lambda c: c, c)
        return jax.lax.cond((c.mode != FLIGHT) & (c.mode != DONE), contact, lambda c: c, c)

    running = lambda c: (c.mode != DONE) & (c.phases < options.max_phases)  # noqa: E731
    return finish(jax.lax.while_loop(running, turn, initial_carry(_PROBLEM, options)))


def _summary(outcome):
    return [x.tolist() for x in (outcome.status, outcome.contacts, outcome.end_time)]


@pytest.mark.parametrize("max_phases", range(1, 3 * BOUNCES + 3))
def test_landed_contact_runs_the_phases_of_one_phase_a_turn(max_phases):
    """Status (separated, or phase_limit where the bound cuts the run), contacts and the end time
    (which encodes the order of the phases) equal, for every bound from 1 phase to beyond the run's
    3·BOUNCES + 1."""
    options = SimpleNamespace(max_phases=max_phases, samples_per_phase=0, gravity=True)
    outcome = jax.jit(lambda: run_phases(_PROBLEM, options, _flight, _contact, landed_contact=True))()
    assert _summary(outcome) == _summary(jax.jit(lambda: _landed_turns(options))())


_flight_away = functools.partial(_flight, bounces=1)  # the approach, then away for good (no gravity)


def _contact_of_phases(c):
    """Loading over three segments (`Carry.segment` counts them), then unloading, which ends in a
    flight; each a phase."""
    loaded = (c.mode == ADVANCE) & (c.segment == 2)
    mode = jnp.where(c.mode == ADVANCE, jnp.where(loaded, RECEDE, ADVANCE), FLIGHT)
    return replace(c, mode=mode, segment=c.segment + 1, phases=c.phases + 1, t=2.0 * c.t + 1.0)


@pytest.mark.parametrize("max_phases", range(1, 8))
def test_a_contact_without_gravity_runs_the_phases_of_one_phase_a_turn(max_phases):
    """Without gravity (the approach, the contact's phases, the flight away): status, contacts
    and end time equal to one phase a turn's, for every bound from 1 phase to beyond the run's 6."""
    options = SimpleNamespace(max_phases=max_phases, samples_per_phase=0, gravity=False)
    straight = jax.jit(lambda: run_phases(_PROBLEM, options, _flight_away, _contact_of_phases, landed_contact=True))
    turns = jax.jit(lambda: _landed_turns(options, _flight_away, _contact_of_phases))
    assert _summary(straight()) == _summary(turns())
