"""Parameter sweeps: one compiled `jax.vmap` of `simulate.solve` over chunks of a batched Physics.

    result = impact.sweep("configs/thornton_ning.yaml",
                          {"initial.velocity": np.geomspace(0.2, 20, 400),
                           "effects.adhesion.work_of_adhesion": [0.02, 0.05, 0.1]})
    result.restitution.shape          # (400, 3), like every other result and result.params[...]

How it runs:
- Plan (`plan_sweep`): every point is validated (`sweep_file`), its SI parameters are computed
  for all points at once with numpy (the base scene copied with arrays in place of the swept
  values: no per-point `physics_for`), and the points are split into groups of equal static
  choices (`Numerics`: solver, springs, limits, adhesion on/off, attach on touch). Each group
  compiles once; changing only the swept values never recompiles.
- Order: a vmapped batch runs as long as its slowest member (diffrax's while loops run in
  lock step), so with `order="cost"` each group is sorted by the expected cost, v/v_s (touch
  speed over the closed-form sticking velocity: the scaled problem depends on nothing else),
  or v where no closed form gives v_s. Chunks then hold points of like cost.
- Chunks of `chunk` points (padded with copies of their last point to a multiple of the device
  count) go through `jit(vmap(point))`, compiled ahead of time for that shape, on inputs
  sharded with `NamedSharding(Mesh(devices, ("batch",), AxisType.Auto), P("batch"))` over the
  local devices. The next chunk is dispatched before the previous one is read back.
- Shares (`share=(i, n)`, multi-host): process i takes every n-th point of each group's order,
  so every process gets a like mix of costs.
- A chunk whose batched run raises (under vmap one lane's failed runtime check stops every
  lane, even a check in a branch the lane does not take) is solved again unbatched, point after
  point inside one compiled `lax.map`; a point that raises even so gets `solver_failure`.
"""

import contextlib
import logging
import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import jax
import jax.numpy as jnp
import numpy as np
from jax.sharding import AxisType, NamedSharding, PartitionSpec
from matplotlib.figure import Figure
from matplotlib.ticker import FormatStrFormatter, FuncFormatter, NullFormatter
from scipy.special import gammaln

from .. import profiles
from .. import theory
from .._integrate.codes import RESULT_CODE, RESULT_CODES
from .._scene.scene import Scene
from .._integrate.problem import Numerics, Physics, touch_velocity
from .simulate import numerics_for, physics_for, solve
from .._scene.sweep import SweepError, SweepSpec, make_spec, with_values

__all__ = [
    "RESULTS",
    "SweepResult",
    "sweep",
    "run_spec",
    "plan_sweep",
    "restitution_figure",
    "save_restitution_figure",
    "closed_form_name",
    "closed_form_names",
    "sticking_estimates",
    "SweepError",
]

DEFAULT_CHUNK = 1000
VELOCITY = "initial.velocity"

# Scalar results per point: name → (dtype, fill value for points not run, unit, description).
RESULTS = {
    "restitution": (np.float64, np.nan, "", "rebound speed over touch speed of the first contact (0 if captured)"),
    "stuck": (np.bool_, False, "", "the body ended captured"),
    "status": (np.int32, -1, "", "result code, an index into phases.RESULT_CODES (-1: not run)"),
    "contact_time": (np.float64, np.nan, "s", "duration of the first contact (inf if it never let go, NaN if no touch)"),
    "max_indentation": (np.float64, np.nan, "m", "deepest indentation"),
    "max_force": (np.float64, np.nan, "N", "largest compressive force"),
    "min_force": (np.float64, np.nan, "N", "most adhesive (negative) force"),
    "bounces": (np.int32, -1, "", "contacts simulated"),
    "touch_velocity": (np.float64, np.nan, "m s-1", "speed at the first touch"),
    "separation_velocity": (np.float64, np.nan, "m s-1", "speed when the first contact let go (0 if captured)"),
    "dissipated_energy": (np.float64, np.nan, "J", "energy lost in the first contact"),
    "steps": (np.int64, -1, "", "solver steps"),
    "accepted_steps": (np.int64, -1, "", "accepted solver steps"),
    "rejected_steps": (np.int64, -1, "", "rejected solver steps"),
    "theory_restitution": (np.float64, np.nan, "", "closed-form restitution of the chapter (NaN where none)"),
}


# --- results ---------------------------------------------------------------------------------


