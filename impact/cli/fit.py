"""`impact fit`: calibrate scene values against measurements (declared in `commands`).

    impact fit FIT.yaml [-o DIR] [--set PATH=VALUE ...] [--overwrite]

`--set dotted.path=value` overrides a value of the fit file before it is read (its scene's
values under `scene.`, a parameter's start under `parameters.<path>.start`: see
`impact._scene.overrides`); fit.h5 then stores the fit file as overridden. Bad input (the fit
file, its scene or data, an override, the output folder) exits with code 2, names the
field, prints no traceback and writes nothing. It says what it fits, then prints each
Levenberg–Marquardt step's χ² and parameters when the solve has ended; DIR then receives
fit.yaml, fit.h5 and fit.png, each written atomically (a folder created here is removed again
if a write fails).
"""

import math
from pathlib import Path

from .._io.fit import write_fit, write_fit_yaml
from .._plots.figures import import_ahead
from .._plots.fit import save_fit_figure
from .._run.fit import FitResult, fit_spec
from .._scene.errors import SceneError
from .._scene.fit_spec import FitSpec, load_fit
from .console import refuse, say, warn
from .folders import check_output, make_folder, removed_on_failure
from .long_runs import interruptible


def run_fit(fit_file: Path, output: Path | None, assignments: list[str], overwrite: bool) -> None:
    """`impact fit`: fit the parameters of a fit file (with its `--set` overrides); write
    fit.yaml, fit.h5 and fit.png."""
    try:
        spec = load_fit(fit_file, assignments)
    except SceneError as error:
        refuse(f"{fit_file} is not a valid fit", error.problems)
    folder = output or Path("runs") / "fits" / fit_file.stem
    check_output(folder, overwrite, holds="fit")
    import_ahead()  # matplotlib, for the figure, while the fit computes
    say(_announcement(spec))
    try:
        result = interruptible(lambda: fit_spec(spec, spec.model, progress=_progress(spec)))
    except SceneError as error:
        refuse(f"{fit_file} is not a valid fit", error.problems)
    _write(result, folder)
    _summary(result)
    say(f"fit written to {folder}")


def _announcement(spec: FitSpec) -> str:
    """What the fit is about to do, said before it starts (its steps are printed when it ends)."""
    values = "value" if len(spec.parameters) == 1 else "values"
    return (
        f"fitting {len(spec.parameters)} {values} to {spec.rows} rows with model {spec.model!r} "
        f"(Levenberg–Marquardt; its steps are printed when it ends)"
    )


def _progress(spec: FitSpec):
    names = list(spec.parameters)

    def show(step: int, chi2: float, values: dict[str, float]) -> None:
        listed = ", ".join(f"{name} = {values[name]:.6g}" for name in names)
        say(f"step {step:3d}  χ² = {chi2:.6g}  {listed}")

    return show


def _write(result: FitResult, folder: Path) -> None:
    with removed_on_failure(folder):
        make_folder(folder, exist_ok=True, holds="fit")
        write_fit_yaml(result, folder / "fit.yaml")
        write_fit(result, folder / "fit.h5")
        save_fit_figure(result, folder)


def _summary(result: FitResult) -> None:
    for path, value in result.values.items():
        error = result.standard_errors[path]
        shown = "not determined" if math.isnan(error) else f"± {error:.3g}"
        say(f"{path} = {value:.6g} {shown}")
    say(f"χ² = {result.chi2:.4g} for {result.dof} degrees of freedom")
    say(f"standard errors: {result.sigma_source}")
    say(f"{'converged' if result.converged else 'NOT converged'} after {result.iterations} steps")
    for message in result.unidentifiable:
        warn(f"unidentifiable: {message}")
