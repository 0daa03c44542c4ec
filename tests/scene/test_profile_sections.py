"""The profile section (`body.profile`, the union `ProfileSpec`): numbers as YAML writes them, each
shape's refusals by field and in words, every field documented. (Each shape's section builds its
profile: tests/profiles/test_profiles.py.)"""

import pytest
from pydantic import TypeAdapter, ValidationError

from impact._scene import profiles as ps

SPEC = TypeAdapter(ps.ProfileSpec)


def test_schema_number_coercion():
    assert SPEC.validate_python({"shape": "paraboloid", "R": "1e-3"}).R == 1e-3
    assert SPEC.validate_python({"shape": "power_law", "n": 2, "c": " 5e2 "}).n == 2.0
    assert SPEC.validate_python({"shape": "tabulated", "r": [0, "1e-4"], "f": ["0", 1e-6]}).r == [0.0, 1e-4]


@pytest.mark.parametrize(
    "data, field, message",
    [
        ({"shape": "paraboloid", "R": 0}, "R", "0 m is outside the allowed range [1e-12, 1000] m"),
        ({"shape": "sphere", "R": -1e-3}, "R", "-0.001 m is outside the allowed range"),
        ({"shape": "ellipsoid", "R": 1e-3, "k": 0}, "k", "0 1/m is outside the allowed range [0.001, 1e12] 1/m"),
        ({"shape": "flat_punch", "radius": "-1e-4"}, "radius", "-0.0001 m is outside the allowed range"),
        ({"shape": "capped_cone", "b": 0, "theta": 0.3}, "b", "0 m is outside the allowed range"),
        ({"shape": "wavy_paraboloid", "R": 1e-3, "amplitude": 1e-6, "wavelength": 0}, "wavelength", "0 m is outside"),
        ({"shape": "power_law", "n": 2, "c": 0}, "c", "0 m^(1-n) is outside the allowed range [1e-300, 1e300]"),
        ({"shape": "power_law", "n": 0, "c": 1.0}, "n", "0 is outside the allowed range [0.001, 100]"),
        (
            {"shape": "wavy_paraboloid", "R": 1e-3, "amplitude": -1e-8, "wavelength": 1e-5},
            "amplitude",
            "-1e-08 m is outside the allowed range [0, 1000] m",
        ),
        ({"shape": "cone", "theta": 0}, "theta", "0 rad is outside the allowed range [1e-6, 1.5698] rad"),
        ({"shape": "truncated_cone", "b": 1e-4, "theta": 1.6}, "theta", "1.6 rad is outside the allowed range"),
        ({"shape": "paraboloid", "R": "one"}, "R", "expected a number such as 1e-3, got the string 'one'"),
        ({"shape": "paraboloid", "R": True}, "R", "expected a number"),
        ({"shape": "paraboloid", "R": "inf"}, "R", "finite number"),
        ({"shape": "capped_paraboloid", "b": 1e-4, "R1": 1e-3, "R2": 2e-3}, "R1", "cap radius R1 >= base radius R2"),
        ({"shape": "tabulated", "r": [0.0], "f": [0.0]}, "r", "tabulated r needs at least 2 points"),
        ({"shape": "tabulated", "r": [0, 2e-4, 1e-4], "f": [0, 1, 2]}, "r", "tabulated r must be strictly increasing"),
        ({"shape": "tabulated", "r": [1e-5, 1e-4], "f": [0, 1e-6]}, "r", "tabulated r must start at r = 0"),
        ({"shape": "tabulated", "r": [0, 1e-4], "f": [1e-7, 1e-6]}, "f", "tabulated f must start at 0 at r = 0"),
        ({"shape": "tabulated", "r": [0, 1e-4, 2e-4], "f": [0, 1e-6]}, "f", "r and f must have the same length"),
        ({"shape": "paraboloid", "R": 1e-3, "radius": 1}, "radius", "Extra inputs are not permitted"),
        ({"shape": "cylinder", "R": 1e-3}, "shape", "does not match any of the expected tags"),
    ],
)
def test_schema_rejects(data, field, message):
    with pytest.raises(ValidationError) as err:
        SPEC.validate_python(data)
    assert field in str(err.value) and message in str(err.value)


def test_schema_fields_documented():
    for spec in (getattr(ps, n) for n in ps.__all__ if n != "ProfileSpec"):
        for name, field in spec.model_fields.items():
            assert name == "shape" or field.description, (spec.__name__, name)