@dataclass
class SweepResult:
    """Every scalar result of a sweep as an array in the sweep's shape (grid: one axis per swept
    field, in the order given; zip: one axis). `params[path]` holds the swept values per point,
    `status` the result codes (`phases.RESULT_CODES`; -1 for a point not run), `stats` the
    cost of the run (points, chunk, devices, groups, plan/compile/solve time in s, points/s)."""

    spec: SweepSpec
    params: dict[str, np.ndarray]
    restitution: np.ndarray
    stuck: np.ndarray
    status: np.ndarray
    contact_time: np.ndarray
    max_indentation: np.ndarray
    max_force: np.ndarray
    min_force: np.ndarray
    bounces: np.ndarray
    touch_velocity: np.ndarray
    separation_velocity: np.ndarray
    dissipated_energy: np.ndarray
    steps: np.ndarray
    accepted_steps: np.ndarray
    rejected_steps: np.ndarray
    theory_restitution: np.ndarray
    stats: dict = field(default_factory=dict)

    @property
    def scene(self) -> Scene:
        return self.spec.scene

    @property
    def shape(self) -> tuple[int, ...]:
        return self.spec.shape

    @property
    def axes(self) -> dict[str, np.ndarray]:
        """The values of each axis (1-D)."""
        return {axis.path: axis.values for axis in self.spec.axes}

    @property
    def results(self) -> dict[str, np.ndarray]:
        return {name: getattr(self, name) for name in RESULTS}

    @property
    def success(self) -> np.ndarray:
        """Points with a physical outcome (separated or captured)."""
        return (self.status == RESULT_CODE["separated"]) | (self.status == RESULT_CODE["captured"])

    def status_names(self) -> np.ndarray:
        """Result codes as names ('not run' for -1)."""
        names = np.array([*RESULT_CODES, "not run"], dtype=object)
        return names[np.where(self.status < 0, len(RESULT_CODES), self.status)]

    def max_theory_error(self) -> float:
        """max |e − e_theory| over the points with a physical outcome and a closed form (NaN if none)."""
        usable = self.success & np.isfinite(self.theory_restitution)
        if not usable.any():
            return math.nan
        return float(np.max(np.abs(self.restitution[usable] - self.theory_restitution[usable])))

    @classmethod
    def from_flat(cls, spec: SweepSpec, params: dict, results: dict, stats: dict | None = None) -> "SweepResult":
        shape = spec.shape
        return cls(
            spec=spec,
            params={path: np.asarray(values).reshape(shape) for path, values in params.items()},
            **{name: np.asarray(results[name]).reshape(shape) for name in RESULTS},
            stats=dict(stats or {}),
        )


def empty_results(size: int) -> dict[str, np.ndarray]:
    return {name: np.full(size, fill, dtype=dtype) for name, (dtype, fill, _, _) in RESULTS.items()}


# --- plan ------------------------------------------------------------------------------------


@dataclass
class Plan:
    """What to run: SI parameters of every point, its group (static choices) and the order."""

    spec: SweepSpec
    params: dict[str, np.ndarray]  # flat [N], C order of spec.shape
    physics: Physics  # numpy leaves [N, ...]
    numerics: list[Numerics]  # of each group
    group: np.ndarray  # [N] group of each point
    cost: np.ndarray  # [N] expected-cost key (v/v_s, or v)
    order: np.ndarray  # [N] processing order: group by group, each by cost (or as given)
    time: float = 0.0  # s spent planning

    @property
    def size(self) -> int:
        return len(self.group)

    def share(self, index: int = 0, count: int = 1) -> list[np.ndarray]:
        """The points of process `index` of `count`, per group in processing order."""
        shares = []
        for group in range(len(self.numerics)):
            points = self.order[self.group[self.order] == group]
            shares.append(points[index::count])
        return shares


def plan_sweep(spec: SweepSpec) -> Plan:
    start = time.perf_counter()
    params = spec.flat_params()
    size = spec.size
    physics = batch_physics(spec.scene, params, size)
    numerics, group = _groups(spec, params, size)
    cost = expected_cost(spec.scene, physics)
    if spec.order == "cost":
        order = np.concatenate([np.flatnonzero(group == g)[np.argsort(cost[group == g], kind="stable")]
                                for g in range(len(numerics))])
    else:
        order = np.concatenate([np.flatnonzero(group == g) for g in range(len(numerics))])
    return Plan(spec, params, physics, numerics, group, cost, order, time.perf_counter() - start)


def batch_physics(scene: Scene, params: Mapping[str, np.ndarray], size: int) -> Physics:
    """`physics_for` of every point at once: numpy leaves with a leading axis of `size`.

    The base scene is copied with the swept values as arrays (no validation: the points are
    validated already), so derived values (E* from E and ν, mass from density) follow the
    scene's own formulas elementwise."""
    template = physics_for(scene)
    batch = with_values(scene, params)
    if any(path.startswith("body.profile.") for path in params):
        profile = batch.body.profile.build()
    else:
        profile = template.profile
    reference, treedef = jax.tree.flatten(template.profile)
    leaves = [_batched(np.asarray(new), np.shape(ref), size) for new, ref in zip(jax.tree.leaves(profile), reference)]
    adhesion, gravity = batch.effects.adhesion, batch.effects.gravity
    stress = np.full((), np.nan)
    if adhesion is None:
        work = approach = np.zeros(())
    else:
        adhesive = np.asarray(adhesion.work_of_adhesion) > 0
        work = np.where(adhesive, adhesion.work_of_adhesion, 0.0)
        if adhesion.model == "maugis_dugdale":
            stress = np.where(adhesive, adhesion.adhesive_stress, np.nan)
            approach = np.zeros(())
        else:
            approach = np.where(adhesive, adhesion.approach, 0.0)
    duration, length, springs = batch.limits.duration, batch.contact.length, batch.contact.springs
    return Physics(
        profile=jax.tree.unflatten(treedef, leaves),
        E_star=_batched(batch.material.effective_modulus, (), size),
        mass=_batched(batch.body.resolved_mass, (), size),
        velocity=_batched(batch.initial.velocity, (), size),
        gap=_batched(batch.initial.gap, (), size),
        work_of_adhesion=_batched(work, (), size),
        approach_work_of_adhesion=_batched(approach, (), size),
        adhesive_stress=_batched(stress, (), size),
        gravity=_batched(0.0 if gravity is None else gravity.g, (), size),
        time_limit=_batched(np.inf if duration is None else duration, (), size),
        spring_length=_batched(np.nan if length is None else length, (), size),
        spring_count=_batched(np.nan if isinstance(springs, str) else springs, (), size),
    )


