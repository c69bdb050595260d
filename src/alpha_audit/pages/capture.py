"""One page in one state: load it, find its icons, capture it as drawn and with them hidden.

Once the page is held still (:mod:`alpha_audit.pages.stillness`), three
screenshots per page and state, of the box holding every icon (plus a margin
for the ring around them), at the browser's device scale: the icons as drawn,
then all of them ``visibility: hidden`` at once, then as drawn again.  What
the second shows is the backdrop the browser composited behind them; the third
must equal the first, or the page state is a problem (it still moves).
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
from alpha_audit.errors import UsageError
from alpha_audit.pages.cascade import IconSources, collect_sources
from alpha_audit.pages.states import State
from alpha_audit.pages.stillness import check_still, hold_still
from alpha_audit.safe_text import MAX_NAME, safe_text, shorten

__all__ = [
    "ICON_KINDS",
    "MARGIN",
    "MAX_DOM_PATH",
    "Capture",
    "FoundIcon",
    "capture_page",
    "check_globals",
]

MARGIN = 4  # CSS pixels of backdrop kept around the icons' box (the ring "around" each icon)
# Bounds on what a page supplies (docs/ci.md, "Every bound"): a DOM path is shown, so it is
# shortened; the probe sends at most MAX_GEOMETRY characters of path data (probe.js).
MAX_DOM_PATH = 1000
MAX_GEOMETRY = 262_144
ICON_KINDS = ("svg", "use", "img", "mask", "selector")
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
# The values each Storybook global can take, where the Storybook says: a toolbar's
# items (globalTypes[name].toolbar.items), and @storybook/addon-themes' themes (its
# decorator announces them on the channel, which keeps the last message of each kind).
# Read in the page's own world (an isolated one cannot see its globals): data only.
_TOOLBAR = (
    "(() => { const p = window.__STORYBOOK_PREVIEW__; const out = {};"
    " if (!p) return out;"
    " const store = p.storyStoreValue || p.storyStore || {};"
    " const types = (store.projectAnnotations || {}).globalTypes || {};"
    " for (const [name, type] of Object.entries(types)) {"
    "  const items = (type && type.toolbar && type.toolbar.items) || [];"
    "  const values = items.map((i) => (i && typeof i === 'object' ? i.value : i))"
    "   .filter((v) => typeof v === 'string');"
    "  if (values.length) out[name] = values; }"
    " const themes = ((p.channel && p.channel.data) || {})['storybook/themes/REGISTER_THEMES'];"
    " const said = Array.isArray(themes) ? themes[0] : null;"
    " if (said && Array.isArray(said.themes)) out.theme = said.themes.filter("
    "  (v) => typeof v === 'string');"
    " return out; })()"
)
MAX_TOOLBAR_VALUES = 256  # values of one global a page may name (a refusal lists them)


def check_globals(browser: Browser, state: State) -> None:
    """Refuse a state's Storybook global whose value is none the Storybook offers.

    A value its toolbar (or the themes addon) does not list renders the story
    unstyled without a word, so the audit would judge a theme no one ships.  A
    global the Storybook declares nowhere cannot be checked and is let through.
    """
    known: Any = browser.evaluate(_TOOLBAR)
    if not isinstance(known, dict):
        return
    for name, value in state.globals:
        values = known.get(name)
        if not isinstance(values, list) or not values:
            continue
        allowed = [str(v) for v in values[:MAX_TOOLBAR_VALUES]]
        if value not in allowed:
            raise UsageError(
                safe_text(
                    f"`globals` {name}:{value}: the Storybook's {name} is one of "
                    f"{', '.join(allowed)}; a value it does not offer would audit an "
                    "unstyled story"
                )
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


def _text(value: object, limit: int) -> str | None:
    """A string the page supplied, or ``None`` when it is missing or longer than ``limit``."""
    return value if isinstance(value, str) and len(value) <= limit else None


def _number(value: object) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise TypeError(f"{value!r:.40} is not a finite number")
    return float(value)


def _found_icon(raw: Any) -> FoundIcon:
    """One icon of the probe's answer, checked; names the page supplied, bounded.

    The DOM path (ids are the page's) is shortened to :data:`MAX_DOM_PATH`
    characters, start and end kept; a key (``data-icon`` value, sprite id,
    file name) longer than :data:`~alpha_audit.safe_text.MAX_NAME` matches no
    manifest name, so it is dropped; a paint's colour text longer than that is
    no colour an engine computes.
    """
    kind = raw["kind"]
    if kind not in ICON_KINDS:
        raise TypeError(f"icon kind {kind!r:.40}")
    path = raw["path"]
    if not isinstance(path, str):
        raise TypeError("a DOM path that is not text")
    keys = raw["keys"]
    paints = []
    for paint in raw["paints"]:
        kinds = tuple(k for k in paint["kinds"] if k in ("fill", "stroke"))
        color = _text(paint["color"], MAX_NAME)
        current = paint["current"]
        if color is None or len(kinds) != len(paint["kinds"]) or not isinstance(current, bool):
            raise TypeError("a paint of another shape")
        opacity = _number(paint["opacity"])
        paints.append(
            {"color": color, "opacity": opacity, "kinds": list(kinds), "current": current}
        )
    box = tuple(_number(raw["box"][k]) for k in range(4))
    return FoundIcon(
        kind,
        shorten(path, MAX_DOM_PATH),
        (box[0], box[1], box[2], box[3]),
        {
            "data": _text(keys["data"], MAX_NAME),
            "sprite": _text(keys["sprite"], MAX_NAME),
            "file": _text(keys["file"], MAX_NAME),
            "geometry": _text(keys["geometry"], MAX_GEOMETRY),
        },
        tuple(paints),
    )


def _found_icons(found: Any, label: str) -> list[FoundIcon]:
    """The probe's icons; an answer of another shape is a :class:`BrowserError`.

    Where the engine has no isolated world (WebKitGTK), the probe runs beside
    the page's scripts, which may have replaced what it calls: its answer is
    data from the page like any other.
    """
    try:
        icons = found["icons"]
        if not isinstance(icons, list):
            raise TypeError("icons is not a list")
        return [_found_icon(raw) for raw in icons]
    except (KeyError, IndexError, TypeError, ValueError) as exc:
        raise BrowserError(f"{label}: the icon probe returned malformed data ({exc})") from None


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
        if state.globals:
            check_globals(browser, state)
    _mark_html(browser, state)
    browser.evaluate(_SETTLED, isolated=isolated)
    hold_still(browser)  # before the icons' boxes are read: a finished animation moves them
    browser.evaluate(f"(globalThis.{_PROBE} = {_probe_source()}, true)", isolated=isolated)
    options = {"selector": selector, "attribute": attribute, "maxSize": max_icon_size}
    found: Any = browser.evaluate(f"{_PROBE}.find({json.dumps(options)})", isolated=isolated)
    if not isinstance(found, dict) or not isinstance(found.get("height"), int | float):
        raise BrowserError(f"{browser.LABEL}: the icon probe returned malformed data")
    page_h = int(min(found["height"], 1 << 20))
    if page_h > height and height < 4096:
        # Icons below the fold: make the viewport as tall as the page (4096 px at most).
        browser.set_viewport(width, min(page_h, 4096), scale)
        height = min(page_h, 4096)
        browser.evaluate(_SETTLED, isolated=isolated)
        hold_still(browser)
        found = browser.evaluate(f"{_PROBE}.find({json.dumps(options)})", isolated=isolated)
    icons = _found_icons(found, browser.LABEL)
    if not icons:
        empty = np.zeros((0, 0, 3), dtype=np.uint8)
        return Capture((), None, scale, empty, empty)
    clip = _union(icons, width, height)
    drawn = _png(browser.screenshot(clip))
    browser.evaluate(f"{_PROBE}.hide(true)", isolated=isolated)
    hidden = _png(browser.screenshot(clip))
    browser.evaluate(f"{_PROBE}.hide(false)", isolated=isolated)
    check_still(drawn, _png(browser.screenshot(clip)))
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
