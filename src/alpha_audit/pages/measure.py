"""From a capture pair to measured paints: full coverage, gated contrast, backdrop, drift.

Per icon, inside its box (device pixels), with ``D`` the drawn capture and
``B`` the hidden one (the backdrop the browser composited behind the icons):

* **touched** pixels differ between the two captures;
* a paint's **full-coverage colour** at a pixel is what the browser draws
  there for the paint at full coverage: its computed colour at its opacity
  chain, composited source-over on encoded sRGB over ``B`` at that pixel and
  kept to 8 bits (:func:`~alpha_audit.color.composite_paint` ``css``);
* a touched pixel is **fully covered** by the paint whose full-coverage colour
  is nearest to ``D`` there, when that is within :data:`FULL_TOLERANCE` codes
  in every channel.  Antialiased mixes (edges, concave corners, diagonals of
  thin strokes) sit between ``B`` and the paint's colour, so they never count,
  whatever the stroke width, angle or size; they never decide which paint a
  pixel belongs to either (they follow their nearest fully covered pixel, for
  coverage figures only);
* where the computed colour does not explain the pixels (a CSS filter, a blend
  mode, an ``<img>`` whose paints are unknown) the fully covered pixels are a
  **plateau**: the drawn colour furthest from the backdrop shared by at least
  :func:`plateau_pixels` pixels, one of them inside the shape (its 3 x 3
  neighbourhood touched), never a single pixel.  A plateau the computed colour
  explains as partial coverage (a mix of it with the backdrop) counts only deep
  inside a shape (a 5 x 5 neighbourhood touched: a CSS ``filter: opacity()``),
  never on a stroke under 2 device pixels; no plateau at all is ``could not
  measure`` (a hairline: no pixel shows the paint, so no verdict);
* an icon that changes no pixel is judged where its full-coverage colour is the
  backdrop's (an icon the colour of its surface: contrast 1);
* the **gated contrast** is the least WCAG 2.2 contrast
  (:func:`~alpha_audit.color.judged_contrast`) of the fully covered pixels
  against ``B`` at the same pixel (over a gradient, the least-contrasting
  area), taking on each backdrop colour the paint's most frequent drawn colour
  there (a pixel one code off beside the paint's own colour never limits);
  that pair of colours, the limiting pair, is the paint's **drawn** colour on
  its **behind** colour (a report's "draws X on Y: r:1" is that pair);
  **around** is the median of ``B`` in a ring of ``2 * scale`` device pixels
  just outside the touched pixels;
* for diagnosis, worst and median contrast over the *candidate* pixels (touched
  pixels whose 3 x 3 neighbourhood is touched: antialiased mixes included);
* **coverage** per touched pixel, ``q = (D - B)·(P - B) / |P - B|²`` in encoded
  values with ``P`` the full-coverage colour, clipped to [0, 1] and 1 on fully
  covered pixels (:func:`~alpha_audit.color.coverage_stats`);
* the **model's prediction** for the same paint and backdrop under ``linear``
  and ``css``, and the CIEDE2000 from the drawn colour to each.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from coloraide import Color
from numpy.typing import NDArray

from alpha_audit.color import (
    Pipeline,
    composite_paint,
    contrast_ratio,
    coverage_stats,
    delta_e_2000,
    from_8bit,
    judged_contrast,
    linear_to_hex,
    pack_8bit,
    srgb_decode,
    to_8bit,
)
from alpha_audit.model import Icon, Location
from alpha_audit.observed import (
    MEASURED,
    UNMEASURED,
    Basis,
    Coverage,
    IconMatch,
    MeasuredPaint,
    Prediction,
)
from alpha_audit.pages.capture import Capture, FoundIcon

__all__ = [
    "FULL_TOLERANCE",
    "DeclaredPaint",
    "PageContext",
    "declared_paints",
    "full_coverage_colour",
    "icon_name",
    "icon_region",
    "measure_capture",
    "plateau_pixels",
    "ring_width",
]

Linear = tuple[float, float, float]
# Where the page sets an icon's paint (its index in the probe's paints; None: an image).
Locate = Callable[[FoundIcon, int | None], tuple[Location, ...]]


@dataclass(frozen=True)
class DeclaredPaint:
    """A paint as the engine computed it: colour (linear sRGB), opacity, kinds, currentColor."""

    color: Linear | None
    opacity: float
    kinds: tuple[str, ...]
    current: bool
    text: str
    index: int | None = None  # its place in the probe's paints of the icon (None: an image)

    @property
    def label(self) -> str:
        """How a report names the paint: ``image``, ``currentColor`` or its hex colour."""
        if self.color is None:
            return "image"
        return "currentColor" if self.current else linear_to_hex(self.color)


@dataclass(frozen=True)
class PageContext:
    """Who a capture belongs to (copied into every measured paint)."""

    source: str
    source_kind: str
    state: str
    engine: str
    file: Path | None = None  # the story's or page's source file


def _parse(text: str) -> tuple[Linear, float] | None:
    """A computed CSS colour -> (linear sRGB clipped to the gamut, its alpha), or None."""
    try:
        color = Color(text).convert("srgb")
    except (ValueError, TypeError, AttributeError):
        return None
    alpha = float(color.alpha())
    color = color.fit("srgb", method="clip")  # engines clip out-of-gamut colours for sRGB output
    encoded = np.nan_to_num(np.array(color.coords(), dtype=np.float64))
    lin = srgb_decode(np.clip(encoded, 0.0, 1.0))
    return (float(lin[0]), float(lin[1]), float(lin[2])), (0.0 if math.isnan(alpha) else alpha)


def declared_paints(icon: FoundIcon) -> tuple[DeclaredPaint, ...]:
    """The icon's paints as the probe reported them, colour alpha folded into opacity."""
    out = []
    for index, paint in enumerate(icon.paints):
        parsed = _parse(str(paint.get("color", "")))
        opacity = float(paint.get("opacity", 1.0))
        color = None
        if parsed is not None:
            color, own_alpha = parsed
            opacity *= own_alpha
        kinds = tuple(str(k) for k in paint.get("kinds", ()))
        text = str(paint.get("color", ""))
        out.append(DeclaredPaint(color, opacity, kinds, bool(paint.get("current")), text, index))
    return tuple(p for p in out if p.opacity > 0)