def _batched(value, shape: tuple, size: int) -> np.ndarray:
    value = np.asarray(value, dtype=np.float64)
    if value.shape == (size, *shape):
        return value
    return np.ascontiguousarray(np.broadcast_to(value, (size, *shape)))


def _groups(spec: SweepSpec, params: dict, size: int) -> tuple[list[Numerics], np.ndarray]:
    """Numerics of each group and the group of each point. `numerics_for` is evaluated once per
    distinct combination of the swept static fields (solver.*, limits.*, contact.*, effects.*)."""
    static = [axis.path for axis in spec.axes if axis.static]
    if not static:
        return [numerics_for(spec.scene, trajectory=False)], np.zeros(size, dtype=np.int64)
    columns = np.stack([params[path].astype(np.float64) for path in static], axis=1)
    combos, first, inverse = np.unique(columns, axis=0, return_index=True, return_inverse=True)
    found: dict[Numerics, int] = {}
    numerics, combo_group = [], np.empty(len(combos), dtype=np.int64)
    for combo in np.argsort(first):  # groups in the order their first point appears
        point = first[combo]
        scene = with_values(spec.scene, {path: params[path][point].item() for path in spec.paths})
        choice = numerics_for(scene, trajectory=False)
        if choice not in found:
            found[choice] = len(numerics)
            numerics.append(choice)
        combo_group[combo] = found[choice]
    return numerics, combo_group[inverse.reshape(-1)]


def expected_cost(scene: Scene, physics: Physics) -> np.ndarray:
    """Sort key of the points by expected solver cost: touch speed over the closed-form sticking
    velocity where the chapter has one (paraboloid, power law, cone with adhesion), else the
    touch speed. In scaled units the impact depends on v/v_s alone."""
    gravity = scene.effects.gravity is not None
    speed = physics.velocity
    if gravity:
        speed = np.sqrt(speed**2 + 2.0 * physics.gravity * physics.gap)
    sticking = sticking_velocity(scene, physics)
    usable = np.isfinite(sticking) & (sticking > 0)
    return np.where(usable, speed / np.where(usable, sticking, 1.0), speed)


def sticking_velocity(scene: Scene, physics: Physics) -> np.ndarray:
    """Closed-form sticking velocity (m/s) of each point of a batched Physics, numpy; NaN where
    the chapter gives none (the same formulas as `theory.*_sticking_velocity`)."""
    profile, mass, modulus, work = physics.profile, physics.mass, physics.E_star, physics.work_of_adhesion
    nan = np.full(np.shape(mass), np.nan)
    with np.errstate(all="ignore"):
        if isinstance(profile, profiles.Paraboloid):
            loss = np.cbrt(profile.R**4 * (np.pi * work) ** 5 / modulus**2) * (1 + np.cbrt(864.0)) / 10
            return np.where(work > 0, np.sqrt(2 * loss / mass), nan)
        if isinstance(profile, (profiles.PowerLaw, profiles.Cone)):
            if isinstance(profile, profiles.Cone):
                n, c = np.ones_like(mass), np.tan(profile.theta)
            else:
                n, c = profile.n, profile.c
            kappa = np.sqrt(np.pi) * np.exp(gammaln(n / 2 + 1) - gammaln((n + 1) / 2))
            p = 1 / (2 * n - 1)
            stiffness = modulus * (n * c * kappa) ** 2
            scale = ((np.pi * work / 2) ** (2 * n + 1) / stiffness**2) ** p
            shape = (8 * n - 4) / (2 * n**2 + 3 * n + 1) * (n + (n + 1) * (2 * n) ** (4 * p))
            return np.where((work > 0) & (n > 0.5), np.sqrt(scale * shape / mass), nan)
    return nan


# --- the compiled batch ----------------------------------------------------------------------


