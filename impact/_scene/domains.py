"""The allowed range (domain) of every number of a scene, in SI units.

Each domain is a closed interval [low, high], or (low, high] where zero is no meaningful value,
optionally with 0 allowed besides (0 or [low, high]). They are physical and generous: from below
atomic sizes to a kilometre, from soft gels to above diamond. What the scaled problem can
represent depends on several fields at once and is checked across fields (`representable`).
`within(domain)` is the pydantic metadata that checks a field; the scene reference shows the
domain from the field's description.
"""

import math
import typing
from dataclasses import dataclass
from typing import Any

from pydantic import AfterValidator
from pydantic.fields import FieldInfo


@dataclass(frozen=True)
class Domain:
    """An interval from `low` to `high` in `unit`, closed unless `open_low`/`open_high`, with 0
    allowed besides if `zero`."""

    low: float
    high: float
    unit: str
    open_low: bool = False
    open_high: bool = False
    zero: bool = False
    reason: str = ""  # why these bounds, said with a refusal

    def __contains__(self, value: float) -> bool:
        if self.zero and value == 0:
            return True
        above = value > self.low if self.open_low else value >= self.low
        below = value < self.high if self.open_high else value <= self.high
        return above and below

    def __str__(self) -> str:
        interval = (
            f"{'(' if self.open_low else '['}{short(self.low)}, {short(self.high)}{')' if self.open_high else ']'}"
        )
        unit = f" {self.unit}" if self.unit else ""
        return f"0 or {interval}{unit}" if self.zero else f"{interval}{unit}"

    def check(self, value: float) -> float:
        """The value, or ValueError naming it and the allowed range."""
        if value not in self:
            raise ValueError(outside(value, self, self.reason))
        return value


def short(value: float) -> str:
    """A bound as the docs write it: 1e4, 1e-12, 2.5e-7, 0.5, 1.5698."""
    if value == 0 or 1e-3 <= abs(value) < 1e4:
        return f"{value:.6g}"
    exponent = math.floor(math.log10(abs(value)))
    mantissa = f"{value / 10.0**exponent:.4g}"
    return f"1e{exponent}" if mantissa == "1" else f"{mantissa}e{exponent}"


def outside(value: float, domain: Domain, why: str = "") -> str:
    """'<value> <unit> is outside the allowed range <domain>[: why]'."""
    unit = f" {domain.unit}" if domain.unit else ""
    return f"{value:g}{unit} is outside the allowed range {domain}" + (f": {why}" if why else "")


def within(domain: Domain) -> Any:
    """Pydantic metadata that refuses a value outside `domain` (after numeric coercion)."""
    return AfterValidator(domain.check)


def domains_of(field: FieldInfo) -> list[Domain]:
    """The domains a scene field checks (`within`): in its own metadata, then in the
    alternatives of its type (a number, or a literal, or None), each once."""
    found = [domain for item in field.metadata if (domain := _checked(item)) is not None]
    for domain in _in_annotation(field.annotation):
        if domain not in found:
            found.append(domain)
    return found


def _in_annotation(annotation) -> list[Domain]:
    """The domains checked by the metadata of an annotation and of its alternatives."""
    found: list[Domain] = []
    for argument in (annotation, *typing.get_args(annotation)):
        inner: list[Domain | None] = []
        if typing.get_origin(argument) is typing.Annotated:
            inner += _in_annotation(typing.get_args(argument)[0])
            inner += map(_checked, argument.__metadata__)
        elif argument is not annotation:
            inner += _in_annotation(argument)
        found += [domain for domain in inner if domain is not None and domain not in found]
    return found


def _checked(item) -> Domain | None:
    """The domain a metadata item of `within` checks (None for any other item)."""
    domain = getattr(getattr(item, "func", None), "__self__", None)
    return domain if isinstance(domain, Domain) else None


_POWERS = {"²": "2", "³": "3"}


def udunits(unit: str) -> str:
    """A domain's unit as the files write units (UDUNITS, as CF conventions read them):
    'm/s' → 'm s-1', 'J/m²' → 'J m-2', 'N s/m' → 'N s m-1', '1/m' → 'm-1'; '' stays ''."""
    numerator, _, denominator = unit.partition("/")
    terms = [term for term in numerator.split() if term != "1"]
    for term in denominator.split():
        base = term.rstrip("".join(_POWERS))
        terms.append(f"{base}-{_POWERS.get(term[len(base) :], '1')}")
    return " ".join(terms)


# --- the domains ------------------------------------------------------------------------------

