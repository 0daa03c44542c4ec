"""Parameter sweeps: one compiled `jax.vmap` of `impact._run.impacts.solve` over chunks of a batched Physics.

    result = impact.sweep("configs/thornton_ning.yaml",
                          {"initial.velocity": np.geomspace(0.2, 20, 400),
                           "effects.adhesion.work_of_adhesion": [0.02, 0.05, 0.1]})
    result.restitution.shape          # (400, 3), like every other result and result.params[...]

How it runs:
- Plan (`plan_sweep`): every point is validated (`impact._scene.sweep`), its SI parameters are computed
  for all points at once with numpy (the base scene copied with arrays in place of the swept
  values: no per-point `physics_for`), and the points are split into groups of equal static
  choices (the integrator and `Options`: solver, springs, limits, adhesion on/off, attach on touch). Each group
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

from .batch import local_devices
from .closed_forms import closed_form_name, closed_form_restitution, sticking_velocity
from .execute import DEFAULT_CHUNK, Progress, default_chunk, execute, run_spec, sweep
from .plan import Plan, batch_physics, plan_sweep
from .result import RESULTS, SweepResult, empty_results, result_names
from .theory_curves import VELOCITY, closed_form_names, sticking_estimates, theory_curve

__all__ = [
    "DEFAULT_CHUNK",
    "default_chunk",
    "RESULTS",
    "VELOCITY",
    "Plan",
    "Progress",
    "SweepResult",
    "batch_physics",
    "closed_form_name",
    "closed_form_names",
    "closed_form_restitution",
    "empty_results",
    "execute",
    "local_devices",
    "plan_sweep",
    "result_names",
    "run_spec",
    "sticking_estimates",
    "sticking_velocity",
    "sweep",
    "theory_curve",
]