# Engines draw a paint at full coverage to within this many 8-bit codes per channel of
# CSS source-over on encoded sRGB kept to 8 bits (the prediction).  Measured on the pages
# of tests/pages/test_measure_engines.py, every pixel deep inside a filled shape (its
# 7 x 7 neighbourhood touched): opaque paints on opaque and on rgba() backdrops exact in
# Chromium, Firefox and WebKitGTK; paints under opacity 0.4-0.95 off by -1 to +1 (Chromium
# and Firefox quantise the opacity to 8 bits and round down about half the time), never 2.
FULL_TOLERANCE = 1
# A plateau pixel within this distance (Euclidean, 8-bit codes: one code per channel is
# sqrt(3)) of the segment from the backdrop to a declared full-coverage colour is a mix of
# the two: the declaration explains it as partial coverage.
_ON_SEGMENT = 2.0


def plateau_pixels(scale: int) -> int:
    """Fewest device pixels a plateau needs: one CSS pixel's worth, never a single pixel."""
    return max(2, scale * scale)


def _erode(mask: NDArray[np.bool_]) -> NDArray[np.bool_]:
    """Pixels whose 3 x 3 neighbourhood lies in ``mask`` (outside the array counts as out)."""
    padded = np.pad(mask, 1, constant_values=False)
    out = np.ones_like(mask)
    h, w = mask.shape
    for dy in range(3):
        for dx in range(3):
            out &= padded[dy : dy + h, dx : dx + w]
    return out


def _dilate(mask: NDArray[np.bool_], steps: int) -> NDArray[np.bool_]:
    out = mask.copy()
    for _ in range(steps):
        padded = np.pad(out, 1, constant_values=False)
        h, w = out.shape
        grown = out.copy()
        for dy in range(3):
            for dx in range(3):
                grown |= padded[dy : dy + h, dx : dx + w]
        out = grown
    return out


def _spread(labels: NDArray[np.int64], wanted: NDArray[np.bool_]) -> NDArray[np.int64]:
    """Give each ``wanted`` pixel without a label (-1) the label of a neighbour, repeatedly."""
    labels = labels.copy()
    for _ in range(8):
        missing = wanted & (labels < 0)
        if not missing.any():
            break
        padded = np.pad(labels, 1, constant_values=-1)
        h, w = labels.shape
        for dy in range(3):
            for dx in range(3):
                near = padded[dy : dy + h, dx : dx + w]
                take = missing & (labels < 0) & (near >= 0)
                labels[take] = near[take]
    return labels


