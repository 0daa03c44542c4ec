"""Updating equinox modules by field name, reading them as {field name: value}, and choosing between
two of them elementwise."""

import dataclasses
from typing import Any, TypeVar

import equinox as eqx
import jax
import jax.numpy as jnp

Module = TypeVar("Module", bound=eqx.Module)


def replace(module: Module, **changes: Any) -> Module:
    """A copy of `module` with the named fields replaced (no field is ever matched by position)."""
    names = tuple(changes)
    return eqx.tree_at(
        lambda node: tuple(getattr(node, name) for name in names),
        module,
        tuple(changes[name] for name in names),
        is_leaf=lambda leaf: leaf is None,
    )


def fields(module: eqx.Module) -> dict[str, Any]:
    """{field name: value} of a module (a pytree `jax.export` can serialize)."""
    return {field.name: getattr(module, field.name) for field in dataclasses.fields(module)}


def where(condition: Any, when_true: Module, when_false: Module) -> Module:
    """Leaf by leaf, `when_true` where `condition` holds, else `when_false` (same structure)."""
    return jax.tree.map(lambda a, b: jnp.where(condition, a, b), when_true, when_false)


def replace_where(module: Module, condition: Any, **changes: Any) -> Module:
    """A copy of `module` with the named fields set to the given values where `condition`
    holds (an array value cast to its field's dtype; a module, such as a status, leaf by leaf),
    kept elsewhere."""
    kept = {name: getattr(module, name) for name in changes}

    def chosen(value, old):
        if isinstance(old, eqx.Module):
            return where(condition, value, old)
        return jnp.where(condition, jnp.asarray(value, old.dtype), old)

    return replace(module, **{name: chosen(value, kept[name]) for name, value in changes.items()})
