"""What every figure shares: SI prefixes for axis units, the frame of a force–indentation plot,
writing figures atomically, and importing matplotlib ahead while a command computes.

Figures are drawn on matplotlib's Agg canvas (no pyplot, no display, no global state), and
matplotlib is imported only inside the functions that draw, so `import impact` never loads it.
"""

import math
import threading
from pathlib import Path

from .._io.files import atomic_path

_PREFIXES = {-18: "a", -15: "f", -12: "p", -9: "n", -6: "µ", -3: "m", 0: "", 3: "k", 6: "M", 9: "G"}


def si_prefix(magnitude: float) -> tuple[float, str]:
    """(factor, prefix) that brings |magnitude| into [1, 1000): 3.9e-8 → (1e9, "n")."""
    if not math.isfinite(magnitude) or magnitude == 0:
        return 1.0, ""
    exponent = 3 * math.floor(math.log10(abs(magnitude)) / 3)
    exponent = min(max(exponent, min(_PREFIXES)), max(_PREFIXES))
    return 10.0**-exponent, _PREFIXES[exponent]


def frame_force_indentation(axes, length_prefix: str, force_prefix: str, legend: str) -> None:
    """The frame of a force–indentation plot: the axes through the origin, a grid, d and F
    labelled with their units (`length_prefix`m, `force_prefix`N) and signs, the legend at `legend`."""
    axes.axhline(0.0, color="0.6", lw=0.8, zorder=0)
    axes.axvline(0.0, color="0.6", lw=0.8, zorder=0)
    axes.grid(alpha=0.3)
    axes.set_xlabel(f"indentation d ({length_prefix}m), > 0 pressed in")
    axes.set_ylabel(f"force F ({force_prefix}N), > 0 compressive")
    axes.legend(loc=legend, fontsize="small")


def write_figures(folder: str | Path, named) -> list[Path]:
    """Write each (file name, figure) into `folder` at 150 dpi, atomically; return the paths. The
    PNG is compressed at zlib level 1: the same pixels as the default level 6, in a slightly larger
    file written in less time."""
    paths = []
    for name, figure in named:
        path = Path(folder) / name
        with atomic_path(path) as temporary:
            figure.savefig(temporary, dpi=150, pil_kwargs={"compress_level": 1})
        paths.append(path)
    return paths


def import_ahead() -> threading.Thread:
    """Start importing matplotlib's figure and Agg canvas in a background thread, and return it.
    A command that draws calls this before it computes: the import (much Python) then
    runs while the main thread waits on compiled code (loading an executable from the cache and
    running it release the GIL), instead of after it. A failed import is left to the one where
    the figures are drawn, which raises it; this thread prints nothing."""
    thread = threading.Thread(target=_import_drawing, name="import matplotlib", daemon=True)
    thread.start()
    return thread


def _import_drawing() -> None:
    try:
        import matplotlib.backends.backend_agg  # noqa: F401 - what `savefig` to PNG draws with
        import matplotlib.figure  # noqa: F401
    except Exception:  # noqa: BLE001 - raised again where the figures are drawn
        pass
