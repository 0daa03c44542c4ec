"""Names of the motion phases, events and statuses shared by the integrators."""

from typing import Any

import equinox as eqx
import jax
import jax.numpy as jnp

# Motion phases (the contact radius a(d) of each is smooth; changes between them are events).
FLIGHT = 0  # no contact: analytic free flight or ballistic arc
ADVANCE = 1  # a on an increasing segment of the attach edge function (loading)
HOLD = 2  # a fixed at its largest value (or at the body's wall)
RECEDE = 3  # a on an increasing segment of the detach edge function (unloading)
DONE = 4

# Event kinds, in the order of their codes.
EVENT_KINDS = (
    "touch",  # first contact of a bounce (with the jump-in, if any); Maugis–Dugdale: the body
    # comes within the range of the adhesive stress
    "max_indentation",  # turnaround while loading: loading → hold
    "detach_start",  # hold → unloading: the edge spring reaches Δl(a)
    "snap_in",  # outward cascade: the contact radius jumps out
    "snap_out",  # inward cascade: the contact radius jumps in
    "separation",  # the last spring lets go
    "capture",  # turnaround while unloading: the body can never leave
    "limit",  # a bound on bounces, time or phases ended the run
    "contact_start",  # Maugis–Dugdale: the centre of the adhesive zone closes into a contact
    "contact_end",  # Maugis–Dugdale: the contact opens into an adhesive zone without contact
    "yield",  # plasticity: loading reaches the depth where plastic flow starts (or resumes)
)
EVENT_CODE = {kind: code for code, kind in enumerate(EVENT_KINDS)}


def _member(message: str) -> Any:
    """An enumeration member's message, typed as Any: mypy reads an `eqx.Enumeration`'s members
    as their messages (str) rather than as members (equinox issue #1121)."""
    return message


class Status(eqx.Enumeration):
    """What a run came to (as diffrax's `RESULTS`): the first two are physical outcomes, the
    others name why the run could not give one."""

    separated = _member("the body left the surface (without gravity: for good)")
    captured = _member("the body is stuck: restitution 0")
    bounce_limit = _member("gravity: max_bounces contacts were simulated, still bouncing")
    time_limit = _member("t_max reached")
    solver_failure = _member("the ODE solver failed (max_steps, step size)")
    radius_overflow = _member("the contact radius left the tabulated range of the profile")
    unbounded_contact = _member("the contact grows without limit on an unbounded body (e.g. n ≤ 1/2, (3.79–80))")
    phase_limit = _member("more phases than the run holds")
    branch_overflow = _member("the edge functions turn more often than the branch tables hold")
    overdamped = _member("damping holds the body in contact: it creeps towards rest, never turning or let go")
    unresolved_zone = _member(
        "a Maugis–Dugdale spring array too coarse for the adhesive zone: its answer would be wrong"
    )
    energy_drift = _member("the solver's speed disagrees with the energy balance")
    off_branch = _member("a contact phase started off its edge function (d ≠ h(a)): a jump of the radius landed wrong")


# The statuses by name in the order of their codes, the integers a run's outcome and a sweep's
# files hold (`status_code`).
RESULT_CODES: tuple[str, ...] = tuple(Status._name_to_item)


def status_code(status: Status) -> jax.Array:
    """The integer code of a status (its index in `RESULT_CODES`), as outcomes and files keep it."""
    return jnp.asarray(status._value)


# Each status's code by name, for what reads outcomes as integers (sweeps, files, figures).
RESULT_CODE = {name: code for code, name in enumerate(RESULT_CODES)}
# What went wrong and what to do, for the result codes whose name does not say it (`impact run`
# and `impact sweep` print it after their warning).
REMEDIES = {
    "energy_drift": (
        "a contact phase ended with a speed that disagrees with its energy balance, so the restitution "
        "would be wrong: tighten solver.rtol/atol, or use solver.phase_ends: energy"
    ),
    "off_branch": (
        "a jump of the contact radius (jump-in, snap-in or snap-out) landed where the contact law does not hold, "
        "so the energy would be wrong: a defect of impact's edge-function tables for this profile; please report "
        "the scene"
    ),
}


def is_success(code) -> bool:
    """Whether a result code is a physical outcome (separated or captured)."""
    return int(code) in (RESULT_CODE["separated"], RESULT_CODE["captured"])
