"""The reference cases: impacts whose restitution is known in closed form (Popov, Heß & Willert,
Handbook of Contact Mechanics (Springer 2019), ch. 3, eqs. (3.50)–(3.51) and (3.81)–(3.82))."""

import math
from dataclasses import dataclass

from .. import theory
from .._integrate.codes import RESULT_CODE
from .plans import CONE_ANGLE, E_STAR, MASS, OTHER_FACTOR, POWER_C, POWER_N, RADIUS, TN_FACTORS, WORK_OF_ADHESION


@dataclass(frozen=True)
class Case:
    """A reference impact: its scene, closed-form restitution and the data of the baseline."""

    name: str
    group: str
    scene: dict
    reference: float
    n: float  # power-law exponent of g (for the baseline: g = aⁿ in JKR units)
    c: float  # f = c·rⁿ (m^(1−n))
    attach_on_touch: bool

    @property
    def velocity(self) -> float:
        return float(self.scene["initial"]["velocity"])


def case_scene(name: str, profile: dict, velocity: float, approach: float | None = None) -> dict:
    """The scene definition of a benchmark impact: the body of mass MASS with `profile` at
    `velocity` (m/s) on E* = E_STAR, adhesion Δγ = WORK_OF_ADHESION (approach Δγa if given)."""
    adhesion = {"work_of_adhesion": WORK_OF_ADHESION}
    if approach is not None:
        adhesion["approach_work_of_adhesion"] = approach
    return dict(
        name=name,
        body=dict(profile=profile, mass=MASS),
        material=dict(E_star=E_STAR),
        initial=dict(velocity=velocity),
        effects=dict(adhesion=adhesion),
    )


def sticking_velocity() -> float:
    """Thornton–Ning sticking velocity of the benchmark paraboloid (m/s)."""
    return float(theory.thornton_ning_sticking_velocity(MASS, RADIUS, E_STAR, WORK_OF_ADHESION))


def reference_cases(groups=("tn", "cone", "power", "attach")) -> list[Case]:
    """The reference impacts of the named groups, each with its closed-form restitution."""
    v_s = sticking_velocity()
    paraboloid = dict(shape="paraboloid", R=RADIUS)
    cases = []
    if "tn" in groups:
        for factor in TN_FACTORS:
            velocity = factor * v_s
            cases.append(
                Case(
                    f"thornton_ning_{factor:g}",
                    "tn",
                    case_scene("tn", paraboloid, velocity),
                    float(theory.thornton_ning_restitution(velocity, MASS, RADIUS, E_STAR, WORK_OF_ADHESION)),
                    2.0,
                    0.5 / RADIUS,
                    False,
                )
            )
    for group, name, profile, n, c in (
        ("cone", "cone", dict(shape="cone", theta=CONE_ANGLE), 1.0, math.tan(CONE_ANGLE)),
        ("power", "power_law_1.5", dict(shape="power_law", n=POWER_N, c=POWER_C), POWER_N, POWER_C),
    ):
        if group in groups:
            v_n = float(theory.power_law_sticking_velocity(MASS, n, c, E_STAR, WORK_OF_ADHESION))
            velocity = OTHER_FACTOR * v_n
            cases.append(
                Case(
                    name,
                    group,
                    case_scene(name, profile, velocity),
                    float(theory.power_law_restitution(velocity, MASS, n, c, E_STAR, WORK_OF_ADHESION)),
                    n,
                    c,
                    False,
                )
            )
    if "attach" in groups:
        velocity = OTHER_FACTOR * v_s
        cases.append(
            Case(
                "attach_on_touch",
                "attach",
                case_scene("attach", paraboloid, velocity, approach=0.0),
                float(theory.attach_on_touch_restitution(velocity, MASS, RADIUS, E_STAR, WORK_OF_ADHESION)),
                2.0,
                0.5 / RADIUS,
                True,
            )
        )
    return cases


def restitution(outcome) -> float:
    """e of a scaled outcome (nan unless the body separated)."""
    if int(outcome.status) != RESULT_CODE["separated"]:
        return float("nan")
    return float(outcome.separation_velocity) / float(outcome.touch_velocity)
