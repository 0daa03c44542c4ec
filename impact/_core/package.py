"""The installed distribution: its name on the package index and its version."""

from importlib import metadata

DISTRIBUTION = "impact-mdr"  # the import name and the command stay `impact`
__version__ = metadata.version(DISTRIBUTION)
