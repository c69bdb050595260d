"""A page held still before it is captured, and a page that would not hold still, refused.

The script is ``still.js``.

A verdict must not depend on when the screenshot was taken: a CSS animation on an
icon's colour gave three identical runs the exits 1, 1 and 0.  :func:`hold_still`
stops what moves, in every engine, through the DOM's own interfaces:

* every animation ``document.getAnimations()`` (and each open shadow root's)
  lists, CSS animations, CSS transitions and scripted ones alike: one that ends
  is finished (the page as it rests once it has played: a fade-in ends shown),
  one that never ends is paused at the start of its first iteration (the same
  frame on every run, whatever the phase it had reached); SVG animations
  (SMIL) are paused at time 0 and media paused;
* a style sheet, first in the document and each open shadow root, in a
  cascade layer of its own (the first layer's ``!important`` declarations win
  over every later layer and every unlayered one, CSS Cascade 5, section 6.4):
  no transition (the icons are hidden at once for the second capture), every
  new animation paused, carets transparent;
* in the page's own world, every pending timer, interval, animation frame and
  idle callback cancelled, so no script changes the page between the captures
  (time stands still for the page: nothing scheduled runs).

What is left moving (an animated image, a video frame, a canvas drawn by a
worker) :func:`check_still` finds by comparing two captures of the icons as
drawn, taken around the capture with them hidden; a difference makes the page
state a problem (:class:`PageUnstable`), never a verdict.
"""

from __future__ import annotations

from importlib import resources

import numpy as np
from numpy.typing import NDArray

from alpha_audit.browser import Browser, BrowserError

__all__ = ["MAX_CANCELLED", "PageUnstable", "check_still", "hold_still"]

MAX_CANCELLED = 1_000_000  # timer and frame ids cancelled at most (ids count up from 1)


def _source() -> str:
    return resources.files("alpha_audit.pages").joinpath("still.js").read_text(encoding="utf-8")


class PageUnstable(BrowserError):
    """The page kept changing between two captures of one state: not judged."""


def hold_still(browser: Browser) -> None:
    """Stop the page's animations, transitions, timers and frame callbacks (see above)."""
    source = _source()
    browser.evaluate(f"({source}).hold()", isolated=browser.ISOLATED_SCRIPTS)
    browser.evaluate(f"({source}).quiet({MAX_CANCELLED})", isolated=False)


# How much two captures of a still page may differ: rendering, not motion (check_still).
NOISE_CODES = 8
NOISE_SHARE = 0.01


def check_still(first: NDArray[np.uint8], second: NDArray[np.uint8]) -> None:
    """Raise :class:`PageUnstable` unless two captures of the icons as drawn agree.

    An engine may raster the same still page a little differently the second time
    (Chromium at device scale 1: a dozen edge pixels, at most 6 codes, every time), so
    up to :data:`NOISE_SHARE` of the pixels may differ by at most :data:`NOISE_CODES`
    codes; what moves differs by more (an animated image, a video, a canvas).

    >>> still = np.zeros((10, 10, 3), dtype=np.uint8)
    >>> check_still(still, still.copy())
    >>> noise = still.copy(); noise[0, 0, 1] = NOISE_CODES
    >>> check_still(still, noise)  # one pixel of 100, a few codes: rendering, not motion
    >>> moved = still.copy(); moved[0, 0, 1] = NOISE_CODES + 1
    >>> check_still(still, moved)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    alpha_audit.pages.stillness.PageUnstable: the page kept changing ... (1 of 100 pixels ...
    """
    if first.shape == second.shape:
        delta = np.abs(first.astype(np.int16) - second.astype(np.int16)).max(axis=-1)
        changed = int((delta > 0).sum())
        if int(delta.max(initial=0)) <= NOISE_CODES and changed <= NOISE_SHARE * delta.size:
            return
    else:
        changed = first.shape[0] * first.shape[1]
    total = first.shape[0] * first.shape[1]
    raise PageUnstable(
        "the page kept changing between two captures of the same state "
        f"({changed} of {total} pixels differ) although its animations, transitions, timers "
        "and animation frames were stopped: something alpha-audit cannot pause (an "
        "animated image, a video, a canvas or a worker) moves; the state is not judged"
    )