def _hex(codes: NDArray[np.float64]) -> tuple[str, Linear]:
    lin = from_8bit(np.rint(codes))
    return linear_to_hex(lin), (float(lin[0]), float(lin[1]), float(lin[2]))


def _predictions(
    drawn: Linear, behind: Linear, source: Linear, alpha: float, opacity: float
) -> tuple[Prediction, ...]:
    out = []
    pipelines: tuple[Pipeline, ...] = ("linear", "css")
    for pipeline in pipelines:
        if pipeline == "css" and not 0.0 <= alpha * opacity <= 1.0:
            continue  # CSS clamps opacity: the css pipeline cannot draw this coefficient
        shown = composite_paint(source, behind, alpha, opacity, pipeline)
        out.append(
            Prediction(
                pipeline,
                linear_to_hex(shown),
                (float(shown[0]), float(shown[1]), float(shown[2])),
                float(judged_contrast(shown, behind)),
                float(delta_e_2000(drawn, shown)),
                float(contrast_ratio(shown, behind)),
            )
        )
    return tuple(out)


def full_coverage_colour(paint: DeclaredPaint, behind: NDArray[np.float64]) -> NDArray[np.float64]:
    """8-bit codes the paint shows at full coverage over each backdrop pixel (codes, ``(..., 3)``).

    CSS source-over on encoded sRGB at the paint's opacity chain, kept to 8
    bits: what a browser draws (:func:`~alpha_audit.color.composite_paint` ``css``).

    >>> paint = DeclaredPaint((1.0, 1.0, 1.0), 0.4, ("fill",), False, "white")
    >>> full_coverage_colour(paint, np.array([[0.0, 0.0, 0.0]])).tolist()
    [[102.0, 102.0, 102.0]]
    """
    assert paint.color is not None  # only declared colours have a prediction
    shown = composite_paint(paint.color, from_8bit(behind), 1.0, min(1.0, paint.opacity), "css")
    return to_8bit(shown).astype(np.float64)


