"""Names of the motion phases, events and result codes shared by the integrators."""

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

# Result codes of a simulation; the first two are successful outcomes.
RESULT_CODES = (
    "separated",  # the body left the surface (without gravity: for good)
    "captured",  # the body is stuck: restitution 0
    "bounce_limit",  # gravity: max_bounces contacts were simulated, still bouncing
    "time_limit",  # t_max reached
    "solver_failure",  # the ODE solver failed (max_steps, step size)
    "radius_overflow",  # the contact radius left the tabulated range of the profile
    "unbounded_contact",  # the contact grows without limit on an unbounded body (e.g. n ≤ 1/2, (3.79–80))
    "phase_limit",  # more phases than the run holds
    "branch_overflow",  # the edge functions turn more often than the branch tables hold
    "overdamped",  # damping holds the body in contact: it creeps towards rest, never turning or let go
    "unresolved_zone",  # a Maugis–Dugdale spring array too coarse for the adhesive zone: its answer would be wrong
    "energy_drift",  # the solver's speed disagrees with the energy balance: tighten rtol/atol or use phase_ends: energy
    "off_branch",  # a contact phase started off its edge function (d ≠ h(a)): a jump of the radius landed wrong
)
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
