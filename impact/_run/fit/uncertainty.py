"""Standard errors, correlations and unidentifiable directions of a weighted least-squares fit.

With weighted residuals r = (model − data)/σ and their Jacobian J in the physical parameters,
the covariance of the estimate is (JᵀJ)⁻¹ (Bard 1974, Nonlinear Parameter Estimation, §7-5),
multiplied by χ²/dof when σ is unknown (a common σ estimated from the scatter). Everything is
computed in relative parameters (d ln p) and on the correlation-scaled matrix, whose
eigenvalues then compare parameters of any unit: an eigenvalue below `IDENTIFIABILITY` times
the largest marks a direction the data do not determine, reported in words, and the covariance
is the pseudo-inverse on the determined directions only. A determined parameter whose standard
error exceeds its value is reported in words as well.
"""

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

# Smallest eigenvalue of the correlation-scaled JᵀJ, relative to the largest, of a direction the
# data determine: below it (correlations beyond 1 − 5e-10) the direction is reported instead.
IDENTIFIABILITY = 1e-9
# Components of an undetermined direction below this fraction of its largest are left out.
INVOLVED = 0.05
# A determined parameter whose standard error exceeds this fraction of its value is reported in
# words too: the data bound it, but not even to its order of magnitude (e.g. the Maugis–Dugdale
# range near the JKR limit, where the curve depends on it weakly but not exactly not at all).
LOOSE = 1.0


@dataclass(frozen=True)
class Uncertainty:
    """Covariance [p, p] in the physical units, standard errors [p] (nan: not determined by the
    data), correlation [p, p], and each undetermined direction (and each parameter determined
    more loosely than its own size) in words."""

    covariance: np.ndarray
    standard_errors: np.ndarray
    correlation: np.ndarray
    unidentifiable: list[str]


def uncertainty(
    jacobian: np.ndarray, values: np.ndarray, names: Sequence[str], observed: Sequence[str], variance: float
) -> Uncertainty:
    """The uncertainty of a fit from the Jacobian [residuals, p] of its weighted residuals at the
    fitted `values`; `variance` multiplies the covariance (χ²/dof for unknown σ, else 1)."""
    scale = np.where(values != 0, np.abs(values), 1.0)
    relative = jacobian * scale
    hessian = relative.T @ relative
    norm = np.sqrt(np.diag(hessian))
    norm = np.where(norm > 0, norm, 1.0)
    eigenvalues, vectors = np.linalg.eigh(hessian / np.outer(norm, norm))
    weak = eigenvalues < IDENTIFIABILITY * eigenvalues[-1]
    kept = vectors[:, ~weak]
    inverse = kept @ np.diag(1.0 / eigenvalues[~weak]) @ kept.T
    covariance = variance * inverse / np.outer(norm, norm) * np.outer(scale, scale)
    directions = [vectors[:, index] / norm for index in np.flatnonzero(weak)]
    undetermined = np.zeros(len(values), bool)
    for direction in directions:
        undetermined |= np.abs(direction) >= INVOLVED * np.abs(direction).max()
    errors = np.where(undetermined, np.nan, np.sqrt(np.diag(covariance)))
    correlation = covariance / np.outer(errors, errors)
    np.fill_diagonal(correlation, np.where(undetermined, np.nan, 1.0))
    words = [describe(direction, names, observed) for direction in directions]
    loose = np.flatnonzero(~undetermined & (errors > LOOSE * np.abs(values)))
    words += [describe_loose(names[index], values[index], errors[index], observed) for index in loose.tolist()]
    return Uncertainty(covariance, errors, correlation, words)


def _data(observed: Sequence[str]) -> tuple[str, str]:
    """("restitution alone" | "force and max_force", "fixes" | "fix")."""
    data = " and ".join(observed) + (" alone" if len(observed) == 1 else "")
    return data, "fixes" if len(observed) == 1 else "fix"


def describe_loose(name: str, value: float, error: float, observed: Sequence[str]) -> str:
    """A parameter the data bound only loosely (standard error beyond `LOOSE` of its value)."""
    data, verb = _data(observed)
    return (
        f"{data} {verb} {name} only to ±{error / abs(value):.0%} of its value ({value:.4g} ± {error:.2g}): "
        "the model hardly changes with it, so fix it or add data that depend on it"
    )


def describe(direction: np.ndarray, names: Sequence[str], observed: Sequence[str]) -> str:
    """An undetermined direction (in d ln p) in words: which parameters it mixes and how, and
    for two of them the one product of powers the data do fix."""
    direction = direction / direction[np.argmax(np.abs(direction))]
    involved = [index for index, part in enumerate(direction) if abs(part) >= INVOLVED]
    data, verb = _data(observed)
    if len(involved) == 1:
        return f"{data} {verb} no value of {names[involved[0]]}: the model does not change with it"
    listed = ", ".join(names[index] for index in involved[:-1]) + f" and {names[involved[-1]]}"
    ratio = " : ".join(f"{direction[index]:.3g}" for index in involved)
    text = (
        f"{data} {verb} only a combination of {listed}: changing their logarithms in the ratio {ratio} "
        "leaves the model unchanged, so their values and standard errors are not determined"
    )
    if len(involved) == 2:
        first, second = involved
        text += f"; the data determine {names[first]} · {names[second]}^{-direction[first] / direction[second]:.3g}"
    return text
