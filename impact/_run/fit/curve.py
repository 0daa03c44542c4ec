"""The closed-form model of a quasi-static indentation curve (the AFM use): the observable at a
given control value on the branch the test is on.

Under the reversible JKR law (rule of Heß, Δγa = Δγ) an attached contact of radius a has the
indentation d = h(a) = g(a) − √(2πaΔγ/E*) and the force F = 2E*(a·d − G(a)) (3.26), (3.28); for
the paraboloid these are (3.44). For a body whose h(a) (and F along it) has one minimum (the
profiles of `SHAPES`), the stable branch is the part beyond that minimum, where the controlled
value rises with a; the state at a control value is the root a of that rise, found by bisection
in log a and differentiated by the implicit function theorem:

- displacement control (ξ = 1): on approach the contact jumps in at first touch (d = 0, radius
  a₀ with g(a₀) = Δl(a₀)) and follows the branch for d ≥ 0; on retract it follows the branch
  down to the minimum of h (the critical point of (3.30), ξ = 1) and jumps out below it;
- force control (ξ = 3): on approach the body lands at F = 0 on the branch and follows it for
  F ≥ 0; on retract it follows it down to the minimum of F (the JKR pull-off (3.46) for the
  paraboloid).

Beyond the jump (d < 0 on approach, d below the critical point on retract) there is no contact:
the force and the contact radius are 0, whatever the parameters; such rows weigh in χ² with a
zero derivative, and tell the fit where the jump is only through which branch a row falls on.
Under force control a force beyond the branch's end has no contact and no defined indentation:
the model holds the state at the end of the branch (leave such rows out of the data).
"""

import functools
from dataclasses import dataclass

import jax
import jax.numpy as jnp
import yaml

from ..._core.search import log_sign_change
from ..._integrate.quasistatic.loading import SCALE_DECADES, SCALE_STEPS
from ..._scene.fit_spec import FitSpec
from ..._scene.paths import with_values
from ..._scene.scene import Scene, load_scene, scene_yaml

# The profiles whose JKR curve h(a) = g(a) − Δl(a) falls to one minimum and then rises.
SHAPES = ("paraboloid", "sphere", "ellipsoid", "cone", "power_law")
# The scene values the curve depends on: the modulus, the work of adhesion, the profile.
CURVE_PATHS = ("material.", "body.profile.", "effects.adhesion.work_of_adhesion")
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
        scene = _scene(self.scene)
        batch = with_values(scene, {path: x[index] for index, path in enumerate(self.varied)})
        adhesion = batch.effects.adhesion
        assert adhesion is not None, "checked: model 'theory' needs adhesion"
        state = curve_state(
            batch.body.profile.build(),
            jnp.asarray(batch.material.effective_modulus, jnp.float64),
            jnp.asarray(adhesion.work_of_adhesion, jnp.float64),
            scene.control == "force",
            x[-2],
            x[-1] > 0.5,
        )
        return jnp.stack([state[name] for name in self.observables])


def curve_model(spec: FitSpec) -> IndentationCurve:
    """The closed-form curve of an indentation scene as a model (checked by `curve_problems`)."""
    return IndentationCurve(scene_yaml(spec.scene), (*spec.parameters, *spec.inputs), tuple(spec.observables))


def curve_problems(spec: FitSpec) -> list[tuple[str, str]]:
    """(field, message) of what the closed-form curve cannot describe."""
    scene = spec.scene
    adhesion = scene.active_adhesion
    problems = []
    if scene.body.profile.shape not in SHAPES:
        shapes = ", ".join(SHAPES)
        problems.append(("scene.body.profile.shape", f"model 'theory' of an indentation curve takes {shapes}"))
    if adhesion is None or adhesion.model != "jkr" or adhesion.approach != adhesion.work_of_adhesion:
        problems.append(("scene.effects.adhesion", "model 'theory' needs reversible JKR adhesion (Δγa = Δγ)"))
    for key, paths in (("parameters", spec.parameters), ("inputs", spec.inputs)):
        for path in paths:
            if not path.startswith(CURVE_PATHS):
                allowed = "material.*, body.profile.* and effects.adhesion.work_of_adhesion"
                problems.append((f"{key}.{path}", f"the curve of model 'theory' depends only on {allowed}"))
    return problems


def curve_state(profile, E_star, work_of_adhesion, force_control: bool, control, retract) -> dict[str, jax.Array]:
    """contact_radius, indentation and force (SI) of the quasi-static JKR test at the control
    value (d under displacement control, F under force control) on its branch."""

    def indentation(a):
        return profile.g(a) - jnp.sqrt(2.0 * jnp.pi * a * work_of_adhesion / E_star)

    def force(a):
        return 2.0 * E_star * (a * indentation(a) - profile.G(a))

    controlled = force if force_control else indentation
    scale = profile.radius_scale()
    lower = jnp.maximum(scale * 10.0**-SCALE_DECADES, 1e-300)
    upper = jnp.minimum(profile.extent() * (1.0 - EDGE_MARGIN), scale * 10.0**SCALE_DECADES)
    slope = jax.grad(controlled)
    turn, _ = log_sign_change(slope, lower, upper, SCALE_STEPS)
    turn = jax.lax.stop_gradient(turn)  # only a bracket and the end of the branch
    start = jnp.where(retract, controlled(turn), 0.0)  # where the branch begins: jump-out or touch
    contact = control >= start
    # Off contact, any point well on the branch (the root at its end has no derivative).
    target = jnp.where(contact, control, controlled(jnp.minimum(2.0 * turn, 0.5 * (turn + upper))))
    radius, _ = log_sign_change(lambda a: controlled(a) - target, turn, upper, SCALE_STEPS)
    if force_control:  # no contact: the end of the branch (no indentation is defined)
        radius = jnp.where(contact, radius, turn)
        return {"contact_radius": radius, "indentation": indentation(radius), "force": force(radius)}
    zero = jnp.zeros_like(radius)
    return {
        "contact_radius": jnp.where(contact, radius, zero),
        "indentation": control,
        "force": jnp.where(contact, force(radius), zero),
    }
