"""Splitting sheets larger than :data:`~.surface.PIXEL_BUDGET` into pages.

Every layout can say how large a sheet of given icons (or colours) will be
before drawing it (its *frame*), so pages are planned before any work and
their file names are known up front.  A sheet that fits stays one file under
its usual name; one that does not becomes ``<name>-01.png``, ``<name>-02.png``
and so on, each under the budget.  Pages split the manifest's own order (icons
for grid and compare, colours for swatches; canvases too for compare), so the
same inputs always give the same pages; icons that fail to render only leave
gaps, never make a page larger.  A sheet too large even for one item a page is
refused with a :class:`~alpha_audit.errors.UsageError`.

At most :data:`MAX_SHEETS` files come out of one run, counted as the pages are
planned: each file costs its drawing, labels and encoding whatever it holds,
so a theme of thousands of canvases is refused at once (the ``--html`` page
draws any number), not after minutes of small files.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import replace
from pathlib import Path
from typing import Any, NoReturn, assert_never

from alpha_audit.color import NON_TEXT_THRESHOLD
from alpha_audit.errors import InputError, UsageError
from alpha_audit.model import IconSet
from alpha_audit.preview.sheets.compare import compare_frame
from alpha_audit.preview.sheets.grid import grid_frame
from alpha_audit.preview.sheets.plan import (
    Alpha,
    Layout,
    Page,
    SheetSpec,
    sheet_rows,
    sheet_title,
)
from alpha_audit.preview.sheets.render import DEFAULT_MAX_WIDTH
from alpha_audit.preview.sheets.surface import PIXEL_BUDGET
from alpha_audit.preview.sheets.swatches import swatch_colors, swatch_frame

__all__ = ["MAX_SHEETS", "paginate"]

# PNG files one preview writes: a sheet per canvas and size (pages included).
# A 40-canvas theme at three sizes is 120; each small sheet takes some tens of
# milliseconds, so this many finish in well under a minute.
MAX_SHEETS = 512

Span = tuple[int, int]


def _spans(n: int, fits: Callable[[int, int], bool], refuse: Callable[[], NoReturn]) -> list[Span]:
    """Split ``range(n)`` into few, even, consecutive spans that each ``fits``.

    Sheet sizes grow with the number of items, so the largest first span is
    found by bisection; the pages are then evened out when every even span
    fits too.  ``refuse()`` is called (and must raise) when one item does not fit.
    """
    if fits(0, n):
        return [(0, n)]
    spans: list[Span] = []
    start = 0
    while start < n:
        if not fits(start, start + 1):
            refuse()
        lo, hi = 1, n - start  # the largest k with fits(start, start + k)
        while lo < hi:
            mid = (lo + hi + 1) // 2
            if fits(start, start + mid):
                lo = mid
            else:
                hi = mid - 1
        spans.append((start, start + lo))
        start += lo
    step = math.ceil(n / len(spans))
    even = [(a, min(a + step, n)) for a in range(0, n, step)]
    return even if all(fits(a, b) for a, b in even) else spans


def _placeholder(spec: SheetSpec, n: int) -> SheetSpec:
    """``spec`` with a page note at least as wide as any real one (for measuring)."""
    return replace(
        spec, page=Page(n, n, n - 1, n, f"icons {n}-{n} of {n}, canvases {n}-{n} of {n}")
    )


def _note(noun: str, span: Span, total: int) -> str:
    return f"{noun} {span[0] + 1}-{span[1]} of {total}"


def _paged(spec: SheetSpec, parts: Sequence[tuple[SheetSpec, Span, str]]) -> list[SheetSpec]:
    """Number the parts of one sheet as pages (one part keeps the sheet as it was)."""
    if len(parts) == 1:
        return [parts[0][0]]
    stem = spec.name.removesuffix(".png")
    width = len(str(len(parts)))
    return [
        replace(
            part,
            name=f"{stem}-{k:0{width}d}.png",
            page=Page(k, len(parts), span[0], span[1], note),
        )
        for k, (part, span, note) in enumerate(parts, start=1)
    ]


def _distinct(specs: list[SheetSpec]) -> list[SheetSpec]:
    """File names made unique (a canvas slug can equal another sheet's page name)."""
    seen: set[str] = set()
    out = []
    for spec in specs:
        name, k = spec.name, 1
        while name in seen:
            k += 1
            name = f"{spec.name.removesuffix('.png')}-{k}.png"
        seen.add(name)
        out.append(spec if name == spec.name else replace(spec, name=name))
    return out


def paginate(
    specs: Sequence[SheetSpec],
    iconset: IconSet,
    *,
    alphas: Sequence[Alpha] | None = None,
    threshold: float = NON_TEXT_THRESHOLD,
    max_width: int = DEFAULT_MAX_WIDTH,
    title: str | None = None,
    budget: int = PIXEL_BUDGET,
    source: Path | None = None,
) -> list[SheetSpec]:
    """Planned sheets split into pages of at most ``budget`` pixels each.

    Takes the same ``alphas``, ``threshold``, ``max_width`` and ``title`` as
    :func:`~alpha_audit.preview.sheets.render.render_sheet` will be given;
    ``budget`` may only be lower than :data:`~.surface.PIXEL_BUDGET`, which
    every drawn sheet is held to.  More than :data:`MAX_SHEETS` pages is an
    input error naming ``source`` (the theme whose canvases they are), raised
    as soon as the count passes it.
    """
    label = title or iconset.name
    out: list[SheetSpec] = []
    _check_count(len(specs), source)
    for spec in specs:
        out += _paged(spec, _parts(spec, iconset, alphas, threshold, max_width, label, budget))
        _check_count(len(out), source)
    return _distinct(out)


def _parts(
    spec: SheetSpec,
    iconset: IconSet,
    alphas: Sequence[Alpha] | None,
    threshold: float,
    max_width: int,
    label: str,
    budget: int,
) -> Parts:
    """One planned sheet split into parts of at most ``budget`` pixels each."""
    rows = sheet_rows(spec.layout, iconset, alphas)
    match spec.layout:
        case Layout.GRID:
            return _split(
                spec,
                iconset.icons,
                "icons",
                lambda probe, part, text: grid_frame(probe, part, rows, threshold, max_width, text),
                label,
                budget,
            )
        case Layout.SWATCHES:
            real = [a for a in rows if a is not None]  # swatch rows are never None
            return _split(
                spec,
                swatch_colors(iconset),
                "colours",
                lambda probe, part, text: swatch_frame(probe, part, real, threshold, text),
                label,
                budget,
            )
        case Layout.COMPARE:
            return _compare_parts(spec, iconset, rows, label, budget)
        case _:
            assert_never(spec.layout)


def _check_count(sheets: int, source: Path | None) -> None:
    if sheets > MAX_SHEETS:
        raise InputError(
            f"would write more than {MAX_SHEETS} PNG sheets (one per canvas and size, pages "
            "included); preview fewer canvases or `sizes`, or write the page (`html_path`)",
            path=source,
        )


Parts = list[tuple[SheetSpec, Span, str]]


def _refusal(spec: SheetSpec, budget: int) -> Callable[[], NoReturn]:
    def refuse() -> NoReturn:
        item = "colour" if spec.layout is Layout.SWATCHES else "icon"
        raise UsageError(
            f"sheet {spec.name} would be larger than {budget:,} px even with one {item} a "
            "page; use fewer alpha rows, a smaller size or fewer canvases"
        )

    return refuse


def _split(
    spec: SheetSpec,
    items: Sequence[Any],
    noun: str,
    frame: Callable[[SheetSpec, Sequence[Any], str], Any],
    label: str,
    budget: int,
) -> Parts:
    """Sheets split by ``noun`` (icons or colours); ``frame`` measures a part's sheet."""
    probe = _placeholder(spec, len(items))
    text = sheet_title(probe, label)

    def fits(a: int, b: int) -> bool:
        f = frame(probe, items[a:b], text)
        return bool(f.width * f.height <= budget)

    spans = _spans(len(items), fits, _refusal(spec, budget))
    return [(spec, s, _note(noun, s, len(items))) for s in spans]


def _compare_parts(
    spec: SheetSpec,
    iconset: IconSet,
    rows: Sequence[Alpha],
    label: str,
    budget: int,
) -> Parts:
    """Compare sheets split by canvases, and by icons when one canvas row is too large."""
    icons, canvases = iconset.icons, spec.canvases
    refuse = _refusal(spec, budget)
    probe = _placeholder(spec, max(len(icons), len(canvases)))
    text = sheet_title(probe, label)

    def fits(a: int, b: int, c: int, d: int) -> bool:
        f = compare_frame(replace(probe, canvases=canvases[c:d]), icons[a:b], rows, text)
        return f.width * f.height <= budget

    if fits(0, len(icons), 0, len(canvases)):
        return [(spec, (0, len(icons)), "")]
    icon_spans = _spans(len(icons), lambda a, b: fits(a, b, 0, 1), refuse)
    parts = []
    for a, b in icon_spans:

        def fits_canvases(c: int, d: int, a: int = a, b: int = b) -> bool:
            return fits(a, b, c, d)

        for c, d in _spans(len(canvases), fits_canvases, refuse):
            note = _note("canvases", (c, d), len(canvases))
            if len(icon_spans) > 1:
                note = f"{_note('icons', (a, b), len(icons))}, {note}"
            parts.append((replace(spec, canvases=canvases[c:d]), (a, b), note))
    return parts
