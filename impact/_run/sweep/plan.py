"""Planning a sweep: SI parameters of every point at once, groups of equal static choices, and
the processing order by expected cost."""

import time
from collections.abc import Mapping
from dataclasses import dataclass
from typing import NamedTuple

import jax
import numpy as np

from ..._integrate.base import AbstractIntegrator
from ..._integrate.problem import Options, Physics
from ..._scene.paths import with_values
from ..._scene.scene import Scene
from ..._scene.sweep_spec import SweepSpec
from ..parameters import integrator_for, options_for, physics_for
from .closed_forms import sticking_velocity


class StaticChoices(NamedTuple):
    """What a point compiles: its integrator and options (points that share them share a compile)."""

    integrator: AbstractIntegrator
    options: Options


@dataclass
class Plan:
    """What to run: SI parameters of every point, its group (static choices) and the order."""

    spec: SweepSpec
    params: dict[str, np.ndarray]  # flat [N], C order of spec.shape
    physics: Physics  # numpy leaves [N, ...]
    choices: list[StaticChoices]  # of each group
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
        for group in range(len(self.choices)):
            points = self.order[self.group[self.order] == group]
            shares.append(points[index::count])
        return shares


def plan_sweep(spec: SweepSpec) -> Plan:
    start = time.perf_counter()
    params = spec.flat_params()
    size = spec.size
    physics = batch_physics(spec.scene, params, size)
    choices, group = _groups(spec, params, size)
    cost = expected_cost(spec.scene, physics)
    if spec.order == "cost":
        order = np.concatenate(
            [np.flatnonzero(group == g)[np.argsort(cost[group == g], kind="stable")] for g in range(len(choices))]
        )
    else:
        order = np.concatenate([np.flatnonzero(group == g) for g in range(len(choices))])
    return Plan(spec, params, physics, choices, group, cost, order, time.perf_counter() - start)


def batch_physics(scene: Scene, params: Mapping[str, np.ndarray], size: int) -> Physics:
    """`physics_for` of every point at once: numpy leaves with a leading axis of `size`."""
    template = physics_for(scene)
    physics = physics_with(scene, params, np)
    return jax.tree.map(lambda new, ref: _batched(new, np.shape(ref), size), physics, template)


def physics_with(scene: Scene, params: Mapping, xp=np) -> Physics:
    """`physics_for` of the scene with the fields at dotted paths set to `params`, in the array
    module `xp` (numpy for a sweep's batch, `jax.numpy` for traced values).

    The base scene is copied with the values (no validation: they are validated already, or
    traced), so derived values (E* from E and ν, mass from density) follow the scene's own
    formulas elementwise."""
    batch = with_values(scene, params)
    swept = any(path.startswith(("body.profile.", "counterpart.profile.")) for path in params)
    profile = (batch if swept else scene).contact_profile.build()
    return physics_for(batch, xp, profile=jax.tree.map(lambda leaf: xp.asarray(leaf, dtype=xp.float64), profile))


def _batched(value, shape: tuple, size: int) -> np.ndarray:
    value = np.asarray(value, dtype=np.float64)
    if value.shape == (size, *shape):
        return value
    return np.ascontiguousarray(np.broadcast_to(value, (size, *shape)))


def _groups(spec: SweepSpec, params: dict, size: int) -> tuple[list[StaticChoices], np.ndarray]:
    """(integrator, options) of each group and the group of each point, evaluated once per
    distinct combination of the swept static fields (solver.*, limits.*, contact.*, effects.*)."""
    static = [axis.path for axis in spec.axes if axis.static]
    if not static:
        return [static_choices(spec.scene)], np.zeros(size, dtype=np.int64)
    columns = np.stack([params[path].astype(np.float64) for path in static], axis=1)
    combos, first, inverse = np.unique(columns, axis=0, return_index=True, return_inverse=True)
    found: dict[StaticChoices, int] = {}
    choices: list[StaticChoices] = []
    combo_group = np.empty(len(combos), dtype=np.int64)
    for combo in np.argsort(first):  # groups in the order their first point appears
        point = first[combo]
        scene = with_values(spec.scene, {path: params[path][point].item() for path in spec.paths})
        choice = static_choices(scene)
        if choice not in found:
            found[choice] = len(choices)
            choices.append(choice)
        combo_group[combo] = found[choice]
    return choices, combo_group[inverse.reshape(-1)]


def static_choices(scene: Scene) -> StaticChoices:
    """The static choices of a point."""
    return StaticChoices(integrator_for(scene), options_for(scene, trajectory=False))


def expected_cost(scene: Scene, physics: Physics) -> np.ndarray:
    """Sort key of the points by expected solver cost: touch speed over the closed-form sticking
    velocity where the chapter has one (paraboloid, power law, cone with adhesion), else the
    touch speed. In scaled units the impact depends on v/v_s alone."""
    gravity = scene.effects.gravity is not None
    speed = physics.velocity
    if gravity:
        speed = np.sqrt(speed**2 + 2.0 * physics.gravity.acceleration * physics.gap)
    sticking = sticking_velocity(scene, physics)
    usable = np.isfinite(sticking) & (sticking > 0)
    return np.where(usable, speed / np.where(usable, sticking, 1.0), speed)