def _point_function(numerics: Numerics) -> Callable:
    """One impact → its scalar results in SI (the arithmetic of `simulate.to_result`)."""
    separated, captured = RESULT_CODE["separated"], RESULT_CODE["captured"]

    def point(physics: Physics) -> dict:
        scales, o = solve(physics, numerics)
        time_unit, length, force = scales.time, scales.normal, scales.force
        speed = length / time_unit
        touch = o.touch_velocity
        success = (o.status == separated) | (o.status == captured)
        ratio = o.separation_velocity / jnp.where(touch > 0, touch, 1.0)
        return {
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
            "dissipated_energy": o.first_contact_work * force * length,
            "steps": o.steps,
            "accepted_steps": o.accepted_steps,
            "rejected_steps": o.rejected_steps,
            "theory_restitution": closed_form_restitution(physics, numerics),
        }

    return point


def closed_form_restitution(physics: Physics, numerics: Numerics):
    """The chapter's restitution for one point (traced): Thornton–Ning for the paraboloid with
    Δγa = Δγ, (3.82) for power laws (n > 1/2) and cones (n = 1, c = tan θ) with Δγa = Δγ,
    attach on touch for the paraboloid with Δγa = 0, all without gravity; 1 without adhesion;
    NaN elsewhere. Maugis–Dugdale points get their JKR limit (Λ → ∞): no closed form has a
    finite range."""
    if not numerics.adhesive:
        return jnp.ones(())
    nan = jnp.full((), jnp.nan)
    if numerics.gravity:
        return nan
    profile = physics.profile
    v, m, modulus = touch_velocity(physics, numerics), physics.mass, physics.E_star
    work, approach = physics.work_of_adhesion, physics.approach_work_of_adhesion
    reversible = (approach == work) | (numerics.adhesion_model == "maugis_dugdale")
    if type(profile) is profiles.Paraboloid:
        jkr = theory.thornton_ning_restitution(v, m, profile.R, modulus, work)
        on_touch = theory.attach_on_touch_restitution(v, m, profile.R, modulus, work)
        return jnp.where(reversible, jkr, jnp.where(approach == 0, on_touch, nan))
    if type(profile) is profiles.PowerLaw:
        n = jnp.where(profile.n > 0.5, profile.n, 2.0)
        power = theory.power_law_restitution(v, m, n, profile.c, modulus, work)
        return jnp.where(reversible & (profile.n > 0.5), power, nan)
    if type(profile) is profiles.Cone:
        power = theory.power_law_restitution(v, m, 1.0, jnp.tan(profile.theta), modulus, work)
        return jnp.where(reversible, power, nan)
    return nan


_COMPILED: dict = {}


def local_devices(devices: "int | Sequence | None" = None) -> list:
    """The devices a sweep runs on: all local ones (None), the first n, or the ones given."""
    available = jax.local_devices()
    if devices is None:
        return available
    if isinstance(devices, int):
        if not 1 <= devices <= len(available):
            raise SweepError([("--devices", f"{devices} devices asked for, {len(available)} visible "
                                            f"({available[0].platform}); on CPU set JAX_NUM_CPU_DEVICES before jax starts")])
        return available[:devices]
    return list(devices)


def batch_sharding(devices: Sequence) -> NamedSharding:
    """The points' axis split over a 1-D mesh of the devices (AxisType.Auto: diffrax's events
    work under it, where an Explicit mesh, shard_map and pmap fail)."""
    mesh = jax.make_mesh((len(devices),), ("batch",), axis_types=(AxisType.Auto,), devices=devices)
    return NamedSharding(mesh, PartitionSpec("batch"))


def compiled_batch(numerics: Numerics, physics: Physics, size: int, devices: Sequence):
    """(compiled jit(vmap(point)) for `size` points of this structure, compile time in s).

    Compiled once per (numerics, leaf structure, size, devices) and kept for the session."""
    leaves, treedef = jax.tree.flatten(physics)
    key = (numerics, treedef, tuple((leaf.shape[1:], leaf.dtype) for leaf in leaves), size, tuple(d.id for d in devices))
    if key in _COMPILED:
        return _COMPILED[key], 0.0
    start = time.perf_counter()
    sharding = batch_sharding(devices)
    dtype = jnp.result_type(float)
    abstract = [jax.ShapeDtypeStruct((size, *leaf.shape[1:]), dtype, sharding=sharding) for leaf in leaves]
    function = jax.jit(jax.vmap(_point_function(numerics)))
    compiled = function.lower(jax.tree.unflatten(treedef, abstract)).compile()
    _COMPILED[key] = compiled
    return compiled, time.perf_counter() - start


_MAPPED: dict = {}
_SINGLE: dict = {}
COMPILE_SECONDS = {"unbatched": 0.0}  # time spent compiling the fallbacks, this session


