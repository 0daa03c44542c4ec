"""Maugis–Dugdale adhesion on a viscoelastic half-space: the spring array of
`viscoelastic_springs` (midpoint springs x_j, each the medium's Prony element) with a Dugdale
zone a < r < c around the contact (V. L. Popov, M. Heß, E. Willert, Handbook of Contact
Mechanics, Springer 2019, §3.8).

- Springs in contact (x < a) follow the body, u = d − g(x), as in `viscoelastic_springs`.
- Free springs are under force control: the Dugdale stress σ0 over a < r < c is, in the MDR, the
  line load −2σ0·√(c² − x²) on the springs of the zone (3.148). Spring j carries it on its hat
  function φ_j (1 at x_j, 0 at its neighbours, flat on [0, x_1]),
  f_j(c) = −(2σ̂/Δx)·∫ φ_j(x)·√(c² − x²) dx over [0, c] (0 beyond c), and creeps under it
  (`PronyElement.forced`; over a step the load is linear in time from f_j(c₀) to f_j(c₁)).
- The zone radius c is where the gap reaches the range h (3.152). The 3-D gap at r = c is the
  Abel transform of the springs' 1-D gaps s_j = u_j − (d − g(x_j)) (0 in contact), interpolated
  linearly between the springs and integrated exactly against the kernel:
  gap(c) = (2/π)·Σ_j s_j·K_j(c), K_j(c) = ∫ φ_j(x)/√(c² − x²) dx over [0, c].
  With the same hat functions for the loads this is the stationarity in c of the interface energy
  U = −Δγ·πc² + 2Δx·Σ_j (−f_j(c))·s_j (the adhesive stress's work on the gaps, σ0·∫gap dA, in
  the MDR; d(Δx·f_j)/dc = −2σ̂·c·K_j): U is the Dugdale zone's energy, so the body's work
  is the dashpots' dissipation, the stored elastic energy, U and the snaps. (Gaps constant over
  each spring's cell would give the kernel a √(c − x) onset at every cell, and c(d) a staircase.)
- The edge is continuous: a spring in contact lets go where its force falls to its zone load
  f_j(c), a free one attaches where its gap s_j closes; neither snaps. The contact stays one disc
  (`change_times`).
- The zone is born (before contact) where the first spring's gap falls to h: the loads jump on
  at the stable root c of the range condition (the first from below where the gap rises through
  h), the springs respond at the instantaneous modulus E₀*. It collapses where the range
  condition has no root near c (the fold of the pull-off): the loads drop, the springs in
  tension let go, each snapping at E₀*. Both snaps dissipate −(Δ stored + ΔU).

In the elastic limits the zone springs hold u_j = f_j/E* (τ → 0: E∞*, τ → ∞: E₀*) and the array
is the Maugis–Dugdale spring array of that modulus (`dugdale_springs`, which takes the zone's
transform exactly; here the interpolated gaps converge to it in Δx).
Units of `Scales` (E∞ = 1); σ̂ = σ0·ℓx/(E∞*·ℓz), ĥ = h/ℓz.
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from .outward_root import root_outward
from .prony import PronyElement
from .viscoelastic_springs import Evolved, SpringStates, StepTotals, change_times
from .zone_geometry import zone_kernel, zone_loads
from .zone_steps import FOLD_HALVINGS, FoldBracket, Segment, Snap, Walked

# Sub-steps of the zone's path: c moves at most this many spacings in one (near the fold, where
# c(t) runs as a square root of the time left, and after the zone's birth), down to the step over
# 2^_SUBSTEP_HALVINGS.
_SUBSTEP_MOVE = 0.25
_SUBSTEP_HALVINGS = 12


class ZoneSprings(eqx.Module):
    """The springs and the Dugdale zone's radius c (0: no zone)."""

    springs: SpringStates
    zone: jax.Array


