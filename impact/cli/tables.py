"""The rich tables the command line prints: a scene's key facts, the results of a run or an
indentation test, and the summary of a sweep with its sticking velocities."""

import math
from typing import TYPE_CHECKING

import numpy as np
from rich import box
from rich.table import Table
from rich.text import Text

from .._integrate.codes import RESULT_CODE, RESULT_CODES
from .._plots.figures import si_prefix
from .._run.impacts import Result
from .._scene.scene import Scene
from .._scene.sections import QUADRATURE, SPRING_METHODS
from .._scene.sweep_method import scene_sweep_method

if TYPE_CHECKING:  # imported by the commands that make them: `impact run` of an impact needs none
    from .._run.indentation import IndentationResult
    from .._run.shear import ShearResult
    from .._run.sweep import SweepResult

OUTCOMES = ("separated", "captured")


def quantity(value: float, unit: str) -> str:
    """A value with an SI prefix: 3.92e-8, "s" → "39.21 ns"."""
    factor, prefix = si_prefix(value)
    return f"{value * factor:.4g} {prefix}{unit}"


def compressive(max_force: float) -> str:
    """The largest force (N), or "no compressive force" where every contact force was adhesive."""
    return "no compressive force" if max_force <= 0 else quantity(max_force, "N")


def key_value_table(title: str, rows: list[tuple[str, str]]) -> Table:
    """A headerless two-column table: names in bold, values as plain text."""
    table = Table(title=Text(title), show_header=False)
    table.add_column(style="bold")
    table.add_column()
    for name, value in rows:
        table.add_row(Text(name), Text(value))
    return table


def result_table(result: "Result | IndentationResult | ShearResult", wall_time: float | None) -> Table:
    """The key results of an impact, an indentation test or a shear test (wall time in s, if known)."""
    if isinstance(result, Result):
        return impact_table(result, wall_time)
    from .._run.shear import ShearResult  # a shear test's module, where one is shown (not for an impact)

    if isinstance(result, ShearResult):
        return shear_table(result, wall_time)
    return indentation_table(result, wall_time)


def shear_table(result: "ShearResult", wall_time: float | None) -> Table:
    """The held normal state and the extremes of a shear test's program."""
    largest = float(np.max(np.abs(result.force), initial=0.0))
    rows = [
        ("status", result.status),
        ("normal force", quantity(result.normal_force, "N")),
        ("indentation", quantity(result.indentation, "m")),
        ("contact radius", quantity(result.contact_radius, "m")),
        ("largest |Q|", quantity(largest, "N")),
        ("largest |δ|", quantity(float(np.max(np.abs(result.displacement), initial=0.0)), "m")),
        ("springs", f"{result.stats['springs']} (spacing {quantity(result.stats['spacing'], 'm')})"),
        ("points", str(len(result.force))),
        _wall_time(wall_time),
    ]
    return key_value_table(f"{result.scene.name} (shear)", rows)


def _wall_time(wall_time: float | None) -> tuple[str, str]:
    return ("wall time", "unknown" if wall_time is None else quantity(wall_time, "s"))


def indentation_table(result: "IndentationResult", wall_time: float | None) -> Table:
    """The pull-off (last stable state before the contact is lost) and the extremes of a test."""
    pull_off = result.pull_off

    def value(number: float, unit: str) -> str:
        return quantity(number, unit) if math.isfinite(number) else "—"

    snaps = sum(kind in ("snap_in", "snap_out") for _, kind in result.events)
    rows = [
        ("control", f"{result.scene.control} (ξ = {result.xi})"),
        ("status", result.status),
        ("pull-off force", value(pull_off.force, "N")),
        ("pull-off indentation", value(pull_off.indentation, "m")),
        ("pull-off contact radius", value(pull_off.contact_radius, "m")),
        ("max force", compressive(result.max_force)),
        ("max indentation", quantity(result.max_indentation, "m")),
        ("max contact radius", quantity(result.max_contact_radius, "m")),
        ("jumps (snaps, jump-in)", str(snaps)),
        ("points", str(len(result.force))),
        _wall_time(wall_time),
    ]
    return key_value_table(f"{result.scene.name} (indentation)", rows)


