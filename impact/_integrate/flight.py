"""Free flight between contacts: analytic, from the carry's state to the next touch (or out of
reach for good), shared by every integrator."""

import jax.numpy as jnp

from .._core.pytree import replace
from .._effects.gravity import flight_to_touch
from .carry import Carry, log_event, store_samples
from .codes import DONE, EVENT_CODE, Status
from .problem import AbstractProblem, Options
from .transitions import Next, touch


def land(
    problem: AbstractProblem, options: Options, c: Carry, surface, landing: Next, landing_force, samples: bool
) -> Carry:
    """Fly to the touch at d = `surface` and start the contact `landing` there (its jump-in),
    with the force `landing_force`; or end the run where the body never comes back, where the
    bounces are used up or where the touch lies beyond the time limit.

    With `samples` the flight's trajectory is stored in its block of the buffer (integrators
    that store their own rows pass False).
    """
    duration, speed, reaches = flight_to_touch(problem.motion.gravity, c.d - surface, c.v)
    touch_time = c.t + duration
    over_bounces = c.contacts >= options.max_bounces
    over_time = touch_time > problem.motion.time_limit
    lands = reaches & ~over_bounces & ~over_time
    if samples and options.samples_per_phase:
        c = store_samples(c, options, _flight_rows(problem, options, c, lands, duration))
    status = Status.where(
        ~reaches, Status.separated, Status.where(over_bounces, Status.bounce_limit, Status.time_limit)
    )
    stopped = landing.stops
    c = log_event(c, touch_time, EVENT_CODE["touch"], lands)
    c = log_event(c, c.t, EVENT_CODE["limit"], reaches & ~lands)
    c = log_event(c, touch_time, EVENT_CODE["limit"], lands & stopped)
    first = c.contacts == 0
    return replace(
        c,
        t=jnp.where(lands, touch_time, c.t),
        d=jnp.where(lands, surface, c.d),
        v=jnp.where(lands, speed, c.v),
        mode=jnp.where(lands, jnp.where(stopped, DONE, landing.mode), DONE),
        segment=landing.segment,
        radius=landing.radius,
        phases=c.phases + 1,
        contacts=c.contacts + jnp.asarray(lands, int),
        status=Status.where(lands, Status.where(stopped, landing.stop, c.status), status),
        touch_velocity=jnp.where(lands & first, speed, c.touch_velocity),
        touch_time=jnp.where(lands & first, touch_time, c.touch_time),
        contact_work=jnp.zeros(()),
        contact_viscous_work=jnp.zeros(()),
        max_force=jnp.where(lands, jnp.maximum(c.max_force, landing_force), c.max_force),
        min_force=jnp.where(lands, jnp.minimum(c.min_force, landing_force), c.min_force),
    )


def land_on_touch(problem, options: Options, c: Carry) -> Carry:
    """`land` on the undeformed surface (d = 0) with the continuum law's jump-in
    (`transitions.touch`)."""
    landing = touch(problem)
    return land(problem, options, c, 0.0, landing, problem.law.force(landing.radius, 0.0), samples=True)


def _flight_rows(problem: AbstractProblem, options: Options, c: Carry, lands, duration):
    """Samples (t, d, v, F = 0, a = 0) of the arc to the touch (only its start where it does not land)."""
    gravity = problem.motion.gravity
    tau = jnp.linspace(0.0, jnp.where(lands, duration, 0.0), options.samples_per_phase)
    kept = lands | (jnp.arange(options.samples_per_phase) == 0)
    zeros = jnp.zeros_like(tau)
    rows = jnp.stack(
        [c.t + tau, c.d + c.v * tau + 0.5 * gravity * tau**2, c.v + gravity * tau, zeros, zeros],
        axis=1,
    )
    return jnp.where(kept[:, None], rows, jnp.nan)
