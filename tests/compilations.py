"""Counting XLA's compilations: what a test of "no recompilation" asserts on."""

import jax

COMPILE = "/jax/core/compile/backend_compile_duration"


class Compiles:
    """Counts XLA backend compilations while in its `with` block."""

    def __enter__(self) -> "Compiles":
        self.count = 0
        jax.monitoring.register_event_duration_secs_listener(self._listen)
        return self

    def _listen(self, event: str, duration: float, **kwargs) -> None:
        self.count += event == COMPILE

    def __exit__(self, *exc) -> None:
        jax.monitoring.unregister_event_duration_listener(self._listen)