def impact_table(result: Result, wall_time: float | None) -> Table:
    """The key results of an impact."""
    stats = result.stats
    tabor = result.tabor_parameter
    effects = result.scene.effects
    viscous = effects.damping is not None or effects.viscoelasticity is not None
    rows = [
        ("restitution e", _restitution(result)),
        ("stuck", "yes" if result.stuck else "no"),
        ("status", result.status),
        ("contact time", _contact_time(result)),
        ("max indentation", quantity(result.max_indentation, "m")),
        ("max force", compressive(result.max_force)),
        ("min force", quantity(result.min_force, "N")),
        *([("Tabor parameter Λ", f"{tabor:.6g}")] if math.isfinite(tabor) else []),
        *([("plastic work", quantity(result.plastic_work, "J"))] if effects.plasticity else []),
        *(
            [("adhesion hysteresis", quantity(result.adhesion_hysteresis, "J"))]
            if (effects.plasticity or viscous) and result.scene.adhesive
            else []
        ),
        *([("viscous work", quantity(result.viscous_work, "J"))] if viscous else []),
        *(
            [("unrecovered elastic energy", quantity(result.unrecovered_elastic_energy, "J"))]
            if (effects.damping and not result.scene.adhesive) or effects.viscoelasticity
            else []
        ),
        *_two_body_rows(result),
        *_sliding_rows(result),
        ("bounces (contacts)", str(result.bounces)),
        ("solver steps", f"{stats['steps']} ({stats['accepted_steps']} accepted, {stats['rejected_steps']} rejected)"),
        _wall_time(wall_time),
    ]
    return key_value_table(f"{result.scene.name}", rows)


def _restitution(result: Result) -> str:
    """e of the first contact (0 where it captured the body; so said where more contacts
    followed), or why there is none."""
    if math.isnan(result.restitution):
        return f"— (no physical outcome: {result.status})"
    first = f" (of the first of {result.bounces} contacts)" if result.bounces > 1 else ""
    return f"{result.restitution:.8g}{first}"


def _contact_time(result: Result) -> str:
    """The first contact's duration, or why it has none."""
    duration = result.contact_time
    if math.isfinite(duration):
        return quantity(duration, "s")
    if math.isnan(duration):
        return "— (never touched)"
    return "∞ (never let go)" if result.success else f"— (ended in contact: {result.status})"


def _two_body_rows(result: Result) -> list[tuple[str, str]]:
    """The velocities after the impact of a scene with a counterpart (lab and centre-of-mass frame)."""
    if result.scene.counterpart is None:
        return []
    return [
        ("body after (lab, cm)", f"{result.body_velocity_after:.6g} m/s, {result.body_velocity_after_cm:.6g} m/s"),
        (
            "counterpart after (lab, cm)",
            f"{result.counterpart_velocity_after:.6g} m/s, {result.counterpart_velocity_after_cm:.6g} m/s",
        ),
    ]


def _sliding_rows(result: Result) -> list[tuple[str, str]]:
    """The tangential results of an oblique impact with friction."""
    if result.scene.effects.friction is None:
        return []
    return [
        ("tangential velocity after", f"{result.tangential_velocity_after:.6g} m/s"),
        ("spin after", f"{result.spin_after:.6g} rad/s"),
        (
            "tangential restitution",
            f"{result.tangential_restitution:.6g} (contact point {result.contact_point_tangential_restitution:.6g})",
        ),
        ("rebound angle", f"{result.rebound_angle:.6g} rad"),
        ("friction work", quantity(result.friction_work, "J")),
    ]


def _effects(scene: Scene) -> str:
    """The adhesion and gravity a scene names, with their parameters in SI units."""
    adhesion, gravity = scene.active_adhesion, scene.effects.gravity
    effects = []
    if adhesion is not None:
        effects.append(adhesion.describe())
    if gravity is not None:
        effects.append(f"gravity (g = {gravity.g:g} m/s²)")
    if scene.effects.plasticity is not None:
        effects.append(f"plasticity (p_y = {scene.effects.plasticity.yield_pressure:.6g} Pa)")
    if scene.effects.damping is not None:
        effects.append(scene.effects.damping.describe())
    if scene.effects.viscoelasticity is not None:
        effects.append(scene.effects.viscoelasticity.describe())
    if scene.effects.friction is not None:
        effects.append(scene.effects.friction.describe())
    return ", ".join(effects) or "none (elastic Hertz/MDR contact)"


