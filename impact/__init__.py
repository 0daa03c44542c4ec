"""impact: time-stepping simulator of adhesive impacts (MDR contact law on JAX and diffrax)."""

__version__ = "0.1.0"
