"""Make viscoelastic_indentation.csv: synthetic indentation curves of a viscoelastic film at three
rates, for viscoelastic_indentation.yaml.

A paraboloid (R = 10 µm) pressed 1 µm deep at 0.2, 1 and 5 µm/s, held 0.2 s at the peak and
withdrawn at the same rate (displacement control). The film is a standard linear solid,
E*(t) = E∞* + E1·e^(−t/τ) with E∞* = 1 MPa, E1 = 2 MPa, τ = 0.5 s: the values the fit should
find. Its force is Lee & Radok's hereditary integral while loading and held, and Ting's while
unloading (the integral up to the time t1 of the loading with the same contact radius, the root
of ∫_{t1}^{t} E*(t − s)·ḋ(s) ds = 0), computed here by scipy's quad and brentq, independently of
impact's closed forms. 40 times per curve, evenly over its duration; Gaussian noise of 5 nN on
the force. Seed 15. Run from anywhere: python configs/fits/make_viscoelastic_data.py
"""

from pathlib import Path

import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq

SEED = 15
RADIUS, PEAK, HOLD = 1e-5, 1e-6, 0.2  # m, m, s
RATES = (2e-7, 1e-6, 5e-6)  # m/s
RELAXED, MODULUS, TIME = 1e6, 2e6, 0.5  # Pa, Pa, s: what the fit should find
POINTS = 40  # per curve
FORCE_SIGMA = 5e-9  # N


def relaxation(t: float) -> float:
    return RELAXED + MODULUS * np.exp(-t / TIME)


def force(t: float, rate: float) -> float:
    """The force (N) at time t (s) of the test at `rate` (m/s)."""
    ramp = PEAK / rate
    unloading = ramp + HOLD

    def integral(a, b):  # ∫_a^b E*(t − s) ds
        return quad(lambda s: relaxation(t - s), a, b, epsabs=0, epsrel=1e-13)[0]

    if t <= unloading:
        loaded = min(t, ramp)
    elif integral(0.0, ramp) <= integral(unloading, t):
        return 0.0  # the contact is lost
    else:
        loaded = brentq(lambda t1: integral(t1, ramp) - integral(unloading, t), 0.0, ramp, xtol=1e-16)
    integrand = lambda s: relaxation(t - s) * 1.5 * rate**1.5 * np.sqrt(s)  # noqa: E731
    return 4 * np.sqrt(RADIUS) / 3 * quad(integrand, 0.0, loaded, epsabs=0, epsrel=1e-13, limit=200)[0]


def viscoelastic_data(seed: int = SEED) -> dict[str, np.ndarray]:
    """The columns of the three curves: time (s), force (N), program.rate (m/s)."""
    noise = np.random.default_rng(seed).standard_normal(POINTS * len(RATES))
    times, forces, rates = [], [], []
    for rate in RATES:
        for t in np.linspace(0.0, 2 * PEAK / rate + HOLD, POINTS + 1)[1:]:
            times.append(t)
            forces.append(force(t, rate))
            rates.append(rate)
    return {
        "time": np.array(times),
        "force": np.array(forces) + FORCE_SIGMA * noise,
        "program.rate": np.array(rates),
    }


def main() -> None:
    columns = viscoelastic_data()
    header = (
        f"# Synthetic indentation curves of viscoelastic_indentation.yaml made by make_viscoelastic_data.py\n"
        f"# (seed {SEED}): a paraboloid, R = {RADIUS:g} m, pressed {PEAK:g} m at three rates, held {HOLD:g} s, a\n"
        f"# standard linear solid E∞* = {RELAXED:g} Pa, E1 = {MODULUS:g} Pa, τ = {TIME:g} s (Lee & Radok, Ting);\n"
        f"# Gaussian noise sigma {FORCE_SIGMA:g} N on the force. time in s, force in N, program.rate in m/s.\n"
    )
    rows = [",".join(columns)] + [
        f"{t:.10g},{f:.10g},{r:.10g}"
        for t, f, r in zip(columns["time"], columns["force"], columns["program.rate"], strict=True)
    ]
    (Path(__file__).parent / "viscoelastic_indentation.csv").write_text(header + "\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
