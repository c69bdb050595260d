"""What every renderer of every result type shares, stated once.

- :class:`RenderOptions` and the :class:`Renderer` protocol: a renderer is a pure
  function ``(result, options) -> str``; everything it may know about its
  destination is in the options (never probed inside).
- :func:`escape_markdown` / :func:`escape_html`: text from input files (names,
  paths, reasons) made inert in a pull-request comment or an HTML page.
- :func:`dumps` and :func:`records`: one JSON policy for every document.
- :func:`to_text`: a rich renderable rendered to a string at a fixed width.
- :func:`shorten_names`: long icon lists kept to a few names and a count.
- :data:`SUFFIXES`: which file extensions each format's reports may carry.

Only the standard library and rich (for :func:`to_text`) are imported here, so
every renderer can use it without pulling in the audit or the gate.
"""

from __future__ import annotations

import dataclasses
import html
import json
import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from io import StringIO
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol, TypeVar

if TYPE_CHECKING:
    from rich.console import RenderableType

__all__ = [
    "SUFFIXES",
    "RenderOptions",
    "Renderer",
    "check_suffix",
    "display_path",
    "dumps",
    "escape_html",
    "escape_markdown",
    "records",
    "shorten_names",
    "to_text",
]


@dataclass(frozen=True)
class RenderOptions:
    """What a renderer may know about its destination (never probed inside).

    ``base`` is the folder file paths are shown relative to (the working
    directory, usually the repository root in CI).
    """

    width: int = 100
    color: bool = False
    base: Path | None = None


ResultT_contra = TypeVar("ResultT_contra", contravariant=True)


class Renderer(Protocol[ResultT_contra]):
    """One output format of one result type: a pure function of the result."""

    def __call__(self, result: ResultT_contra, options: RenderOptions, /) -> str:
        """The whole report as text (ends with a newline)."""
        ...


# Report extensions per format value.  An output file whose extension belongs to
# another format (``-f junit -o report.sarif``) is a usage error; an extension
# no format claims (or none) is the user's choice.
SUFFIXES: Mapping[str, tuple[str, ...]] = {
    "table": (".txt",),
    "json": (".json",),
    "junit": (".xml",),
    "sarif": (".sarif", ".json"),  # SARIF 2.1.0 3.2: ".sarif", sometimes ".sarif.json"
    "markdown": (".md", ".markdown"),
    "github": (".txt", ".log"),
}


def check_suffix(fmt: str, path: Path) -> None:
    """Refuse ``path`` for format ``fmt`` when its extension belongs to another format.

    An extension no format claims (or none) is the user's choice.

    >>> check_suffix("sarif", Path("a.sarif.json"))  # SARIF also goes by .json
    >>> check_suffix("junit", Path("a.sarif"))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    alpha_audit.errors.UsageError: a.sarif: has the extension of another format; junit ...
    """
    from alpha_audit.errors import UsageError

    known = {suffix for suffixes in SUFFIXES.values() for suffix in suffixes}
    suffix = path.suffix.lower()
    if suffix in known and suffix not in SUFFIXES[fmt]:
        raise UsageError(
            f"has the extension of another format; {fmt} reports are "
            f"{' or '.join(SUFFIXES[fmt])} (or give a name without one)",
            path=path,
        )


def display_path(path: Path | str | None, base: Path | None) -> str | None:
    """``path`` relative to ``base`` when inside it, in POSIX form; else as given.

    >>> display_path("/repo/icons/a.svg", Path("/repo"))
    'icons/a.svg'
    """
    if path is None:
        return None
    p = Path(path)
    if base is not None and p.is_absolute():
        try:
            return p.relative_to(base).as_posix()
        except ValueError:
            pass
    return p.as_posix()


# ------------------------------------------------------------------ escaping

# What changes meaning inside a GFM table cell: emphasis, code, links, pipes,
# strikethrough (GFM spec 0.29, sections 4.10, 6.1-6.7).
_MARKDOWN_SPECIAL = re.compile(r"([\\`*_\[\]|~])")
# C0/C1 controls, and the bidirectional overrides and isolates (Unicode UAX #9)
# that reorder how a line reads (Trojan Source, CVE-2021-42574).
_CONTROL = re.compile(r"[\x00-\x1f\x7f-\x9f\u061c\u200e\u200f\u202a-\u202e\u2066-\u2069]+")
# GFM autolinks (extension, section 6.9) start at "www." or a scheme's "://";
# an entity there leaves a text GitHub no longer turns into a link.
_AUTOLINK = re.compile(r"(?i)(?<=www)\.|:(?=//)")


