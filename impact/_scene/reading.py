"""Reading the files a user names: text of a bounded size, and YAML with every key once and a
bounded nesting.

PyYAML keeps the last of two equal keys of a mapping silently (`velocity: 0.6` then
`velocity: 60.0` runs at 60) and composes nested collections recursively (20 000 brackets end in
a RecursionError); its aliases can expand a small file into billions of values. Here a key
given twice is refused with both lines, and a document nested deeper than `MAX_DEPTH` or
holding more than `MAX_VALUES` values (aliases expanded) is refused before it is built.
"""

import io
from collections.abc import Callable
from pathlib import Path
from typing import Any

import yaml
from yaml.composer import Composer
from yaml.constructor import SafeConstructor
from yaml.resolver import Resolver

from .errors import SceneError

# The largest YAML file read (bytes): read in about a second; a scene with a tabulated profile of
# the most points it takes (10⁴) is 0.3 MB.
MAX_YAML_BYTES = 2_000_000
# The largest CSV file of a fit's data (bytes): 10⁶ rows of a few columns.
MAX_TABLE_BYTES = 50_000_000
# Levels of mappings and lists (a scene nests 5, a fit file with an inline scene 7).
MAX_DEPTH = 32
# Values of a document, counting every value an alias repeats.
MAX_VALUES = 1_000_000
# What libyaml says of flow collections nested beyond its own bound (1000 levels): it refuses
# them while scanning ahead, before the composer sees `MAX_DEPTH`.
_LIBYAML_TOO_DEEP = "exceeded maximum nesting depth"


def read_text(path: Path, limit: int = MAX_YAML_BYTES) -> str:
    """The text of a file the user named, or SceneError saying why it cannot be read (missing,
    a directory or other non-file, larger than `limit` bytes, unreadable, not UTF-8 text)."""
    if not path.exists():
        raise SceneError([("", f"no such file: {path}")])
    if path.is_dir():
        raise SceneError([("", f"{path} is a directory, not a file")])
    if not path.is_file():
        raise SceneError([("", f"{path} is not a regular file")])
    size = path.stat().st_size
    if size > limit:
        raise SceneError([("", f"{path} holds {size / 1e6:.3g} MB; impact reads files of at most {limit / 1e6:g} MB")])
    try:
        return path.read_text(encoding="utf-8")
    except UnicodeDecodeError as error:
        raise SceneError(
            [("", f"{path} is not UTF-8 text (byte {error.object[error.start]:#04x} at {error.start})")]
        ) from None
    except OSError as error:
        raise SceneError([("", f"cannot read {path}: {error.strerror}")]) from None


def parse_yaml(text: str, source: str) -> Any:
    """The YAML document of `text`, or SceneError naming `source` (a file, an option): invalid
    YAML, a key twice in one mapping, nesting deeper than `MAX_DEPTH`, more than `MAX_VALUES`
    values."""
    stream = io.StringIO(text)
    stream.name = source  # named in PyYAML's messages instead of "<file>"
    loader = _FastLoader(stream) if _FastLoader is not None else _Loader(stream)
    try:
        return loader.get_single_data()
    except _Refused as error:
        raise SceneError([("", f"{source}: {error}")]) from None
    except yaml.MarkedYAMLError as error:
        if error.problem == _LIBYAML_TOO_DEEP and error.problem_mark is not None:  # libyaml's own bound, 1000
            raise SceneError([("", f"{source}: {_too_deep(error.problem_mark.line + 1)}")]) from None
        raise SceneError([("", f"invalid YAML in {source}: {error}")]) from None
    except yaml.YAMLError as error:
        raise SceneError([("", f"invalid YAML in {source}: {error}")]) from None


def _too_deep(line: int) -> str:
    return f"mappings and lists nested deeper than {MAX_DEPTH} levels (line {line})"