def sequential(plan: Plan, group: int, points: np.ndarray, size: int) -> dict:
    """Results of the points solved one after another inside one compiled `lax.map` (no
    batching: each point takes only its own branches). The fallback for a chunk whose
    batched run raised; a point that raises even so is isolated by `one_by_one`."""
    numerics = plan.numerics[group]
    padded = np.concatenate([points, np.full(size - len(points), points[-1])])
    batch = jax.device_put(jax.tree.map(lambda leaf: leaf[padded], plan.physics), jax.local_devices()[0])
    leaves, treedef = jax.tree.flatten(batch)
    key = (numerics, treedef, tuple((leaf.shape, leaf.dtype) for leaf in leaves))
    if key not in _MAPPED:
        start = time.perf_counter()
        function = jax.jit(lambda physics: jax.lax.map(_point_function(numerics), physics))
        _MAPPED[key] = function.lower(batch).compile()
        COMPILE_SECONDS["unbatched"] += time.perf_counter() - start
    try:
        values = jax.device_get(_MAPPED[key](batch))
    except jax.errors.JaxRuntimeError:
        return one_by_one(plan, group, points)
    return {name: np.asarray(values[name])[: len(points)] for name in RESULTS}


def one_by_one(plan: Plan, group: int, points: np.ndarray) -> dict:
    """Results of the points solved one call each; a point whose solve raises gets the result
    code solver_failure."""
    numerics = plan.numerics[group]
    if numerics not in _SINGLE:
        _SINGLE[numerics] = jax.jit(_point_function(numerics))
    function = _SINGLE[numerics]
    results = empty_results(len(points))
    for row, point in enumerate(points):
        physics = jax.tree.map(lambda leaf: leaf[point], plan.physics)
        try:
            values = jax.device_get(function(physics))
        except jax.errors.JaxRuntimeError:
            results["status"][row] = RESULT_CODE["solver_failure"]
            continue
        for name in RESULTS:
            results[name][row] = values[name]
    return results


# --- running ---------------------------------------------------------------------------------


class Progress:
    """Callbacks of a running sweep (override what you need)."""

    def compiling(self, group: int, groups: int) -> None: ...

    def compiled(self, seconds: float) -> None: ...

    def advance(self, points: int) -> None: ...