def escape_markdown(text: object) -> str:
    """``text`` inert in Markdown (a table cell or a line of a PR comment), on one line.

    HTML is escaped (no ``<img>``, ``<details>``), ``@`` cannot mention anyone,
    punctuation that starts emphasis, code, links or cells is backslash-escaped,
    line breaks, control characters and bidirectional overrides become one
    space, and bare URLs are broken so GitHub does not autolink them.

    >>> escape_markdown("a|b <script> @team\\n*x*")
    'a\\\\|b &lt;script&gt; &#64;team \\\\*x\\\\*'
    >>> escape_markdown("see https://x.io or www.x.io")
    'see https&#58;//x.io or www&#46;x.io'
    """
    s = str(text).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    s = s.replace("@", "&#64;")
    s = _CONTROL.sub(" ", s)
    s = _AUTOLINK.sub(lambda m: "&#58;" if m.group() == ":" else "&#46;", s)
    return _MARKDOWN_SPECIAL.sub(r"\\\1", s).strip()


def escape_html(text: object) -> str:
    """``text`` safe as HTML element content or a quoted attribute value.

    >>> escape_html('<a href="x">')
    '&lt;a href=&quot;x&quot;&gt;'
    """
    return html.escape(str(text), quote=True)


# ------------------------------------------------------------------ JSON

# One policy for every document: NaN and infinities are refused (they are not
# JSON, RFC 8259 section 6), and the text is ASCII, so writing a report can
# never fail on an encoding, whatever a name in an input file holds (a lone
# surrogate is a legal YAML escape).  Parsed, the values are the same either way.
_ENCODER = json.JSONEncoder(ensure_ascii=True, allow_nan=False, separators=(", ", ": "))
_INDENT = "  "


_SCALARS = frozenset({str, int, float, bool, type(None)})


def _flat(value: dict[Any, Any] | list[Any]) -> bool:
    """A dict or list holding only scalars (and lists of scalars): written on one line."""
    items = list(value.values() if isinstance(value, dict) else value)
    if all(map(_SCALARS.__contains__, map(type, items))):  # the common case, at C speed
        return True
    return all(
        not isinstance(v, dict)
        and (not isinstance(v, list) or all(not isinstance(x, dict | list) for x in v))
        for v in items
    )


def _pretty(value: Any, level: int, out: list[str]) -> None:
    if not isinstance(value, dict | list) or not value or (level > 0 and _flat(value)):
        # json's C encoder (used only without indent) for every leaf and flat record:
        # a 5,000-row report costs one C call per row, not the pure-Python encoder.
        out.append(_ENCODER.encode(value))
        return
    pad, inner = _INDENT * level, _INDENT * (level + 1)
    if isinstance(value, dict):
        out.append("{")
        for k, (key, item) in enumerate(value.items()):
            out.append(("," if k else "") + "\n" + inner + _ENCODER.encode(str(key)) + ": ")
            _pretty(item, level + 1, out)
        out.append("\n" + pad + "}")
    else:
        out.append("[")
        for k, item in enumerate(value):
            out.append(("," if k else "") + "\n" + inner)
            _pretty(item, level + 1, out)
        out.append("\n" + pad + "]")


def dumps(document: object) -> str:
    """``document`` as strict JSON text: nested objects indented, flat records on one line.

    Key order is kept; the text ends with a newline.

    >>> print(dumps({"schema": "x/1", "rows": [{"a": 1.5, "b": [1, 2]}]}), end="")
    {
      "schema": "x/1",
      "rows": [
        {"a": 1.5, "b": [1, 2]}
      ]
    }
    """
    out: list[str] = []
    _pretty(document, 0, out)
    return "".join(out) + "\n"


def records(rows: Iterable[Any]) -> list[dict[str, Any]]:
    """Flat dataclass instances as dicts, field by field.

    ``dataclasses.asdict`` deep-copies every value of every row; rows of scalars
    need none of that (a 5,000-row report spent most of its JSON time there).
    """
    out: list[dict[str, Any]] = []
    names: tuple[str, ...] | None = None
    for row in rows:
        if names is None:
            names = tuple(f.name for f in dataclasses.fields(row))
        out.append({n: getattr(row, n) for n in names})
    return out


# ------------------------------------------------------------------ text


def to_text(renderable: RenderableType, options: RenderOptions) -> str:
    """Render at ``options.width`` columns, with or without ANSI colour."""
    from rich.console import Console

    buffer = StringIO()
    console = Console(
        file=buffer,
        width=options.width,
        color_system="truecolor" if options.color else None,
        force_terminal=options.color,
        no_color=not options.color,
        highlight=False,
        emoji=False,
    )
    console.print(renderable)
    return buffer.getvalue()


def shorten_names(names: Sequence[str], limit: int = 3) -> str:
    """``a, b, c`` or ``a, b, c +4 more``: long icon lists stay on one line.

    >>> shorten_names(["a", "b", "c", "d"], 2)
    'a, b +2 more'
    """
    head = ", ".join(names[:limit])
    return head if len(names) <= limit else f"{head} +{len(names) - limit} more"
