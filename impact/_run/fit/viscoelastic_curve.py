"""The closed-form model of an indentation curve of a viscoelastic half-space (a fit's `model:
theory`): the force at each row's time of a paraboloid loaded at the program's rate to its peak,
held and unloaded (`theory.ting_force`: Lee & Radok, then Ting), so that a fit of curves at
several rates (`inputs: [program.rate]`) finds the relaxed modulus and the Prony terms."""

import functools
from dataclasses import dataclass

import jax
import jax.numpy as jnp
import yaml

from ... import theory
from ..._law.viscoelastic import Viscoelastic
from ..._scene.fit_spec import FitSpec
from ..._scene.paths import with_values
from ..._scene.scene import Scene, load_scene, scene_yaml

# The scene values the curve depends on.
CURVE_PATHS = ("material.", "body.profile.R", "effects.viscoelasticity.prony.", "program.rate", "program.hold")


@functools.lru_cache(maxsize=8)
def _scene(text: str) -> Scene:
    return load_scene(yaml.safe_load(text))


@dataclass(frozen=True)
class ViscoelasticCurve:
    """The force of the test as a model of x = [varied scene values, time, branch]; equal
    instances share one compiled fit."""

    scene: str  # the scene as YAML (hashable)
    varied: tuple[str, ...]  # the dotted paths set from x, in order

    def __call__(self, x: jax.Array) -> jax.Array:
        count = len(self.varied)
        return self.batched(x[:count], x[None, count:])[0]

    def batched(self, values: jax.Array, rows: jax.Array) -> jax.Array:
        """The force [rows, 1] at the fitted `values` and the rows [inputs, time, branch]."""
        inputs = len(self.varied) - len(values)

        def force(row):
            assigned = jnp.concatenate([values, row[:inputs]])
            batch = with_values(_scene(self.scene), dict(zip(self.varied, assigned, strict=True)))
            law = batch.contact_law(jnp)
            assert isinstance(law, Viscoelastic), "checked: a viscoelastic scene"
            program = batch.loading
            rate = jnp.asarray(program.rate, jnp.float64)
            time = row[inputs]
            return theory.ting_force(
                time,
                rate,
                batch.body.profile.R,
                jnp.asarray(batch.material.effective_modulus, jnp.float64),
                law.moduli,
                law.times,
                program.peak / rate,
                program.hold,
            )

        return jax.vmap(force)(rows)[:, None]


def viscoelastic_curve_model(spec: FitSpec) -> ViscoelasticCurve:
    """The closed-form curve of the scene as a model (checked by `viscoelastic_curve_problems`)."""
    return ViscoelasticCurve(scene_yaml(spec.scene), (*spec.parameters, *spec.inputs))


def viscoelastic_curve_problems(spec: FitSpec) -> list[tuple[str, str]]:
    """(field, message) of what the closed forms of Lee & Radok and Ting cannot describe."""
    scene = spec.scene
    problems = []
    theory_of = "model 'theory' of a viscoelastic curve (Lee & Radok, Ting)"
    if scene.body.profile.shape != "paraboloid":
        problems.append(("scene.body.profile.shape", f"{theory_of} describes a paraboloid"))
    if scene.control != "displacement":
        problems.append(("scene.control", f"{theory_of} takes displacement control (d linear in time)"))
    if scene.effects.adhesion is not None:
        problems.append(("scene.effects.adhesion", f"{theory_of} has no adhesion"))
    program = scene.loading
    if program.cycles != 1:
        problems.append(("scene.program.cycles", f"{theory_of} is one cycle (Ting's receding contact once)"))
    for key, paths in (("parameters", spec.parameters), ("inputs", spec.inputs)):
        for path in paths:
            if not path.startswith(CURVE_PATHS):
                allowed = ", ".join(CURVE_PATHS)
                problems.append((f"{key}.{path}", f"{theory_of} depends only on {allowed}"))
    if set(spec.observables) != {"force"}:
        problems.append(("observables", f"{theory_of} gives the force"))
    return problems
