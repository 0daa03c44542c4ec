"""The quasi-static march of the continuum law: along the edges, cascades and force jumps."""

import functools

import jax.numpy as jnp

from ..codes import Status
from .continuum_cascade import after_cascade, cascade_bracket, cascade_outcome
from .continuum_pieces import move, plan
from .continuum_state import Carry, ContinuumMarch
from .events import EventLog, MarchRecord, end_march, run_march
from .loading import FREE, QuasiStaticNumerics, QuasiStaticOutcome
from .setup import Built, bracketed_root, edge_path


def march_continuum(built: Built, numerics: QuasiStaticNumerics) -> QuasiStaticOutcome:
    """March the program one piece per step: an approach, a hold, a ride over one interval
    between turning points, or a cascade. Every step solves one bisection, whatever its mode (a
    ride's crossing of the target, or where a cascade stops), so the loop body and its compile
    time stay small."""
    attach, detach = built.problem.attach, built.problem.detach
    steps = numerics.steps(built.program.targets.shape[0])
    march = ContinuumMarch(
        built=built,
        up=edge_path(attach, built.attach3, built.top, True),
        down=edge_path(detach, built.detach3, built.top, False),
        grid=jnp.linspace(0.0, 1.0, numerics.samples),
        extent=built.law.extent(),
    )
    return run_march(functools.partial(step, march), initial(built, numerics, steps), steps, built.top)


def initial(built: Built, numerics: QuasiStaticNumerics, steps: int) -> Carry:
    """The state before the first step: apart, on the first leg, with empty buffers for the
    curve and its events (or done at once where a branch table overflowed)."""
    carry = Carry(
        **built.program.start(),
        mode=jnp.asarray(FREE),
        wall=jnp.asarray(False),
        a=jnp.zeros(()),
        d=jnp.zeros(()),
        pre=jnp.zeros(2),
        record=MarchRecord.empty(rows=steps * (numerics.samples + 8), events=4 * steps),
    )
    attach, detach = built.problem.attach, built.problem.detach
    overflow = attach.overflow | detach.overflow | built.attach3.overflow | built.detach3.overflow
    return end_march(carry, overflow, Status.branch_overflow)


def step(march: ContinuumMarch, c: Carry) -> Carry:
    """One piece: every mode's piece is set up from the state, the one bisection solves the
    ride's crossing of the target (or where the cascade stops), then the piece of the current
    mode is applied (`move`) and the cascade's outcome (`after_cascade`)."""
    log = EventLog()
    a, d = c.a, c.d
    p = plan(march, c)
    bracket = cascade_bracket(march, c, p.up)
    root = bracketed_root(
        march.law,
        p.rode.edge,
        march.program.force_control & ~p.is_cascade,
        jnp.where(p.is_cascade, d, c.target),
        jnp.where(p.is_cascade, bracket.lower, p.rode.lo),
        jnp.where(p.is_cascade, bracket.upper, p.rode.hi),
    )
    c = move(march, c, log, p, root)
    c = after_cascade(march, c, log, p.is_cascade, a, d, cascade_outcome(march, bracket, root, a, p.up), p.up)
    return log.write(c)
