"""The global options of `impact` (where the compilation cache lives) and the process settings
each command starts with."""

import warnings
from dataclasses import dataclass
from pathlib import Path

import typer

from .console import warn


@dataclass(frozen=True)
class CacheChoice:
    """The compilation cache the global options ask for."""

    directory: Path | None = None  # --cache-dir (None: $IMPACT_CACHE_DIR, else the per-user default)
    enabled: bool = True  # False with --no-cache


def configured(ctx: typer.Context) -> None:
    """Float64, whole-loop compilation and the compilation cache the global options ask for
    (`impact.configure`, which imports JAX); a cache directory that cannot be used is reported
    as one warning line and the command goes on without a cache."""
    choice = ctx.obj if isinstance(ctx.obj, CacheChoice) else CacheChoice()
    from .._core import runtime  # imports JAX: only once a command runs (see `commands`)

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", RuntimeWarning)
        runtime.configure(choice.directory, cache=choice.enabled)
    for warning in caught:
        warn(f"warning: {warning.message}")
