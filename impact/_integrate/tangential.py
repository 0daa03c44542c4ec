"""The tangential springs of a spring array over one time step, and the body's sliding and spin.

The body (mass 1 in scaled units) slides with the velocity v_t of its centre and spins with the
surface speed Ω = Rω (R the lever arm from the centre to the contact, ω > 0 the spin that rolls
it along +x); the contact point slides with w = v_t − Ω. The springs' tangential force Q
decelerates the centre and spins the body up: dv_t/dt = −Q, dΩ/dt = ρ·Q with ρ = mR²/I, so
dw/dt = −(1 + ρ)·Q; a spring that sticks follows the contact point, du_i/dt = w.

One step of length h is the trapezoidal rule (implicit, second order, A-stable),

    W = w − (1 + ρ)·h·(Q + Q')/2,    u'_i = P(u_i + h·(w + W)/2),    Q' = κ·Σ u'_i,

with P the friction limit's projection at the end of the step (`_law.tangential`), solved for
the new slip velocity W exactly: the residual is piecewise linear and increasing in W, and a
Newton iteration kept inside a bracket (bisection where a step leaves it) ends on its root.
Its discrete energy balance is exact: the kinetic energy ½v_t² + ½Ω²/ρ plus the springs'
½κ·Σu_i² falls by D = κ·Σ ½(u_i + u'_i)·s_i, s_i the slip of spring i (its trial minus its
projected displacement), in every step whatever h: D is the friction work.
"""

import equinox as eqx
import jax
import jax.numpy as jnp

from .._core.pytree import replace
from .._law.tangential import AbstractFrictionLimit, Projection, stick_radius

# Iterations of the bracketed Newton solve at most (bisection alone halves the bracket to its
# last bits in about 60; a Newton step on the right piece ends it in one).
_MAX_ITERATIONS = 80


class TangentialState(eqx.Module):
    """The tangential springs and the body's sliding and spin (scaled units)."""

    displacement: jax.Array  # [N] u_i of the springs (0 where detached)
    velocity: jax.Array  # v_t of the centre
    surface_speed: jax.Array  # Ω = Rω
    force: jax.Array  # Q = κ·Σ u_i
    stick_radius: jax.Array  # inner radius c of the slip zone after the last step
    work: jax.Array  # friction work of the contact under way

    @property
    def slip_velocity(self):
        """w = v_t − Ω, the contact point's sliding velocity."""
        return self.velocity - self.surface_speed


class TangentialMotion(eqx.Module):
    """What the tangential motion needs besides its state (scaled units)."""

    limit: AbstractFrictionLimit
    heights: jax.Array  # [N] g_i of the springs
    rotation: jax.Array  # ρ = mR²/I
    spacing: jax.Array  # Δx

    def start(self, velocity, surface_speed) -> TangentialState:
        """No spring displaced, the body sliding with `velocity` and spinning with `surface_speed`."""
        zero = jnp.zeros(())
        return TangentialState(jnp.zeros_like(self.heights), velocity, surface_speed, zero, zero, zero)

    def step(self, state: TangentialState, h, indentation, attached, normal_force) -> TangentialState:
        """Advance by h to the indentation d, springs `attached` ([N] bool) and normal force F_n
        of the end of the step."""
        gain = 0.5 * (1.0 + self.rotation) * h
        slip = state.slip_velocity

        def projected(new_slip) -> Projection:
            trial = jnp.where(attached, state.displacement + 0.5 * h * (slip + new_slip), 0.0)
            return self.limit.project(trial, attached, indentation, self.heights, normal_force)

        def residual(new_slip):
            projection = projected(new_slip)
            value = new_slip - slip + gain * (state.force + self.limit.force(projection.displacement))
            return value, 1.0 + gain * 0.5 * h * projection.force_slope

        bound = self.limit.bound(attached, indentation, self.heights, normal_force)
        lower = slip - gain * (state.force + bound)
        upper = slip - gain * (state.force - bound)
        scale = jnp.abs(slip) + gain * (jnp.abs(state.force) + bound)
        new_slip = bracketed_newton(residual, slip, lower, upper, scale)

        projection = projected(new_slip)
        trial = jnp.where(attached, state.displacement + 0.5 * h * (slip + new_slip), 0.0)
        displacement = projection.displacement
        force = self.limit.force(displacement)
        mean = 0.5 * (state.force + force)
        work = self.limit.stiffness * jnp.sum(0.5 * (state.displacement + displacement) * (trial - displacement))
        return replace(
            state,
            displacement=displacement,
            velocity=state.velocity - h * mean,
            surface_speed=state.surface_speed + self.rotation * h * mean,
            force=force,
            stick_radius=stick_radius(projection, attached, self.spacing),
            work=state.work + work,
        )

    def detach(self, state: TangentialState, attached) -> TangentialState:
        """Springs that left the contact lose their displacement; its energy ½κ·u_i² is lost
        (booked as friction work: nothing recovers it)."""
        lost = jnp.where(attached, 0.0, state.displacement)
        displacement = jnp.where(attached, state.displacement, 0.0)
        return replace(
            state,
            displacement=displacement,
            force=self.limit.force(displacement),
            work=state.work + 0.5 * self.limit.stiffness * jnp.sum(lost**2),
        )


def bracketed_newton(residual, start, lower, upper, scale):
    """The root of an increasing piecewise-linear `residual` (returning value and slope) in
    [lower, upper], from `start`: Newton steps, a bisection where one leaves the bracket; ends
    where a step moves less than a few ulps of `scale`."""
    tolerance = 8.0 * jnp.finfo(jnp.float64).eps * scale

    def running(carry):
        _, _, _, moved, count = carry
        return (moved > tolerance) & (count < _MAX_ITERATIONS)

    def iterate(carry):
        x, low, high, _, count = carry
        value, slope = residual(x)
        low = jnp.where(value <= 0.0, x, low)
        high = jnp.where(value >= 0.0, x, high)
        newton = x - value / slope
        inside = (newton >= low) & (newton <= high)
        following = jnp.where(inside, newton, 0.5 * (low + high))
        return following, low, high, jnp.abs(following - x), count + 1

    start = jnp.clip(start, lower, upper)
    first = (start, lower, upper, jnp.asarray(jnp.inf), jnp.zeros((), int))
    return jax.lax.while_loop(running, iterate, first)[0]
