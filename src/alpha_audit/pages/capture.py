"""One page in one state: load it, find its icons, capture it as drawn and with them hidden.

Exactly two screenshots per page and state, of the box holding every icon
(plus a margin for the ring around them), at the browser's device scale: the
icons as drawn, then all of them ``visibility: hidden`` at once.  What the
second shows is the backdrop the browser composited behind them.
"""

from __future__ import annotations

import io
import json
import math
from dataclasses import dataclass, replace
from importlib import resources
from typing import Any

import numpy as np
from numpy.typing import NDArray
from PIL import Image

from alpha_audit.browser import Browser, BrowserError, Clip
from alpha_audit.pages.cascade import IconSources, collect_sources
from alpha_audit.pages.states import State

__all__ = ["MARGIN", "Capture", "FoundIcon", "capture_page"]

MARGIN = 4  # CSS pixels of backdrop kept around the icons' box (the ring "around" each icon)
_PROBE = "__alphaAuditProbe"
# Storybook 7-10 mark <body> once a story has rendered (or failed); a page is ready when
# loaded, its fonts are in and its images decoded.
_STORY_READY = (
    "(() => { const c = document.body && document.body.classList;"
    " if (!c) return false;"
    " if (c.contains('sb-show-errordisplay')) return 'error';"
    " const root = document.getElementById('storybook-root') || document.getElementById('root');"
    " return c.contains('sb-show-main') && !!root && root.childElementCount > 0"
    " && !c.contains('sb-show-preparing-story'); })()"
)
# Then quiet: no DOM change for QUIET_MS (a decorator's effect that sets the theme after
# the story rendered, a late class), at most SETTLE_MS in all.
QUIET_MS, SETTLE_MS = 100, 3000
_SETTLED = (
    "(async () => { await document.fonts.ready;"
    " await Promise.all(Array.from(document.images, (i) => i.decode().catch(() => null)));"
    " await new Promise((resolve) => { let timer; const start = performance.now();"
    "  const done = () => { observer.disconnect(); resolve(); };"
    "  const observer = new MutationObserver(() => { clearTimeout(timer);"
    f"   timer = setTimeout(done, performance.now() - start > {SETTLE_MS} ? 0 : {QUIET_MS}); }});"
    "  observer.observe(document, {subtree: true, attributes: true, childList: true,"
    "   characterData: true});"
    f"  timer = setTimeout(done, {QUIET_MS}); }});"
    " await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));"
    " return true; })()"
)


@dataclass(frozen=True)
class FoundIcon:
    """An icon as the probe reported it (see ``probe.js``)."""

    kind: str
    dom_path: str
    box: tuple[float, float, float, float]
    keys: dict[str, Any]
    paints: tuple[dict[str, Any], ...]
    sources: IconSources | None = None
    """Where its colours and its backdrop's are declared (:mod:`alpha_audit.pages.cascade`)."""


@dataclass(frozen=True)
class Capture:
    """The two captures of one page and state, and the icons in them.

    ``drawn`` and ``hidden`` are ``(H, W, 3)`` 8-bit sRGB; pixel ``(0, 0)`` is
    CSS point ``clip.x, clip.y``; ``scale`` device pixels per CSS pixel.
    """

    icons: tuple[FoundIcon, ...]
    clip: Clip | None
    scale: int
    drawn: NDArray[np.uint8]
    hidden: NDArray[np.uint8]


def _probe_source() -> str:
    return resources.files("alpha_audit.pages").joinpath("probe.js").read_text(encoding="utf-8")


def _png(data: bytes) -> NDArray[np.uint8]:
    with Image.open(io.BytesIO(data)) as image:
        return np.asarray(image.convert("RGB"), dtype=np.uint8)


def _union(icons: list[FoundIcon], width: int, height: int) -> Clip:
    """The whole-pixel box holding every icon and its margin, inside the viewport."""
    x0 = min(i.box[0] for i in icons) - MARGIN
    y0 = min(i.box[1] for i in icons) - MARGIN
    x1 = max(i.box[0] + i.box[2] for i in icons) + MARGIN
    y1 = max(i.box[1] + i.box[3] for i in icons) + MARGIN
    left, top = max(0, math.floor(x0)), max(0, math.floor(y0))
    right, bottom = min(width, math.ceil(x1)), min(height, math.ceil(y1))
    return Clip(left, top, max(1, right - left), max(1, bottom - top))


