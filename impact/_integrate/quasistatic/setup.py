"""Setting up a quasi-static march: its units, the branches, and the bracketed roots along them
(Popov, Heß & Willert, Handbook of Contact Mechanics (Springer 2019), ch. 3, eqs. (3.26–3.35))."""

import dataclasses
import operator

import equinox as eqx
import jax
import jax.numpy as jnp

from ..._core.search import log_sign_change
from ..._law.base import AbstractAdhesiveLaw, AbstractEdgeLaw
from ..._law.branches import Branch, build_branch
from ..._law.law import ContactLaw
from ..._law.scales import Scales
from ..problem import Motion, Problem
from .loading import BISECTION_STEPS, OCTAVES, SCALE_DECADES, SCALE_STEPS, TOP_MARGIN, Loading, QuasiStaticNumerics
from .program import Program


def _log_bisect(excess, lower, upper):
    """Where `excess` changes sign between two radii, bisected in log x; nan without a change."""
    radius, found = log_sign_change(excess, lower, upper, SCALE_STEPS)
    return jnp.where(found, radius, jnp.nan)


def loading_scales(loading: Loading, adhesive: bool) -> Scales:
    """Units: the jump-in radius a0 (g(a0) = √(2πa0Δγ/E*)) and its Heß length, as for impacts
    (`scales.adhesive_scales`), or the wall radius of a walled body; else the radius where the
    non-adhesive law reaches the program's peak, and g there."""
    profile, E_star = loading.profile, loading.E_star
    reference = profile.radius_scale()
    walled = jnp.isfinite(profile.extent())
    lower = jnp.maximum(reference * 10.0**-SCALE_DECADES, 1e-300)
    upper = jnp.minimum(profile.extent(), jnp.minimum(reference * 10.0**SCALE_DECADES, 1e300))

    law = loading.law
    work_of_adhesion = law.work_of_adhesion if isinstance(law, AbstractAdhesiveLaw) else jnp.zeros(())

    def hess(x):
        return jnp.sqrt(2.0 * jnp.pi * x * work_of_adhesion / E_star)

    def reach(x):  # the non-adhesive indentation or force at radius x, less the peak
        g = profile.g(x)
        return jnp.where(loading.force_control, 2.0 * E_star * (x * g - profile.G(x)), g) - loading.peak

    if adhesive:
        # A jump-in radius: h = g − Δl rises through 0 from below (n > 1/2). Where h starts
        # positive (n < 1/2) its far zero is no scale of the contact.
        rises = profile.g(lower) < hess(lower)
        jump_in = jnp.where(rises, _log_bisect(lambda x: profile.g(x) - hess(x), lower, upper), jnp.nan)
        adhesive_radius = jnp.where(jnp.isfinite(jump_in), jump_in, jnp.where(walled, upper, jnp.nan))
    else:
        adhesive_radius = jnp.full((), jnp.nan)
    peak_radius = _log_bisect(reach, lower, upper)
    radial = jnp.where(
        jnp.isfinite(adhesive_radius), adhesive_radius, jnp.where(jnp.isfinite(peak_radius), peak_radius, reference)
    )
    length = jnp.where(jnp.isfinite(adhesive_radius), hess(radial), profile.g(radial))
    normal = jnp.where(length > 0, length, radial)
    return Scales(radial=radial, normal=normal, force=E_star * radial * normal, time=jnp.ones(()))


def branch_problem(law: ContactLaw, attach, detach) -> Problem:
    """A `Problem` holding the law and its two branches (the impact-only fields are zero)."""
    zero = jnp.zeros(())
    still = Motion(start_indentation=zero, start_velocity=zero, touch_speed=zero, gravity=zero, time_limit=zero)
    given = {"law": law, "attach": attach, "detach": detach, "motion": still}
    return Problem(**{f.name: given.get(f.name, zero) for f in dataclasses.fields(Problem) if f.init})


class Built(eqx.Module):
    """The scaled law, its branches (λ and 3λ for attach and detach) and the program."""

    problem: Problem
    attach3: Branch  # Branch of the ξ = 3 attach edge: extrema of the loading force
    detach3: Branch  # Branch of the ξ = 3 detach edge: extrema of the unloading force
    program: Program
    top: jax.Array
    bounded: jax.Array  # the program's peak is reached at a finite radius

    @property
    def law(self) -> ContactLaw:
        return self.problem.law


