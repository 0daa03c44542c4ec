"""Test configuration: float64 physics, as in the CLI entry point."""

import jax

jax.config.update("jax_enable_x64", True)
