"""A scene as a differentiable function: `as_function(scene, inputs, output)` → f(x), x the
values of traced scene fields, f the SI results of one impact, with exact derivatives.

How f is differentiated: diffrax's default adjoint (a `custom_vjp`) forbids forward mode and
the phase loop (a `lax.while_loop`) forbids reverse mode; forward mode passes through both
(`dfx.ForwardMode`). So f is a `jax.custom_jvp` whose rule computes the whole Jacobian in
forward mode, one tangent per input (a few inputs: cheap), and returns J·ẋ. That is linear in
ẋ, so JAX transposes it for reverse mode: `jax.grad`, `jax.jacrev`, `jax.jacfwd`, `jax.vmap`
and `jax.jit` all work, and f's value alone runs the program of an ordinary run. The event
times are differentiated by the implicit function theorem (optimistix's root finding under
diffrax's events), the searches of the contact law likewise (`impact._core.derivatives`).
"""

import dataclasses
import functools
from collections.abc import Callable, Sequence
from pathlib import Path

import jax
import jax.numpy as jnp
import numpy as np

from .._core.runtime import compiler_options, float64
from .._core.stored import compile_stored
from .._integrate.base import AbstractAdaptiveIntegrator
from .._integrate.verlet import Verlet
from .._scene.errors import SceneError
from .._scene.paths import AbsentSection, NoField, resolve_field, with_values
from .._scene.scene import Scene, load_scene, scene_yaml
from .._scene.sweep_axes import numeric_field
from .sweep.batch import point_function
from .sweep.plan import StaticChoices, physics_with, static_choices

# The results of `point_function` that are smooth functions of the traced values (SI).
OUTPUTS = (
    "restitution",
    "contact_time",
    "max_indentation",
    "max_force",
    "min_force",
    "touch_velocity",
    "separation_velocity",
    "dissipated_energy",
    "tangential_velocity_after",
    "spin_after",
    "tangential_restitution",
    "contact_point_tangential_restitution",
    "rebound_angle",
    "friction_work",
)
_STATIC = (
    "selects the compiled program (a static choice of the solver, the limits, the contact or "
    "the effects): it cannot be an input; inputs are traced values such as velocities, moduli, "
    "works of adhesion, masses and profile parameters"
)


@float64
def as_function(
    scene: "Scene | dict | str | Path", inputs: Sequence[str], output: "str | Sequence[str]"
) -> Callable[[jax.Array], jax.Array]:
    """f(x): the `output` (one name: a float64 scalar; a list: a vector) of the impact with the
    scene fields at the dotted paths `inputs` set to x[0], x[1], … (SI units).

    f is jax-traceable and differentiable (`jax.grad`, `jax.jacfwd`, `jax.jacrev`, `jax.vmap`,
    `jax.jit`), computed in float64 whatever JAX's global flag (with the flag off JAX holds no
    float64 in a traced program: f computes on the host and answers in float32). Its value is
    NaN where the impact does not end in a success (separated or captured); it is
    differentiable where the first contact ends in a clean separation (a capture makes e jump
    to 0). Raises `SceneError` naming an input that
    is not a traced value of the scene, an unknown output, or a scene f cannot differentiate.

        f = impact.as_function("configs/thornton_ning.yaml",
                               ["effects.adhesion.work_of_adhesion", "initial.velocity"], "restitution")
        jax.grad(f)(jnp.array([0.05, 0.6]))  # [-4.931, 0.4931]: de/dΔγ (m²/J), de/dv0 (s/m)
    """
    scene = load_scene(scene)
    if scene.kind != "impact":
        raise SceneError([("kind", f"as_function runs impacts; the scene is of kind {scene.kind!r}")])
    paths = list(inputs)
    names = [output] if isinstance(output, str) else list(output)
    choices = static_choices(scene)
    _check(scene, paths, names, choices)
    described = SceneFunction(scene_yaml(scene), tuple(paths), tuple(names), isinstance(output, str))
    _PREPARED.setdefault(described, (scene, *_programs(choices)))
    value = _compiled_once(_value, described)
    jacobian = _compiled_once(_jacobian, described)

    # Not itself under jax.jit: a jitted custom_jvp function, vmapped and differentiated inside
    # an outer jit (a fit: jit(jvp(vmap(f)))), returned its outputs transposed (jax 0.10.2).
    @jax.custom_jvp
    def solved(x: jax.Array) -> jax.Array:
        return value(x)

    @solved.defjvp
    def solved_jvp(primals, tangents):
        # The value from its own program, not from the Jacobian's batch of jvps: taken from
        # there, vmapped under an outer jit (optimistix's Levenberg–Marquardt over a fit's rows)
        # the outputs came back transposed (jax 0.10.2). One solve more per Jacobian.
        derivative = jacobian(primals[0])[1]
        return value(primals[0]), derivative @ tangents[0]

    return _in_float64(solved, jacobian, paths, () if isinstance(output, str) else (len(names),))