def build(loading: Loading, numerics: QuasiStaticNumerics) -> Built:
    """Scale the loading, find how far the contact can grow and build the four branches."""
    profile = loading.profile
    scales = loading_scales(loading, numerics.adhesive)
    if numerics.adhesive:
        assert isinstance(loading.law, AbstractEdgeLaw), "a branch march is of an edge law"
        detach_coefficient, attach_coefficient = loading.law.hess_coefficients(scales, loading.E_star)
    else:
        detach_coefficient = attach_coefficient = jnp.zeros(())
    law = ContactLaw(profile, scales, detach_coefficient, attach_coefficient, numerics.adhesive)
    unit = jnp.where(loading.force_control, scales.force, scales.normal)
    targets = loading.targets / unit
    peak = loading.peak / unit

    # How far the contact grows: beyond the first radius after which the loading value (d or F
    # along the attach edge) stays above the peak. None such: the contact grows without limit.
    low, high = OCTAVES
    grid = jnp.minimum(2.0 ** (jnp.arange(4 * low, 4 * high + 1) / 4.0), law.extent())
    value = edge_value(law, grid, attach_coefficient, loading.force_control)
    value = jnp.where(jnp.isnan(value), -jnp.inf, value)
    floor = jax.lax.cummin(value, reverse=True)
    above = floor > peak
    index = jnp.argmax(above)
    bounded = jnp.any(above) | jnp.isfinite(law.extent())
    top = jnp.minimum(law.extent(), jnp.where(jnp.any(above), TOP_MARGIN * grid[index], grid[-1]))

    coefficients = jnp.stack(
        [attach_coefficient, detach_coefficient, 3.0 * attach_coefficient, 3.0 * detach_coefficient]
    )
    branches = jax.vmap(lambda c: build_branch(law, c, top, numerics.tabulation, 0))(coefficients)
    attach, detach, attach3, detach3 = (jax.tree.map(operator.itemgetter(i), branches) for i in range(4))
    return Built(
        problem=branch_problem(law, attach, detach),
        attach3=attach3,
        detach3=detach3,
        program=Program(
            force_control=jnp.asarray(loading.force_control),
            directions=loading.directions,
            targets=targets,
            legs=loading.legs,
        ),
        top=top,
        bounded=bounded,
    )


def edge_value(law: ContactLaw, x, coefficient, force_control):
    """The controlled quantity along an edge d = h(x): d itself, or the force there."""
    h = law.edge(x, coefficient)
    return jnp.where(force_control, law.force(x, h), h)


def bracketed_root(law: ContactLaw, coefficient, force_control, target, lower, upper):
    """x in [lower, upper] where the (increasing) edge value meets the target, by bisection."""

    def step(_, bracket):
        lo, hi = bracket
        mid = 0.5 * (lo + hi)
        below = edge_value(law, mid, coefficient, force_control) < target
        return jnp.where(below, mid, lo), jnp.where(below, hi, mid)

    lo, hi = jax.lax.fori_loop(0, BISECTION_STEPS, step, (lower, upper))
    return 0.5 * (lo + hi)


class EdgePath(eqx.Module):
    """The turning points of a march's path along one edge (out or in), sorted, and whose they are."""

    nodes: jax.Array  # radii (scaled)
    tags: jax.Array  # 0: a turning point of h, 1: of the force (ξ = 3)


def edge_path(h_branch, f_branch, top, up: bool) -> EdgePath:
    """Turning points of h and of the ξ = 3 edge, merged and sorted, with a tag (0: h, 1: force).

    At equal radii the h nodes come first on the way out and last on the way in, so a march
    meets a turning point of h before it leaves it; nodes at the top are h nodes (the end)."""
    first, second = (h_branch.nodes, f_branch.nodes) if up else (f_branch.nodes, h_branch.nodes)
    tags = jnp.concatenate([jnp.zeros(first.shape, int), jnp.ones(second.shape, int)])
    if not up:
        tags = 1 - tags
    nodes = jnp.concatenate([first, second])
    order = jnp.argsort(nodes, stable=True)
    nodes, tags = nodes[order], tags[order]
    return EdgePath(nodes=nodes, tags=jnp.where(nodes >= top, 0, tags))