def _segment_distance(
    drawn: NDArray[np.float64], behind: NDArray[np.float64], full: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Distance (codes) from each drawn colour to the segment backdrop -> full colour, and
    where along it (0 the backdrop, 1 the full colour) its nearest point lies."""
    span = full - behind
    norm = (span * span).sum(axis=-1)
    t = np.where(norm > 0, ((drawn - behind) * span).sum(axis=-1) / np.where(norm > 0, norm, 1), 0)
    t = np.clip(t, 0.0, 1.0)
    gap = drawn - behind - t[..., np.newaxis] * span
    return np.sqrt((gap * gap).sum(axis=-1)), t


def _plateau(
    drawn: NDArray[np.float64],
    behind: NDArray[np.float64],
    pool: NDArray[np.bool_],
    interior: NDArray[np.bool_],
    least: int,
) -> NDArray[np.bool_] | None:
    """The pixels of ``pool`` at the paint's extreme: the most frequent drawn colour among
    those furthest from their backdrop, shared by ``least`` pixels, one of them interior."""
    if not pool.any():
        return None
    codes = drawn[pool]
    keys = pack_8bit(codes)
    colours, first, group, counts = np.unique(
        keys, return_index=True, return_inverse=True, return_counts=True
    )
    inner = np.bincount(group, weights=interior[pool].astype(np.float64), minlength=colours.size)
    reach = np.sqrt(((codes - behind[pool]) ** 2).sum(axis=-1))
    # A plateau's distance from its backdrop: its median pixel's (a gradient varies it).
    order = np.lexsort((reach, group))
    starts = np.searchsorted(group[order], np.arange(colours.size))
    median = reach[order][starts + (counts - 1) // 2]
    eligible = (counts >= least) & (inner > 0)
    if not eligible.any():
        return None
    top = median[eligible].max()
    near = eligible & (median >= top - math.sqrt(3.0) * FULL_TOLERANCE)
    chosen = codes[first[np.argmax(np.where(near, counts, -1))]]
    plateau: NDArray[np.bool_] = pool & (np.abs(drawn - chosen).max(axis=-1) <= FULL_TOLERANCE)
    return plateau


@dataclass(frozen=True)
class _Found:
    """A paint's fully covered pixels and the full-coverage colour per pixel (codes)."""

    basis: Basis | None  # None: could not measure
    full: NDArray[np.bool_]
    target: NDArray[np.float64] | None  # (H, W, 3), None when could not measure


def _find_full(
    drawn: NDArray[np.float64],
    hidden: NDArray[np.float64],
    inside: NDArray[np.bool_],
    touched: NDArray[np.bool_],
    paints: Sequence[DeclaredPaint],
    scale: int,
) -> list[_Found]:
    """Each paint's fully covered pixels (see the module's docstring)."""
    shape = touched.shape
    targets = [full_coverage_colour(p, hidden) if p.color is not None else None for p in paints]
    # Nothing drawn at all: a paint whose full colour is the backdrop is invisible there.
    eligible = touched if touched.any() else inside
    gap = np.stack(
        [
            np.abs(drawn - t).max(axis=-1) if t is not None else np.full(shape, np.inf)
            for t in targets
        ]
    )
    nearest = np.argmin(gap, axis=0)
    matched = eligible & (gap.min(axis=0) <= FULL_TOLERANCE)
    found: list[_Found | None] = [None] * len(paints)
    for k, target in enumerate(targets):
        full = matched & (nearest == k)
        if target is not None and full.any():
            found[k] = _Found(Basis.DECLARED, full, target)
    # Pixels the measured paints explain (fully covered, or a mix with the backdrop) are no
    # other paint's; what is left may be a paint the computed colour does not explain.
    explained = np.zeros(shape, dtype=bool)
    for f in found:
        if f is not None and f.target is not None:
            explained |= f.full | (_segment_distance(drawn, hidden, f.target)[0] <= _ON_SEGMENT)
    interior = _erode(touched)
    out = []
    for k, f in enumerate(found):
        if f is None:
            full = _plateau(drawn, hidden, touched & ~explained, interior, plateau_pixels(scale))
            target = targets[k]
            if full is not None and target is not None:
                # Mixes of the declared colour with the backdrop: partial coverage (a stroke
                # under 2 device pixels), unless deep inside a shape (its 5 x 5 neighbourhood
                # touched), where the geometry covers the pixel and something else (a filter's
                # opacity) takes the colour towards the backdrop.
                distance, along = _segment_distance(drawn[full], hidden[full], target[full])
                on_segment = np.median(distance) <= _ON_SEGMENT and np.median(along) < 1.0
                if on_segment and not (full & _erode(interior)).any():
                    full = None
            if full is None:
                f = _Found(None, np.zeros(shape, dtype=bool), target)
            else:
                plateau = np.broadcast_to(np.median(drawn[full], axis=0), drawn.shape).copy()
                f = _Found(Basis.PLATEAU, full, plateau)
        out.append(f)
    return out


def _coverage(
    drawn: NDArray[np.float64],
    hidden: NDArray[np.float64],
    touched: NDArray[np.bool_],
    found: _Found,
) -> Coverage:
    """Coverage figures of a paint's touched pixels, relative to its full-coverage colour."""
    full = found.full
    if found.target is None or not touched.any():
        return Coverage(int(touched.sum()), int(full.sum()), 0.0, math.nan, math.nan)
    span = found.target[touched] - hidden[touched]
    norm = (span * span).sum(axis=-1)
    diff = drawn[touched] - hidden[touched]
    q = np.where(norm > 0, (diff * span).sum(axis=-1) / np.where(norm > 0, norm, 1), 1.0)
    q = np.where(full[touched], 1.0, np.clip(q, 0.0, 1.0))
    stats = coverage_stats(q)
    return Coverage(int(touched.sum()), int(full.sum()), stats.ink, stats.q50, stats.full_share)


def ring_width(scale: int) -> int:
    """Device pixels of backdrop measured around an icon (the "around" ring): 2 CSS px."""
    return 2 * scale


def icon_region(
    capture: Capture, box: tuple[float, float, float, float], pad: int
) -> tuple[slice, slice, slice, slice]:
    """Rows/columns of ``box`` (CSS px of the page) and of it grown by ``pad`` device px."""
    assert capture.clip is not None
    s = capture.scale
    x, y, w, h = box
    h_px, w_px = capture.drawn.shape[:2]
    x0 = max(0, math.floor((x - capture.clip.x) * s))
    y0 = max(0, math.floor((y - capture.clip.y) * s))
    x1 = min(w_px, math.ceil((x + w - capture.clip.x) * s))
    y1 = min(h_px, math.ceil((y + h - capture.clip.y) * s))
    return (
        slice(y0, y1),
        slice(x0, x1),
        slice(max(0, y0 - pad), min(h_px, y1 + pad)),
        slice(max(0, x0 - pad), min(w_px, x1 + pad)),
    )


def _limit(
    drawn: NDArray[np.float64], behind: NDArray[np.float64]
) -> tuple[float, NDArray[np.float64], NDArray[np.float64]]:
    """The least judged contrast of a paint's fully covered pixels (codes ``(n, 3)``), and the
    pair of colours giving it.

    On each backdrop colour the paint shows its most frequent drawn colour there, so a
    pixel one code off (an edge at 99 % coverage, an engine's rounding) never limits
    where the paint's own colour is beside it.
    """
    keys = pack_8bit(behind) * (1 << 24) + pack_8bit(drawn)
    pairs, first, counts = np.unique(keys, return_index=True, return_counts=True)
    on = pairs >> 24
    order = np.lexsort((-counts, on))  # by backdrop, the most frequent drawn colour first
    modal = first[order[np.r_[True, on[order][1:] != on[order][:-1]]]]
    shown, canvas = drawn[modal], behind[modal]
    per_pair = judged_contrast(
        from_8bit(shown.astype(np.uint8)), from_8bit(canvas.astype(np.uint8))
    )
    k = int(np.argmin(per_pair))
    return float(per_pair[k]), shown[k], canvas[k]


def icon_name(icon: FoundIcon, manifest_icon: Icon | None) -> str:
    """What reports call an icon: the manifest's icon, else what the page names it
    (``data-icon``, ``aria-label``, ``<title>``, ``alt``, ``id``), else a short DOM path
    (its last two steps)."""
    if manifest_icon is not None:
        return manifest_icon.name
    for key in ("data", "label", "title", "alt", "id"):
        value = icon.keys.get(key)
        if isinstance(value, str) and value.strip():
            return " ".join(value.split())
    return " > ".join(icon.dom_path.split(" > ")[-2:])


def _diagnosis(
    drawn: NDArray[np.float64], behind: NDArray[np.float64]
) -> tuple[float | None, float | None]:
    """Worst and median contrast of candidate pixels (codes ``(n, 3)``), antialiased mixes
    included: for diagnosis only (None where there is none)."""
    if not len(drawn):
        return None, None
    per_pixel = contrast_ratio(from_8bit(drawn), from_8bit(behind))
    return float(per_pixel.min()), float(np.median(per_pixel))


@dataclass(frozen=True)
class _Model:
    """What the model was given for a paint, and what it predicts on the measured backdrop."""

    source: str | None = None
    alpha: float | None = None
    opacity: float | None = None
    predictions: tuple[Prediction, ...] = ()
    drift: float | None = None


def _model(
    paint: DeclaredPaint, manifest_icon: Icon | None, drawn: Linear, behind: Linear
) -> _Model:
    """The model's input for ``paint`` (the manifest's colour and alpha when the icon maps to
    ``manifest_icon``, else the colour the engine computed at alpha 1) and its predictions."""
    source, alpha = paint.color, 1.0
    if manifest_icon is not None:
        source, alpha = manifest_icon.linear, float(manifest_icon.alpha)
    if source is None:
        return _Model()
    opacity = min(1.0, paint.opacity)
    predictions = _predictions(drawn, behind, source, alpha, opacity)
    drift = min(p.drift for p in predictions) if predictions else None
    return _Model(linear_to_hex(source), alpha, opacity, predictions, drift)


def _crop(
    capture: Capture, icon: FoundIcon, ring: int
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]]:
    """The icon's box grown by ``ring`` in both captures (codes), and which pixels are in
    the box itself."""
    rows, cols, grown_rows, grown_cols = icon_region(capture, icon.box, ring)
    drawn = capture.drawn[grown_rows, grown_cols].astype(np.float64)
    hidden = capture.hidden[grown_rows, grown_cols].astype(np.float64)
    inside = np.zeros(drawn.shape[:2], dtype=bool)
    inside[
        rows.start - grown_rows.start : rows.stop - grown_rows.start,
        cols.start - grown_cols.start : cols.stop - grown_cols.start,
    ] = True
    return drawn, hidden, inside


