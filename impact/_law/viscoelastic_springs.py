"""N springs of a viscoelastic half-space (`prony.PronyElement` each) at the midpoints
x_j = (j − ½)·Δx, advanced exactly over a step in which the indentation changes linearly.

In the MDR the springs are independent given the indentation d(t) (Popov, Willert & Heß,
Facta Universitatis, Mech. Eng. 16 (2018) 99), and each is a unilateral contact of its own:

- a free spring attaches once the indenter reaches its surface, d − g(x) ≥ u (its creeping
  displacement, 0 while it never touched); with approach adhesion once the gap u − (d − g(x))
  closes to √(2πxΔγa/E₀*), and it jumps onto the indenter;
- an attached spring lets go where its force (not its displacement) returns to zero, or with
  adhesion where its tension reaches √(2πxΔγE₀*) per unit width, and then creeps back freely.

Springs leaving a receding contact where their force vanishes reproduce Ting's (J. Appl. Mech.
33 (1966) 845) receding contact; a growing one that of Lee & Radok (J. Appl. Mech. 27 (1960)
438). With adhesion the rule of Heß (3.26) is a Griffith balance of the instantaneous snap: the
crack passes a spring far faster than the medium relaxes (V. L. Popov, "Energy criterion for
attachment and detachment in viscoelastic adhesive contacts", Adhesives 1 (2025) 9), so its
dashpots stand still, and the energy the snap releases, f²/(2E₀*) per unit width, meets the
work of adhesion of the spring's ring, πxΔγ: the criterion sees the instantaneous modulus
E₀* = E∞* + Σ E_i. Attaching, likewise, gains ½E₀*·Δu² for the jump Δu.

The contact stays one disc (the MDR describes a simply connected contact): only its edge
changes. A spring lets go once every spring outside it has, and attaches once every spring
inside it has; where its own criterion was met earlier it follows at once (the cascades of the
rule of Heß: the jump-in at the touch, the snap-off at the critical point).

Within a step each spring changes at most once, at the root of its force (or gap) in the step,
found by Newton's method inside a bracket and differentiated implicitly, or later in a cascade;
a second change in the same step waits for the next one. Lengths, forces and times are those of `Scales` (per unit
width: force in E∞·ℓz; totals in E∞·ℓx·ℓz, both sides of the axis counted).
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core import derivatives
from .prony import PronyElement

# Newton's steps inside the bracket (halving where a step leaves it), until every root moves by
# less than this fraction of the step, or at most this many.
_ROOT_SETTLED = 1e-13
_ROOT_STEPS = 60


class SpringStates(eqx.Module):
    """The springs' state: attached or free, displacement u and arm stretches q."""

    attached: jax.Array  # [N] bool
    displacement: jax.Array  # [N] u (attached: d − g(x), plus the jump of an adhesive attach)
    stretches: jax.Array  # [N, M] q_i

    @staticmethod
    def virgin(count: int, terms: int) -> "SpringStates":
        """Springs that never touched: free, at rest."""
        return SpringStates(jnp.zeros(count, bool), jnp.zeros(count), jnp.zeros((count, terms)))


class StepTotals(eqx.Module):
    """What a step did to the whole array (scaled, both sides of the axis)."""

    impulse: jax.Array  # ∫F ds
    dissipation: jax.Array  # the dashpots' work
    released: jax.Array  # elastic energy released by the springs that let go (f²/(2e₀) each)
    gained: jax.Array  # elastic energy gained by the springs that jumped onto the indenter
    last_release: jax.Array  # time into the step of the last spring that let go (−inf: none)


