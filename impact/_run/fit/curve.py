"""The closed-form model of a quasi-static indentation curve (the AFM use): the observable at a
given control value on the branch the test is on.

Under the JKR law (rule of Heß) an attached contact of radius a on the edge of a work of
adhesion w has the indentation d = h_w(a) = g(a) − √(2πaw/E*) and the force
F = 2E*(a·d − G(a)) (3.26), (3.28); for the paraboloid these are (3.44). For a body whose h(a)
(and F along it) has one minimum (the profiles of `SHAPES`), the stable branch is the part
beyond that minimum, where the controlled value rises with a; the state at a control value is
the root a of that rise, found by bisection in log a and differentiated by the implicit function
theorem. Approach follows the edge of the approach work of adhesion Δγa, retract that of Δγ
(attach hysteresis, 0 ≤ Δγa ≤ Δγ; Δγa = Δγ is the reversible JKR law):

- displacement control (ξ = 1): on approach the contact jumps in at first touch (d = 0, radius
  a₀ with h_Δγa(a₀) = 0) and follows the Δγa branch up to the program's peak, radius a_max;
  on retract the radius stays at a_max (F = 2E*(a_max·d − G(a_max))) down to the detach
  criterion d = h_Δγ(a_max), then follows the Δγ branch down to its minimum (the critical point
  of (3.30), ξ = 1) and jumps out below it;
- force control (ξ = 3): on approach the body lands at F = 0 on the Δγa branch and follows it
  for F ≥ 0; on retract it holds a_max down to the force at the detach criterion, then follows
  the Δγ branch down to the minimum of F (the JKR pull-off (3.46) for the paraboloid).

Beyond the jump (d < 0 on approach, d below the critical point on retract) there is no contact:
the force and the contact radius are 0, whatever the parameters; such rows weigh in χ² with a
zero derivative, and tell the fit where the jump is only through which branch a row falls on.
Under force control a force beyond the branch's end has no contact and no defined indentation:
the model holds the state at the end of the branch (leave such rows out of the data). The
approach rows are the first loading, the retract rows the last unloading from the peak (the
program's `peak`, or the row's own control value where it lies beyond).

Adhesion of finite range (Maugis–Dugdale, Greenwood–Johnson) under displacement control is the
model of `range_curve`.
"""

import functools
from dataclasses import dataclass

import jax
import jax.numpy as jnp
import yaml

from ..._core import derivatives
from ..._core.search import log_sign_change
from ..._integrate.quasistatic.loading import SCALE_DECADES, SCALE_STEPS
from ..._scene.adhesion import AbstractAdhesion
from ..._scene.fit_spec import FitSpec
from ..._scene.paths import with_values
from ..._scene.scene import Scene, load_scene, scene_yaml
from .range_curve import finite_range_state

# The profiles whose JKR curve h(a) = g(a) − Δl(a) falls to one minimum and then rises.
SHAPES = ("paraboloid", "sphere", "ellipsoid", "cone", "power_law")
# The scene values the curve depends on: the modulus, the profile, the adhesion's parameters.
CURVE_PATHS = ("material.", "body.profile.", "effects.adhesion.")
# A contact radius never reaches the end of a walled or bounded profile (the sphere's equator).
EDGE_MARGIN = 1e-9


@functools.lru_cache(maxsize=8)
def _scene(text: str) -> Scene:
    return load_scene(yaml.safe_load(text))