def _mark_html(browser: Browser, state: State) -> None:
    if not state.marks_html:
        return
    script = (
        "(() => { const html = document.documentElement;"
        f" for (const [k, v] of {json.dumps(list(state.attributes))}) html.setAttribute(k, v);"
        f" for (const c of {json.dumps(list(state.classes))}) html.classList.add(c);"
        " return true; })()"
    )
    browser.evaluate(script, isolated=browser.ISOLATED_SCRIPTS)


def capture_page(
    browser: Browser,
    url: str,
    state: State,
    *,
    storybook: bool,
    viewport: tuple[int, int],
    scale: int,
    selector: str | None,
    attribute: str,
    max_icon_size: int,
    sources: bool = True,
) -> Capture:
    """Load ``url`` in ``state`` and take the two captures (the colour scheme is the browser's).

    With ``sources``, each icon's :attr:`FoundIcon.sources` says which
    declarations set its colours, read after the captures (the icons shown
    again first), so that nothing of it can change what they show.
    """
    isolated = browser.ISOLATED_SCRIPTS
    width, height = viewport
    if (browser.scale, browser.viewport) != (scale, viewport):
        browser.set_viewport(width, height, scale)
    browser.open(url)
    if storybook:
        ready = browser.wait_for(_STORY_READY, isolated=isolated)
        if ready == "error":
            raise BrowserError("the story failed to render (Storybook shows its error display)")
    _mark_html(browser, state)
    browser.evaluate(_SETTLED, isolated=isolated)
    browser.evaluate(f"(globalThis.{_PROBE} = {_probe_source()}, true)", isolated=isolated)
    options = {"selector": selector, "attribute": attribute, "maxSize": max_icon_size}
    found: Any = browser.evaluate(f"{_PROBE}.find({json.dumps(options)})", isolated=isolated)
    if not isinstance(found, dict):
        raise BrowserError(f"{browser.LABEL}: the icon probe returned {type(found).__name__}")
    page_h = int(found["height"])
    if page_h > height and height < 4096:
        # Icons below the fold: make the viewport as tall as the page (4096 px at most).
        browser.set_viewport(width, min(page_h, 4096), scale)
        height = min(page_h, 4096)
        browser.evaluate(_SETTLED, isolated=isolated)
        found = browser.evaluate(f"{_PROBE}.find({json.dumps(options)})", isolated=isolated)
    icons = [
        FoundIcon(
            str(i["kind"]),
            str(i["path"]),
            (float(i["box"][0]), float(i["box"][1]), float(i["box"][2]), float(i["box"][3])),
            dict(i["keys"]),
            tuple(dict(p) for p in i["paints"]),
        )
        for i in found["icons"]
    ]
    if not icons:
        empty = np.zeros((0, 0, 3), dtype=np.uint8)
        return Capture((), None, scale, empty, empty)
    clip = _union(icons, width, height)
    drawn = _png(browser.screenshot(clip))
    browser.evaluate(f"{_PROBE}.hide(true)", isolated=isolated)
    hidden = _png(browser.screenshot(clip))
    expected = (clip.height * scale, clip.width * scale)
    if drawn.shape[:2] != expected or hidden.shape != drawn.shape:
        raise BrowserError(
            f"{browser.LABEL} returned a {drawn.shape[1]} x {drawn.shape[0]} capture for a "
            f"{expected[1]} x {expected[0]} box"
        )
    if sources:
        browser.evaluate(f"{_PROBE}.hide(false)", isolated=isolated)
        found_sources = collect_sources(browser, _PROBE, [i.paints for i in icons], url)
        icons = [replace(i, sources=s) for i, s in zip(icons, found_sources, strict=True)]
    return Capture(tuple(icons), clip, scale, drawn, hidden)
