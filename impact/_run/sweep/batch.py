"""The compiled batch: one impact as a function of its Physics (SI results), vmapped and
sharded over the local devices; the unbatched fallbacks."""

import operator
import time
from collections.abc import Callable, Sequence
from types import SimpleNamespace

import jax
import jax.numpy as jnp
import numpy as np
from jax.sharding import AxisType, NamedSharding, PartitionSpec

from ..._core.runtime import compiler_options
from ..._core.stored import compile_stored
from ..._integrate.codes import RESULT_CODE
from ..._integrate.problem import Physics
from ..._scene.errors import SweepError
from ..losses import adhesion_hysteresis, plastic_work, unrecovered_elastic_energy
from ..programs import solve
from ..tangential import TANGENTIAL_RESULTS, tangential_results
from .closed_forms import closed_form_restitution
from .plan import Plan, StaticChoices
from .result import SOLVED, empty_results

# Compiled batches by (static choices, Physics structure and shapes, devices), this session.
_COMPILED: dict = {}


# The outcome's fields that `point_function` reads: XLA drops the rest (the event log) from its
# compiled program; `impact bench speed` times the integration stage with exactly these.
POINT_READS = (
    "status", "stuck", "touch_velocity", "separation_velocity", "touch_time", "separation_time",
    "max_indentation", "max_force", "min_force", "contacts", "first_contact_work",
    "first_contact_viscous_work", "first_contact_stored_energy", "steps", "accepted_steps", "rejected_steps",
)  # fmt: skip


def point_function(choices: StaticChoices) -> Callable:
    """One impact → its scalar results in SI (the arithmetic of `impact._run.impacts.to_result`):
    the columns `SOLVED`, every named loss among them (a sweep keeps those its scene names)."""

    def point(physics: Physics) -> dict:
        scales, outcome = solve(choices.integrator, physics, choices.options)
        return point_results(choices, physics, scales, point_reads(outcome))

    return point


def point_reads(outcome) -> dict:
    """The fields of an outcome that `point_results` reads (`POINT_READS`, and an oblique
    impact's `tangential`): XLA drops the rest (the event log) from a compiled point."""
    return {**{name: getattr(outcome, name) for name in POINT_READS}, "tangential": outcome.tangential}


def point_results(choices: StaticChoices, physics: Physics, scales, reads: dict) -> dict:
    """The scalar results in SI of one impact from its units and the outcome's `point_reads`."""
    separated, captured = RESULT_CODE["separated"], RESULT_CODE["captured"]
    options = choices.options
    o = SimpleNamespace(**reads)
    time_unit, length, force = scales.time, scales.normal, scales.force
    speed = length / time_unit
    touch = o.touch_velocity
    success = (o.status == separated) | (o.status == captured)
    ratio = o.separation_velocity / jnp.where(touch > 0, touch, 1.0)
    dissipated = o.first_contact_work * force * length
    viscous = o.first_contact_viscous_work * force * length
    stored = o.first_contact_stored_energy * force * length
    plastic = plastic_work(choices.integrator, physics, o.max_indentation * length, dissipated)
    rebound = jnp.where(success & jnp.isfinite(o.separation_time), o.separation_velocity * speed, jnp.nan)
    sliding = point_tangential(o.tangential, physics, speed, force * length, rebound)
    return {
        **sliding,
        "restitution": jnp.where((touch > 0) & success, ratio, jnp.nan),
        "stuck": o.stuck,
        "status": o.status.astype(jnp.int32),
        "contact_time": jnp.where(
            ~jnp.isfinite(o.touch_time),
            jnp.nan,  # never touched
            jnp.where(~jnp.isfinite(o.separation_time), jnp.inf, (o.separation_time - o.touch_time) * time_unit),
        ),
        "max_indentation": o.max_indentation * length,
        "max_force": o.max_force * force,
        "min_force": o.min_force * force,
        "bounces": o.contacts.astype(jnp.int32),
        "touch_velocity": touch * speed,
        "separation_velocity": o.separation_velocity * speed,
        "dissipated_energy": dissipated,
        "plastic_work": plastic,
        "viscous_work": viscous,
        "adhesion_hysteresis": adhesion_hysteresis(options.adhesive, dissipated, plastic, viscous, stored),
        "unrecovered_elastic_energy": unrecovered_elastic_energy(
            options.adhesive, options.damped, dissipated, viscous, stored
        ),
        "steps": o.steps,
        "accepted_steps": o.accepted_steps,
        "rejected_steps": o.rejected_steps,
        "theory_restitution": closed_form_restitution(physics, choices),
    }


