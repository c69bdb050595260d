"""Extended-coefficient compositing in linear sRGB (paper, Section 3), and what browsers do.

``raw = Cb + a (Cs - Cb)`` is ordinary source-over on an opaque canvas written
as a scaling of the object-background difference; any finite real ``a`` is
allowed and the result is clipped per channel to [0, 1].  Antialiased coverage
``q`` stays separate from ``a`` (paper, Appendix A.2).

Two pipelines draw a paint (see docs/model.md):

* ``linear`` -- the paper: the WebGL shader, an SVG filter in linearRGB or
  exported per-theme colours; any real ``a``, clipped per channel in linear light;
* ``css`` -- what a browser does with CSS ``opacity`` or ``rgba()``: source-over
  on gamma-encoded sRGB values (CSS Compositing 1, section 5.1, applied to the
  encoded values as CSS Color 3 section 5 / SVG 1.1 ``color-interpolation:
  sRGB`` prescribe), then 8-bit; ``a`` is limited to [0, 1].
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from alpha_audit.color.srgb import srgb_decode, srgb_encode

__all__ = [
    "PIPELINES",
    "Pipeline",
    "composite_coverage",
    "composite_css",
    "composite_css_least",
    "composite_extended",
    "composite_paint",
    "composite_raw",
    "difference_blend",
    "exclusion_blend",
]

Pipeline = Literal["linear", "css"]
# How close (in 8-bit code units) a css blend must be to a half code to be that tie:
# far above float64 noise on codes (~1e-13), far below any real blend's distance from
# one (an alpha of d decimals on integer codes gives multiples of 10**-d).
_TIE = 1e-9
PIPELINES: tuple[Pipeline, ...] = ("linear", "css")


def composite_raw(
    source: ArrayLike, background: ArrayLike, alpha: ArrayLike
) -> NDArray[np.float64]:
    """Unclipped ``Cb + a (Cs - Cb)``; ``alpha`` broadcasts against the leading shape.

    >>> composite_raw([1.0, 0.5, 0.0], [0.5, 0.5, 0.5], 2.0).tolist()
    [1.5, 0.5, -0.5]
    """
    s = np.asarray(source, dtype=np.float64)
    b = np.asarray(background, dtype=np.float64)
    a = np.asarray(alpha, dtype=np.float64)[..., np.newaxis]
    return b + a * (s - b)


def composite_extended(
    source: ArrayLike, background: ArrayLike, alpha: ArrayLike
) -> NDArray[np.float64]:
    """``clip(Cb + a (Cs - Cb), 0, 1)`` per channel, the paper's displayed output.

    ``source`` and ``background`` are linear sRGB in [0, 1] with channels last;
    ``alpha`` has the leading shape (or broadcasts to it).

    >>> composite_extended([1.0, 0.5, 0.0], [0.5, 0.5, 0.5], 2.0).tolist()
    [1.0, 0.5, 0.0]
    """
    return np.clip(composite_raw(source, background, alpha), 0.0, 1.0)


def composite_coverage(
    source: ArrayLike, background: ArrayLike, alpha: ArrayLike, coverage: ArrayLike
) -> NDArray[np.float64]:
    """``q * clip(Cb + a (Cs - Cb)) + (1 - q) * Cb`` for an antialiased mask ``q``.

    ``coverage`` has the leading (pixel) shape; the coefficient scales the colour
    difference, coverage only mixes the clipped output with the canvas.
    """
    b = np.asarray(background, dtype=np.float64)
    q = np.asarray(coverage, dtype=np.float64)[..., np.newaxis]
    out = composite_extended(source, b, alpha)
    return q * out + (1.0 - q) * b


def _check_css_alpha(alpha: NDArray[np.float64]) -> None:
    if np.any((alpha < 0.0) | (alpha > 1.0)):
        bad = float(alpha[(alpha < 0.0) | (alpha > 1.0)].flat[0])
        raise ValueError(
            f"alpha {bad:g} cannot be expressed in CSS (opacity is limited to [0, 1]); "
            "use the linear pipeline or export per-theme colours"
        )


def composite_css(
    source: ArrayLike, background: ArrayLike, alpha: ArrayLike
) -> NDArray[np.float64]:
    """What a browser shows for CSS ``opacity: a``: blend the encoded values, then 8-bit.

    ``source`` and ``background`` are linear sRGB (channels last), as everywhere
    in alpha-audit; the blend ``Cb' + a (Cs' - Cb')`` happens on their sRGB
    encodings, is rounded to 8-bit codes (half to even) and returned as linear
    light again.  ``alpha`` outside [0, 1] raises :class:`ValueError`: CSS
    clamps it, so an extended coefficient cannot be drawn this way.

    >>> from alpha_audit.color.srgb import hex_to_linear, linear_to_hex
    >>> linear_to_hex(composite_css(hex_to_linear("#ee7733"), hex_to_linear("#ffffff"), 0.6))
    '#f5ad85'
    """
    a = np.asarray(alpha, dtype=np.float64)
    _check_css_alpha(a)
    s = srgb_encode(np.asarray(source, dtype=np.float64))
    b = srgb_encode(np.asarray(background, dtype=np.float64))
    codes = np.clip(b + a[..., np.newaxis] * (s - b), 0.0, 1.0) * 255.0
    # An 8-bit colour's encoding comes back from linear light within ~1e-13 of code/255,
    # so a blend exactly half-way between two codes (alpha 0.9 of 17 over 32 is 18.5)
    # would round by that noise; snapped to the half, it rounds half to even as written.
    halves = np.round(codes * 2.0) / 2.0
    codes = np.where(np.abs(codes - halves) < _TIE, halves, codes)
    return srgb_decode(np.rint(codes) / 255.0)  # np.rint rounds half to even


def composite_css_least(
    source: ArrayLike, background: ArrayLike, alpha: ArrayLike
) -> NDArray[np.float64]:
    """Of what browsers may show for CSS ``opacity: a``, the colour nearest the backdrop.

    Engines blend in 8 bits in their own ways: the opacity itself is quantised to
    an 8-bit alpha (``a * 255`` rounded either way) and each blended channel is
    rounded by the engine's rule, so one paint can come out a code apart in two
    browsers.  Here the alpha is taken down to ``floor(a * 255) / 255`` and every
    channel rounded towards the backdrop's: a fix judged on this colour passes in
    every engine, not just in the formula (:func:`composite_css` rounds half to
    even).  Opacity 1 is the source itself.

    >>> from alpha_audit.color.srgb import hex_to_linear, linear_to_hex
    >>> grey, white = hex_to_linear("#57606a"), hex_to_linear("#ffffff")
    >>> linear_to_hex(composite_css(grey, white, 0.5))
    '#abb0b4'
    >>> linear_to_hex(composite_css_least(grey, white, 0.5))
    '#acb0b5'
    """
    a = np.asarray(alpha, dtype=np.float64)
    _check_css_alpha(a)
    a8 = np.floor(a * 255.0 + 1e-9) / 255.0
    s = srgb_encode(np.asarray(source, dtype=np.float64))
    b = srgb_encode(np.asarray(background, dtype=np.float64))
    codes = np.clip(b + a8[..., np.newaxis] * (s - b), 0.0, 1.0) * 255.0
    # Towards the backdrop: down where the paint is above it, up where below.
    codes = np.where(s > b, np.floor(codes + 1e-6), np.ceil(codes - 1e-6))
    return srgb_decode(codes / 255.0)


def composite_paint(
    source: ArrayLike,
    background: ArrayLike,
    alpha: ArrayLike,
    opacity: ArrayLike = 1.0,
    pipeline: Pipeline = "linear",
) -> NDArray[np.float64]:
    """Displayed colour of a paint at opacity ``o`` (times coverage) under ``pipeline``.

    ``linear``: ``o * clip(Cb + a (Cs - Cb)) + (1 - o) * Cb`` in linear light
    (the paper's coverage form, unrounded); ``css``: the browser multiplies
    every opacity on the way down, so the encoded values blend with ``a * o``
    and the result is 8-bit.  Unknown pipelines raise :class:`ValueError`
    listing the valid ones.

    >>> composite_paint([1.0, 1.0, 1.0], [0.0, 0.0, 0.0], 2.0, 0.25).tolist()
    [0.25, 0.25, 0.25]
    """
    if pipeline == "linear":
        return composite_coverage(source, background, alpha, opacity)
    if pipeline == "css":
        a = np.asarray(alpha, dtype=np.float64)
        _check_css_alpha(a)
        return composite_css(source, background, a * np.asarray(opacity, dtype=np.float64))
    raise ValueError(f"unknown pipeline {pipeline!r}; use one of {', '.join(PIPELINES)}")


def difference_blend(source: ArrayLike, background: ArrayLike) -> NDArray[np.float64]:
    """W3C Compositing ``difference``: ``|Cs - Cb|`` (the paper's control)."""
    return np.abs(np.asarray(source, dtype=np.float64) - np.asarray(background, dtype=np.float64))


def exclusion_blend(source: ArrayLike, background: ArrayLike) -> NDArray[np.float64]:
    """W3C Compositing ``exclusion``: ``Cs + Cb - 2 Cs Cb`` (the paper's control)."""
    s = np.asarray(source, dtype=np.float64)
    b = np.asarray(background, dtype=np.float64)
    return s + b - 2.0 * s * b