LENGTH = Domain(1e-12, 1e3, "m", reason="from below atomic size to a kilometre")
LENGTH_OR_ZERO = Domain(0.0, 1e3, "m", reason="up to a kilometre")
GAP = Domain(1e-15, 1e3, "m", zero=True, reason="touching, or a drop of at most a kilometre")
INVERSE_LENGTH = Domain(1e-3, 1e12, "1/m", reason="semi-axes from 1 pm to 1 km")
# Flank angle of a cone: below 1e-6 rad the contact grows beyond any body; above π/2 − 1e-3
# (slope 1000) the solver fails as the angle nears π/2 (π/2 − 1e-8 ends in solver_failure).
ANGLE = Domain(1e-6, math.pi / 2 - 1e-3, "rad", reason="slopes from 1e-6 to 1000")
# Power-law exponent: κ(n) holds Γ(n/2 + 1), which overflows float64 for n > 341 (n = 400 gives
# e = 8e6); n = 100 keeps a factor 3.
EXPONENT = Domain(1e-3, 100.0, "", reason="κ(n) overflows float64 beyond n = 341")
PREFACTOR = Domain(1e-300, 1e300, "m^(1-n)", reason="float64's range")
MASS = Domain(1e-30, 1e6, "kg", reason="from below an electron to a thousand tonnes")
DENSITY = Domain(1e-3, 1e5, "kg/m³", reason="from below aerogels to above osmium")
MODULUS = Domain(1.0, 1e13, "Pa", reason="from the softest gels to ten times diamond")
DOUBLE_HERTZ_FACTOR = Domain(1e-6, 1e6, "", reason="from DMT (k → 0) to JKR (k → ∞) within float64's reach")
STRESS = Domain(1.0, 1e13, "Pa", reason="up to ten times the modulus of diamond")
VELOCITY = Domain(
    1e-20,
    1e4,
    "m/s",
    zero=True,
    reason="0 for a body dropped by gravity; above 10 km/s an impact is no elastic contact",
)
COUNTERPART_VELOCITY = Domain(
    1e-20,
    1e4,
    "m/s",
    zero=True,
    reason="its speed towards the body, 0 at rest; above 10 km/s an impact is no elastic contact",
)
WORK_OF_ADHESION = Domain(0.0, 1e4, "J/m²", reason="measured works of adhesion lie below 10 J/m²")
# Brilliantov's dissipative constant A is a relaxation time: 1 s is far beyond any solid's.
DISSIPATIVE_CONSTANT = Domain(0.0, 1.0, "s", reason="a relaxation time of at most a second")
DAMPING_COEFFICIENT = Domain(0.0, 1e12, "N s/m", reason="from none to far beyond overdamping any contact")
GRAVITY = Domain(1e-6, 1e4, "m/s²", reason="up to a thousand g")
SPRINGS = Domain(1, 1e9, "", reason="a spring count float64 holds exactly, with room")
RTOL = Domain(1e-16, 0.5, "", reason="from float64's resolution to a loose 50 %")
ATOL = Domain(1e-300, 1.0, "", reason="the scaled state is of order 1")
MAX_STEPS = Domain(16, 1e6, "", reason="a million steps per phase at most")
STEP_BUDGET = Domain(1.0, 1e15, "", reason="a spring array's or Verlet's steps, estimated before the run")
TIME_STEP = Domain(1e-30, 1.0, "s", reason="float64's range of contact times")
DURATION = Domain(1e-30, 1e9, "s", reason="up to thirty years")
# Each bounce allocates four phases of 64 trajectory samples: 1000 bounces hold about 10 MB.
BOUNCES = Domain(1, 1000, "", reason="each bounce allocates its trajectory samples")
POISSON = Domain(-1.0, 0.5, "", open_low=True, open_high=True, reason="a stable isotropic solid")
CYCLES = Domain(1, 100, "", reason="each cycle adds legs to the compiled march")
PEAK = Domain(0.0, 1e6, "N or m", reason="a load of at most a meganewton or a kilometre")
UNLOAD_TO = Domain(-1e6, 1e6, "N or m", reason="as program.peak")
# A viscoelastic medium (effects.viscoelasticity) and the rate-controlled program it is tested by.
RELAXATION_TIME = Domain(
    1e-30, 1e12, "s", reason="from far below any contact time (relaxed) to thirty thousand years (glassy)"
)
# The springs' state is N × (Prony terms) numbers, all updated every step.
VISCOELASTIC_SPRINGS = Domain(1, 1e5, "", reason="every spring is updated every step")
LOADING_RATE = Domain(0.0, 1e9, "m/s or N/s", open_low=True, reason="a test at rate 0 never reaches its peak")
HOLD = Domain(0.0, 1e9, "s", reason="up to thirty years")
