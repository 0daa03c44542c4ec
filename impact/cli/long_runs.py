"""Long computations on the command line: `--allow-long`, and Ctrl-C.

`--allow-long` lifts the budgets a scene or sweep is checked against before it compiles
(`impact._scene.cost`: a run's estimated solver steps, the memory of its arrays, a sweep's
points).

XLA runs a compiled program to its end without returning to Python, and Python raises the
KeyboardInterrupt of a Ctrl-C only once it does: a long run ignored Ctrl-C until it ended. A
command therefore computes in a worker thread (`interruptible`) while the main thread
waits in Python, where Ctrl-C arrives at once: the process ends within a fraction of a second
with exit code 130, before anything is written (a sweep keeps its finished chunks, as after a
kill). A Ctrl-C anywhere else (starting, reading, checking, writing) ends the command with code
130 too (`command_scope`, `catch_ctrl_c`); a run's folder half written is removed first.
"""

import contextlib
import contextvars
import os
import signal
import sys
import threading
from collections.abc import Callable, Iterator
from typing import Annotated, TypeVar

import typer

from .console import warn

INTERRUPTED = 130  # exit code after Ctrl-C (128 + SIGINT), as the shells use
_POLL_SECONDS = 0.1  # how often the main thread looks at the worker


class Interrupted(BaseException):
    """Ctrl-C in the `impact` process (`catch_ctrl_c`): not a KeyboardInterrupt, which click
    turns into "Aborted!" and exit code 1."""


def catch_ctrl_c() -> None:
    """Make Ctrl-C (SIGINT) raise `Interrupted`, unless the process was started with it ignored."""
    if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        signal.signal(signal.SIGINT, _raise_interrupted)


def _raise_interrupted(signum, frame) -> None:  # noqa: ARG001 - a signal handler's arguments
    raise Interrupted


AllowLong = Annotated[
    bool,
    typer.Option(
        "--allow-long",
        help="accept a run or sweep beyond the budgets it is checked against before it compiles (solver steps, "
        "memory, sweep points); not beyond the machine's memory",
        show_default=False,
    ),
]

Value = TypeVar("Value")


def interruptible(compute: Callable[[], Value], interrupted: str = "interrupted") -> Value:
    """`compute()` run in a worker thread (in this thread's context: `impact.allow_long` and the
    like hold there) while this thread waits; its value, or its exception raised here. Ctrl-C
    prints `interrupted` and ends the process at once with exit code 130."""
    context = contextvars.copy_context()
    outcome: dict[str, object] = {}

    def work() -> None:
        try:
            outcome["value"] = context.run(compute)
        except BaseException as error:  # noqa: BLE001 - handed to the waiting thread as it is
            outcome["error"] = error

    worker = threading.Thread(target=work, name="impact-compute", daemon=True)
    worker.start()
    try:
        while worker.is_alive():
            worker.join(_POLL_SECONDS)
    except (KeyboardInterrupt, Interrupted):
        warn(interrupted)
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(INTERRUPTED)  # the worker is inside XLA: nothing else would stop it
    if "error" in outcome:
        raise outcome["error"]  # type: ignore[misc]
    return outcome["value"]  # type: ignore[return-value]


@contextlib.contextmanager
def command_scope(allow_long: bool) -> Iterator[None]:
    """Where a command runs: with the budgets lifted if `allow_long` (`impact.allow_long`), and
    a Ctrl-C ending it with "interrupted" and exit code 130 (not click's "Aborted!" and 1)."""
    from .._scene.cost import allow_long as lifted  # imports JAX: only once a command runs

    try:
        with lifted() if allow_long else contextlib.nullcontext():
            yield
    except (KeyboardInterrupt, Interrupted):
        warn("interrupted")
        raise typer.Exit(INTERRUPTED) from None