@dataclasses.dataclass(frozen=True)
class SceneFunction:
    """What names the programs of one f: the scene (YAML), the input paths, the output names
    and whether f answers a scalar (one name given as a string)."""

    scene: str
    paths: tuple[str, ...]
    names: tuple[str, ...]
    scalar: bool


# The scene of every f made and its two point functions (`_programs`), by f's description: what
# a trace of f's programs reads (the scene loaded where f is made: loading one computes its
# checks, which a trace cannot).
_PREPARED: dict[SceneFunction, tuple[Scene, Callable, Callable]] = {}


def _results(described: SceneFunction, point: Callable, x: jax.Array) -> jax.Array:
    """The outputs of `point` at x: NaN where the impact does not end in a success."""
    scene = _PREPARED[described][0]
    values = point(physics_with(scene, dict(zip(described.paths, x, strict=True)), jnp))
    success = jnp.isfinite(values["restitution"])
    out = jnp.stack([jnp.where(success, values[name], jnp.nan) for name in described.names])
    return out[0] if described.scalar else out


def _value(described: SceneFunction, x: jax.Array) -> jax.Array:
    """f(x), by the point function of an ordinary run."""
    return _results(described, _PREPARED[described][1], x)


def _jacobian(described: SceneFunction, x: jax.Array) -> tuple[jax.Array, jax.Array]:
    """(f(x), ∂f/∂x [outputs…, inputs]): one forward-mode tangent per input, the point
    repeated with it (a tangent batched over an unbatched point trips optimistix's implicit
    solve at diffrax's events). grad, jacfwd and jacrev all call it."""
    forward = _PREPARED[described][2]

    def tangent_of(point: jax.Array, tangent: jax.Array) -> tuple[jax.Array, jax.Array]:
        return jax.jvp(lambda y: _results(described, forward, y), (point,), (tangent,))

    size = x.shape[0]
    values, columns = jax.vmap(tangent_of)(jnp.broadcast_to(x, (size, size)), jnp.eye(size, dtype=x.dtype))
    return values[0], jnp.moveaxis(columns, 0, -1)


def _in_float64(
    solved: Callable, jacobian: Callable, paths: list[str], shape: tuple
) -> Callable[[jax.Array], jax.Array]:
    """f computing in float64 whatever JAX's global flag. With the flag on, f is `solved`
    (its programs compiled). With it off JAX holds no float64 value in a traced program, so f hands the
    solve and its Jacobian to the host (`jax.pure_callback`, where they run in float64, a
    batch point by point) and returns the dtype of its input; J·ẋ keeps it differentiable."""

    def compiled_jacobian(x: jax.Array) -> jax.Array:
        return jacobian(x)[1]

    def on_host(function: Callable, dtype) -> Callable:
        def run(x: np.ndarray) -> np.ndarray:
            with jax.enable_x64(True):
                flat = np.asarray(x, np.float64).reshape(-1, len(paths))
                out = np.stack([np.asarray(function(point)) for point in flat])
            return out.reshape(x.shape[:-1] + out.shape[1:]).astype(dtype)

        return run

    @jax.custom_jvp
    def hosted(x: jax.Array) -> jax.Array:
        result = jax.ShapeDtypeStruct(shape, x.dtype)
        return jax.pure_callback(on_host(solved, x.dtype), result, x, vmap_method="expand_dims")

    @hosted.defjvp
    def hosted_jvp(primals, tangents):
        (x,), (dx,) = primals, tangents
        value = hosted(x)
        result = jax.ShapeDtypeStruct((*value.shape, len(paths)), x.dtype)
        derivative = jax.pure_callback(on_host(compiled_jacobian, x.dtype), result, x, vmap_method="expand_dims")
        return value, derivative @ dx

    def f(x: jax.Array) -> jax.Array:
        if jnp.shape(x) != (len(paths),):
            raise ValueError(f"f takes its {len(paths)} inputs {paths} as a vector, got shape {jnp.shape(x)}")
        if jax.config.read("jax_enable_x64"):
            return solved(jnp.asarray(x, jnp.float64))
        return hosted(jnp.asarray(x, jnp.result_type(float)))

    return f