def _around(
    hidden: NDArray[np.float64], touched: NDArray[np.bool_], ring: int
) -> tuple[str, Linear] | tuple[None, None]:
    """The median backdrop in a ring of ``ring`` pixels just outside the touched ones."""
    mask = _dilate(touched, ring) & ~touched
    if not mask.any():
        return None, None
    return _hex(np.median(hidden[mask], axis=0))


def _measure_icon(
    capture: Capture,
    icon: FoundIcon,
    page: PageContext,
    manifest_icon: Icon | None,
    match: IconMatch,
    locate: Locate | None = None,
) -> list[MeasuredPaint]:
    ring = ring_width(capture.scale)
    drawn_all, hidden_all, inside = _crop(capture, icon, ring)
    touched = inside & (np.abs(drawn_all - hidden_all).max(axis=-1) > 0)
    candidates = _erode(touched)
    around, around_lin = _around(hidden_all, touched, ring)
    declared = declared_paints(icon)
    if icon.paints and not declared:
        return []  # every paint transparent or at opacity 0: the icon draws nothing
    paints = declared or (DeclaredPaint(None, 1.0, ("image",), False, "image"),)
    found = _find_full(drawn_all, hidden_all, inside, touched, paints, capture.scale)
    # Edge pixels follow their nearest fully covered pixel (for coverage and candidates only).
    labels = np.full(touched.shape, -1, dtype=np.int64)
    for k, f in enumerate(found):
        labels[f.full] = k
    labels = _spread(labels, touched) if len(paints) > 1 else np.where(touched, 0, -1)
    name = icon_name(icon, manifest_icon)
    out = []
    for k, (paint, f) in enumerate(zip(paints, found, strict=True)):
        mine = labels == k
        worst, median = _diagnosis(drawn_all[candidates & mine], hidden_all[candidates & mine])
        only = manifest_icon if paint.current or len(paints) == 1 else None
        gated, (drawn, drawn_lin), (behind, behind_lin), model = _judge(
            paint, f, drawn_all, hidden_all, only
        )
        out.append(
            MeasuredPaint(
                source=page.source,
                source_kind=page.source_kind,
                state=page.state,
                engine=page.engine,
                name=name,
                icon=manifest_icon.name if manifest_icon is not None else None,
                match=match,
                element=icon.kind,
                dom_path=icon.dom_path,
                paint=paint.label,
                kinds=paint.kinds,
                declared=None if paint.color is None else linear_to_hex(paint.color),
                declared_opacity=min(1.0, paint.opacity),
                drawn=drawn,
                drawn_linear=drawn_lin,
                behind=behind,
                behind_linear=behind_lin,
                around=around,
                around_linear=around_lin,
                coverage=_coverage(drawn_all, hidden_all, touched & mine, f),
                contrast=gated,
                contrast_worst=worst,
                contrast_median=median,
                model_source=model.source,
                model_alpha=model.alpha,
                model_opacity=model.opacity,
                predictions=model.predictions,
                render_drift=model.drift,
                box=icon.box,
                status=MEASURED if gated is not None else UNMEASURED,
                basis=f.basis,
                file=page.file,
                locations=() if locate is None else locate(icon, paint.index),
            )
        )
    return out


