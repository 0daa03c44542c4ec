"""The literal MDR spring array in scaled units: N springs of stiffness E*·Δx at the midpoints
x_i = (i − ½)·Δx of [0, L], with the k inner springs attached.

With k springs attached the force is F = 2Δx·(k·d − S_k), S_k = Σ_{i≤k} g(x_i) (3.28 summed
over the springs). A spring attaches moving in once d ≥ h_attach(x) and detaches moving out once
d ≤ h_detach(x) (3.26), each followed by the cascade of neighbours whose thresholds are already
passed. `ComputedSpringArray` stores nothing of size N (thresholds come from the law when asked);
`TabulatedSpringArray` tabulates them (the quasi-static march pads them to a compiled capacity).
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from .law import ContactLaw


class Attached(eqx.Module):
    """The k inner springs in contact and S_k = Σ_{i≤k} g(x_i) (scaled units).

    S_k is summed as springs attach and detach, compensated (Kahan–Babuška–Neumaier): `total`
    holds the rounded sum and `compensation` the round-off it lost, so S_k = total + compensation
    stays within an ulp or so of the exact sum over millions of events.
    """

    count: jax.Array  # k
    total: jax.Array
    compensation: jax.Array

    @staticmethod
    def none() -> "Attached":
        return Attached(jnp.zeros((), int), jnp.zeros(()), jnp.zeros(()))

    def profile_sum(self):
        """S_k."""
        return self.total + self.compensation

    def changed(self, step, term) -> "Attached":
        """k + step springs, S_k + term; back to an exact 0 once no spring is left."""
        total = self.total + term
        lost = jnp.where(jnp.abs(self.total) >= jnp.abs(term), (self.total - total) + term, (term - total) + self.total)
        count = self.count + step
        empty = count == 0
        return Attached(count, jnp.where(empty, 0.0, total), jnp.where(empty, 0.0, self.compensation + lost))


class TabulatedSpringArray(eqx.Module):
    """Tabulated thresholds and prefix sums of N springs (scaled units, O(N) memory): the
    quasi-static march (`quasistatic`) pads them to a compiled capacity. The impact integrators
    use `ComputedSpringArray`, which stores nothing of size N."""

    spacing: jax.Array  # Δx
    attach_level: jax.Array  # [N] h_attach(x_i)
    detach_level: jax.Array  # [N] h_detach(x_i)
    prefix: jax.Array  # [N+1] S_k = Σ_{i≤k} g(x_i)
    beyond_level: jax.Array  # attach threshold of a spring just past the array (inf at a wall)

    @property
    def count(self) -> int:
        return self.attach_level.shape[0]

    def force(self, attached, indentation):
        """F = 2Δx·(k·d − S_k)."""
        return 2.0 * self.spacing * (attached * indentation - self.prefix[attached])

    def attach_cascade(self, attached, indentation):
        """Attach the next springs while their attach thresholds lie at or below d."""

        def more(k):
            return (k < self.count) & (self.attach_level[jnp.minimum(k, self.count - 1)] <= indentation)

        return jax.lax.while_loop(more, lambda k: k + 1, attached)

    def detach_cascade(self, attached, indentation):
        """Detach the edge springs while their detach thresholds lie at or above d."""

        def more(k):
            return (k > 0) & (self.detach_level[jnp.maximum(k - 1, 0)] >= indentation)

        return jax.lax.while_loop(more, lambda k: k - 1, attached)


class ComputedSpringArray(eqx.Module):
    """N midpoint springs on [0, L] (scaled units); thresholds and g(x_i) are evaluated when
    needed, so nothing of size N is stored."""

    law: ContactLaw
    attach_coefficient: jax.Array  # λa of the attach edge h_attach
    detach_coefficient: jax.Array  # λ of the detach edge h_detach
    spacing: jax.Array  # Δx
    count: jax.Array  # N (an integer; may be traced)
    beyond_level: jax.Array  # attach threshold of a spring just past the array (inf at a wall)

    def position(self, index):
        """x of the spring at 0-based `index`: (index + ½)·Δx."""
        return (index + 0.5) * self.spacing

    def frontier(self, count, inward):
        """0-based index of the spring that changes next: k + 1 attaches moving in, k detaches
        moving out (spring 1 when none is attached)."""
        return jnp.where(inward, count, jnp.maximum(count - 1, 0))

    def next_level(self, count, inward):
        """Threshold of that spring: h_attach(x_{k+1}) moving in, h_detach(x_k) moving out."""
        coefficient = jnp.where(inward, self.attach_coefficient, self.detach_coefficient)
        return self.law.edge(self.position(self.frontier(count, inward)), coefficient)

    def change(self, attached: Attached, inward) -> Attached:
        """Attach spring k + 1 (moving in) or detach spring k (moving out)."""
        step = jnp.where(inward, 1, -1)
        return attached.changed(step, step * self.law.g(self.position(self.frontier(attached.count, inward))))

    def force(self, attached: Attached, indentation):
        """F = 2Δx·(k·d − S_k)."""
        return 2.0 * self.spacing * (attached.count * indentation - attached.profile_sum())

    def work(self, attached: Attached, start, end):
        """∫F dd over an arc with k springs attached (F linear in d)."""
        return self.spacing * (attached.count * (end**2 - start**2) - 2.0 * attached.profile_sum() * (end - start))

    def cascade(self, attached: Attached, indentation, inward) -> Attached:
        """Moving in, attach the next springs while their attach thresholds lie at or below d;
        moving out, detach the edge springs while their detach thresholds lie at or above d."""
        return self.cascade_from(attached, self.next_level(attached.count, inward), indentation, inward)[0]

    def cascade_from(self, attached: Attached, level, indentation, inward) -> tuple[Attached, jax.Array]:
        """The cascade of `cascade` from a frontier spring whose threshold `level` is already
        known. Returns the springs then attached and the threshold of the spring it stopped at
        (`next_level`), each threshold computed once: a threshold computed again elsewhere in
        the same program may round otherwise (fused multiply–adds), and a spring whose event
        was located at `level` must then be tested against that very number."""

        def more(state):
            a, level = state
            return jnp.where(
                inward, (a.count < self.count) & (level <= indentation), (a.count > 0) & (level >= indentation)
            )

        def change(state):
            a = self.change(state[0], inward)
            return a, self.next_level(a.count, inward)

        return jax.lax.while_loop(more, change, (attached, jnp.asarray(level)))