class ViscoelasticArray(eqx.Module):
    """The springs' places and thresholds, and their element. The array has a compiled number of
    slots; the springs beyond `count` (traced) never touch (their g is infinite)."""

    element: PronyElement
    spacing: jax.Array  # Δx
    count: jax.Array  # N
    profile: jax.Array  # [slots] g(x_j)
    attach_gap: jax.Array  # [slots] the gap at which a free spring attaches: √(2πx_jΔγa/E₀*) (scaled)
    tension: jax.Array  # [slots] the force per width at which an attached spring lets go: √(2πx_jΔγE₀*)

    @property
    def slots(self) -> int:
        return self.profile.shape[0]

    def virgin(self, terms: int) -> SpringStates:
        """The medium at rest."""
        return SpringStates.virgin(self.slots, terms)

    def springs_of(self, states: SpringStates) -> SpringStates:
        """The springs' states: the array's state itself."""
        return states

    def engaged(self, states: SpringStates):
        """Whether the body is in contact."""
        return jnp.any(states.attached)

    def onset(self, indentation):
        """Where the contact phase starts: the touch, d = 0."""
        return jnp.zeros_like(indentation)

    def forces(self, states: SpringStates):
        """Each spring's force per width (0 where free)."""
        return jnp.where(states.attached, self.element.force(states.displacement, states.stretches), 0.0)

    def force(self, states: SpringStates):
        """F = 2Δx·Σ f_j."""
        return 2.0 * self.spacing * jnp.sum(self.forces(states))

    def stored(self, states: SpringStates):
        """The elastic energy the array holds, attached springs and free ones."""
        return 2.0 * self.spacing * jnp.sum(self.element.stored(states.displacement, states.stretches))

    def contact_radius(self, states: SpringStates):
        """The outer edge of the outermost attached spring (0 without contact)."""
        outermost = jnp.max(jnp.where(states.attached, jnp.arange(self.slots), -1))
        return (outermost + 1) * self.spacing

    def overflows(self, states: SpringStates):
        """Whether the last spring is attached: the contact may have grown beyond the array."""
        return states.attached[self.count - 1]

    def advance(self, states: SpringStates, indentation, rate, duration) -> tuple[SpringStates, StepTotals]:
        """The springs after `duration` with d(s) = `indentation` + `rate`·s, and the step's totals."""
        count = self.slots
        rate_n = jnp.full(count, rate)
        element = self.element
        change = self._change_time(states, indentation, rate_n, duration)
        before = self._evolve(states, rate_n, change)
        changing = change < duration
        # The jump at the change: attaching onto the indenter, or the snap of a spring letting go.
        onto = indentation + rate * change - self.profile
        leaving = states.attached & changing
        force = element.force(before.states.displacement, before.states.stretches)
        jump = jnp.where(
            changing, jnp.where(leaving, -force / element.instantaneous, onto - before.states.displacement), 0.0
        )
        jumped = SpringStates(
            attached=states.attached ^ changing,
            displacement=before.states.displacement + jump,
            stretches=before.states.stretches + jump[:, None],
        )
        energy = 0.5 * element.instantaneous * jump**2
        after = self._evolve(jumped, rate_n, duration - change)
        width = 2.0 * self.spacing
        return after.states, StepTotals(
            impulse=width * jnp.sum(before.impulse + after.impulse),
            dissipation=width * jnp.sum(before.dissipation + after.dissipation),
            released=width * jnp.sum(jnp.where(leaving, energy, 0.0)),
            gained=width * jnp.sum(jnp.where(changing & ~leaving, energy, 0.0)),
            last_release=jnp.max(jnp.where(leaving, change, -jnp.inf)),
        )

    def _evolve(self, states: SpringStates, rate, duration) -> "Evolved":
        """Each spring after `duration` in its mode (attached: u follows the indenter at `rate`;
        free: creeping back)."""
        element = self.element
        loaded = element.loaded(states.displacement, states.stretches, rate, duration)
        free, free_dissipation = element.free(states.stretches, duration)
        attached = states.attached
        stretches = jnp.where(attached[:, None], loaded.stretches, free)
        displacement = jnp.where(attached, states.displacement + rate * duration, element.free_displacement(free))
        return Evolved(
            states=SpringStates(attached, displacement, stretches),
            impulse=jnp.where(attached, loaded.force_integral, 0.0),
            dissipation=jnp.where(attached, loaded.dissipation, free_dissipation),
        )

    def _criterion(self, states: SpringStates, indentation, rate, time):
        """(value, slope) at `time` into the step of what changes a spring: attached, its force
        plus the tension it may bear (it lets go below 0); free, its gap to the indenter less
        the attach gap (it attaches below 0)."""
        element = self.element
        force, force_slope = element.loaded_force(states.displacement, states.stretches, rate, time)
        surface, surface_slope = element.free_surface(states.stretches, time)
        gap = surface - (indentation + rate * time - self.profile) - self.attach_gap
        attached = states.attached
        return (
            jnp.where(attached, force + self.tension, gap),
            jnp.where(attached, force_slope, surface_slope - rate),
        )

    def _change_time(self, states: SpringStates, indentation, rate, duration):
        """When in [0, duration] each spring changes (`duration` where it does not): `change_times`
        of `_criterion`."""

        def criterion(inputs, time):
            return self._criterion(*inputs, time)

        return change_times(criterion, (states, indentation, rate), states.attached, duration)


