"""The adhesion models a scene may name (`effects.adhesion.model`), one module each, and their
union: `AdhesionSpec`, discriminated by `model` ('jkr' where it is left out)."""

from typing import Annotated, Any, get_args

from pydantic import Discriminator, Tag

from .base import AbstractAdhesion
from .greenwood_johnson import GreenwoodJohnsonAdhesion
from .jkr import JKRAdhesion
from .maugis_dugdale import MaugisDugdaleAdhesion

_DEFAULT = "jkr"


def _model_of(data: Any) -> Any:
    """The model a section names: its `model` key, 'jkr' where it has none."""
    if isinstance(data, dict):
        return data.get("model", _DEFAULT)
    return getattr(data, "model", _DEFAULT)


AdhesionSpec = Annotated[
    Annotated[JKRAdhesion, Tag("jkr")]
    | Annotated[MaugisDugdaleAdhesion, Tag("maugis_dugdale")]
    | Annotated[GreenwoodJohnsonAdhesion, Tag("greenwood_johnson")],
    Discriminator(_model_of),
]


def _tags(union: Any) -> tuple[str, ...]:
    """The tags of a tagged union's members, in order."""
    members = get_args(get_args(union)[0])
    return tuple(next(tag.tag for tag in get_args(member)[1:] if isinstance(tag, Tag)) for member in members)


MODEL_NAMES = _tags(AdhesionSpec)  # every model a scene may name

__all__ = [
    "MODEL_NAMES",
    "AbstractAdhesion",
    "AdhesionSpec",
    "GreenwoodJohnsonAdhesion",
    "JKRAdhesion",
    "MaugisDugdaleAdhesion",
]
