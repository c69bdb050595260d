"""From a capture pair to measured paints: coverage, drawn colour, backdrop, contrast, drift.

Per icon, inside its box (device pixels):

* **touched** pixels differ between the drawn and the hidden capture;
  **fully covered** ones are touched pixels whose 3 x 3 neighbourhood is
  touched too (the icon's interior: antialiasing only reaches one device
  pixel into a shape at the scales used, 2 or more);
* with several declared paints, each fully covered pixel goes to the paint
  whose colour, composited by the browser's rule (source-over on encoded
  sRGB, :func:`~alpha_audit.color.composite_paint` ``css``) over that pixel's
  backdrop, is nearest; edge pixels follow their nearest fully covered pixel;
* the **drawn** colour is the median of a paint's fully covered pixels,
  **behind** the median of the hidden capture under them, **around** the
  median of the hidden capture in a ring of ``2 * scale`` device pixels just
  outside the touched pixels;
* **contrast** (WCAG 2.2) per fully covered pixel against the backdrop at the
  same pixel: worst (minimum) and median;
* **coverage** per touched pixel, ``q = (D - B)·(P - B) / |P - B|²`` in encoded
  values with ``P`` the drawn colour, clipped to [0, 1]
  (:func:`~alpha_audit.color.coverage_stats`);
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
    srgb_decode,
)
from alpha_audit.model import Icon, Location
from alpha_audit.observed import (
    MEASURED,
    NO_INTERIOR,
    Coverage,
    IconMatch,
    MeasuredPaint,
    Prediction,
)
from alpha_audit.pages.capture import Capture, FoundIcon

__all__ = [
    "DeclaredPaint",
    "PageContext",
    "declared_paints",
    "icon_name",
    "icon_region",
    "measure_capture",
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


def _assign(
    full: NDArray[np.bool_],
    touched: NDArray[np.bool_],
    drawn: NDArray[np.float64],
    behind: NDArray[np.float64],
    paints: Sequence[DeclaredPaint],
) -> NDArray[np.int64]:
    """Paint index per pixel (-1 for none): nearest css-composited colour, then spread."""
    labels = np.full(full.shape, -1, dtype=np.int64)
    known = [k for k, p in enumerate(paints) if p.color is not None]
    if len(known) <= 1:
        labels[touched] = known[0] if known else 0
        return labels
    b_lin = srgb_decode(behind[full] / 255.0)
    distances = []
    for k in known:
        paint = paints[k]
        assert paint.color is not None  # known paints have a colour
        shown = composite_paint(paint.color, b_lin, 1.0, min(1.0, paint.opacity), "css")
        codes = np.rint(np.clip(_encode(shown), 0, 1) * 255.0)
        distances.append(np.abs(codes - drawn[full]).sum(axis=-1))
    nearest = np.asarray(known)[np.argmin(np.stack(distances), axis=0)]
    labels[full] = nearest
    return _spread(labels, touched)


def _encode(linear: NDArray[np.float64]) -> NDArray[np.float64]:
    from alpha_audit.color import srgb_encode

    return srgb_encode(linear)


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


def _measure_icon(
    capture: Capture,
    icon: FoundIcon,
    page: PageContext,
    manifest_icon: Icon | None,
    match: IconMatch,
    locate: Locate | None = None,
) -> list[MeasuredPaint]:
    ring = ring_width(capture.scale)
    rows, cols, grown_rows, grown_cols = icon_region(capture, icon.box, ring)
    drawn_all = capture.drawn[grown_rows, grown_cols].astype(np.float64)
    hidden_all = capture.hidden[grown_rows, grown_cols].astype(np.float64)
    inside = np.zeros(drawn_all.shape[:2], dtype=bool)
    inside[
        rows.start - grown_rows.start : rows.stop - grown_rows.start,
        cols.start - grown_cols.start : cols.stop - grown_cols.start,
    ] = True
    touched = inside & (np.abs(drawn_all - hidden_all).max(axis=-1) > 0)
    full = _erode(touched)
    if touched.any() and not full.any():
        # Hairlines: no interior at this scale; the strongest differences stand in for it.
        strength = np.abs(drawn_all - hidden_all).max(axis=-1)
        full = touched & (strength >= 0.9 * strength[touched].max())
    around_mask = _dilate(touched, ring) & ~touched
    paints = declared_paints(icon) or (DeclaredPaint(None, 1.0, ("image",), False, "image"),)
    labels = _assign(full, touched, drawn_all, hidden_all, paints)
    name = icon_name(icon, manifest_icon)
    out = []
    for k, paint in enumerate(paints):
        mine = labels == k
        mine_full = full & mine
        drawn = behind = around = None
        drawn_lin = behind_lin = around_lin = None
        worst = median = None
        predictions: tuple[Prediction, ...] = ()
        model_source = model_alpha = model_opacity = drift = None
        coverage = Coverage(0, 0, 0.0, math.nan, math.nan)
        if mine_full.any():
            d_codes = drawn_all[mine_full]
            b_codes = hidden_all[mine_full]
            drawn, drawn_lin = _hex(np.median(d_codes, axis=0))
            behind, behind_lin = _hex(np.median(b_codes, axis=0))
            if around_mask.any():
                around, around_lin = _hex(np.median(hidden_all[around_mask], axis=0))
            per_pixel = contrast_ratio(from_8bit(d_codes), from_8bit(b_codes))
            worst, median = float(per_pixel.min()), float(np.median(per_pixel))
            # Coverage: the share of the way from backdrop to drawn colour, per touched pixel.
            p_codes = np.median(d_codes, axis=0)
            t = touched & mine
            diff = drawn_all[t] - hidden_all[t]
            span = p_codes - hidden_all[t]
            norm = (span * span).sum(axis=-1)
            q = np.where(norm > 0, (diff * span).sum(axis=-1) / np.where(norm > 0, norm, 1), 1.0)
            q = np.clip(q, 0.0, 1.0)
            stats = coverage_stats(q)
            coverage = Coverage(
                int(t.sum()), int(mine_full.sum()), stats.ink, stats.q50, stats.full_share
            )
            source, alpha = paint.color, 1.0
            if manifest_icon is not None and (paint.current or len(paints) == 1):
                source, alpha = manifest_icon.linear, float(manifest_icon.alpha)
            if source is not None:
                model_source = linear_to_hex(source)
                model_alpha, model_opacity = alpha, min(1.0, paint.opacity)
                predictions = _predictions(drawn_lin, behind_lin, source, alpha, model_opacity)
                drift = min(p.drift for p in predictions) if predictions else None
        painted = (
            "image"
            if paint.color is None
            else ("currentColor" if paint.current else linear_to_hex(paint.color))
        )
        gated = (
            None
            if drawn_lin is None or behind_lin is None
            else float(judged_contrast(drawn_lin, behind_lin))
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
                paint=painted,
                kinds=paint.kinds,
                declared=None if paint.color is None else linear_to_hex(paint.color),
                declared_opacity=min(1.0, paint.opacity),
                drawn=drawn,
                drawn_linear=drawn_lin,
                behind=behind,
                behind_linear=behind_lin,
                around=around,
                around_linear=around_lin,
                coverage=coverage,
                contrast=gated,
                contrast_worst=worst,
                contrast_median=median,
                model_source=model_source,
                model_alpha=model_alpha,
                model_opacity=model_opacity,
                predictions=predictions,
                render_drift=drift,
                box=icon.box,
                status=MEASURED if gated is not None else NO_INTERIOR,
                file=page.file,
                locations=() if locate is None else locate(icon, paint.index),
            )
        )
    return out


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