@dataclass(frozen=True)
class IndentationCurve:
    """The curve as a model of x = [varied scene values, control value, branch (0 approach,
    1 retract)]: the `observables` at that point; equal instances share one compiled fit."""

    scene: str  # the scene as YAML (hashable)
    varied: tuple[str, ...]  # the dotted paths set from x, in order
    observables: tuple[str, ...]

    def __call__(self, x: jax.Array) -> jax.Array:
        count = len(self.varied)
        return self.states(x[:count], x[None, count:])[0]

    def batched(self, values: jax.Array, rows: jax.Array) -> jax.Array:
        """The observables [rows, observables] at the fitted `values` and the rows [inputs,
        control value, branch]: without inputs the curve is computed once, not per row."""
        inputs = rows.shape[1] - 2
        if inputs:  # scene values set row by row: each row has a curve of its own
            return jax.vmap(lambda row: self.states(jnp.concatenate([values, row[:inputs]]), row[None, inputs:])[0])(
                rows
            )
        return self.states(values, rows)

    def states(self, values: jax.Array, rows: jax.Array) -> jax.Array:
        """The observables [rows, observables] at the values of all varied paths and each row
        [control value, branch] (what does not depend on the row computed once: the branches,
        their turning points, the equilibrium curve of a finite-range law)."""
        scene = _scene(self.scene)
        batch = with_values(scene, {path: values[index] for index, path in enumerate(self.varied)})
        adhesion = batch.effects.adhesion
        assert adhesion is not None, "checked: model 'theory' needs adhesion"
        if not adhesion.zero_range:

            def state(control, retract):
                return finite_range_state(scene, batch, control, retract)

        else:

            def state(control, retract):
                return curve_state(
                    batch.body.profile.build(),
                    jnp.asarray(batch.material.effective_modulus, jnp.float64),
                    jnp.asarray(adhesion.work_of_adhesion, jnp.float64),
                    jnp.asarray(adhesion.approach, jnp.float64),
                    scene.control == "force",
                    jnp.asarray(scene.loading.peak, jnp.float64),
                    control,
                    retract,
                )

        states = jax.vmap(state)(rows[:, 0], rows[:, 1] > 0.5)
        return jnp.stack([states[name] for name in self.observables], axis=1)


def curve_model(spec: FitSpec) -> IndentationCurve:
    """The closed-form curve of an indentation scene as a model (checked by `curve_problems`)."""
    return IndentationCurve(scene_yaml(spec.scene), (*spec.parameters, *spec.inputs), tuple(spec.observables))


def curve_problems(spec: FitSpec) -> list[tuple[str, str]]:
    """(field, message) of what the closed-form curve cannot describe."""
    scene = spec.scene
    adhesion = scene.active_adhesion
    if adhesion is None:
        return [("scene.effects.adhesion", "model 'theory' of an indentation curve needs adhesion")]
    problems = []
    if not adhesion.zero_range:
        if scene.control != "displacement":
            problems.append(
                ("scene.control", f"model 'theory' of a {adhesion.name} curve takes displacement control only")
            )
        if adhesion.hysteretic:
            problems.append(
                (
                    "scene.effects.adhesion.approach_work_of_adhesion",
                    f"{adhesion.approach:g} J/m²: model 'theory' of a {adhesion.name} curve is the reversible one "
                    f"(approach_work_of_adhesion = work_of_adhesion, {adhesion.work_of_adhesion:g} J/m²)",
                )
            )
    elif scene.body.profile.shape not in SHAPES:
        shapes = ", ".join(SHAPES)
        problems.append(("scene.body.profile.shape", f"model 'theory' of a JKR curve takes {shapes}"))
    for key, paths in (("parameters", spec.parameters), ("inputs", spec.inputs)):
        for path in paths:
            if problem := _path_problem(path, adhesion):
                problems.append((f"{key}.{path}", problem))
    return problems


def _path_problem(path: str, adhesion: AbstractAdhesion) -> str | None:
    """Why the curve cannot vary the scene value at `path` (None where it can)."""
    if not path.startswith(CURVE_PATHS):
        return "the curve of model 'theory' depends only on material.*, body.profile.* and effects.adhesion.*"
    if not path.startswith("effects.adhesion."):
        return None
    name, fields = path.rsplit(".", 1)[1], adhesion.curve_fields
    return None if name in fields else f"a {adhesion.name} curve depends on {', '.join(fields)}"


