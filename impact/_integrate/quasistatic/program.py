"""The loading program of a quasi-static march in the march's units, and how a march moves
through it: a landing at constant force ends back on its leg, a finished leg hands over to the
next one (a reversal where the body is in contact) or ends the march after the last."""

import equinox as eqx
import jax
import jax.numpy as jnp

from ..._core.pytree import replace, replace_where
from .events import Carried, EventLog
from .loading import EVENT


class Program(eqx.Module):
    """The program of a test, scaled: its control, and per leg its direction and target."""

    force_control: jax.Array  # bool: the program is in force (else in indentation)
    directions: jax.Array  # [L] +1 load, −1 unload (padded: see `legs`)
    targets: jax.Array  # [L] where each leg ends (scaled force or indentation); −inf: unload to pull-off
    legs: jax.Array  # legs of the program (≤ L)

    def start(self) -> dict[str, jax.Array]:
        """A march's place in the program before its first step (`AbstractMarchCarry`'s
        fields): on the first leg, in its direction, aiming at its target, not landing."""
        return {
            "leg": jnp.zeros((), int),
            "direction": jnp.asarray(self.directions[0], int),
            "target": self.targets[0],
            "landing": jnp.asarray(False),
        }


def back_on_leg(c: Carried, program: Program, condition) -> Carried:
    """Where `condition` holds a landing ends: the march aims at its leg's target again, in the
    leg's direction."""
    return replace_where(
        c, condition, landing=False, target=program.targets[c.leg], direction=program.directions[c.leg]
    )


def next_leg(c: Carried, program: Program, log: EventLog, finished, touching) -> Carried:
    """Where the leg `finished`: on to the next leg (a reversal, logged where the body is
    `touching`), or the march is done after the last one."""
    more = c.leg + 1 < program.legs
    following = jnp.minimum(c.leg + 1, program.legs - 1)
    log.event(EVENT["reversal"], finished & more & touching)
    c = replace(c, record=replace_where(c.record, finished, done=~more))
    return replace_where(
        c, finished, leg=following, direction=program.directions[following], target=program.targets[following]
    )