def facts_table(scene: Scene) -> Table:
    """The resolved key facts of a scene, in SI units."""
    body, material = scene.body, scene.material
    parameters = ", ".join(
        f"{name} = {value:g}" if isinstance(value, float) else f"{name} = {value}"
        for name, value in body.profile.model_dump(exclude={"shape"}).items()
    )
    springs = scene.contact.springs
    derived = "" if material.E_star is not None else " (from E and ν)"
    shape = ("shape", f"{body.profile.shape} ({parameters})")
    modulus = ("E*", f"{material.effective_modulus:.6g} Pa{derived}")
    effect_rows = [
        ("effects", _effects(scene)),
        ("contact", "continuum" if springs == "continuum" else f"{springs} springs"),
    ]
    if scene.kind == "indentation":
        program = scene.loading
        unit = "N" if scene.control == "force" else "m"
        unloading = "" if program.unload_to is None else f" unloading to {program.unload_to:g} {unit}"
        cycles = f", {program.cycles} cycles{unloading}" if program.cycles > 1 else ""
        timed = "" if program.rate is None else f" at {program.rate:g} {unit}/s, held {program.hold:g} s"
        rows = [
            ("kind", f"indentation, {scene.control} control"),
            shape,
            modulus,
            (
                "program",
                f"peak {program.peak:g} {unit}{timed}{cycles}, then to pull-off"
                if scene.shear is None
                else f"peak {program.peak:g} {unit} held; shear ({scene.shear.control}) through {scene.shear.path}",
            ),
            *effect_rows,
        ]
        return key_value_table(f"{scene.name} (SI units)", rows)
    density = "" if body.density is None else f" (density {body.density:g} kg/m³)"
    solver = scene.solver
    if solver.method in SPRING_METHODS:
        steps = f"dt {solver.dt:g} s"
    elif solver.method == QUADRATURE and scene.contact.springs != "continuum":
        steps = "each contact of the spring array whole from prefix sums, timed by its harmonic arcs"
    elif solver.method == QUADRATURE:
        steps = "phase ends from the energy, timed by quadrature"
    else:
        steps = f"rtol {solver.rtol:g}, atol {solver.atol:g}"
        if scene.phase_ends == "energy":
            steps += ", phase ends from the energy"
    rows = [
        shape,
        ("mass", f"{body.resolved_mass:.6g} kg{density}"),
        *_counterpart_rows(scene),
        modulus,
        ("initial", _initial(scene)),
        *effect_rows,
        ("solver", f"{solver.method}, {steps}"),
        ("in a sweep", "{}: {}".format(*scene_sweep_method(scene))),
    ]
    return key_value_table(f"{scene.name} (SI units)", rows)


def _initial(scene: Scene) -> str:
    """The initial state: speed and gap, and where given the angle of incidence and the spin."""
    start = scene.start
    words = f"velocity {start.velocity:g} m/s, gap {start.gap:g} m"
    if start.angle:
        words += f", angle {start.angle:g} rad from the normal"
    if start.spin:
        words += f", spin {start.spin:g} rad/s"
    return words


def _counterpart_rows(scene: Scene) -> list[tuple[str, str]]:
    """The counterpart of a two-body scene and the effective radius and mass of the contact."""
    counterpart = scene.counterpart
    if counterpart is None:
        return []
    surface = "flat" if counterpart.radius is None else f"paraboloid (R = {counterpart.radius:g} m)"
    rows = [
        ("counterpart", f"{surface}, mass {counterpart.resolved_mass:.6g} kg, velocity {counterpart.velocity:g} m/s"),
        ("reduced mass", f"{scene.reduced_mass:.6g} kg"),
    ]
    if scene.effective_radius is not None:
        rows.append(("effective radius", f"{scene.effective_radius:.6g} m"))
    return rows


def outcome_counts(result: "SweepResult") -> dict[str, int]:
    """Points per result code name ('not run' included), for the codes that occur."""
    names = result.status_names().reshape(-1)
    return {name: int(np.sum(names == name)) for name in (*RESULT_CODES, "not run") if np.any(names == name)}


