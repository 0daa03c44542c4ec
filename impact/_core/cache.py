"""The persistent compilation cache: XLA programs compiled once per machine, not once per process.

JAX stores each compiled program on disk, keyed by the program, its shapes and dtypes, its
static choices and the versions of jax and XLA; a later process with the same key loads it
instead of compiling (seconds → a fraction of one). Where it lives:

- `configure(cache_dir=DIR)` or the command line's `--cache-dir DIR`: DIR;
- else the environment variable `IMPACT_CACHE_DIR=DIR`: DIR (`IMPACT_CACHE_DIR=off`, or
  `configure(cache=False)` / `--no-cache`, switches the cache off);
- else `platformdirs.user_cache_dir("impact")/jax` (e.g. ~/.cache/impact/jax on Linux).

The cache is trusted: anyone who can write to its directory can run code in the processes that
read it, so never point it at a directory others may write to.
"""

import os
import tempfile
import warnings
from pathlib import Path

import jax
import platformdirs
from jax.experimental.compilation_cache import compilation_cache

CACHE_VARIABLE = "IMPACT_CACHE_DIR"
OFF = "off"  # IMPACT_CACHE_DIR=off switches the cache off

_in_use: Path | None = None  # set by `use_cache`


def cache_directory(cache_dir: str | os.PathLike[str] | None = None, *, cache: bool = True) -> Path | None:
    """The directory the cache would use, or None where it is switched off: `cache_dir`, else
    $IMPACT_CACHE_DIR (`off`: none), else the per-user cache directory of the platform."""
    if not cache:
        return None
    if cache_dir is not None:
        return Path(cache_dir).expanduser()
    value = os.environ.get(CACHE_VARIABLE, "").strip()
    if value.lower() == OFF:
        return None
    if value:
        return Path(value).expanduser()
    return Path(platformdirs.user_cache_dir("impact")) / "jax"


def use_cache(directory: Path | None) -> Path | None:
    """Store and load compiled programs in `directory` (None: compile in every process); return
    the directory in use. One that cannot be created or written is not used: a RuntimeWarning
    says why and the process goes on compiling without a cache."""
    if directory is not None:
        try:
            directory.mkdir(parents=True, exist_ok=True)
            with tempfile.TemporaryFile(dir=directory):
                pass
        except OSError as error:
            reason = error.strerror or str(error)
            warnings.warn(
                f"compilation cache {directory} is not usable ({reason}); compiling without a cache",
                RuntimeWarning,
                stacklevel=3,
            )
            directory = None
    global _in_use
    _in_use = directory
    if directory is None:
        jax.config.update("jax_enable_compilation_cache", False)
        return None
    compilation_cache.reset_cache()  # JAX opens its cache once per process: open this one
    jax.config.update("jax_enable_compilation_cache", True)
    jax.config.update("jax_compilation_cache_dir", str(directory))
    # Store every program, however small or quick to compile (a run compiles a few small ones
    # besides the solver: their compilations add up too).
    jax.config.update("jax_persistent_cache_min_compile_time_secs", 0.0)
    jax.config.update("jax_persistent_cache_min_entry_size_bytes", -1)
    return directory


def directory_in_use() -> Path | None:
    """The cache directory `configure` switched on in this process (None: no cache)."""
    return _in_use
