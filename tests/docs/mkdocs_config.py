"""The site's configuration as the docs tests read it."""

from pathlib import Path

import yaml


class _ConfigLoader(yaml.SafeLoader):
    """YAML of mkdocs.yml: its tags (`!relative`, `!!python/name:`) name mkdocs objects, whose values
    the tests do not need (read as None)."""


_ConfigLoader.add_multi_constructor("!", lambda loader, suffix, node: None)
_ConfigLoader.add_multi_constructor("tag:yaml.org,2002:python/", lambda loader, suffix, node: None)


def mkdocs_config(path: Path) -> dict:
    """The mapping of docs/mkdocs.yml."""
    return yaml.load(path.read_text(), Loader=_ConfigLoader)