class DugdaleZoneArray(eqx.Module):
    """N viscoelastic springs with a Dugdale zone (scaled). Slots beyond `count` never touch."""

    element: PronyElement
    spacing: jax.Array  # Δx
    count: jax.Array  # N
    profile: jax.Array  # [slots] g(x_j) (inf beyond N)
    stress: jax.Array  # σ̂
    range: jax.Array  # ĥ

    @property
    def slots(self) -> int:
        return self.profile.shape[0]

    @property
    def length(self):
        return self.spacing * self.count

    def onset(self, indentation):
        """Where the contact phase starts: the tip within the range, d = −ĥ (or `indentation`
        where the body starts nearer)."""
        return jnp.maximum(-self.range, indentation)

    def virgin(self, terms: int) -> ZoneSprings:
        """The medium at rest, no zone."""
        return ZoneSprings(SpringStates.virgin(self.slots, terms), jnp.zeros(()))

    def springs_of(self, state: ZoneSprings) -> SpringStates:
        """The springs' states, without the zone's radius."""
        return state.springs

    def engaged(self, state: ZoneSprings):
        """Whether the body feels the medium: a contact or a zone."""
        return jnp.any(state.springs.attached) | (state.zone > 0.0)

    def loads(self, zone):
        """f_j(c) [slots]: the zone's line load on the springs' hat functions (`zone_loads`)."""
        return zone_loads(self.spacing, self.slots, self.stress, zone)

    def kernel(self, zone):
        """K_j(c) [slots]: the springs' hat functions against the Abel kernel (`zone_kernel`)."""
        return zone_kernel(self.spacing, self.slots, zone)

    def gaps(self, springs: SpringStates, indentation):
        """s_j = u_j − (d − g(x_j)) of the free springs (0 attached or unused)."""
        used = jnp.arange(self.slots) < self.count
        gap = springs.displacement - indentation + jnp.where(used, self.profile, 0.0)
        return jnp.where(springs.attached | ~used, 0.0, gap)

    def range_excess(self, springs: SpringStates, indentation, zone):
        """gap(c) − ĥ: the Abel transform of the 1-D gaps at r = c less the range (3.152)."""
        return (2.0 / jnp.pi) * jnp.sum(self.kernel(zone) * self.gaps(springs, indentation)) - self.range

    def interface(self, state: ZoneSprings, indentation):
        """U = −πσ̂ĥc² + 2Δx·Σ_j (−f_j)·s_j: the zone's interface energy (0 without a zone)."""
        zone = state.zone
        work = 2.0 * self.spacing * jnp.sum(-self.loads(zone) * self.gaps(state.springs, indentation))
        return jnp.where(zone > 0.0, work - jnp.pi * self.stress * self.range * zone**2, 0.0)

    def forces(self, state: ZoneSprings):
        """Each spring's force per width: its element's in contact, its zone load free."""
        springs = state.springs
        own = self.element.force(springs.displacement, springs.stretches)
        return jnp.where(springs.attached, own, self.loads(state.zone))

    def force(self, state: ZoneSprings):
        """F = 2Δx·Σ f_j (the contact's springs and the zone's)."""
        return 2.0 * self.spacing * jnp.sum(self.forces(state))

    def stored(self, state: ZoneSprings):
        """The elastic energy the springs hold."""
        springs = state.springs
        return 2.0 * self.spacing * jnp.sum(self.element.stored(springs.displacement, springs.stretches))

    def contact_radius(self, state: ZoneSprings):
        """The outer edge of the outermost attached spring (0 without contact)."""
        outermost = jnp.max(jnp.where(state.springs.attached, jnp.arange(self.slots), -1))
        return (outermost + 1) * self.spacing

    def overflows(self, state: ZoneSprings):
        """Whether the contact or the zone reaches the array's end."""
        return state.springs.attached[self.count - 1] | (state.zone >= self.length)

    def advance(self, state: ZoneSprings, indentation, rate, duration) -> tuple[ZoneSprings, StepTotals]:
        """The medium after `duration` with d(s) = `indentation` + `rate`·s, and the step's totals
        (`released`: the snaps' dissipation, the zone's birth and collapse −(Δ stored + ΔU) and
        the edge's springs letting go; `gained`: the edge's springs attaching)."""
        springs, zone = state.springs, state.zone
        on = zone > 0.0
        born_at = jnp.where(on, 0.0, self._birth_time(springs, indentation, rate, duration))
        before = self._segment(springs, zone, zone, indentation, rate, born_at)  # no zone: loads 0
        depth = indentation + rate * born_at
        born = ~on & (born_at < duration)
        rest = duration - born_at
        birth = jax.lax.cond(
            born,
            lambda: self._birth(before.springs, depth, rate, rest),
            lambda: Snap(before.springs, zone, jnp.zeros(())),
        )
        springs = jax.tree.map(lambda b, k: jnp.where(born, b, k), birth.springs, before.springs)
        zone = jnp.where(born, birth.zone, zone)
        walk = self._zone_walk(springs, zone, depth, rate, rest, held=~(on & (rest > 0.0)))
        folds = walk.folds
        folded = depth + rate * walk.elapsed
        collapse = self._collapse(ZoneSprings(walk.springs, walk.zone), folded)
        springs = jax.tree.map(lambda c, k: jnp.where(folds, c, k), collapse.springs, walk.springs)
        none = jnp.zeros_like(zone)
        after = self._segment(springs, none, none, folded, rate, rest - walk.elapsed)  # no zone
        snaps = jnp.where(born, birth.dissipation, 0.0) + jnp.where(folds, collapse.dissipation, 0.0)
        last_release = jnp.maximum(
            jnp.maximum(before.last_release, born_at + walk.last_release),
            born_at + walk.elapsed + jnp.where(folds, jnp.maximum(after.last_release, 0.0), after.last_release),
        )
        ended = jax.tree.map(lambda f, k: jnp.where(folds, f, k), after.springs, walk.springs)
        zone = jnp.where(folds, 0.0, jnp.where(walk.overflow, self.length, walk.zone))
        return ZoneSprings(ended, zone), StepTotals(
            impulse=before.impulse + walk.impulse + after.impulse,
            dissipation=before.dissipation + walk.dissipation + after.dissipation,
            released=snaps + before.released + walk.released + after.released,
            gained=before.gained + walk.gained + after.gained,
            last_release=last_release,
        )

    def _zone_walk(self, springs: SpringStates, zone, indentation, rate, duration, held) -> Walked:
        """The zone's part of a step: sub-steps, each with the loads linear in time to the root of
        the range condition at its end, halved (down to the step / 2^`_SUBSTEP_HALVINGS`) where c
        would move more than `_SUBSTEP_MOVE`·Δx or the root is lost, doubled again after each one
        taken. A root lost at the shortest sub-step is the fold: located by bisecting that
        sub-step (`FOLD_HALVINGS` halvings, iterations of the walk's own loop, so that the range
        condition's search is compiled once), the walk goes on to it (c runs there as a square
        root of the time left: the sub-steps shrink towards it) and stops. No root outward: the
        zone outgrows the array (`overflow`), the walk stops. `held` (the step the zone is born in,
        or none): one sub-step at the loads of `zone`, no search."""
        shortest = duration * 2.0**-_SUBSTEP_HALVINGS
        zero = jnp.zeros_like(duration)

        def walking(walk: Walked):
            return ~walk.folds & ~walk.overflow & ~walk.finished

        def substep(walk: Walked) -> Walked:
            left = walk.until - walk.elapsed
            length = jnp.minimum(walk.length, left)
            depth = indentation + rate * walk.elapsed
            fold = walk.fold
            bisecting = fold.halvings < FOLD_HALVINGS
            middle = 0.5 * (fold.low + fold.high)
            end, found, outward = self._zone_end(
                walk.springs, walk.zone, depth, rate, jnp.where(bisecting, middle, length), held
            )
            end, found, outward = jnp.where(held, walk.zone, end), found | held, outward & ~held
            # A halving of the fold's bracket: the range condition keeps a root up to `low`.
            low = jnp.where(found, middle, fold.low)
            located_at = fold.halvings + 1 == FOLD_HALVINGS
            halved = eqx.tree_at(
                lambda w: (w.fold, w.length, w.until),
                walk,
                (
                    FoldBracket(low, jnp.where(found, fold.high, middle), fold.halvings + 1),
                    jnp.where(located_at, low, walk.length),
                    jnp.where(located_at, walk.elapsed + low, walk.until),
                ),
            )
            inward_lost = ~found & ~outward
            can_halve = length > shortest
            halve = can_halve & (inward_lost | (found & (jnp.abs(end - walk.zone) > _SUBSTEP_MOVE * self.spacing)))
            stuck = inward_lost & ~can_halve  # the fold within this sub-step: bisected next
            located = stuck & ~walk.pending
            take = found & ~halve
            taken = jnp.where(take, length, 0.0)
            part = self._segment(walk.springs, walk.zone, end, depth, rate, taken)
            # c still jumping at the shortest sub-step: a snap of the zone between two roots (the
            # discrete zone's fold at a spring), which dissipates what the energies say.
            jumps = take & ~can_halve & (jnp.abs(end - walk.zone) > _SUBSTEP_MOVE * self.spacing)
            energy = self.stored(ZoneSprings(walk.springs, walk.zone)) + self.interface(
                ZoneSprings(walk.springs, walk.zone), depth
            )
            after = ZoneSprings(part.springs, end)
            change = self.stored(after) + self.interface(after, depth + rate * taken) - energy
            snap = rate * part.impulse - part.dissipation - part.released + part.gained - change
            reached = take & (length >= left)
            pending = walk.pending | stuck
            released = jnp.where(take, part.last_release, -jnp.inf)
            stepped = Walked(
                springs=jax.tree.map(lambda p, k: jnp.where(take, p, k), part.springs, walk.springs),
                zone=jnp.where(take, end, walk.zone),
                elapsed=walk.elapsed + taken,
                impulse=walk.impulse + jnp.where(take, part.impulse, 0.0),
                dissipation=walk.dissipation + jnp.where(take, part.dissipation, 0.0),
                released=walk.released + jnp.where(take, part.released + jnp.where(jumps, snap, 0.0), 0.0),
                gained=walk.gained + jnp.where(take, part.gained, 0.0),
                last_release=jnp.maximum(walk.last_release, walk.elapsed + released),
                folds=(pending & reached) | (stuck & walk.pending),
                overflow=~found & outward,
                length=jnp.where(halve, 0.5 * length, jnp.where(take, 2.0 * length, length)),
                finished=reached & ~pending,
                until=walk.until,
                pending=pending,
                fold=FoldBracket(jnp.zeros_like(length), length, jnp.where(located, 0, fold.halvings)),
            )
            return jax.tree.map(lambda h, s: jnp.where(bisecting, h, s), halved, stepped)

        false = jnp.asarray(False)
        start = Walked(
            springs=springs,
            zone=zone,
            elapsed=zero,
            impulse=zero,
            dissipation=zero,
            released=zero,
            gained=zero,
            last_release=zero - jnp.inf,
            folds=false,
            overflow=false,
            length=duration,
            finished=false,
            until=duration,
            pending=false,
            fold=FoldBracket.idle(duration),
        )
        return jax.lax.while_loop(walking, substep, start)

    def _segment(self, springs: SpringStates, zone, end, indentation, rate, duration) -> Segment:
        """The springs over `duration` with the zone loads linear in time from f(`zone`) to
        f(`end`), each spring changing at most once (`change_times`)."""
        start_load = self.loads(zone)
        load_rate = (self.loads(end) - start_load) / jnp.where(duration > 0.0, duration, 1.0)
        inputs = (springs, start_load, load_rate, indentation, rate)
        change = change_times(self._criterion, inputs, springs.attached, duration)
        first = self._evolve(springs, start_load, load_rate, rate, change)
        changing = change < duration
        leaving = springs.attached & changing
        # Where the disc's edge rule held a spring past its own change, it snaps at E₀* (its force
        # onto its zone load, or its surface onto the body); else the jump is the root's residual.
        e0 = self.element.instantaneous
        before = first.states
        surplus = start_load + load_rate * change - self.element.force(before.displacement, before.stretches)
        onto = indentation + rate * change - self.profile
        jump = jnp.where(changing, jnp.where(leaving, surplus / e0, onto - before.displacement), 0.0)
        moved = self._snapped(SpringStates(springs.attached ^ changing, before.displacement, before.stretches), jump)
        second = self._evolve(moved, start_load + load_rate * change, load_rate, rate, duration - change)
        width = 2.0 * self.spacing
        return Segment(
            springs=second.states,
            impulse=width * jnp.sum(first.impulse + second.impulse),
            dissipation=width * jnp.sum(first.dissipation + second.dissipation),
            released=width * jnp.sum(jnp.where(leaving, 0.5 * e0 * jump**2, 0.0)),
            gained=width * jnp.sum(jnp.where(changing & ~leaving, 0.5 * e0 * jump**2, 0.0)),
            last_release=jnp.max(jnp.where(leaving, change, -jnp.inf)),
        )

    def _evolve(self, springs: SpringStates, load, load_rate, rate, duration) -> Evolved:
        """Each spring after `duration` [slots]: attached, following the body at `rate`; free,
        under its load `load` + `load_rate`·s."""
        element = self.element
        rates = jnp.full(self.slots, rate)
        loaded = element.loaded(springs.displacement, springs.stretches, rates, duration)
        forced = element.forced(springs.stretches, load, load_rate, duration)
        attached = springs.attached
        return Evolved(
            states=SpringStates(
                attached,
                jnp.where(attached, springs.displacement + rate * duration, forced.displacement),
                jnp.where(attached[:, None], loaded.stretches, forced.stretches),
            ),
            impulse=jnp.where(attached, loaded.force_integral, (load + 0.5 * load_rate * duration) * duration),
            dissipation=jnp.where(attached, loaded.dissipation, forced.dissipation),
        )

    def _criterion(self, inputs, time):
        """(value, slope) at `time` of what changes a spring (below 0: it changes): attached, its
        force less its zone load; free, its gap to the body."""
        springs, load, load_rate, indentation, rate = inputs
        element = self.element
        rates = jnp.full(self.slots, rate)
        force, force_slope = element.loaded_force(springs.displacement, springs.stretches, rates, time)
        surface, surface_slope = element.forced_surface(springs.stretches, load, load_rate, time)
        gap = surface - (indentation + rate * time - self.profile)
        attached = springs.attached
        return (
            jnp.where(attached, force - load - load_rate * time, gap),
            jnp.where(attached, force_slope - load_rate, surface_slope - rate),
        )

    def _birth_time(self, springs: SpringStates, indentation, rate, duration):
        """When the first spring's gap falls to ĥ, the zone's birth (`duration` where it does not;
        0 where it is in contact)."""

        def criterion(inputs, time):
            stretches, displacement, attached = inputs
            surface, slope = self.element.free_surface(stretches, time)
            value = surface - (indentation + rate * time - self.profile[:1]) - self.range
            return jnp.where(attached, -1.0, value), jnp.where(attached, 0.0, slope - rate)

        first = (springs.stretches[:1], springs.displacement[:1], springs.attached[:1])
        return change_times(criterion, first, jnp.zeros(1, bool), duration)[0]

    def _snapped(self, springs: SpringStates, jump):
        """The springs after an instantaneous jump of their displacement (dashpots at rest)."""
        return SpringStates(springs.attached, springs.displacement + jump, springs.stretches + jump[:, None])

    def _birth(self, springs: SpringStates, indentation, rate, duration) -> Snap:
        """The zone born at `indentation`, `duration` before the step's end: its loads jump on,
        the free springs responding at E₀* (those it pulls onto the body attach), and are held
        while the springs creep to the step's end, where c is the first root from below of the
        range condition. With the loads held, the interface energy U changes by their work, so
        the snap's −(Δ stored + ΔU) closes the balance whatever the creep; τ → 0 and τ → ∞ end
        on the elastic zone of E∞* and of E₀*."""
        e0 = self.element.instantaneous
        gaps = self.gaps(springs, indentation)

        def jumped(zone):
            # A spring the load would pull past the body lands on it instead (a contact born with
            # the zone: its force then exceeds its zone load).
            pulled = jnp.where(springs.attached, 0.0, self.loads(zone) / e0)
            lands = ~springs.attached & (gaps + pulled < 0.0)
            snapped = self._snapped(springs, jnp.where(lands, -gaps, pulled))
            return SpringStates(springs.attached | lands, snapped.displacement, snapped.stretches)

        def excess(zone):
            after = self._segment(jumped(zone), zone, zone, indentation, rate, duration)
            return self.range_excess(after.springs, indentation + rate * duration, zone)

        start = 0.5 * self.spacing
        zone, _, _ = root_outward(excess, start, self.spacing, self.length, value=-1.0)
        born = ZoneSprings(jumped(zone), zone)
        dissipation = self.stored(ZoneSprings(springs, zone)) - self.stored(born) - self.interface(born, indentation)
        return Snap(born.springs, zone, dissipation)

    def _collapse(self, state: ZoneSprings, indentation) -> Snap:
        """The zone gone at `indentation`: its loads drop and the springs in tension let go,
        each snapping at E₀*."""
        springs = state.springs
        forces = self.forces(state)
        leaving = springs.attached & (forces < 0.0)
        jump = jnp.where(springs.attached & ~leaving, 0.0, -forces / self.element.instantaneous)
        snapped = self._snapped(springs, jump)
        snapped = SpringStates(springs.attached & ~leaving, snapped.displacement, snapped.stretches)
        gone = ZoneSprings(snapped, jnp.zeros(()))
        dissipation = self.stored(state) + self.interface(state, indentation) - self.stored(gone)
        return Snap(snapped, jnp.zeros(()), dissipation)

    def _zone_end(self, springs: SpringStates, zone, indentation, rate, duration, skip=False):
        """(c₁, found, outward): the zone radius at the end of a step from `zone` that satisfies the range
        condition there, the springs having crept under loads linear in time to f(c₁); the root
        nearest `zone` in the direction the condition points (`outward`: c grows). Not found
        inward: the fold. Nothing searched (nor found) where `skip`."""
        depth = indentation + rate * duration
        safe = jnp.where(zone > 0.0, zone, 0.5 * self.spacing)

        def excess(end):
            after = self._segment(springs, safe, end, indentation, rate, duration)
            return self.range_excess(after.springs, depth, end)

        root, found, here = root_outward(excess, safe, self.spacing, self.length, skip=skip)
        return root, found, here < 0.0


def zone_array(element: PronyElement, g, length, count, slots: int, stress, adhesion_range) -> DugdaleZoneArray:
    """`count` springs at the midpoints of [0, `length`] in `slots` slots (the rest never touch)
    for the scaled profile `g`, the Dugdale stress σ̂ = `stress` and the range ĥ = `adhesion_range`."""
    spacing = length / count
    index = jnp.arange(slots)
    used = index < count
    positions = (index + 0.5) * spacing
    return DugdaleZoneArray(
        element=element,
        spacing=spacing,
        count=jnp.asarray(count, int),
        profile=jnp.where(used, g(jnp.where(used, positions, 0.5 * spacing)), jnp.inf),
        stress=jnp.asarray(stress),
        range=jnp.asarray(adhesion_range),
    )
