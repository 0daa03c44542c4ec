"""One quasi-static test: the continuum or the spring-array march of a loading."""

import equinox as eqx

from .continuum import march_continuum
from .loading import Loading, QuasiStaticNumerics
from .setup import build
from .springs import march_springs


@eqx.filter_jit
def march(loading: Loading, numerics: QuasiStaticNumerics):
    """Build and march one quasi-static program; returns (scales, scaled outcome)."""
    built = build(loading, numerics)
    if numerics.springs is None:
        return built.law.scales, march_continuum(built, numerics)
    return built.law.scales, march_springs(built, numerics, loading.spring_length, loading.spring_count)
