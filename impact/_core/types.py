"""Type aliases shared by the package's modules."""

import jax
import numpy as np

# The leaves of a parameter pytree (Physics, Adhesion, Gravity, Loading): traced arrays, or
# numpy arrays with a leading batch axis while a sweep assembles them on the host.
Parameter = jax.Array | np.ndarray
