"""The units of a run's results, stated once for the HDF5 files (`impact._io`) and the labelled
tables (`impact._run.labelled`): UDUNITS symbols, as every file's `unit` attributes ('' for a
dimensionless value). A sweep's columns carry theirs in `sweep.result.RESULTS`."""

from .tangential import TANGENTIAL_RESULTS

# An impact's scalar results (`Result` fields): name → unit.
SCALAR_UNITS = {
    "restitution": "",
    "stuck": "",
    "status": "",
    "contact_time": "s",
    "max_indentation": "m",
    "max_force": "N",
    "min_force": "N",
    "bounces": "",
    "touch_velocity": "m s-1",
    "separation_velocity": "m s-1",
    "dissipated_energy": "J",
    "plastic_work": "J",
    "viscous_work": "J",
    "tabor_parameter": "",
    "centre_of_mass_velocity": "m s-1",
    "body_velocity_after": "m s-1",
    "counterpart_velocity_after": "m s-1",
    **{name: unit for name, (unit, _) in TANGENTIAL_RESULTS.items()},
}
# Losses derived from the others (`Result` properties, in J), stored where the scene names what
# they describe (`losses.NAMED_LOSSES`).
DERIVED_LOSSES = ("adhesion_hysteresis", "unrecovered_elastic_energy")
# An impact's time series of the contact (`Result` fields, sampled at `Result.t` in s):
# name → (unit, description); with friction also `tangential.TANGENTIAL_SERIES`.
CONTACT_SERIES = {
    "indentation": ("m", "indentation d of the half-space; > 0 pressed in, < 0 a gap"),
    "contact_radius": ("m", "contact radius a"),
    "force": ("N", "normal force on the body; > 0 compressive, < 0 adhesive"),
}
# The body's velocity, sampled with them: (unit, description).
VELOCITY_SERIES = ("m s-1", "velocity ḋ of the body, towards the surface > 0")

# An indentation test's curve in program order (`IndentationResult` fields): name → (unit, description).
INDENTATION_CURVE = {
    "contact_radius": ("m", "contact radius a"),
    "indentation": ("m", "indentation d; > 0 pressed in, < 0 pulled out"),
    "force": ("N", "normal force; > 0 compressive, < 0 adhesive"),
    "leg": ("", "leg of the loading program: 0 first loading, 1 first unloading, ..."),
}
# The time of each point of a viscoelastic half-space's test at a rate (`IndentationResult.time`).
CURVE_TIME = ("s", "time of each point since the first touch")
# Its pull-off (`PullOff` fields) and its extremes (`IndentationResult` properties): name → unit.
PULL_OFF_UNITS = {"contact_radius": "m", "indentation": "m", "force": "N"}
MAXIMA_UNITS = {"max_force": "N", "max_indentation": "m", "max_contact_radius": "m"}
# The springs of a viscoelastic medium when an impact ends (`Relaxation` fields): name → (unit,
# description).
RELAXATION_FIELDS = {
    "spring_position": ("m", "x of each spring"),
    "displacement": ("m", "displacement u of each spring; > 0 pressed in"),
    "arm_stretch": ("m", "stretch q_i of each spring's Maxwell arms, one column per Prony term"),
    "attached": ("", "whether each spring is in contact"),
    "stored_energy": ("J", "elastic energy the medium held when the first contact ended"),
    "released_energy": ("J", "elastic energy released by the springs that let go in the first contact"),
    "gained_energy": ("J", "elastic energy gained by the springs that jumped onto the body in the first contact"),
}