def _compiled_once(function: Callable, described: SceneFunction) -> Callable:
    """`function(described, x)` compiled ahead once per shape and dtype of a concrete vector x and
    that executable run for every concrete vector; stored traced in the cache
    (`impact._core.stored`), so that a later process neither traces nor compiles it. Called
    from the rule of a custom_jvp function, a jitted function is lowered and compiled again
    under each transformation (jacfwd, grad and a plain call would each compile the Jacobian
    again). A tracer (f under an outer jit or vmap) goes to the jitted
    function."""
    program = jax.jit(functools.partial(function, described))
    executables: dict[tuple, Callable] = {}

    def once(x):
        if isinstance(x, jax.core.Tracer):
            return program(x)
        x = np.asarray(x)
        key = (x.shape, x.dtype)
        if key not in executables:
            abstract = jax.ShapeDtypeStruct(x.shape, x.dtype)
            label = f"{function.__module__}.{function.__qualname__} {described!r}"
            executables[key] = compile_stored(program, label, abstract, compiler_options())
        return executables[key](x)

    return once


def _programs(choices: StaticChoices) -> tuple[Callable, Callable]:
    """(the point as sweeps run it, the point with its rides in forward-mode adjoint)."""
    integrator = choices.integrator
    if isinstance(integrator, AbstractAdaptiveIntegrator):
        forward = StaticChoices(integrator.__class__(**{**_fields(integrator), "adjoint": "forward"}), choices.options)
    else:
        forward = choices
    return point_function(choices), point_function(forward)


def _fields(module) -> dict:
    return {field.name: getattr(module, field.name) for field in dataclasses.fields(module)}


def _check(scene: Scene, paths: list[str], names: list[str], choices: StaticChoices) -> None:
    """Refuse what f cannot be: inputs that are not traced values, unknown outputs, the
    fixed-step spring array (its results jump with every spring: no derivative)."""
    problems = []
    if isinstance(choices.integrator, Verlet):
        problems.append(
            ("solver.method", "verlet steps a spring array at a fixed dt: its results jump with every spring, "
             "so they have no derivative; use an adaptive method or the exact spring array")
        )  # fmt: skip
    if not paths:
        problems.append(("inputs", "name at least one input, e.g. initial.velocity"))
    problems += [(path, "named twice") for index, path in enumerate(paths) if path in paths[:index]]
    for path in dict.fromkeys(paths):
        reason = _not_traced(scene, path, choices)
        if reason:
            problems.append((path, reason))
    if not names:
        problems.append(("output", f"name at least one output; known: {', '.join(OUTPUTS)}"))
    problems += [
        ("output", f"unknown output {name!r}; known: {', '.join(OUTPUTS)}") for name in names if name not in OUTPUTS
    ]
    if problems:
        raise SceneError(problems)


def _not_traced(scene: Scene, path: str, choices: StaticChoices) -> str | None:
    """Why `path` cannot be an input of f (None: it can): no numeric field, an integer, a
    static choice, or a value the impact does not read."""
    try:
        resolve_field(scene, path)
        owner, name = numeric_field(scene, path)
    except (NoField, AbsentSection) as error:
        return str(error)
    except SceneError as error:
        return error.problems[0][1]
    value = getattr(owner, name)
    if value is None:
        return f"{path} is not set in the scene"
    if isinstance(value, (int, np.integer)) and not isinstance(value, bool):
        return f"{path} is an integer ({value}): it has no derivative"
    moved = value * (1.0 + 1e-3) if value != 0 else 1e-3
    changed = with_values(scene, {path: moved})
    if static_choices(changed) != choices:
        return _STATIC
    before = jax.tree.leaves(physics_with(scene, {}, np))
    after = jax.tree.leaves(physics_with(scene, {path: np.float64(moved)}, np))
    if all(np.array_equal(a, b, equal_nan=True) for a, b in zip(before, after, strict=True)):
        return f"{path} does not enter the simulated impact (no traced parameter depends on it)"
    return None
