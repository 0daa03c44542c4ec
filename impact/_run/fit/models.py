"""The model of a fit: a differentiable function of one vector, the fitted parameters then the
row's inputs (in the order of the fit), to the vector of the observables.

`simulation_model` is the simulation itself (`impact.as_function`; impacts only); `theory_model`
the closed form of the Thornton–Ning impact (3.50)–(3.51) and its largest force
(`thornton_ning_max_force`), or of an indentation scene its quasi-static curve (`curve`: JKR with
attach hysteresis; `range_curve`: Maugis–Dugdale, Greenwood–Johnson; `viscoelastic_curve`: Lee &
Radok and Ting on a viscoelastic half-space), a fast model for scenes it
describes; any other such function may be passed to `impact.fit`. A model may also offer
`batched(values, rows)`, the observables of all rows at once (computing what they share once).
"""

import functools
from collections.abc import Callable
from dataclasses import dataclass

import jax
import jax.numpy as jnp
import yaml

from ... import theory
from ..._scene.fit_curve import NOT_DIFFERENTIABLE
from ..._scene.fit_spec import FitError, FitSpec
from ..._scene.profiles import ParaboloidSpec
from ..._scene.scene import scene_yaml
from ..differentiable import as_function
from .curve import IndentationCurve, curve_model, curve_problems
from .viscoelastic_curve import ViscoelasticCurve, viscoelastic_curve_model, viscoelastic_curve_problems

Model = Callable[[jax.Array], jax.Array]

# Scene paths the closed form takes, by the name of its argument.
THEORY_ARGUMENTS = {
    "initial.velocity": "velocity",
    "body.mass": "mass",
    "body.profile.R": "R",
    "material.E_star": "E_star",
    "effects.adhesion.work_of_adhesion": "work_of_adhesion",
}
THEORY_OBSERVABLES = {
    "restitution": theory.thornton_ning_restitution,
    "max_force": theory.thornton_ning_max_force,
}


@dataclass(frozen=True)
class SimulatedImpact:
    """The simulation of a scene as a model: `impact.as_function` of the scene with the dotted
    paths `inputs` (the fitted parameters, then the input columns) as its inputs and the
    `observables` as its (vector) output. Equal instances share one compiled fit."""

    scene: str  # the scene as YAML (hashable)
    inputs: tuple[str, ...]
    observables: tuple[str, ...]

    def __call__(self, x: jax.Array) -> jax.Array:
        return _simulation(self.scene, self.inputs, self.observables)(x)


@functools.lru_cache(maxsize=8)
def _simulation(scene: str, inputs: tuple[str, ...], observables: tuple[str, ...]) -> Model:
    """`as_function` kept per scene, paths and observables: a later fit of the same model
    (other data, starts or bounds) reuses its compiled programs."""
    return as_function(yaml.safe_load(scene), inputs=list(inputs), output=list(observables))


def simulation_model(spec: FitSpec) -> SimulatedImpact:
    """The simulation of the scene as a model (impacts only), its function built here (it
    checks the scene and its inputs, concretely: not inside a fit's trace)."""
    if spec.scene.kind == "indentation":
        raise FitError([("model", NOT_DIFFERENTIABLE)])
    model = SimulatedImpact(scene_yaml(spec.scene), (*spec.parameters, *spec.inputs), tuple(spec.observables))
    _simulation(model.scene, model.inputs, model.observables)
    return model


@dataclass(frozen=True)
class ClosedForm:
    """The Thornton–Ning closed form as a model: `varied` arguments from x, the others `fixed`
    (argument name, value); equal instances share one compiled fit."""

    varied: tuple[str, ...]
    fixed: tuple[tuple[str, float], ...]
    observables: tuple[str, ...]

    def __call__(self, x: jax.Array) -> jax.Array:
        arguments = dict(self.fixed) | {name: x[index] for index, name in enumerate(self.varied)}
        return jnp.stack([THEORY_OBSERVABLES[name](**arguments) for name in self.observables])


def theory_model(spec: FitSpec) -> Model:
    """The closed form of the scene as a model: of an impact, Thornton–Ning (a paraboloid with
    reversible JKR adhesion and no gravity); of an indentation, the quasi-static JKR curve
    (`curve`). FitError naming the field it cannot describe."""
    _check_theory(spec)
    if spec.scene.effects.viscoelasticity is not None:
        return viscoelastic_curve_model(spec)
    if spec.scene.kind == "indentation":
        return curve_model(spec)
    scene = spec.scene
    adhesion = scene.active_adhesion
    assert isinstance(scene.body.profile, ParaboloidSpec) and adhesion is not None, "checked"
    fixed = {
        "velocity": scene.start.velocity,
        "mass": scene.body.resolved_mass,
        "R": scene.body.profile.R,
        "E_star": scene.material.effective_modulus,
        "work_of_adhesion": adhesion.work_of_adhesion,
    }
    varied = tuple(THEORY_ARGUMENTS[path] for path in (*spec.parameters, *spec.inputs))
    constant = tuple((name, value) for name, value in fixed.items() if name not in varied)
    return ClosedForm(varied, constant, tuple(spec.observables))


# impact's own models: each a frozen dataclass of text, names and numbers, whose repr names
# its compiled programs (the key of a fit's programs stored in the cache, `impact._core.stored`).
DESCRIBED = (SimulatedImpact, ClosedForm, IndentationCurve, ViscoelasticCurve)


def _check_theory(spec: FitSpec) -> None:
    scene = spec.scene
    if scene.kind == "indentation":
        check = viscoelastic_curve_problems if scene.effects.viscoelasticity is not None else curve_problems
        if problems := check(spec):
            raise FitError(problems)
        return
    adhesion = scene.active_adhesion
    problems = []
    if scene.kind != "impact" or scene.body.profile.shape != "paraboloid":
        problems.append(("scene.body.profile.shape", "model 'theory' describes the impact of a paraboloid"))
    if adhesion is None or not adhesion.zero_range or adhesion.approach != adhesion.work_of_adhesion:
        problems.append(("scene.effects.adhesion", "model 'theory' needs reversible JKR adhesion (Δγa = Δγ)"))
    if scene.effects.gravity is not None:
        problems.append(("scene.effects.gravity", "model 'theory' has no gravity"))
    for key, paths in (("parameters", spec.parameters), ("inputs", spec.inputs)):
        for path in paths:
            if path not in THEORY_ARGUMENTS:
                problems.append((f"{key}.{path}", f"model 'theory' takes only {', '.join(THEORY_ARGUMENTS)}"))
    for name in spec.observables:
        if name not in THEORY_OBSERVABLES:
            problems.append((f"observables.{name}", f"model 'theory' gives only {', '.join(THEORY_OBSERVABLES)}"))
    if problems:
        raise FitError(problems)


def theory_applies(spec: FitSpec) -> bool:
    """Whether the closed form describes the scene, its paths and its observables."""
    try:
        _check_theory(spec)
    except FitError:
        return False
    return True
