"""Test configuration: float64 physics and whole-loop compilation, as in the CLI entry point, with
the compilation cache in a temporary directory of this test run (never the user's). The process
that starts the run makes it and removes it at its end; pytest-xdist's workers, which it starts
after loading this file, inherit it through IMPACT_TEST_CACHE_DIR, so a program one worker
compiled is loaded by the other instead of compiled again; the command-line tests'
subprocesses inherit it through IMPACT_CACHE_DIR.

The fixtures shared by every folder are here; the constants and scene builders they share
(collected into parametrize lists before any fixture exists) are in `tests/scenes.py`."""

import atexit
import os
import shutil
import tempfile

import pytest

import impact
from tests.scenes import THORNTON_NING

_RUN_CACHE = "IMPACT_TEST_CACHE_DIR"

if _RUN_CACHE not in os.environ:
    os.environ[_RUN_CACHE] = tempfile.mkdtemp(prefix="impact-test-cache-")
    atexit.register(shutil.rmtree, os.environ[_RUN_CACHE], ignore_errors=True)
os.environ["IMPACT_CACHE_DIR"] = os.environ[_RUN_CACHE]

impact.configure()


@pytest.fixture
def thornton_ning_scene() -> impact.Scene:
    """configs/thornton_ning.yaml loaded: the micro-sphere's impact that most tests strike (each
    test its own copy: a scene is a mutable model)."""
    return impact.load_scene(THORNTON_NING)
