"""Test configuration: float64 physics and whole-loop compilation, as in the CLI entry point."""

import impact

impact.configure()