def chunk_size(chunk: int, devices: int) -> int:
    """`chunk` rounded up to a multiple of the device count."""
    if chunk < 1:
        raise SweepError([("--chunk", f"must be >= 1, got {chunk}")])
    return -(-chunk // devices) * devices


def chunks_of(shares: list[np.ndarray], chunk: int, skip: int = 0) -> list[tuple[int, np.ndarray]]:
    """(group, points) of each chunk, in order, after the first `skip` points of the shares.

    A group of n points is cut into k = ceil(n/chunk) chunks of ceil(n/k) points (the last one
    may be shorter), so no call is mostly padding: 1200 points at chunk 1000 make two calls of
    600, not 1000 + 200 padded to 1000. The cut depends on n and `chunk` alone, not on the
    devices: a resumed sweep recomputes the same chunks."""
    out = []
    for group, points in enumerate(shares):
        if len(points) == 0:
            continue
        length = -(-len(points) // -(-len(points) // chunk))
        for begin in range(0, len(points), length):
            part = points[begin: begin + length]
            if skip >= len(part):
                skip -= len(part)
                continue
            out.append((group, part[skip:]))
            skip = 0
    return out


def execute(
    plan: Plan,
    *,
    chunk: int = DEFAULT_CHUNK,
    devices: "int | Sequence | None" = None,
    share: tuple[int, int] = (0, 1),
    skip: int = 0,
    on_chunk: Callable[[np.ndarray, dict], None] | None = None,
    progress: Progress | None = None,
) -> dict:
    """Run the plan's points of this share (after the first `skip`), chunk by chunk; hand each
    finished chunk (its points, its results) to `on_chunk` in order. Returns timing stats."""
    with _quiet_callback_errors():
        return _execute(plan, chunk, devices, share, skip, on_chunk, progress or Progress())


@contextlib.contextmanager
def _quiet_callback_errors():
    """Keep the log of a failed runtime check (jax.pure_callback) off stderr: `execute`
    handles it by solving the chunk point by point."""
    logger = logging.getLogger("jax._src.callback")
    level = logger.level
    logger.setLevel(logging.CRITICAL)
    try:
        yield
    finally:
        logger.setLevel(level)


def _execute(plan, chunk, devices, share, skip, on_chunk, progress) -> dict:
    devices = local_devices(devices)
    if chunk < 1:
        raise SweepError([("--chunk", f"must be >= 1, got {chunk}")])
    sharding = batch_sharding(devices)
    shares = plan.share(*share)
    work = chunks_of(shares, chunk, skip)
    # Each group's calls take its (first) chunk length, padded to a multiple of the devices.
    sizes = {group: chunk_size(len(chunks_of([points], chunk)[0][1]), len(devices))
             for group, points in enumerate(shares) if len(points)}
    compile_time, pending, done = 0.0, None, 0
    compiled_groups: dict[int, object] = {}
    for group in sorted({group for group, _ in work}):
        progress.compiling(group, len(plan.numerics))
        compiled_groups[group], seconds = compiled_batch(plan.numerics[group], plan.physics, sizes[group], devices)
        compile_time += seconds
        progress.compiled(seconds)
    start = time.perf_counter()
    fallbacks, fallback_compile = 0, COMPILE_SECONDS["unbatched"]

    def finish(entry):
        nonlocal fallbacks
        group, points, outputs = entry
        values = None
        if outputs is not None:
            try:
                values = jax.device_get(outputs)
            except jax.errors.JaxRuntimeError:
                values = None
        if values is None:
            # A runtime check inside the batch failed. Under vmap one lane's failed check
            # stops every lane, even a check in a branch that lane does not take (e.g. the
            # bracket check of the event root finder), so solve the chunk's points one after
            # another, unbatched, as `simulate` would.
            values = sequential(plan, group, points, sizes[group])
            fallbacks += len(points)
        results = {name: np.asarray(values[name])[: len(points)] for name in RESULTS}
        if on_chunk is not None:
            on_chunk(points, results)
        progress.advance(len(points))
        return len(points)

    for group, points in work:
        padded = np.concatenate([points, np.full(sizes[group] - len(points), points[-1])])
        batch = jax.tree.map(lambda leaf: leaf[padded], plan.physics)
        try:
            outputs = compiled_groups[group](jax.device_put(batch, sharding))  # dispatched, not awaited
        except jax.errors.JaxRuntimeError:
            outputs = None  # the error surfaces when reading back (`finish`), or here
        if pending is not None:
            done += finish(pending)
        pending = (group, points, outputs)
    if pending is not None:
        done += finish(pending)
    fallback_compile = COMPILE_SECONDS["unbatched"] - fallback_compile
    solve_time = time.perf_counter() - start - fallback_compile
    return {
        "points": done,
        "solved_unbatched": fallbacks,
        "chunk": chunk,
        "call_sizes": sorted(set(sizes.values())),
        "devices": len(devices),
        "groups": len(plan.numerics),
        "compile_time": compile_time + fallback_compile,
        "solve_time": solve_time,
        "points_per_second": done / solve_time if solve_time > 0 else math.nan,
        "plan_time": plan.time,
        "order": plan.spec.order,
    }


def run_spec(
    spec: SweepSpec,
    *,
    chunk: int = DEFAULT_CHUNK,
    devices: "int | Sequence | None" = None,
    progress: Progress | None = None,
) -> SweepResult:
    """Run a validated sweep in memory."""
    plan = plan_sweep(spec)
    results = empty_results(plan.size)

    def store(points, values):
        for name, column in values.items():
            results[name][points] = column

    stats = execute(plan, chunk=chunk, devices=devices, on_chunk=store, progress=progress)
    return SweepResult.from_flat(spec, plan.params, results, stats)


def sweep(
    scene: "Scene | Mapping | str | Path",
    axes: Mapping[str, object],
    mode: str = "grid",
    *,
    order: str = "cost",
    chunk: int = DEFAULT_CHUNK,
    devices: "int | Sequence | None" = None,
    progress: Progress | None = None,
) -> SweepResult:
    """Simulate a scene over axes of its numeric fields (dotted path → values, or a generator
    such as {"geomspace": [0.2, 20, 400]}), combined as a grid or zipped.

    Returns every scalar result as an array in the sweep's shape, with the chapter's closed-form
    restitution where it has one. Raises SweepError (a SceneError: `.problems` names each bad
    field) before running anything. Enable float64 first (`jax.config.update("jax_enable_x64",
    True)`)."""
    return run_spec(make_spec(scene, axes, mode, order), chunk=chunk, devices=devices, progress=progress)


# --- theory curves, sticking velocities, the figure ---------------------------------------------

_CURVE_POINTS = 512
_CURVES: dict = {}


def theory_curve(spec: SweepSpec, fixed: Mapping[str, object], path: str, values: np.ndarray) -> np.ndarray:
    """The closed-form restitution along `path` = values (other swept fields at `fixed`)."""
    values = np.asarray(values, dtype=np.float64)
    count = len(values)
    size = _CURVE_POINTS * max(1, -(-count // _CURVE_POINTS))
    padded = np.concatenate([values, np.full(size - count, values[-1])])
    params = {p: np.full(size, v) for p, v in fixed.items() if p != path}
    params[path] = padded
    physics = batch_physics(spec.scene, params, size)
    point = with_values(spec.scene, {p: params[p][0].item() for p in params})
    numerics = numerics_for(point, trajectory=False)
    leaves, treedef = jax.tree.flatten(physics)
    key = (numerics, treedef, tuple(leaf.shape for leaf in leaves))
    if key not in _CURVES:
        _CURVES[key] = jax.jit(jax.vmap(lambda p: closed_form_restitution(p, numerics)))
    return np.asarray(_CURVES[key](physics))[:count]


def x_axis(spec: SweepSpec) -> str:
    """The axis figures and sticking estimates run along: the velocity if swept, else the first."""
    return VELOCITY if VELOCITY in spec.paths else spec.paths[0]


def _series(result: SweepResult):
    """(x path, x [N], [(fixed values of the other axes, point indices sorted by x)])."""
    spec = result.spec
    path = x_axis(spec)
    flat = {p: v.reshape(-1) for p, v in result.params.items()}
    x = flat[path]
    others = [p for p in spec.paths if p != path]
    if not others:
        return path, x, [({}, np.argsort(x, kind="stable"))]
    columns = np.stack([flat[p].astype(np.float64) for p in others], axis=1)
    combos, first, inverse = np.unique(columns, axis=0, return_index=True, return_inverse=True)
    inverse = inverse.reshape(-1)
    series = []
    for combo in np.argsort(first):
        members = np.flatnonzero(inverse == combo)
        fixed = {p: flat[p][members[0]].item() for p in others}
        series.append((fixed, members[np.argsort(x[members], kind="stable")]))
    return path, x, series


def _theory_dense(spec: SweepSpec, fixed: dict, path: str, low: float, high: float):
    """(x, e_theory) on a dense grid from low to high, refined three times (uniformly, 512
    points each) in the interval where e_theory leaves 0, which brackets the closed-form
    sticking velocity to ~1e-8 of the interval."""
    logarithmic = low > 0 and high / low > 10
    grid = np.geomspace(low, high, _CURVE_POINTS) if logarithmic else np.linspace(low, high, _CURVE_POINTS)
    values = theory_curve(spec, fixed, path, grid)
    for _ in range(3):
        crossing = np.flatnonzero((values[:-1] == 0) & (values[1:] > 0))
        if not crossing.size:
            break
        refined = np.linspace(grid[crossing[0]], grid[crossing[0] + 1], _CURVE_POINTS)[1:-1]
        grid = np.concatenate([grid, refined])
        values = np.concatenate([values, theory_curve(spec, fixed, path, refined)])
        order = np.argsort(grid, kind="stable")
        grid, values = grid[order], values[order]
    return grid, values


def closed_form_names(result: SweepResult) -> list[str]:
    """The closed forms the sweep's series are compared with."""
    _, _, series = _series(result)
    theory_e = result.theory_restitution.reshape(-1)
    names = []
    for fixed, members in series:
        name = closed_form_name(with_values(result.scene, fixed))
        if np.isfinite(theory_e[members]).any() and name not in names:
            names.append(name)
    return names


def sticking_estimates(result: SweepResult) -> list[dict]:
    """Per combination of the other axes, along the velocity axis: the bracket of the sticking
    velocity (largest captured v, smallest separated v above it), an estimate from the first
    separated points (e² = 1 − (v_s/v)², exact for an energy loss independent of v), the
    closed-form v_s (where e_theory leaves 0) and max |e − e_theory|."""
    if VELOCITY not in result.spec.paths:
        return []
    path, x, series = _series(result)
    e = result.restitution.reshape(-1)
    status = result.status.reshape(-1)
    theory_e = result.theory_restitution.reshape(-1)
    rows = []
    for fixed, members in series:
        ok = members[(status[members] == RESULT_CODE["separated"]) | (status[members] == RESULT_CODE["captured"])]
        v, ev = x[ok], e[ok]
        captured = status[ok] == RESULT_CODE["captured"]
        row = {"fixed": fixed, "low": math.nan, "high": math.nan, "estimate": math.nan, "theory": math.nan,
               "max_error": math.nan, "points": len(members), "failed": len(members) - len(ok)}
        if captured.any():
            row["low"] = float(v[captured].max())
        above = ~captured & (v > (row["low"] if captured.any() else -math.inf))
        if above.any():
            first = np.flatnonzero(above)[:2]
            row["high"] = float(v[first[0]])
            squares = 1.0 - ev[first] ** 2
            estimates = v[first] * np.sqrt(np.clip(squares, 0.0, None))
            if len(first) == 2 and v[first[1]] != v[first[0]]:
                # e² = A − B/v² through the two points: v_s = √(B/A)
                inv = 1.0 / v[first] ** 2
                slope = (ev[first[1]] ** 2 - ev[first[0]] ** 2) / (inv[1] - inv[0])
                intercept = ev[first[0]] ** 2 - slope * inv[0]
                if slope < 0 and intercept > 0:
                    estimates = np.array([math.sqrt(-slope / intercept)])
            estimate = float(estimates[0])
            if captured.any():
                estimate = min(max(estimate, row["low"]), row["high"])
            row["estimate"] = estimate if captured.any() else min(estimate, row["high"])
        th = theory_e[members]
        usable = np.isin(members, ok) & np.isfinite(th)
        if usable.any():
            row["max_error"] = float(np.max(np.abs(e[members][usable] - th[usable])))
            dense_v, dense_e = _theory_dense(result.spec, fixed, path, float(x[members].min()) / 4, float(x[members].max()))
            positive = np.flatnonzero(dense_e > 0)
            if positive.size and positive[0] > 0:
                row["theory"] = float(0.5 * (dense_v[positive[0] - 1] + dense_v[positive[0]]))
        rows.append(row)
    return rows


def _label(fixed: dict) -> str:
    return ", ".join(f"{p.split('.')[-1]} = {v:.4g}" for p, v in fixed.items())


def _two_and_five(value, _position) -> str:
    """Minor tick label of a log axis spanning few decades: 2 and 5 times a power of 10."""
    if value <= 0:
        return ""
    mantissa = round(value / 10 ** math.floor(math.log10(value)), 6)
    return f"{value:g}" if mantissa in (2.0, 5.0) else ""


def closed_form_name(scene: Scene) -> str:
    """Which closed form `theory_restitution` holds for a scene (as the figure names it)."""
    adhesion = scene.effects.adhesion
    if adhesion is None or not adhesion.work_of_adhesion > 0:
        return "no adhesion: e = 1"
    if scene.effects.gravity is not None:
        return "no closed form (gravity)"
    shape = scene.body.profile.shape
    if adhesion.model == "maugis_dugdale":
        limit = {"paraboloid": "Thornton–Ning (3.50–51)", "power_law": "power law (3.81–82)", "cone": "power law (3.81–82)"}
        return f"{limit[shape]}: the JKR limit Λ → ∞ of Maugis–Dugdale"
    if shape == "paraboloid":
        if adhesion.approach == adhesion.work_of_adhesion:
            return "Thornton–Ning (3.50–51)"
        if adhesion.approach == 0:
            return "attach on touch (theory.attach_on_touch_restitution)"
    if shape in ("power_law", "cone") and adhesion.approach == adhesion.work_of_adhesion:
        return "power law (3.81–82)"
    return "closed form"


def restitution_figure(result: SweepResult, max_series: int = 12) -> Figure:
    """e against the velocity (log axis) for each value of the other axes: simulated points
    (open markers, gid "simulated") and the closed-form curve beside them (lines, gid
    "theory"); below, |e − e_theory| of the separated points."""
    path, x, series = _series(result)
    e = result.restitution.reshape(-1)
    theory_e = result.theory_restitution.reshape(-1)
    status = result.status.reshape(-1)
    has_theory = bool(np.isfinite(theory_e).any())
    figure = Figure(figsize=(7.5, 7.0 if has_theory else 5.0), layout="constrained")
    if has_theory:
        top, bottom = figure.subplots(2, 1, sharex=True, height_ratios=(3, 1.3))
    else:
        top, bottom = figure.subplots(), None
    logarithmic = bool(np.all(x > 0)) and x.max() / x.min() > 10
    outcome = (RESULT_CODE["separated"], RESULT_CODE["captured"])
    for k, (fixed, members) in enumerate(series[:max_series]):
        name = closed_form_name(with_values(result.scene, fixed))
        color = f"C{k % 10}"
        label = _label(fixed)
        ok = members[np.isin(status[members], outcome)]
        failed = members[~np.isin(status[members], outcome)]
        if np.isfinite(theory_e[members]).any():
            dense_x, dense_e = _theory_dense(result.spec, fixed, path, float(x[members].min()), float(x[members].max()))
            top.plot(dense_x, dense_e, "-", color=color, lw=1.1, zorder=4, gid="theory",
                     label=f"{name}{': ' + label if label else ''}")
            separated = ok[(status[ok] == RESULT_CODE["separated"]) & np.isfinite(theory_e[ok])]
            error = np.abs(e[separated] - theory_e[separated])
            bottom.plot(x[separated], np.maximum(error, 1e-17), ".", ms=2 if len(separated) > 1000 else 3, color=color)
        # open markers under the closed-form line; at most ~300 drawn per series (all kept as data)
        top.plot(x[ok], e[ok], "o", ms=3.5, mfc="none", mew=0.8, color=color, alpha=0.7, zorder=3, gid="simulated",
                 markevery=max(1, len(ok) // 300), label=f"simulated{': ' + label if label else ''}")
        if failed.size:
            top.plot(x[failed], np.zeros(failed.size), "x", color="red", ms=5, zorder=4,
                     label="no physical outcome (see status)" if k == 0 else None)
    if len(series) > max_series:
        top.text(0.02, 0.02, f"{max_series} of {len(series)} series shown", transform=top.transAxes, fontsize="small")
    unit = " (m/s)" if path == VELOCITY else ""
    for axes in (top, bottom):
        if axes is None:
            continue
        if logarithmic:
            axes.set_xscale("log")
            axes.xaxis.set_major_formatter(FormatStrFormatter("%g"))
            few_decades = math.log10(x.max() / x.min()) < 2.5
            axes.xaxis.set_minor_formatter(FuncFormatter(_two_and_five) if few_decades else NullFormatter())
        axes.grid(alpha=0.3, which="both")
    top.set_ylabel("coefficient of restitution e")
    top.axhline(0.0, color="0.6", lw=0.8, zorder=0)
    top.legend(loc="lower right", fontsize="x-small")
    top.set_title(f"{result.scene.name}: restitution against {path.split('.')[-1]} ({result.restitution.size} points)")
    (bottom or top).set_xlabel(f"{path}{unit}")
    if bottom is not None:
        bottom.set_yscale("log")
        bottom.set_ylabel("|e − e_theory|\n(separated points)")
    return figure


def save_restitution_figure(result: SweepResult, path: "str | Path") -> Path:
    from .._io.run import atomic_path

    path = Path(path)
    with atomic_path(path) as temporary:
        restitution_figure(result).savefig(temporary, dpi=150)
    return path
