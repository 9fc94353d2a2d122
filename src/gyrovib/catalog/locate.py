"""Where a value is in a catalogue file: a path such as ``("sensors", 3, "id")``
to its line and column.

The file is composed into a node tree once, on the first question, and the
tree is kept: every later path costs only its own steps (a list index is
direct; a mapping's keys are indexed once per mapping). Locating N paths is
therefore linear in the file plus N, whatever N is.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import yaml

from gyrovib.catalog.dialect import Loader

_MERGE = "tag:yaml.org,2002:merge"


def _compose(text: str) -> Any:
    """The node tree of ``text`` (None when it cannot be composed)."""
    try:
        return yaml.compose(text, Loader=Loader)
    except (yaml.YAMLError, RecursionError):
        return None


def _flat_pairs(node: Any, depth: int = 0) -> list[tuple[Any, Any]]:
    """A mapping's key/value node pairs with ``<<`` merges expanded (merged first)."""
    pairs: list[tuple[Any, Any]] = []
    own: list[tuple[Any, Any]] = []
    for key_node, value_node in node.value:
        if key_node.tag == _MERGE and depth < 8:
            merged = value_node.value if isinstance(value_node, yaml.SequenceNode) else [value_node]
            for m in merged:
                if isinstance(m, yaml.MappingNode):
                    pairs.extend(_flat_pairs(m, depth + 1))
        else:
            own.append((key_node, value_node))
    return pairs + own


class Index:
    """Lines and columns of the values of one YAML text, composed once."""

    def __init__(self, text: str) -> None:
        self._text: str | None = text
        self._root: Any = None
        self._keys: dict[int, dict[str, tuple[Any, Any]]] = {}

    @property
    def root(self) -> Any:
        if self._text is not None:
            self._root = _compose(self._text)
            self._text = None
        return self._root

    def _mapping(self, node: Any) -> dict[str, tuple[Any, Any]]:
        keys = self._keys.get(id(node))
        if keys is None:
            keys = {}
            for key_node, value_node in _flat_pairs(node):  # later keys win, as in YAML
                if isinstance(key_node, yaml.ScalarNode):
                    keys[key_node.value] = (key_node, value_node)
            self._keys[id(node)] = keys
        return keys

    def find(self, path: Sequence[Any], want_key: bool = False
             ) -> tuple[Any, tuple[int, int] | None]:
        """The node at ``path`` and its (line, column), 1-based.

        Where the path leaves the document (a missing key), the deepest node
        reached is returned. With ``want_key`` the last step gives the key's place.
        """
        node = self.root
        if node is None:
            return None, None
        mark = node.start_mark
        for i, part in enumerate(path):
            if isinstance(node, yaml.MappingNode):
                found = self._mapping(node).get(str(part))
                if found is None:
                    break
                key_node, node = found
                last = i == len(path) - 1
                mark = key_node.start_mark if (last and want_key) else node.start_mark
            elif isinstance(node, yaml.SequenceNode) and isinstance(part, int) \
                    and 0 <= part < len(node.value):
                node = node.value[part]
                mark = node.start_mark
            else:
                break
        return node, (mark.line + 1, mark.column + 1)

    def place(self, path: Sequence[Any], want_key: bool = False) -> tuple[int, int] | None:
        return self.find(path, want_key)[1]

    def scalar(self, path: Sequence[Any]) -> str | None:
        """The text of the scalar at ``path`` as written (``1e400``, ``.nan``)."""
        node = self.find(path)[0]
        return node.value if isinstance(node, yaml.ScalarNode) else None

