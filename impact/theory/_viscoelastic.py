"""A paraboloid indenting a viscoelastic half-space without adhesion: the relaxation modulus of
a Prony series, E*(t) = E∞* + Σ E_i·e^(−t/τ_i), and the force of a test at a constant rate.

Lee & Radok (J. Appl. Mech. 27 (1960) 438): while the contact radius does not shrink,
F(t) = (4√R/3)·∫₀ᵗ E*(t − s)·d/ds[d(s)^(3/2)] ds. Ting (J. Appl. Mech. 33 (1966) 845): while it
shrinks, the same integral ends at t₁(t) < t, the time the loading had the radius of time t,
found from ∫_{t₁}^{t} E*(t − s)·ḋ(s) ds = 0 (in the MDR: the springs let go where their force
returns to zero; Popov, Willert & Heß, Facta Universitatis, Mech. Eng. 16 (2018) 99).

For d = r·s, ∫₀^{t₁} e^(−(t−s)/τ)·(3/2)√s ds = (3/2)·τ^(3/2)·e^(−(t−t₁)/τ)·H(t₁/τ) with
H(X) = √X − D(√X), D Dawson's integral (`lee_radok_kernel`).

The moduli and times are arrays along their last axis (the terms); the other arguments broadcast.
"""

import jax
import jax.numpy as jnp
from jax.scipy.special import dawsn

from .._core import derivatives
from .._core.runtime import float64
from ..profiles import Scalars
from ..profiles._base import as_float

# Below this X, H(X) = √X − D(√X) is its series (terms to X^(35/2): the remainder is below 1e-20
# of it); above, the difference loses at most a digit.
_SERIES_BELOW = 0.5
_SERIES_TERMS = 18
_BISECTION_STEPS = 80  # t₁ of Ting's condition, to the last bit of the loading time


@float64
def prony_relaxation_modulus(time: Scalars, E_relaxed: Scalars, moduli, times):
    """`E*(t) = E∞* + Σ E_i·e^(−t/τ_i)` [Pa] at `time` [s] ≥ 0, for the relaxed modulus
    `E_relaxed` [Pa] and the Prony terms `moduli` [Pa], `times` [s] (last axis)."""
    time = as_float(time)
    return E_relaxed + jnp.sum(moduli * jnp.exp(-time[..., None] / times), axis=-1)


@float64
def lee_radok_kernel(X: Scalars):
    """H(X) = √X − D(√X) = e^(−X)·∫₀^X e^u·√u du (D: Dawson's integral), the hereditary integral
    of a constant-rate paraboloid in units of τ^(3/2); ≈ (2/3)X^(3/2) for small X, √X for large."""
    X = as_float(X)
    small = X < _SERIES_BELOW
    safe = jnp.where(small, 1.0, X)
    root = jnp.sqrt(safe)
    closed = root - dawsn(root)
    # √X − D(√X) = Σ_{n≥1} (−1)^(n+1)·2ⁿ·X^(n+½)/(2n+1)!!
    positive = jnp.where(X > 0.0, X, 0.0)
    term, series = derivatives.sqrt(positive) * positive * 2.0 / 3.0, jnp.zeros_like(positive)
    for n in range(1, _SERIES_TERMS + 1):
        series = series + term
        term = -term * 2.0 * positive / (2 * n + 3)
    return jnp.where(small, series, closed)


@float64
def lee_radok_force(time: Scalars, rate: Scalars, R: Scalars, E_relaxed: Scalars, moduli, times, ramp_time=jnp.inf):
    """Force [N] on a paraboloid of radius R [m] pressed at the constant `rate` [m/s] from its
    first touch at t = 0 until `ramp_time` [s] and held there: Lee & Radok's hereditary integral,
    exact while the contact does not shrink (loading and hold), at `time` [s] ≥ 0."""
    time = as_float(time)
    return _hereditary(time, jnp.minimum(time, ramp_time), rate, R, E_relaxed, moduli, times)


@float64
def ting_contact_time(time: Scalars, E_relaxed: Scalars, moduli, times, ramp_time: Scalars, hold: Scalars = 0.0):
    """t₁ [s]: the time of the loading whose contact radius the contact has at `time` [s] when a
    paraboloid is loaded at a constant rate until `ramp_time` [s], held `hold` [s] and unloaded at
    the same rate (Ting's condition `∫_{t₁}^{t} E*(t − s)·ḋ(s) ds = 0`); `ramp_time` while loaded
    or held, 0 once the contact is lost."""
    time = as_float(time)
    shape = jnp.broadcast_shapes(time.shape, jnp.shape(ramp_time), jnp.shape(hold), jnp.shape(E_relaxed))
    time, ramp_time, hold = (jnp.broadcast_to(as_float(v), shape) for v in (time, ramp_time, hold))
    unloading = ramp_time + hold

    def relaxed(a, b):  # ∫_a^b E*(t − s) ds
        since = (time - b)[..., None] / times, (time - a)[..., None] / times
        return E_relaxed * (b - a) + jnp.sum(moduli * times * (jnp.exp(-since[0]) - jnp.exp(-since[1])), axis=-1)

    def condition(t1):  # decreasing in t₁
        return relaxed(t1, ramp_time) - relaxed(unloading, jnp.maximum(time, unloading))

    def halve(_, bracket):
        low, high = bracket
        middle = 0.5 * (low + high)
        above = condition(middle) > 0.0
        return jnp.where(above, middle, low), jnp.where(above, high, middle)

    # A loop, not unrolled: 80 copies of the condition made every program of the curve slow to compile.
    low, _ = jax.lax.fori_loop(0, _BISECTION_STEPS, halve, (jnp.zeros(shape), ramp_time))
    root = derivatives.implicit_root(condition, low)
    lost = condition(jnp.zeros(shape)) <= 0.0
    return jnp.where(time <= unloading, ramp_time, jnp.where(lost, 0.0, root))


@float64
def ting_force(time: Scalars, rate: Scalars, R: Scalars, E_relaxed: Scalars, moduli, times, ramp_time, hold=0.0):
    """Force [N] on a paraboloid of radius R [m] loaded at `rate` [m/s] until `ramp_time` [s], held
    `hold` [s] and unloaded at the same rate, at `time` [s] ≥ 0: Lee & Radok while loading and
    holding, Ting's receding contact while unloading (the integral up to `ting_contact_time`),
    0 once the contact is lost."""
    time = as_float(time)
    t1 = ting_contact_time(time, E_relaxed, moduli, times, ramp_time, hold)
    return _hereditary(time, jnp.minimum(time, t1), rate, R, E_relaxed, moduli, times)


def _hereditary(time, loaded, rate, R, E_relaxed, moduli, times):
    """(4√R/3)·∫₀^{loaded} E*(t − s)·d/ds[(r·s)^(3/2)] ds at `time`: the loading up to `loaded`."""
    waited = (time - loaded)[..., None]
    kernel = lee_radok_kernel(loaded[..., None] / times)
    arms = jnp.sum(moduli * times**1.5 * jnp.exp(-waited / times) * kernel, axis=-1)
    return 2.0 * jnp.sqrt(R) * rate**1.5 * (E_relaxed * 2.0 / 3.0 * loaded**1.5 + arms)