def change_times(criterion, inputs, attached, duration):
    """When in [0, `duration`] each spring changes (`duration` where it does not), for the
    `criterion`(`inputs`, time) → (value, slope) [N] of what changes it (below 0: it changes).
    Its own time: 0 where its criterion starts below zero, else the root of its criterion where
    it ends below (Newton's method in the bracket, differentiated implicitly); then the edge rule
    of the disc: a spring lets go once every spring outside it has, and attaches once every
    spring inside it has (cascading where its own time has passed)."""
    zeros = jnp.zeros(attached.shape, jnp.result_type(duration, float))
    start, _ = criterion(inputs, zeros)
    end, _ = criterion(inputs, zeros + duration)
    crosses = (end < 0.0) & (start > 0.0)
    frozen = jax.tree.map(jax.lax.stop_gradient, inputs)

    def unsettled(search):
        _, _, _, moved, steps = search
        return (steps < _ROOT_STEPS) & jnp.any(moved > _ROOT_SETTLED * duration)

    def newton(search):
        low, high, time, _, steps = search
        value, slope = criterion(frozen, time)
        low, high = jnp.where(value > 0.0, time, low), jnp.where(value > 0.0, high, time)
        step = time - value / jnp.where(slope != 0.0, slope, 1.0)
        inside = (step >= low) & (step <= high) & jnp.isfinite(step)
        new = jnp.where(inside, step, 0.5 * (low + high))
        return low, high, new, jnp.where(crosses, jnp.abs(new - time), 0.0), steps + 1

    guess = duration * start / jnp.where(crosses, start - end, 1.0)
    search = (zeros, zeros + duration, guess, zeros + duration, jnp.zeros((), int))
    _, _, root, _, _ = jax.lax.while_loop(unsettled, newton, search)
    root = derivatives.implicit_root(lambda time: criterion(inputs, time)[0], root)
    own = jnp.where(end < 0.0, jnp.where(crosses, root, 0.0), duration)
    releases = jax.lax.cummax(jnp.where(attached, own, 0.0), reverse=True)
    attaches = jax.lax.cummax(jnp.where(attached, 0.0, own))
    return jnp.where(attached, releases, attaches)


class Evolved(eqx.Module):
    """Each spring after a stretch of time in its mode, and its ∫f ds and dissipation."""

    states: SpringStates
    impulse: jax.Array  # [N] ∫f ds
    dissipation: jax.Array  # [N]


def spring_array(element: PronyElement, g, length, count, slots: int, detach, attach) -> ViscoelasticArray:
    """`count` springs at the midpoints x_j = (j − ½)·Δx of [0, `length`] in `slots` slots (the
    rest never touch), for the scaled profile `g` and the scaled rule of Heß at the
    instantaneous modulus: a spring lets go at the tension e₀·`detach`·√x and attaches across the
    gap `attach`·√x (`Viscoelastic.hess_lengths`)."""
    spacing = length / count
    index = jnp.arange(slots)
    used = index < count
    positions = (index + 0.5) * spacing
    root = jnp.sqrt(positions)
    return ViscoelasticArray(
        element=element,
        spacing=spacing,
        count=jnp.asarray(count, int),
        profile=jnp.where(used, g(jnp.where(used, positions, 0.5 * spacing)), jnp.inf),
        attach_gap=attach * root,
        tension=element.instantaneous * detach * root,
    )