def point_tangential(tangential, physics: Physics, speed, energy, rebound) -> dict:
    """A point's tangential results in SI (`tangential.tangential_results`) from the scaled
    `tangential` outcome of an oblique impact (units `speed`, `energy`) and the normal
    `rebound` speed (m/s; nan where the first contact did not let go); nan columns for a scene
    without friction (the sweep keeps none)."""
    if tangential is None:
        return {name: jnp.full((), jnp.nan) for name in TANGENTIAL_RESULTS}
    friction = physics.friction
    lever = friction.lever_arm
    separated = jnp.isfinite(rebound)
    after = (
        jnp.where(separated, tangential.velocity * speed, jnp.nan),
        jnp.where(separated, tangential.surface_speed * speed / lever, jnp.nan),
    )
    return tangential_results(
        (friction.tangential_velocity, friction.spin), after, lever, rebound, tangential.friction_work * energy, jnp
    )


def local_devices(devices: "int | Sequence | None" = None) -> list:
    """The devices a sweep runs on: all local ones (None), the first n, or the ones given."""
    available = jax.local_devices()
    if devices is None:
        return available
    if isinstance(devices, int):
        if not 1 <= devices <= len(available):
            raise SweepError(
                [
                    (
                        "--devices",
                        f"{devices} devices asked for, {len(available)} visible "
                        f"({available[0].platform}); on CPU set JAX_NUM_CPU_DEVICES before jax starts",
                    )
                ]
            )
        return available[:devices]
    return list(devices)


def batch_sharding(devices: Sequence) -> NamedSharding:
    """The points' axis split over a 1-D mesh of the devices (AxisType.Auto: diffrax's events
    work under it, where an Explicit mesh, shard_map and pmap fail)."""
    mesh = jax.make_mesh((len(devices),), ("batch",), axis_types=(AxisType.Auto,), devices=devices)
    return NamedSharding(mesh, PartitionSpec("batch"))


def compiled_batch(choices: StaticChoices, physics: Physics, size: int, devices: Sequence):
    """(compiled jit(vmap(point)) for `size` points of this structure, compile time in s).

    Compiled once per (choices, leaf structure, size, devices) and kept for the session."""
    leaves, treedef = jax.tree.flatten(physics)
    key = (choices, treedef, tuple((leaf.shape[1:], leaf.dtype) for leaf in leaves), size, tuple(d.id for d in devices))
    if key in _COMPILED:
        return _COMPILED[key], 0.0
    start = time.perf_counter()
    sharding = batch_sharding(devices)
    dtype = jnp.result_type(float)
    abstract = [jax.ShapeDtypeStruct((size, *leaf.shape[1:]), dtype, sharding=sharding) for leaf in leaves]
    label = f"{__name__}.compiled_batch {choices!r}"
    batch = jax.tree.unflatten(treedef, abstract)
    options = compiler_options(platform=devices[0].platform)
    compiled = compile_stored(jax.vmap(point_function(choices)), label, batch, options)
    _COMPILED[key] = compiled
    return compiled, time.perf_counter() - start


_MAPPED: dict = {}
_SINGLE: dict = {}
COMPILE_SECONDS = {"unbatched": 0.0}  # time spent compiling the fallbacks, this session


def sequential(plan: Plan, group: int, points: np.ndarray, size: int) -> dict:
    """Results of the points solved one after another inside one compiled `lax.map` (no
    batching: each point takes only its own branches). The fallback for a chunk whose
    batched run raised; a point that raises even so is isolated by `one_by_one`."""
    choices = plan.choices[group]
    padded = np.concatenate([points, np.full(size - len(points), points[-1])])
    batch = jax.device_put(jax.tree.map(lambda leaf: leaf[padded], plan.physics), jax.local_devices()[0])
    leaves, treedef = jax.tree.flatten(batch)
    key = (choices, treedef, tuple((leaf.shape, leaf.dtype) for leaf in leaves))
    if key not in _MAPPED:
        start = time.perf_counter()
        point = point_function(choices)
        function = jax.jit(lambda physics: jax.lax.map(point, physics), compiler_options=compiler_options())
        _MAPPED[key] = function.lower(batch).compile()
        COMPILE_SECONDS["unbatched"] += time.perf_counter() - start
    try:
        values = jax.device_get(_MAPPED[key](batch))
    except jax.errors.JaxRuntimeError:
        return one_by_one(plan, group, points)
    return {name: np.asarray(values[name])[: len(points)] for name in SOLVED}


def one_by_one(plan: Plan, group: int, points: np.ndarray) -> dict:
    """Results of the points solved one call each; a point whose solve raises gets the result
    code solver_failure."""
    choices = plan.choices[group]
    if choices not in _SINGLE:
        _SINGLE[choices] = jax.jit(point_function(choices), compiler_options=compiler_options())
    function = _SINGLE[choices]
    results = empty_results(len(points), SOLVED)
    for row, point in enumerate(points):
        physics = jax.tree.map(operator.itemgetter(point), plan.physics)
        try:
            values = jax.device_get(function(physics))
        except jax.errors.JaxRuntimeError:
            results["status"][row] = RESULT_CODE["solver_failure"]
            continue
        for name in SOLVED:
            results[name][row] = values[name]
    return results
