"""The tangential MDR springs: Coulomb friction spring by spring, or over the whole contact.

Each normal spring of the MDR array (stiffness E*·Δx, normal displacement u_z = d − g(x))
carries a tangential spring of stiffness G*·Δx with the displacement u_x (V. L. Popov and
M. Heß, *Method of Dimensionality Reduction in Contact Mechanics and Friction*, Springer 2015,
the chapter on tangential contact; V. L. Popov and M. Heß, Facta Univ. Mech. Eng. 12 (2014) 1;
E. Willert and V. L. Popov, ZAMM 96 (2016) 1089). Normal and tangential are uncoupled
(Goodman's approximation, exact for elastically similar bodies): the normal springs do not feel
the tangential ones. In scaled units (lengths and displacements as in `law.ContactLaw`, forces
in E*·ℓx·ℓz) the array's tangential force is Q = κ·Σ u_i over the springs of one half-line,
κ = 2(G*/E*)·Δx (the 2 for the mirrored half-line, as the normal force F = 2Δx·Σ(d − g_i)).

Two friction limits, each a projection of trial displacements onto what friction admits:

- `PerSpring`: each spring sticks while |G*Δx·u_x| ≤ μ·E*Δx·u_z and slips at that limit,
  |u_x| ≤ λ·max(u_z, 0) with λ = μE*/G*; a spring in tension (adhesion) or detached carries no
  friction. This is Coulomb's law at each point of the MDR, which gives Cattaneo–Mindlin partial
  slip and the Mindlin–Deresiewicz memory of the loading path exactly (K. L. Johnson, *Contact
  Mechanics*, 1985, §7.2 and §7.4).
- `WholeContact`: the limit of Thornton (1991) used by LAMMPS's `jkr` model: the whole contact
  slips when |Q| would exceed μ·|F_n + 2F_c| (F_c = (3/2)πRΔγ for a JKR sphere, 0 without
  adhesion: then μ|F_n|); the displacements are scaled back together, as a DEM code rescales
  its single history vector (C. Thornton, J. Phys. D 24 (1991) 1942; C. Thornton and K. K. Yin,
  Powder Technol. 65 (1991) 153). All springs in contact carry tangential stiffness.
"""

import abc

import equinox as eqx
import jax
import jax.numpy as jnp


class Projection(eqx.Module):
    """Trial displacements projected by a friction limit (scaled)."""

    displacement: jax.Array  # [N] u_i after the projection
    free: jax.Array  # [N] whether spring i kept its trial displacement (sticks)
    force_slope: jax.Array  # dQ/d(trial shift) at this projection: κ·(springs that stick)


class AbstractFrictionLimit(eqx.Module):
    """What friction admits of the tangential springs (scaled units)."""

    stiffness: eqx.AbstractVar[jax.Array]  # κ = 2(G*/E*)·Δx

    @abc.abstractmethod
    def project(self, trial, attached, indentation, heights, normal_force) -> Projection:
        """The displacements friction admits of the `trial` ones ([N]) for springs `attached`
        ([N] bool) at the indentation d with the springs' heights g_i ([N]) and the array's
        normal force F_n (scaled)."""

    @abc.abstractmethod
    def bound(self, attached, indentation, heights, normal_force):
        """The largest |Q| (scaled) friction admits in this state."""

    def force(self, displacement):
        """Q = κ·Σ u_i (scaled)."""
        return self.stiffness * jnp.sum(displacement)


class PerSpring(AbstractFrictionLimit):
    """Coulomb's law spring by spring: |u_i| ≤ λ·max(d − g_i, 0), λ = μE*/G*."""

    stiffness: jax.Array
    ratio: jax.Array  # λ = μE*/G*

    def limits(self, attached, indentation, heights):
        """λ·max(d − g_i, 0) for attached springs, 0 for the others."""
        return jnp.where(attached, self.ratio * jnp.maximum(indentation - heights, 0.0), 0.0)

    def project(self, trial, attached, indentation, heights, normal_force) -> Projection:
        limits = self.limits(attached, indentation, heights)
        free = jnp.abs(trial) < limits
        displacement = jnp.where(free, trial, jnp.sign(trial) * limits)
        return Projection(displacement, free, self.stiffness * jnp.sum(free))

    def bound(self, attached, indentation, heights, normal_force):
        return self.stiffness * jnp.sum(self.limits(attached, indentation, heights))


class WholeContact(AbstractFrictionLimit):
    """Thornton's whole-contact limit: |Q| ≤ μ·|F_n + 2F_c|, the springs scaled back together."""

    stiffness: jax.Array
    coefficient: jax.Array  # μ
    adhesive_load: jax.Array  # 2F_c (scaled; 0 without adhesion)

    def project(self, trial, attached, indentation, heights, normal_force) -> Projection:
        trial = jnp.where(attached, trial, 0.0)
        trial_force = self.force(trial)
        most = self.bound(attached, indentation, heights, normal_force)
        sticks = jnp.abs(trial_force) <= most
        # A slipping contact keeps the pattern of its trial displacements, scaled to the limit.
        scale = most / jnp.where(sticks, 1.0, jnp.abs(trial_force))
        displacement = jnp.where(sticks, trial, trial * scale)
        free = sticks & attached
        return Projection(displacement, free, jnp.where(sticks, self.stiffness * jnp.sum(attached), 0.0))

    def bound(self, attached, indentation, heights, normal_force):
        return jnp.where(jnp.any(attached), self.coefficient * jnp.abs(normal_force + self.adhesive_load), 0.0)


def stick_radius(projection: Projection, attached, spacing):
    """Inner radius c of the slip zone (scaled): the boundary iΔx below the innermost attached
    spring that slips (springs at x_i = (i + ½)Δx), the contact radius kΔx where none slips."""
    count = jnp.sum(attached)
    index = jnp.arange(attached.shape[0])
    slipping = attached & ~projection.free
    first = jnp.min(jnp.where(slipping, index, count))
    return first * spacing
