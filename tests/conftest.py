"""Test configuration: float64 physics and whole-loop compilation, as in the CLI entry point, with
the compilation cache in a temporary directory of this process (never the user's): the
command-line tests' subprocesses inherit it through IMPACT_CACHE_DIR."""

import atexit
import os
import shutil
import tempfile

import impact

_CACHE = tempfile.mkdtemp(prefix="impact-test-cache-")
atexit.register(shutil.rmtree, _CACHE, ignore_errors=True)
os.environ["IMPACT_CACHE_DIR"] = _CACHE

impact.configure()