_Shown = tuple[str | None, Linear | None]  # a colour as hex and linear, or nothing


def _judge(
    paint: DeclaredPaint,
    found: _Found,
    drawn: NDArray[np.float64],
    hidden: NDArray[np.float64],
    manifest_icon: Icon | None,
) -> tuple[
    float | None, tuple[str | None, Linear | None], tuple[str | None, Linear | None], _Model
]:
    """The gated contrast of a paint, the pair that limits it (drawn on behind: the gated
    contrast is theirs, as hex and linear) and the model's input and predictions;
    nothing when no pixel shows the paint at full coverage."""
    if not found.full.any():
        return None, (None, None), (None, None), _Model()
    gated, pair_drawn, pair_behind = _limit(drawn[found.full], hidden[found.full])
    drawn_hex, drawn_lin = _hex(pair_drawn)
    behind_hex, behind_lin = _hex(pair_behind)
    model = _model(paint, manifest_icon, drawn_lin, behind_lin)
    return gated, (drawn_hex, drawn_lin), (behind_hex, behind_lin), model


def measure_capture(
    capture: Capture,
    page: PageContext,
    matches: Sequence[tuple[Icon | None, IconMatch]],
    locate: Locate | None = None,
) -> list[MeasuredPaint]:
    """Every paint of every icon of ``capture``; ``matches`` gives each icon's manifest icon.

    ``locate(icon, index)`` gives where the page sets the paint at ``index`` of the
    icon's probed paints (``None``: an image's own drawing): its CSS declarations,
    then its story or page (:func:`alpha_audit.pages.declarations.paint_locations`).
    """
    out: list[MeasuredPaint] = []
    for icon, (manifest_icon, how) in zip(capture.icons, matches, strict=True):
        out.extend(_measure_icon(capture, icon, page, manifest_icon, how, locate))
    return out
