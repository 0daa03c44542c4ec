"""`simulate` for indentation scenes with a `shear` program: the normal springs pressed to the
held load, then the tangential springs through the program (`_integrate.shear`), in SI."""

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import jax
import jax.numpy as jnp
import numpy as np

from .._core.search import log_sign_change
from .._integrate.shear import normal_state, shear_curve
from .._law.tangential import AbstractFrictionLimit, PerSpring, WholeContact
from .._scene.scene import Scene
from ..profiles import Profile
from .labelled import POINT, attributes, frame_of, number_attributes, require

if TYPE_CHECKING:
    import pandas
    import xarray

# The default array covers this many times the continuum contact radius at the held load.
_LENGTH_MARGIN = 1.25
_BISECTION_STEPS = 200
SHEAR_STATUSES = ("completed", "radius_overflow")
# The program's points (`ShearResult` fields) in order: name → (unit, description).
SHEAR_CURVE = {
    "displacement": ("m", "tangential displacement δ of the body"),
    "force": ("N", "tangential force Q on the body, along δ"),
    "stick_radius": ("m", "inner radius c of the slip zone (the contact radius where no spring slips)"),
    "leg": ("", "leg of the program: 0 first loading, 1 first reversal, ..."),
}
# The normal state held (`ShearResult` fields): name → unit.
HELD_UNITS = {"normal_force": "N", "indentation": "m", "contact_radius": "m"}


@dataclass(frozen=True)
class ShearResult:
    """Outcome of a quasi-static shear test (an indentation scene with `shear`), in SI units.

    Attributes:
        scene: The scene that was run.
        status: `completed`, or `radius_overflow` where the held load needs more springs than
            the array's `contact.length` holds (the curve is then not computed).
        normal_force: The held normal force F_n of the spring array [N].
        indentation: The held indentation d [m].
        contact_radius: The radius the springs in contact cover [m].
        displacement: Tangential displacement δ of each point of the program [m].
        force: Tangential force Q of each point [N].
        stick_radius: Inner radius c of the slip zone at each point [m] (the contact radius where
            no spring slips), to half a spring spacing.
        leg: The program leg of each point: 0 the first loading, 1 the first reversal, ...
        stats: `springs` and `spacing` (m) of the array.
    """

    scene: Scene
    status: str
    normal_force: float
    indentation: float
    contact_radius: float
    displacement: np.ndarray = field(repr=False)
    force: np.ndarray = field(repr=False)
    stick_radius: np.ndarray = field(repr=False)
    leg: np.ndarray = field(repr=False)
    stats: dict = field(repr=False)

    @property
    def success(self) -> bool:
        """Whether the program ran."""
        return self.status == "completed"

    def to_xarray(self) -> "xarray.Dataset":
        """The test as an `xarray.Dataset` (needs the extra `impact-mdr[analysis]`): the program's
        points along `point`, the held normal state as 0-d variables, the status and the scene
        (YAML) and versions as attributes."""
        xarray = require("xarray")
        variables: dict[str, tuple] = {
            name: (POINT, getattr(self, name), number_attributes(unit, what))
            for name, (unit, what) in SHEAR_CURVE.items()
        }
        for name, unit in HELD_UNITS.items():
            variables[name] = ((), getattr(self, name), number_attributes(unit, "the normal state held"))
        return xarray.Dataset(variables, attrs=attributes(self.scene, self.stats, status=self.status))

    def to_pandas(self) -> "pandas.DataFrame":
        """The program's points as a `pandas.DataFrame`, one row a point in order (displacement,
        force, stick_radius, leg); `attrs["units"]` their units (needs the extra
        `impact-mdr[analysis]`)."""
        columns = {name: getattr(self, name) for name in SHEAR_CURVE}
        return frame_of(columns, {name: unit for name, (unit, _) in SHEAR_CURVE.items()}, POINT)


def simulate_shear(scene: Scene) -> ShearResult:
    """Run an indentation scene with a `shear` program on its spring array."""
    friction, shear, springs = scene.effects.friction, scene.shear, scene.contact.springs
    assert friction is not None and shear is not None and not isinstance(springs, str), "validated: a shear test"
    profile = scene.body.profile.build()
    E_star = scene.material.effective_modulus
    force_control = scene.control == "force"
    peak = scene.loading.peak
    length = scene.contact.length or _LENGTH_MARGIN * _contact_radius(profile, E_star, force_control, peak)
    spacing = length / springs
    heights = np.asarray(profile.g((np.arange(springs) + 0.5) * spacing), dtype=np.float64)
    state = normal_state(heights, spacing, E_star, force_control, peak)
    stats = {"springs": springs, "spacing": spacing}
    held = {
        "normal_force": float(state.force),
        "indentation": float(state.indentation),
        "contact_radius": int(state.count) * spacing,
    }
    if bool(state.overflow):
        empty = np.zeros(0)
        return ShearResult(scene, "radius_overflow", **held, displacement=empty, force=empty,
                           stick_radius=empty, leg=np.zeros(0, int), stats=stats)  # fmt: skip
    limit = _limit(scene, spacing)
    curve = _curve(limit, jnp.asarray(heights), jnp.asarray(spacing), state, shear.control == "force",
                   tuple(float(value) for value in shear.path), shear.samples)  # fmt: skip
    return ShearResult(
        scene,
        "completed",
        **held,
        displacement=np.asarray(curve.displacement),
        force=np.asarray(curve.force),
        stick_radius=np.asarray(curve.stick_radius),
        leg=np.asarray(curve.leg),
        stats=stats,
    )


_curve = jax.jit(shear_curve, static_argnames=("force_control", "turning", "samples"))


def _limit(scene: Scene, spacing: float) -> AbstractFrictionLimit:
    """The friction limit of the scene's tangential springs, in SI: κ = 2G*Δx (N/m)."""
    friction = scene.effects.friction
    assert friction is not None, "validated: a shear test names friction"
    E_star, G_star = scene.material.effective_modulus, scene.material.tangential_modulus
    stiffness = jnp.asarray(2.0 * G_star * spacing)
    if friction.limit == "per_spring":
        return PerSpring(stiffness=stiffness, ratio=jnp.asarray(friction.coefficient * E_star / G_star))
    return WholeContact(stiffness=stiffness, coefficient=jnp.asarray(friction.coefficient), adhesive_load=jnp.zeros(()))


def _contact_radius(profile: Profile, E_star: float, force_control: bool, peak: float) -> float:
    """The continuum contact radius a (m) at the load `peak`: 2E*(a·g(a) − G(a)) = F, or g(a) = d."""

    def excess(radius):
        if force_control:
            return 2.0 * E_star * (radius * profile.g(radius) - profile.G(radius)) - peak
        return profile.g(radius) - peak

    lower = profile.radius_scale() * 1e-12
    upper = jnp.minimum(profile.extent(), profile.radius_scale() * 1e12)
    radius, _ = log_sign_change(excess, lower, upper, _BISECTION_STEPS)
    return float(radius)
