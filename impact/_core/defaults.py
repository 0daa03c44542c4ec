"""Defaults that the command line's help text shows, here so that `impact --help` need not import
the modules (and JAX) that use them."""

DEFAULT_CHUNK = 1000  # sweep points per compiled call on CPU devices
# ... and per accelerator (GPU) device: there every iteration of the vmapped loops costs its
# kernel launches whatever the batch, so a call takes as many lanes as memory allows.
ACCELERATOR_CHUNK = 2**17
SPEED_REPEATS = 5  # timed runs per row of `impact bench speed`: the median is reported
