"""Integrators of an impact (one interface: continuum, spring array, Verlet, Maugis–Dugdale),
their shared phase bookkeeping, and the quasi-static march of indentation tests."""
