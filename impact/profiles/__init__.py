"""Rigid axisymmetric body profiles and their MDR equivalents (SI units).

A profile is the height f(r) (m) of the body surface above its tip at radius r (m). The method
of dimensionality reduction replaces it by the 1-D profile (3.24)

    g(x) = x ∫_0^x f'(r) / sqrt(x² - r²) dr = x ∫_0^{π/2} f'(x sin θ) dθ,

and the normal force at contact radius a and indentation d is `F = 2E*(a d - G(a))` with
`G(x) = ∫_0^x g(s) ds` (3.28). Every profile class gives f, g and G in closed form (the wavy
paraboloid through Struve functions evaluated to ~1e-14), elementwise on float64 arrays, safe
under `jax.jit`, `jax.vmap` and `jax.grad` (unused `jnp.where` branches are fed harmless
arguments, so gradients are finite for 0 < x < extent except at genuine kinks).

Shapes with a vertical wall (flat punch, capped flat punch) have f = inf beyond the wall and an
`extent` equal to the wall radius; the sphere and the ellipsoid end at their equator.
`mdr_transform` computes g numerically for any differentiable f(r).
"""

from ._base import Profile as Profile
from ._base import Scalars as Scalars
from ._base import kappa as kappa
from ._base import mdr_transform as mdr_transform
from ._classic import Cone as Cone
from ._classic import Ellipsoid as Ellipsoid
from ._classic import FlatPunch as FlatPunch
from ._classic import Paraboloid as Paraboloid
from ._classic import PowerLaw as PowerLaw
from ._classic import Sphere as Sphere
from ._compound import CappedCone as CappedCone
from ._compound import CappedFlatPunch as CappedFlatPunch
from ._compound import CappedParaboloid as CappedParaboloid
from ._compound import RoundedFlatPunch as RoundedFlatPunch
from ._compound import TruncatedCone as TruncatedCone
from ._compound import TruncatedParaboloid as TruncatedParaboloid
from ._functions import ellipe as ellipe
from ._special import ConstantStress as ConstantStress
from ._special import Tabulated as Tabulated
from ._special import WavyParaboloid as WavyParaboloid

__all__ = [
    "Profile",
    "Paraboloid",
    "Sphere",
    "Ellipsoid",
    "Cone",
    "PowerLaw",
    "FlatPunch",
    "TruncatedCone",
    "TruncatedParaboloid",
    "CappedFlatPunch",
    "CappedCone",
    "CappedParaboloid",
    "RoundedFlatPunch",
    "WavyParaboloid",
    "ConstantStress",
    "Tabulated",
    "kappa",
    "ellipe",
    "mdr_transform",
]
