"""Indentation of a viscoelastic half-space at a rate: Lee & Radok while loading and holding,
Ting while unloading (to 1e-6), their convergence in the number of springs, creep under force
control, the rate-dependent pull-off between its relaxed and glassy limits, results in time."""

import dataclasses

import jax.numpy as jnp
import numpy as np
import pytest

import impact
from impact import theory
from impact._io.indentation import read_indentation, write_indentation
from impact._run.viscoelastic_indentation import rate_numerics, simulate_rate_test

R, RELAXED = 1e-5, 1e6  # m, Pa
PRONY = [{"modulus": 2e6, "time": 0.5}, {"modulus": 5e5, "time": 0.05}]
RATE, PEAK, HOLD = 1e-6, 1e-6, 0.3  # m/s, m, s: a 1 s ramp
SLOTS = 2048  # the compiled array every displacement-controlled test here shares


def scene(springs=2000, control="displacement", program=None, prony=PRONY, adhesion=None) -> impact.Scene:
    data = {
        "name": "viscoelastic_indentation",
        "kind": "indentation",
        "control": control,
        "program": {"peak": PEAK, "rate": RATE, "hold": HOLD, **(program or {})},
        "body": {"profile": {"shape": "paraboloid", "R": R}},
        "material": {"E_star": RELAXED},
        "contact": {"springs": springs},
        "effects": {"viscoelasticity": {"prony": prony}},
    }
    if adhesion is not None:
        data["effects"]["adhesion"] = adhesion
    return impact.load_scene(data)


def run(loaded: impact.Scene):
    return simulate_rate_test(loaded, dataclasses.replace(rate_numerics(loaded), capacity=SLOTS))


def closed_form(result) -> np.ndarray:
    moduli, times = (jnp.asarray([term[key] for term in PRONY]) for key in ("modulus", "time"))
    return np.asarray(theory.ting_force(result.time, RATE, R, RELAXED, moduli, times, PEAK / RATE, HOLD))


def errors(result) -> tuple[float, float]:
    """Largest relative errors against Lee & Radok (loading from t = 0.2 s, where a ≥ 0.45·a_max,
    and the hold) and against Ting (unloading, where F > 5 % of its peak)."""
    expected = closed_form(result)
    loaded = (result.time >= 0.2) & (result.time <= PEAK / RATE + HOLD)
    receding = (result.time > PEAK / RATE + HOLD) & (expected > 0.05 * expected.max())
    relative = np.abs(result.force / np.where(expected > 0, expected, 1.0) - 1.0)
    return float(relative[loaded].max()), float(relative[receding].max())


def test_lee_radok_and_ting_to_one_in_a_million():
    """2000 springs over 1.5 relaxed contact radii: loading and hold within 1e-6 of Lee & Radok,
    unloading within 1e-6 of Ting (measured 7.4e-7, 4.8e-7); time runs from 0 in steps."""
    result = run(scene())
    assert result.status == "separated"
    lee_radok, ting = errors(result)
    assert lee_radok < 1e-6 and ting < 1e-6
    assert result.time[0] > 0 and np.all(np.diff(result.time) > 0)
    assert [kind for _, kind in result.events] == ["touch", "reversal", "pull_off"]


def test_spring_count_converges_at_second_order():
    """The largest error against Lee & Radok and Ting falls as N⁻² (fitted orders 2 ± 0.2 over
    N = 256 … 2048, one compiled array)."""
    counts = np.array([256, 512, 1024, 2048])
    found = np.array([errors(run(scene(int(count)))) for count in counts])
    for column in found.T:
        order = -np.polyfit(np.log(counts), np.log(column), 1)[0]
        assert order == pytest.approx(2.0, abs=0.2), column


def test_contact_is_lost_where_ting_says():
    """The medium recovers late: the contact is lost while d > 0, at the time Ting's condition
    gives (t₁ → 0), within a step of the program."""
    result = run(scene())
    moduli, times = (jnp.asarray([term[key] for term in PRONY]) for key in ("modulus", "time"))
    ramp = PEAK / RATE
    step = ramp / 200
    grid = np.arange(ramp + HOLD, 2 * ramp + HOLD, step / 50)
    t1 = np.asarray(theory.ting_contact_time(grid, RELAXED, moduli, times, ramp, HOLD))
    lost = grid[np.argmax(t1 == 0.0)]
    assert result.pull_off.indentation == pytest.approx(RATE * (2 * ramp + HOLD - lost), abs=1.01 * RATE * step)
    assert result.pull_off.indentation > 0.4 * PEAK


@pytest.mark.slow
def test_creep_under_force_control():
    """A standard linear solid under a force ramp, then held: d^(3/2) = 3/(4√R)·∫J(t − s)Ḟ ds with
    the creep compliance J(t) = 1/E∞ − (1/E∞ − 1/E₀)e^(−t/τ_r), τ_r = τE₀/E∞ (to 3e-5: the force
    is met at each step's end, d linear within it: second order in the step)."""
    modulus, time = 2e6, 0.5
    instantaneous = RELAXED + modulus
    retardation = time * instantaneous / RELAXED
    hold = 2.0
    result = simulate_rate_test(scene(1000, "force", {"hold": hold}, prony=[{"modulus": modulus, "time": time}]))
    ramp = PEAK / RATE
    t = result.time
    loaded = np.minimum(t, ramp)
    compliance = loaded / RELAXED - (1 / RELAXED - 1 / instantaneous) * retardation * (
        np.exp(-(t - loaded) / retardation) - np.exp(-t / retardation)
    )
    expected = (3 / (4 * np.sqrt(R)) * RATE * compliance) ** (2 / 3)
    window = (t > 0.2) & (t <= ramp + hold)
    assert np.max(np.abs(result.indentation[window] / expected[window] - 1)) < 3e-5
    assert result.indentation[window][-1] > 1.4 * result.indentation[np.argmin(np.abs(t - ramp))]  # it crept 42 %


def test_pull_off_between_its_relaxed_and_glassy_limits():
    """With JKR adhesion (Δγ = 0.05 J/m², E₀*/E∞* = 4) the largest tensile force of the retraction
    runs from the relaxed limit (3/2)πR·Δγ·E₀*/E∞* (the rule of Heß at E₀* on relaxed springs) at
    slow pulling to the glassy one (3/2)πRΔγ at fast pulling (each to 1 %: it converges at first
    order in the spacing, as an elastic array's under force control); in between it falls with
    the rate."""
    rates = [1e-9, 1e-3, 1e3]
    adhesion = {"work_of_adhesion": 0.05}
    found = []
    for rate in rates:
        loaded = scene(
            2000,
            program={"rate": rate, "hold": 0.0, "peak": 2e-5},
            prony=[{"modulus": 3e6, "time": 0.5}],
            adhesion=adhesion,
        )
        result = simulate_rate_test(loaded)
        assert result.status == "separated"
        found.append(-result.force.min() / (1.5 * np.pi * R * 0.05))
    assert found[0] == pytest.approx(4.0, rel=1e-2, abs=0.0)
    assert found[-1] == pytest.approx(1.0, rel=1e-2, abs=0.0)
    assert found[0] > found[1] > found[2]


def test_time_in_the_file(tmp_path):
    """run.h5 stores the time of each point (observables/curve/time) and reads it back."""
    result = run(scene(256))
    stored = read_indentation(write_indentation(result, tmp_path / "run.h5"))
    assert np.array_equal(stored.time, result.time)
    assert np.array_equal(stored.force, result.force)
