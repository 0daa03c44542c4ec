"""The columns of a fit of a quasi-static indentation curve (the AFM use), and their checks.

Each row is one point of the curve: the controlled value (the column `indentation` (m) under
displacement control, `force` (N) under force control; `time` (s) for a viscoelastic test at a
rate) is the row's input; the other of the two
(or `contact_radius`) is the observable; the branch (approach or retract) comes from a column of
labels named by the fit file's `branch` key, or, without one, from the order of the rows: up to
the largest control value approach, after it retract (a recorded test in program order).
"""

import numpy as np

from .scene import Scene

CONTROL_COLUMNS = {"displacement": "indentation", "force": "force"}
TIME = "time"  # the control column of a viscoelastic test at a rate (s)
CURVE_OBSERVABLES = ("force", "indentation", "contact_radius")
BRANCHES = {"approach": 0.0, "retract": 1.0}  # the branch labels and their codes in the rows
BRANCH = "branch"  # the column of branch codes in a validated fit's data
VISCOELASTIC_THEORY = (
    "a viscoelastic test at a rate is fitted with model: theory (the closed forms of Lee & Radok and Ting, "
    "exact for a paraboloid under displacement control without adhesion), not through its spring array"
)
NOT_DIFFERENTIABLE = (
    "the quasi-static march of an indentation scene is not differentiable (its jumps and searches "
    "are loops with no derivative); use model: theory, the closed-form JKR curve"
)


def control_column(scene: Scene) -> str | None:
    """The data column of the controlled value of an indentation scene (None for an impact): the
    time of a viscoelastic half-space's test at a rate."""
    if scene.kind != "indentation" or not scene.control:
        return None
    return TIME if scene.effects.viscoelasticity is not None else CONTROL_COLUMNS[scene.control]


def curve_observables(scene: Scene) -> tuple[str, ...]:
    """The observables a fit of the scene's curve can match: all but the controlled value (a
    viscoelastic test at a rate: its force)."""
    if scene.effects.viscoelasticity is not None:
        return ("force",)
    return tuple(name for name in CURVE_OBSERVABLES if name != control_column(scene))


def curve_problems(scene: Scene, branch: str | None, model: str, columns: dict[str, np.ndarray]) -> list:
    """(field, message) of what keeps a fit of the scene's curve from running (none for an
    impact without `branch`)."""
    control = control_column(scene)
    if control is None:
        return [] if branch is None else [("branch", "only an indentation scene has approach and retract branches")]
    problems = []
    if model == "simulation":
        viscoelastic = scene.effects.viscoelasticity is not None
        problems.append(("model", VISCOELASTIC_THEORY if viscoelastic else NOT_DIFFERENTIABLE))
    if control not in columns:
        problems.append(
            (
                "data",
                f"no column {control!r}: the controlled value of a {scene.control}-controlled scene, "
                f"the input of each row; its columns: {', '.join(columns) or 'none'}",
            )
        )
    if branch is not None:
        problems += _label_problems(branch, columns)
    return problems


def _label_problems(branch: str, columns: dict[str, np.ndarray]) -> list[tuple[str, str]]:
    if branch not in columns:
        return [("branch", f"no column {branch!r} in the data; its columns: {', '.join(columns)}")]
    for row, label in enumerate(columns[branch], start=1):
        if str(label) not in BRANCHES:
            expected = " or ".join(BRANCHES)
            return [
                ("branch", f"column {branch!r}, data row {row}: {str(label)!r} is not a branch; expected {expected}")
            ]
    return []


def branch_codes(branch: str | None, control: np.ndarray, columns: dict[str, np.ndarray]) -> np.ndarray:
    """The branch of every row: 0 approach, 1 retract (labels checked by `curve_problems`)."""
    if branch is not None:
        return np.array([BRANCHES[str(label)] for label in columns[branch]])
    return (np.arange(len(control)) > np.argmax(control)).astype(float)