def _run_rows(stats: dict) -> list[tuple[str, str]]:
    """What a sweep's run cost: chunks, devices, times, speed, points solved unbatched."""
    calls = ", ".join(map(str, stats["call_sizes"]))
    rows = [
        (
            "chunks",
            f"up to {stats['chunk']} points (calls of {calls}) "
            f"on {stats['devices']} device(s), {stats['groups']} compiled group(s)",
        ),
        (
            "time",
            f"plan {stats['plan_time']:.3g} s, compile {stats['compile_time']:.3g} s, "
            f"solve {stats['solve_time']:.3g} s",
        ),
        ("speed", f"{stats['points_per_second']:,.0f} points/s (this run: {stats['points']} points)"),
    ]
    if stats.get("solved_unbatched"):
        rows.append(
            (
                "unbatched",
                f"{stats['solved_unbatched']} points: a runtime check stopped their batch, "
                "so they were solved one after another (slower, same results)",
            )
        )
    return rows


def sweep_table(result: "SweepResult", stats: dict) -> Table:
    """A sweep's points, outcomes, run cost (where `stats` holds a run's) and max |e − e_theory|."""
    from .._run.sweep import closed_form_names

    counts = outcome_counts(result)
    shape = " × ".join(map(str, result.shape))
    rows = [
        ("points", f"{result.restitution.size} ({result.spec.mode} {shape}: {', '.join(result.spec.paths)})"),
        ("outcomes", ", ".join(f"{name} {count}" for name, count in counts.items())),
        (
            "method",
            f"{result.spec.method}: {result.spec.method_choice}" if result.spec.method_choice else result.spec.method,
        ),
    ]
    if "solve_time" in stats:
        rows += _run_rows(stats)
    error = result.max_theory_error()
    closed_forms = (
        "no closed form for this scene"
        if math.isnan(error)
        else f"{error:.3g} ({'; '.join(closed_form_names(result))})"
    )
    rows.append(("max |e − e_theory|", closed_forms))
    rows += _sweep_energy_rows(result)
    return key_value_table(f"{result.scene.name} sweep", rows)


def _span(values: np.ndarray, unit: str) -> str:
    """The smallest and largest finite value, with SI prefixes ("—" where none is finite)."""
    finite = values[np.isfinite(values)]
    if finite.size == 0:
        return "—"
    return f"{quantity(float(finite.min()), unit)} … {quantity(float(finite.max()), unit)}"


def _sweep_energy_rows(result: "SweepResult") -> list[tuple[str, str]]:
    """The named losses and a counterpart's lab velocities where the sweep holds them (their
    range over the separated points), and the energy balance of the points with a physical
    outcome."""
    separated = result.status == RESULT_CODE["separated"]
    rows = [
        (name.replace("_", " "), f"{_span(column[separated], 'J')} (separated points)")
        for name, column in result.named_losses().items()
    ]
    for body in ("body", "counterpart"):
        column = getattr(result, f"{body}_velocity_after")
        if column is not None:
            rows.append((f"{body} after (lab)", f"{_span(column[separated], 'm/s')} (separated points)"))
    imbalance = result.energy_imbalance()
    if rows and math.isfinite(imbalance):
        rows.append(("energy balance", f"{imbalance:.2g} (max |½m(v₀² − v₁²) − Σ losses| / energy turned over)"))
    return rows


def _number(value: float, form: str) -> str:
    return "—" if math.isnan(value) else format(value, form)


def sticking_table(estimates: list[dict]) -> Table:
    """Per series along the velocity: the bracket of the sticking velocity v_s (m/s), its
    estimate, the closed form and max |e − e_theory| (rows of `sticking_estimates`)."""
    table = Table(
        title=Text("sticking velocity v_s (m/s): where e leaves 0 along initial.velocity"),
        caption=Text("closed form: where e_theory leaves 0; Δe = e − e_theory"),
        box=box.SIMPLE_HEAD,
        show_edge=False,
        pad_edge=False,
    )
    table.add_column("other axes", overflow="fold")
    for column in ("captured ≤", "separated ≥", "estimate", "closed form", "max |Δe|"):
        table.add_column(column, justify="right")
    for row in estimates:
        label = ", ".join(f"{p.split('.')[-1]} = {v:.4g}" for p, v in row["fixed"].items()) or "—"
        low = "none" if math.isnan(row["low"]) else f"{row['low']:.6g}"
        high = "none" if math.isnan(row["high"]) else f"{row['high']:.6g}"
        if math.isnan(row["low"]) and not math.isnan(row["high"]):
            estimate = f"< {row['high']:.6g}"
        else:
            estimate = _number(row["estimate"], ".6g")
        table.add_row(Text(label), low, high, estimate, _number(row["theory"], ".6g"), _number(row["max_error"], ".3g"))
    return table
