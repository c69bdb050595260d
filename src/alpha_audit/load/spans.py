"""Exact source spans of scalar values, for fixes that rewrite them in place.

Loaders know where a value starts and ends as character offsets into the
text they parsed; :class:`LineIndex` turns offsets into the 1-based lines and
code-point columns of a :class:`~alpha_audit.model.Span` (SARIF 2.1.0 3.30:
a line ends at ``\\n``, which also ends ``\\r\\n``, the default
``newlineSequences``).  Loaders drop a leading byte-order mark before parsing
and say so (``bom=True``), so that columns on line 1 count it as the file does.
"""

from __future__ import annotations

import bisect
import re
from pathlib import Path

from alpha_audit.model import Span, Syntax

__all__ = ["LineIndex"]

_NEWLINE = re.compile("\n")


class LineIndex:
    """Offsets to (line, column) for one text, by bisecting its line starts.

    >>> index = LineIndex("a: 1\\r\\nb: 'x'\\n", Path("m.yaml"), "yaml")
    >>> span = index.span(9, 12)
    >>> span.text, span.start_line, span.start_column, span.end_column
    ("'x'", 2, 4, 7)
    """

    def __init__(self, text: str, path: Path, syntax: Syntax, *, bom: bool = False) -> None:
        self.text = text
        self.path = path
        self.syntax = syntax
        # The file began with a byte-order mark that ``text`` no longer holds: it is
        # still a code point of line 1 in the file, which SARIF columns count.
        self.bom = bom
        self.starts = [0] + [m.end() for m in _NEWLINE.finditer(text)]

    def position(self, offset: int) -> tuple[int, int]:
        """1-based (line, column) of the character at ``offset``."""
        line = bisect.bisect_right(self.starts, offset)
        return line, offset - self.starts[line - 1] + 1 + (self.bom and line == 1)

    def span(self, start: int, end: int) -> Span:
        """The span of ``text[start:end]``; ``end`` is exclusive."""
        start_line, start_column = self.position(start)
        end_line, end_column = self.position(end)
        return Span(
            self.path,
            start_line,
            start_column,
            end_line,
            end_column,
            self.text[start:end],
            self.syntax,
        )
