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

Only the standard library, :mod:`alpha_audit.safe_text` (the one name policy,
which every escaper here starts from) and rich (for :func:`to_text`) are
imported here, so every renderer can use it without pulling in the audit or the
gate.
"""

from __future__ import annotations

import dataclasses
import hashlib
import html
import json
import os
import re
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from io import StringIO
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal, Protocol, TypeVar

from alpha_audit.safe_text import escape_char, safe_text

if TYPE_CHECKING:
    from rich.console import Console, ConsoleOptions, RenderableType
    from rich.segment import Segment
    from rich.table import Table

    from alpha_audit.findings import Finding
    from alpha_audit.gate import GateResult
    from alpha_audit.model import GamutAdjustment, Location
    from alpha_audit.policy import Policy
    from alpha_audit.results import CheckReport, ColorFix, Fix, SafeAlpha

__all__ = [
    "COMMENT_LIMIT",
    "SUFFIXES",
    "EncodedRecords",
    "Records",
    "RenderOptions",
    "Renderer",
    "baselined_text",
    "check_suffix",
    "digest",
    "display_path",
    "dumps",
    "escape_html",
    "escape_markdown",
    "finding_fix",
    "fitted_table",
    "fix_text",
    "fix_to_dict",
    "gamut_line",
    "json_text",
    "location_text",
    "location_to_dict",
    "name_column",
    "names_and",
    "number_column",
    "policy_limits",
    "records",
    "safe_span",
    "shorten_names",
    "stale_text",
    "to_text",
    "where_text",
    "wrap_name",
    "xml_safe",
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


# GitHub refuses issue and pull-request comments longer than 65,536 characters
# (REST API "Create an issue comment": "body is too long (maximum is 65536
# characters)").  The job summary allows 1 MiB, so one text fits both.
COMMENT_LIMIT = 65_536

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
    "gitlab": (".json",),  # GitLab's artifact is gl-code-quality-report.json
    "html": (".html", ".htm"),
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


def gamut_line(note: GamutAdjustment, base: Path | None) -> str:
    """One colour the gamut policy moved, as one line (table and markdown share it).

    Names file and line, the key or token path, the colour before and after,
    the policy and the CIEDE2000 between before and after.
    """
    where = display_path(note.file, base) or "?"
    if note.line:
        where += f":{note.line}"
    owner = f" ({note.mode})" if note.mode else ""
    return (
        f"{where} {note.token}{owner}: {note.text} → {note.output} "
        f"({note.policy}, CIEDE2000 {note.delta_e:.2f})"
    )


def display_path(path: Path | str | None, base: Path | None) -> str | None:
    """``path`` relative to ``base`` when inside it, in POSIX form; else as given.

    >>> display_path("/repo/icons/a.svg", Path("/repo"))
    'icons/a.svg'
    """
    if path is None:
        return None
    p = Path(path)
    if base is not None:
        # A relative path is relative to where the files were opened from, this
        # process's folder; base may be above it (the repository root).
        full = p if p.is_absolute() else Path(os.path.abspath(p))
        try:
            return full.relative_to(base).as_posix()
        except ValueError:
            pass
    return p.as_posix()


# ------------------------------------------------------------------ escaping

# What changes meaning inside a GFM table cell: emphasis, code, links, pipes,
# strikethrough (GFM spec 0.29, sections 4.10, 6.1-6.7).
_MARKDOWN_SPECIAL = re.compile(r"([\\`*_\[\]|~])")
# What ends a line or a table row to Markdown or to a browser (CommonMark 0.30,
# "line ending"; the Unicode line and paragraph separators, NEL).
_LINE_BREAK = re.compile("[\r\n\t\x0b\x0c\x85\u2028\u2029]+")
# GFM autolinks (extension, section 6.9) start at "www." or a scheme's "://";
# an entity there leaves a text GitHub no longer turns into a link.
_AUTOLINK = re.compile(r"(?i)(?<=www)\.|:(?=//)")
# Characters outside XML 1.0's Char production (https://www.w3.org/TR/xml/#charsets):
# what is left of them after safe_text (U+FFFE, U+FFFF) would make the file unparsable.
_XML_INVALID = re.compile("[^\t\n\r\x20-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]")


def escape_markdown(text: object) -> str:
    """``text`` inert in Markdown (a table cell or a line of a PR comment), on one line.

    HTML is escaped (no ``<img>``, ``<details>``), ``@`` cannot mention anyone,
    punctuation that starts emphasis, code, links or cells is backslash-escaped,
    line breaks become one space, other control, bidi and invisible format
    characters are shown as escapes (:func:`~alpha_audit.safe_text.safe_text`),
    and bare URLs are broken so GitHub does not autolink them.

    >>> escape_markdown("a|b <script> @team\\n*x*")
    'a\\\\|b &lt;script&gt; &#64;team \\\\*x\\\\*'
    >>> escape_markdown("see https://x.io or www.x.io")
    'see https&#58;//x.io or www&#46;x.io'
    >>> escape_markdown("evil\\u202e")
    'evil\\\\\\\\u202e'
    """
    s = safe_text(_LINE_BREAK.sub(" ", str(text)))
    s = s.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    s = s.replace("@", "&#64;")
    s = _AUTOLINK.sub(lambda m: "&#58;" if m.group() == ":" else "&#46;", s)
    return _MARKDOWN_SPECIAL.sub(r"\\\1", s).strip()


def escape_html(text: object) -> str:
    """``text`` safe as HTML element content or a quoted attribute value.

    >>> escape_html('<a href="x">')
    '&lt;a href=&quot;x&quot;&gt;'
    """
    return html.escape(safe_text(text), quote=True)  # a newline too: a page is printed to CI logs


def xml_safe(text: object) -> str:
    """``text`` as a string XML 1.0 carries, every unsafe character shown as an escape.

    Controls, bidi and invisible format characters and lone surrogates become
    escapes (:func:`~alpha_audit.safe_text.safe_text`; a newline is kept), and
    the non-characters XML forbids too, so the document always parses.

    >>> xml_safe("bell\\x07 and\\x1b[31m escape\\ufffe")
    'bell\\\\x07 and\\\\x1b[31m escape\\\\ufffe'
    """
    s = safe_text(text, newlines=True)
    return _XML_INVALID.sub(lambda m: escape_char(m.group()), s)


def digest(text: str) -> str:
    """A stable 32-hex-digit fingerprint of ``text`` (lone surrogates included).

    >>> digest("a") == digest("a") != digest("\\ud800")
    True
    """
    return hashlib.sha256(text.encode("utf-8", "surrogatepass")).hexdigest()[:32]


# ------------------------------------------------------------------ JSON

# One policy for every document: NaN and infinities are refused (they are not
# JSON, RFC 8259 section 6), and the text is ASCII, so writing a report can
# never fail on an encoding, whatever a name in an input file holds (a lone
# surrogate is a legal YAML escape).  Parsed, the values are the same either way.
_ENCODER = json.JSONEncoder(ensure_ascii=True, allow_nan=False, separators=(", ", ": "))
_INDENT = "  "


_SCALARS = frozenset({str, int, float, bool, type(None)})


def _flat(value: dict[Any, Any] | list[Any]) -> bool:
    """A record written on one line: scalars, lists of scalars and records of those.

    A list of objects or lists (rows, audits) is what gets indented; a row's
    own small objects (a paint row's ``sizes``) stay on the row's line.
    """
    items = list(value.values() if isinstance(value, dict) else value)
    if all(map(_SCALARS.__contains__, map(type, items))):  # the common case, at C speed
        return True
    for v in items:
        if isinstance(v, list):
            if not all(map(_SCALARS.__contains__, map(type, v))):
                return False
        elif isinstance(v, dict) and not _flat(v):
            return False
    return isinstance(value, dict)


class Records(list[dict[str, Any]]):
    """Rows known to be flat records: :func:`dumps` writes each on one line unchecked.

    A report's rows are built flat by construction; proving it row by row
    (:func:`_flat`) cost more than encoding them.
    """


class EncodedRecords(list[str]):
    """Flat records already encoded, each as :func:`json_text` writes it: :func:`dumps`
    writes each on one line as it is (a writer of many rows encodes them column by column)."""


def json_text(value: object) -> str:
    """``value`` as strict JSON on one line, as :func:`dumps` writes a flat record.

    >>> print(json_text({"a": [1.5, None], "b": "é"}))
    {"a": [1.5, null], "b": "\\u00e9"}
    """
    return _ENCODER.encode(value)


def _pretty(value: Any, level: int, out: list[str]) -> None:
    if isinstance(value, Records | EncodedRecords) and value:
        pad, inner = _INDENT * level, _INDENT * (level + 1)
        lines = value if isinstance(value, EncodedRecords) else map(_ENCODER.encode, value)
        out.append("[\n" + inner + (",\n" + inner).join(lines) + "\n" + pad + "]")
        return
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


def records(rows: Iterable[Any]) -> Records:
    """Flat dataclass instances as dicts, field by field.

    ``dataclasses.asdict`` deep-copies every value of every row; rows of scalars
    need none of that (a 5,000-row report spent most of its JSON time there).
    """
    out = Records()
    names: tuple[str, ...] | None = None
    for row in rows:
        if names is None:
            names = tuple(f.name for f in dataclasses.fields(row))
        out.append({n: getattr(row, n) for n in names})
    return out


# The policy's limits, in the order every JSON document writes them.
_LIMITS = (
    "max_loss",
    "min_delta_e",
    "max_drift",
    "min_size_contrast",
    "visibility_floor",
    "loss_tolerance",
    "near_duplicate_delta_e",
)


def policy_limits(policy: Policy) -> dict[str, float | None]:
    """The policy's numeric limits as JSON data (check's and suggest's documents)."""
    return {name: getattr(policy, name) for name in _LIMITS}


# ------------------------------------------------------------------ text


class _Inert:
    """A renderable whose text reaches the terminal with no instruction character.

    Every segment rich lays out is passed through
    :func:`~alpha_audit.safe_text.safe_text` (line ends kept): whatever a
    renderer forgot to escape -- ESC, C1, bidi controls, a lone surrogate in a
    name built by a library caller -- is shown as an escape, never sent.
    Colour is in the segments' styles, written by rich afterwards, so it stays.
    """

    def __init__(self, inner: RenderableType) -> None:
        self.inner = inner

    def __rich_console__(self, console: Console, options: ConsoleOptions) -> Iterator[Segment]:
        from rich.segment import Segment

        for segment in console.render(self.inner, options):
            shown = segment.text if segment.control else safe_text(segment.text, newlines=True)
            yield segment if shown == segment.text else Segment(shown, segment.style)


def to_text(renderable: RenderableType, options: RenderOptions) -> str:
    """Render at ``options.width`` columns, with or without ANSI colour (text made inert)."""
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
    console.print(_Inert(renderable))
    return buffer.getvalue()


def shorten_names(names: Sequence[str], limit: int = 3) -> str:
    """``a, b, c`` or ``a, b, c +4 more``: long icon lists stay on one line.

    >>> shorten_names(["a", "b", "c", "d"], 2)
    'a, b +2 more'
    """
    head = ", ".join(names[:limit])
    return head if len(names) <= limit else f"{head} +{len(names) - limit} more"


@dataclass(frozen=True)
class TableColumn:
    """One column of a :func:`fitted_table`: a number (never cut) or a name (folds).

    ``min_width`` is how narrow a name column may fold (9 keeps ``■ #rrggbb``
    whole); a number column is always as wide as its widest cell.
    """

    header: str
    number: bool
    justify: Literal["left", "right"] = "left"
    min_width: int = 1
    shrink_first: bool = False


def number_column(header: str, justify: Literal["left", "right"] = "right") -> TableColumn:
    """A column of figures (contrast, gain, alpha, hex, counts): never cut, never wrapped."""
    return TableColumn(header, True, justify)


def name_column(header: str, min_width: int = 1, *, shrink_first: bool = False) -> TableColumn:
    """A column of names from input files: wraps after spaces and separators, folds long words.

    ``shrink_first`` marks a column that gives way before the others (an icon
    list), so the row's key (a canvas name) keeps its line.
    """
    return TableColumn(header, False, "left", min_width, shrink_first)


# Where a name may break besides a space: after a separator, so
# "surface-container-lowest" wraps as "surface-container-" / "lowest".
_BREAK_AFTER = re.compile(r"[\s\-_/.:]+")


def wrap_name(text: str, width: int) -> list[str]:
    """``text`` in lines of at most ``width`` cells, broken after spaces and separators.

    A piece longer than ``width`` is folded; nothing is ever dropped.

    >>> wrap_name("surface-container-lowest", 19)
    ['surface-container-', 'lowest']
    >>> wrap_name("abcdef", 4)
    ['abcd', 'ef']
    """
    from rich.cells import cell_len

    width = max(width, 1)
    pieces, start = [], 0
    for match in _BREAK_AFTER.finditer(text):
        pieces.append(text[start : match.end()])
        start = match.end()
    if start < len(text):
        pieces.append(text[start:])
    lines: list[str] = []
    line = ""
    for piece in pieces:
        if line and cell_len((line + piece).rstrip()) > width:
            lines.append(line.rstrip())
            line = ""
        while cell_len(piece.rstrip()) > width:  # longer than a line: fold it
            cut = width
            while cell_len(piece[:cut]) > width:
                cut -= 1
            lines.append(piece[:cut])
            piece = piece[cut:]
        line += piece
    if line.strip() or not lines:
        lines.append(line.rstrip())
    return lines


class _Name:
    """A cell that wraps after spaces and separators at whatever width rich gives it."""

    def __init__(self, text: Any, min_width: int) -> None:
        from rich.text import Text

        self.text = text if isinstance(text, Text) else Text(str(text))
        self.min_width = min_width

    def __rich_measure__(self, console: Any, options: Any) -> Any:
        from rich.cells import cell_len
        from rich.measure import Measurement

        full = cell_len(self.text.plain)
        return Measurement(min(full, self.min_width), full)

    def __rich_console__(self, console: Any, options: Any) -> Any:
        from rich.text import Text

        plain, offset = self.text.plain, 0
        for line in wrap_name(plain, options.max_width):
            start = plain.index(line, offset) if line else offset
            yield self.text[start : start + len(line)] if line else Text("")
            offset = start + len(line)


class _Fitted:
    """A table whose ``shrink_first`` name columns give way before the other names.

    Rich narrows the widest wrapping column first, so a long canvas name wrapped
    while an icon list beside it kept its line.  At render time (rich's public
    console protocol) this measures the table; if it is wider than the space
    given, the ``shrink_first`` columns get a ``max_width`` (a public column
    setting) that takes the excess from them first, down to their minimum, and
    rich shares out whatever is left as usual.
    """

    def __init__(self, build: Any, donors: list[int], floors: list[int]) -> None:
        self.build, self.donors, self.floors = build, donors, floors

    def __rich_measure__(self, console: Any, options: Any) -> Any:
        from rich.measure import Measurement

        return Measurement.get(console, options, self.build({}))

    def __rich_console__(self, console: Any, options: Any) -> Any:
        from rich.measure import Measurement

        table = self.build({})
        if self.donors:
            widest = Measurement.get(console, options.update(width=1 << 16), table).maximum
            excess = widest - options.max_width
            limits: dict[int, int] = {}
            for k, floor in zip(self.donors, self.floors, strict=True):
                if excess <= 0:
                    break
                own = self._natural(console, options, table, k)
                give = min(excess, max(own - floor, 0))
                limits[k] = own - give
                excess -= give
            if limits:
                table = self.build(limits)
        yield table

    @staticmethod
    def _natural(console: Any, options: Any, table: Table, k: int) -> int:
        """The widest cell of column ``k`` (its header included), in cells."""
        from rich.measure import Measurement

        wide = options.update(width=1 << 16)
        column = table.columns[k]
        return max(
            Measurement.get(console, wide, cell).maximum for cell in [column.header, *column.cells]
        )


def fitted_table(
    columns: Sequence[TableColumn],
    rows: Iterable[Sequence[Any]],
    *,
    section_ends: frozenset[int] = frozenset(),
    **table_options: Any,
) -> RenderableType:
    """A rich table that gives way in its name columns only.

    Rich shares out a too-narrow width by shrinking wrapping columns first and
    then, as a last resort, every column with an ellipsis, which is how a hex
    code became ``#10b9…``.  Here figures are ``no_wrap`` with a minimum width
    of their widest cell (so they are never shrunk) and names fold, so at any
    width where the figures fit, every figure is printed whole; ``shrink_first``
    names give way before the other names (:class:`_Fitted`).  Cells that are
    strings become literal :class:`~rich.text.Text` (names are never markup).
    A rule is drawn under the rows whose index is in ``section_ends``.  Unless
    told, a rule under the header, no padding at the edges, one space between
    columns and a title on the left.
    """
    from rich import box
    from rich.cells import cell_len
    from rich.table import Table
    from rich.text import Text

    body = [[c if isinstance(c, Text) else Text(str(c)) for c in row] for row in rows]
    table_options = {
        "box": box.SIMPLE_HEAD,
        "pad_edge": False,
        "padding": (0, 1, 0, 0),
        "title_justify": "left",
        **table_options,
    }

    def build(limits: dict[int, int]) -> Table:
        table = Table(**table_options)
        for k, column in enumerate(columns):
            if column.number:
                widest = max((cell_len(row[k].plain) for row in body if k < len(row)), default=1)
                table.add_column(
                    column.header,
                    justify=column.justify,
                    no_wrap=True,
                    min_width=max(widest, cell_len(column.header)),
                )
            else:
                table.add_column(
                    column.header,
                    justify=column.justify,
                    overflow="fold",
                    min_width=column.min_width,
                    max_width=limits.get(k),
                )
        for n, row in enumerate(body):
            table.add_row(
                *(
                    cell
                    if k >= len(columns) or columns[k].number
                    else _Name(cell, columns[k].min_width)
                    for k, cell in enumerate(row)
                ),
                end_section=n in section_ends,
            )
        return table

    donors = [k for k, c in enumerate(columns) if c.shrink_first]
    return _Fitted(build, donors, [columns[k].min_width for k in donors])


# ------------------------------------------------------------------ where


def where_text(finding: Finding, names: int = 3) -> str:
    """The icons and canvases of a finding: ``alert on paper`` or ``alert on paper and 8 more``.

    A finding folded over canvases names its worst canvas first; a finding
    about icons, not canvases, names only the icons.
    """
    icons = shorten_names(list(finding.icons), names)
    if finding.canvas is None:
        return icons
    others = len(finding.canvases) - 1
    if others <= 0:
        return f"{icons} on {finding.canvas}"
    return f"{icons} on {finding.canvas} (worst) and {others} more canvas{'es' * (others > 1)}"


def baselined_text(gate: GateResult) -> str:
    """Why a baselined finding does not fail: a baseline file, or the base revision.

    >>> from alpha_audit.gate import Baseline, GateResult
    >>> from alpha_audit.policy import Policy
    >>> baselined_text(GateResult(Policy(), (), baseline=Baseline(kind="base", name="main")))
    'already on the base revision main'
    """
    if gate.on_base and gate.baseline is not None:
        return f"already on the base revision {gate.baseline.name}"
    return "in the baseline"


def stale_text(gate: GateResult) -> str:
    """What the gate's stale baseline entries mean: fixed on the base revision, or gone.

    >>> from alpha_audit.gate import GateResult
    >>> from alpha_audit.policy import Policy
    >>> stale_text(GateResult(Policy(), (), stale=(("t", "s", "loss", ("a",)),)))
    '1 baseline entry no longer occurs'
    """
    n = len(gate.stale)
    if gate.on_base:
        return f"{n} root cause(s) of the base revision fixed by this change"
    return f"{n} baseline {'entry no longer occurs' if n == 1 else 'entries no longer occur'}"


def location_to_dict(location: Location, base: Path | None = None) -> dict[str, Any]:
    """A location as JSON data: file (relative to ``base``), line, column (where the value's
    exact place is known, else null) and what it sets."""
    span = location.span
    return {
        "file": display_path(location.file, base),
        "line": location.line,
        "column": span.start_column if span is not None else None,
        "what": location.what,
    }


def location_text(location: Location, base: Path | None) -> str:
    """``file:line`` of a location, the file relative to ``base`` where inside it.

    >>> from alpha_audit.model import Location
    >>> location_text(Location(Path("/r/set.yaml"), 12, "alpha"), Path("/r"))
    'set.yaml:12'
    """
    return f"{display_path(location.file, base)}:{location.line}"


# ------------------------------------------------------------------ fixes in words


def safe_span(alpha: float) -> str:
    """A largest safe alpha as the range it guarantees, ``[1, alpha]``.

    Not "at most": a colour failing at 0.9 would be sent nowhere ("at most 2").

    >>> safe_span(1.178), safe_span(1.0)
    ('alpha 1 to 1.178', 'alpha 1')
    """
    return "alpha 1" if alpha <= 1.0 else f"alpha 1 to {alpha:g}"


def _page_fix_text(fix: ColorFix, opacity: float) -> str:
    """A CSS paint's fix on its measured backdrop: a higher opacity, or a colour."""
    options = []
    reach = fix.reach.alpha
    if reach is not None and opacity < 1.0:
        options.append(f"opacity {reach * opacity:.4g} or above (now {opacity:g})")
    if fix.nearest is not None and fix.nearest.delta_e > 0:
        at = f" at opacity {opacity:g}" if opacity < 1.0 else ""
        options.append(f"colour {fix.nearest.color}{at} (CIEDE2000 {fix.nearest.delta_e:.2f} away)")
    if not options:
        return f"{fix.color}: no colour of its hue passes on {fix.canvas}; change the hue"
    return f"{fix.color}: {' or '.join(options)}"


def _color_fix_text(fix: ColorFix) -> str:
    if fix.opacity is not None:
        return _page_fix_text(fix, fix.opacity)
    from alpha_audit.rules import RULES, Family

    contrast = any(RULES[r].family is Family.CONTRAST for r in fix.rules)
    options = []
    safe = fix.largest_safe.alpha
    if safe is not None:
        with_ = f" together with {names_and(fix.together)}" if fix.together else ""
        options.append(safe_span(safe) + with_)
    # Reaching the threshold at 1 itself is already inside that range.
    reach = fix.reach.alpha
    if contrast and reach is not None and not (safe is not None and reach <= 1.0):
        options.append(f"alpha {reach:g} or above (every {fix.mode} canvas)")
    if contrast and fix.nearest is not None and fix.nearest.delta_e > 0:
        near = fix.nearest
        options.append(f"colour {near.color} (CIEDE2000 {near.delta_e:.2f} away)")
    if not options and fix.held:  # alpha 1 itself may pass: name what holds it
        one = len(fix.held) == 1
        return (
            f"{fix.color}: no alpha from 1 is safe while {names_and(fix.held[:3])}"
            f"{f' +{len(fix.held) - 3} more' if len(fix.held) > 3 else ''} "
            f"keep{'s' * one} {'its' if one else 'their'} alpha; move the colours apart"
        )
    if not options:
        return f"{fix.color}: not even alpha 1 passes; change the colour"
    return f"{fix.color}: {' or '.join(options)}"


def fix_text(fix: Fix) -> str:
    """A fix in one plain line (no markup), alternatives joined by "or".

    A colour's largest safe alpha answers every rule; the smallest alpha
    reaching the threshold and the nearest colour answer a contrast failure,
    so they are offered only when the colour fails a contrast rule there.  A
    group's fix is the largest safe alpha of its colours moving together (a
    confusion's two roles: the joint answer), else of the whole set.
    """
    from alpha_audit.results import ColorFix

    if isinstance(fix, ColorFix):
        return _color_fix_text(fix)
    who = names_and(fix.colors) + " together" if fix.colors else "the whole set"
    limit = fix.safe.limit
    why = ""
    if limit is not None and limit.roles:  # the pair that limits the group, and where
        why = f" (limited by {names_and(limit.roles)} on {limit.canvas} at {limit.at:.6f})"
    if fix.safe.alpha is None:
        return f"{who}: not even alpha 1 is safe{why}; move the colours apart"
    return f"{who}: {safe_span(fix.safe.alpha)}{why}, or move the colours apart"


def names_and(names: Sequence[str]) -> str:
    """Names joined as prose.

    >>> names_and(["red"]), names_and(["red", "orange"]), names_and(["a", "b", "c"])
    ('red', 'red and orange', 'a, b and c')
    """
    *head, last = names
    return f"{', '.join(head)} and {last}" if head else last


def finding_fix(finding: Finding, report: CheckReport) -> str:
    """How to fix one finding, in words: its computed fixes, else the rule's advice.

    A failing colour beyond the report's fix budget points at ``alpha-audit suggest``.
    """
    from alpha_audit.rules import RULES

    if finding.fixes:
        # One fix per mode: where two modes need the same edit, it is said once.
        return "; ".join(dict.fromkeys(fix_text(report.fixes[k]) for k in finding.fixes))
    if finding.fails and report.fixes_left_out and finding.canvas is not None:
        return "run alpha-audit suggest for the safe alphas (too many failing colours here)"
    return RULES[finding.rule].fix.replace("`", "")


def _safe_to_dict(safe: SafeAlpha) -> dict[str, Any]:
    limit = safe.limit
    return {
        "alpha": safe.alpha,
        "exact": safe.exact,
        "limit": None
        if limit is None
        else {
            "rule": limit.rule.value,
            "canvas": limit.canvas,
            "icons": list(limit.icons),
            "at": limit.at,
            "attained": limit.attained,
            "roles": list(limit.roles),
        },
    }


def fix_to_dict(fix: Fix, base: Path | None = None) -> dict[str, Any]:
    """One fix as plain JSON data (finite floats only; ``None`` where there is no answer)."""
    from alpha_audit.results import ColorFix

    if not isinstance(fix, ColorFix):
        return {
            "kind": "group",
            "theme": fix.theme,
            "iconset": fix.iconset,
            "rule": fix.rule.value,
            "colors": list(fix.colors),
            "confused": list(fix.confused),
            "largest_safe_alpha": _safe_to_dict(fix.safe),
            "text": fix_text(fix),
        }
    near = fix.nearest
    return {
        "kind": "colour",
        "theme": fix.theme,
        "iconset": fix.iconset,
        "color": fix.color,
        "source": fix.source,
        "canvas": fix.canvas,
        "mode": fix.mode,
        "icons": list(fix.icons),
        "rules": [r.value for r in fix.rules],
        "largest_safe_alpha": _safe_to_dict(fix.largest_safe),
        "together": list(fix.together),
        "held": list(fix.held),
        "smallest_alpha_reaching": {
            "alpha": fix.reach.alpha,
            "exact": fix.reach.exact,
            "threshold": fix.reach.threshold,
            "mode": fix.reach.mode,
            "canvases": list(fix.reach.canvases),
        },
        "nearest_color": None
        if near is None
        else {
            "color": near.color,
            "delta_e": near.delta_e,
            "oklch": {"l": near.lightness, "c": near.chroma, "h": near.hue},
        },
        "manifest": display_path(fix.manifest, base),
        "line": fix.line,
        "opacity": fix.opacity,
        "text": fix_text(fix),
    }