class Edge:
    """The JKR edge of a work of adhesion w: d = h(a) = g(a) − √(2πaw/E*), F = 2E*(a·d − G(a))."""

    def __init__(self, profile, E_star, work_of_adhesion, force_control: bool):
        self.profile, self.E_star, self.work = profile, E_star, work_of_adhesion
        self.controlled = self.force if force_control else self.indentation
        scale = profile.radius_scale()
        self.lower = jnp.maximum(scale * 10.0**-SCALE_DECADES, 1e-300)
        self.upper = jnp.minimum(profile.extent() * (1.0 - EDGE_MARGIN), scale * 10.0**SCALE_DECADES)
        # The minimum of the controlled value; at the tip where it rises from there (Δγa = 0).
        slope = jax.grad(self.controlled)
        turn, found = log_sign_change(slope, self.lower, self.upper, SCALE_STEPS)
        self.turn = jax.lax.stop_gradient(jnp.where(found | (slope(self.lower) < 0.0), turn, self.lower))

    def indentation(self, a):
        return self.profile.g(a) - derivatives.sqrt(2.0 * jnp.pi * a * self.work / self.E_star)

    def force(self, a):
        return 2.0 * self.E_star * (a * self.indentation(a) - self.profile.G(a))

    def radius(self, target, upper):
        """a in [turn, upper] where the controlled value meets `target` (differentiated
        implicitly; the upper end where it lies above)."""
        target = jnp.maximum(target, self.controlled(self.turn))
        radius, _ = log_sign_change(lambda a: self.controlled(a) - target, self.turn, upper, SCALE_STEPS)
        return radius

    def regular_radius(self):
        """A radius well on the branch (off contact: the root at its end has no derivative)."""
        return jnp.minimum(2.0 * self.turn, 0.5 * (self.turn + self.upper))


def curve_state(
    profile, E_star, work_of_adhesion, approach_work, force_control: bool, peak, control, retract
) -> dict[str, jax.Array]:
    """contact_radius, indentation and force (SI) of the quasi-static JKR test at the control
    value (d under displacement control, F under force control) on its branch, with attach
    hysteresis (approach work of adhesion Δγa ≤ Δγ) and the program's `peak`."""
    attach = Edge(profile, E_star, approach_work, force_control)
    detach = Edge(profile, E_star, work_of_adhesion, force_control)
    # Approach: from the touch (d = 0, or the landing at F = 0) along the attach branch.
    on_approach = control >= 0.0
    approach = attach.radius(jnp.where(on_approach, control, attach.controlled(attach.regular_radius())), attach.upper)
    # Retract: a_max at the peak, held down to the detach criterion, then the detach branch.
    largest = attach.radius(jnp.maximum(peak, control), attach.upper)
    release = detach.controlled(largest)
    holds = control >= release
    end = jnp.minimum(detach.turn, largest)  # where the contact ends: the turn, or at once
    on_branch = ~holds & (control >= detach.controlled(end))
    goal = jnp.where(on_branch, control, detach.controlled(jnp.minimum(detach.regular_radius(), largest)))
    receding = detach.radius(goal, largest)
    radius = jnp.where(retract, jnp.where(holds, largest, receding), approach)
    contact = jnp.where(retract, holds | on_branch, on_approach)
    held = retract & holds
    if force_control:  # no contact: the end of the branch (no indentation is defined)
        radius = jnp.where(contact, radius, jnp.where(retract, end, attach.turn))
        depth = jnp.where(held, (control / (2.0 * E_star) + profile.G(largest)) / largest, detach.indentation(radius))
        depth = jnp.where(retract, depth, attach.indentation(radius))
        force = jnp.where(retract & ~held, detach.force(radius), attach.force(radius))
        return {"contact_radius": radius, "indentation": depth, "force": jnp.where(held, control, force)}
    zero = jnp.zeros_like(radius)
    force = jnp.where(held, 2.0 * E_star * (largest * control - profile.G(largest)), detach.force(radius))
    force = jnp.where(retract, force, attach.force(radius))
    return {
        "contact_radius": jnp.where(contact, radius, zero),
        "indentation": control,
        "force": jnp.where(contact, force, zero),
    }