def read_yaml(path: str | Path) -> dict:
    """A YAML mapping from a file, or SceneError (missing or too large a file, invalid YAML, not
    a mapping)."""
    path = Path(path)
    data = parse_yaml(read_text(path), str(path))
    if not isinstance(data, dict):
        raise SceneError([("", f"{path} must hold a mapping of scene keys")])
    return data


class _Refused(yaml.YAMLError):
    """A document that is valid YAML but refused: a key twice, too deep, too many values."""


class _Checks(Composer):
    """PyYAML's composer, counting depth and values as it composes and refusing a key that a
    mapping holds twice."""

    peek_event: Callable[[], yaml.Event]  # the parser's, beside it in the loader

    def __init__(self) -> None:  # after the loader's own (which makes the composer's anchors)
        self._depth = 0
        self._values: dict[int, tuple[int, int]] = {}  # id(node) → (values, depth), aliases expanded

    def compose_node(self, parent: yaml.Node | None, index: int) -> yaml.Node | None:
        if self._depth == MAX_DEPTH:
            mark = self.peek_event().start_mark
            raise _Refused(_too_deep(mark.line + 1 if mark is not None else 0))
        self._depth += 1
        try:
            node = super().compose_node(parent, index)
        finally:
            self._depth -= 1
        self._count(node)
        return node

    def compose_mapping_node(self, anchor: Any) -> yaml.MappingNode:
        node = super().compose_mapping_node(anchor)
        seen: dict[tuple[str, str], yaml.ScalarNode] = {}
        for key, _ in node.value:
            if not isinstance(key, yaml.ScalarNode) or key.tag == "tag:yaml.org,2002:merge":
                continue  # merged keys (<<) may be overridden
            earlier = seen.setdefault((key.tag, key.value), key)
            if earlier is not key:
                first, second = earlier.start_mark.line + 1, key.start_mark.line + 1
                where = f"lines {first} and {second}" if first != second else f"twice on line {first}"
                raise _Refused(f"key {key.value!r} appears twice in one mapping ({where}); give each key once")
        return node

    def _count(self, node: yaml.Node | None) -> None:
        """Record the node's values and depth (its children's, aliases expanded); refuse a document
        beyond `MAX_VALUES` values or `MAX_DEPTH` levels once expanded."""
        if node is None or id(node) in self._values:
            return  # an alias of a node counted where it was anchored
        if isinstance(node, yaml.ScalarNode):
            self._values[id(node)] = (1, 0)
            return
        children = node.value if isinstance(node, yaml.SequenceNode) else [n for pair in node.value for n in pair]
        counted = [self._values[id(child)] for child in children]
        values = 1 + sum(count for count, _ in counted)
        depth = 1 + max((level for _, level in counted), default=0)
        line = node.start_mark.line + 1
        if values > MAX_VALUES:
            raise _Refused(f"more than {MAX_VALUES} values, counting those its aliases repeat (line {line})")
        if depth > MAX_DEPTH:
            raise _Refused(f"mappings and lists nested deeper than {MAX_DEPTH} levels through aliases (line {line})")
        self._values[id(node)] = (values, depth)


class _Loader(_Checks, yaml.SafeLoader):
    """The safe loader with `_Checks`, in Python."""

    def __init__(self, stream: io.StringIO):
        yaml.SafeLoader.__init__(self, stream)
        _Checks.__init__(self)


def _fast_loader() -> type | None:
    """The safe loader with `_Checks` on libyaml's parser (several times faster than PyYAML's),
    where PyYAML was built with it; None otherwise."""
    if not yaml.__with_libyaml__:
        return None
    from yaml._yaml import CParser  # libyaml's parser (yaml.cyaml's stubs do not export it)

    class FastLoader(_Checks, CParser, SafeConstructor, Resolver):
        def __init__(self, stream: io.StringIO):
            CParser.__init__(self, stream)
            Composer.__init__(self)  # the composer in Python (its checks), not libyaml's
            SafeConstructor.__init__(self)
            Resolver.__init__(self)
            _Checks.__init__(self)

    return FastLoader


_FastLoader = _fast_loader()
