"""CSS Color 4 gamut mapping to sRGB, vectorised over many colours at once.

CSS Color 4, section 13.2.2 ("CSS Gamut Mapping to an RGB Destination",
https://www.w3.org/TR/css-color-4/#binsearch): keep the colour's OKLCH
lightness and hue and binary-search its chroma until clipping the result to
sRGB moves it less than one just-noticeable difference (deltaEOK < 0.02),
then clip.  coloraide implements the same algorithm one colour at a time
(``fit("srgb", method="minde-chroma", pspace="oklch", jnd=0.02)``, about 30
conversions per colour); here every colour takes the same steps in numpy,
each with its own search interval and stopping point, so thousands of colours
cost a few dozen array operations.  Agreement with coloraide is tested on
random colours (tests/color/test_gamut.py) and timed in
benchmarks/bench_gamut_map.py.

Conversions use coloraide's own matrices (linear sRGB <-> XYZ D65 <-> LMS <->
OKLab, module constants of ``coloraide.spaces``), so a colour takes the same
search path as in coloraide up to float rounding; the sRGB transfer is CSS
Color 4's, extended sign-symmetrically, as coloraide's.
"""

from __future__ import annotations

from functools import cache

import numpy as np
from numpy.typing import ArrayLike, NDArray

from alpha_audit.color.transfer import srgb_decode, srgb_encode

__all__ = ["JND", "map_to_srgb"]

JND = 0.02  # CSS Color 4, 13.2.2: "a JND of 0.02" in deltaEOK
# CSS Color 4, 13.2.2: "epsilon = 0.0001", the chroma interval at which the search
# stops, and the distance under the JND that is close enough.
_EPSILON = 0.0001
# coloraide treats lightness within 1e-6 of white's as white (fit_minde_chroma).
_WHITE_TOLERANCE = 1e-6


@cache
def _matrices() -> tuple[NDArray[np.float64], ...]:
    """(linear sRGB -> LMS, LMS^(1/3) -> OKLab, OKLab -> LMS^(1/3), LMS -> linear sRGB)."""
    from coloraide.spaces import oklab, srgb_linear

    to_lms = np.array(oklab.XYZD65_TO_LMS) @ np.array(srgb_linear.RGB_TO_XYZ)
    from_lms = np.array(srgb_linear.XYZ_TO_RGB) @ np.array(oklab.LMS_TO_XYZD65)
    return to_lms, np.array(oklab.LMS3_TO_OKLAB), np.array(oklab.OKLAB_TO_LMS3), from_lms


def _srgb_to_oklab(encoded: NDArray[np.float64]) -> NDArray[np.float64]:
    to_lms, to_lab, _, _ = _matrices()
    return np.asarray(np.cbrt(srgb_decode(encoded) @ to_lms.T) @ to_lab.T, dtype=np.float64)


def _oklab_to_srgb(oklab: NDArray[np.float64]) -> NDArray[np.float64]:
    """Encoded sRGB, unbounded (channels may lie outside [0, 1])."""
    _, _, to_lms3, from_lms = _matrices()
    return np.asarray(srgb_encode(((oklab @ to_lms3.T) ** 3) @ from_lms.T), dtype=np.float64)


def map_to_srgb(encoded: ArrayLike) -> NDArray[np.float64]:
    """CSS Color 4 gamut mapping of unbounded encoded sRGB colours into [0, 1].

    ``encoded`` has channels on the last axis and may lie outside [0, 1] (any
    CSS colour converted to sRGB without clipping is such a triple).  Colours
    already in gamut come back unchanged.

    >>> map_to_srgb([0.5, 0.25, 1.0]).tolist()
    [0.5, 0.25, 1.0]
    >>> bool(np.all((map_to_srgb([1.2, -0.1, 0.3]) >= 0) & (map_to_srgb([1.2, -0.1, 0.3]) <= 1)))
    True
    """
    rgb = np.asarray(encoded, dtype=np.float64)
    shape = rgb.shape
    flat = rgb.reshape(-1, 3)
    out = np.clip(flat, 0.0, 1.0)
    outside = np.any((flat < 0.0) | (flat > 1.0), axis=1)
    if not outside.any():
        return out.reshape(shape)
    index = np.flatnonzero(outside)
    lab = _srgb_to_oklab(flat[index])
    lightness = lab[:, 0]
    chroma = np.hypot(lab[:, 1], lab[:, 2])
    hue = np.arctan2(lab[:, 2], lab[:, 1])
    white_l = float(_srgb_to_oklab(np.ones((1, 3)))[0, 0])
    # Out of the lightness range: white or black (13.2.2, steps 4-5).
    white = (lightness >= white_l) | np.isclose(lightness, white_l, atol=_WHITE_TOLERANCE, rtol=0)
    black = lightness <= 0.0
    result = np.clip(flat[index], 0.0, 1.0)
    result[white] = 1.0
    result[black] = 0.0
    # Clipping alone is enough when it moves the colour less than the JND.
    moved = np.linalg.norm(_srgb_to_oklab(result) - lab, axis=1)
    active = ~white & ~black & (moved > JND)
    low = np.zeros_like(chroma)
    high = chroma.copy()
    low_in_gamut = np.ones_like(active)
    while True:
        active &= (high - low) > _EPSILON
        if not active.any():
            break
        k = np.flatnonzero(active)
        value = (high[k] + low[k]) * 0.5
        current = np.stack([lightness[k], value * np.cos(hue[k]), value * np.sin(hue[k])], axis=1)
        candidate = _oklab_to_srgb(current)
        in_gamut = np.all((candidate >= 0.0) & (candidate <= 1.0), axis=1)
        raise_low = low_in_gamut[k] & in_gamut
        low[k[raise_low]] = value[raise_low]
        # Out of gamut: clip, and compare the clipped colour with the candidate.
        out_k = k[~raise_low]
        if out_k.size:
            clipped = np.clip(candidate[~raise_low], 0.0, 1.0)
            result[out_k] = clipped
            de = np.linalg.norm(_srgb_to_oklab(clipped) - current[~raise_low], axis=1)
            v = value[~raise_low]
            under = de < JND
            close = under & ((JND - de) < _EPSILON)
            active[out_k[close]] = False  # close enough to the JND: done
            tune = under & ~close
            low_in_gamut[out_k[tune]] = False
            low[out_k[tune]] = v[tune]
            high[out_k[~under]] = v[~under]
    out[index] = result
    return out.reshape(shape)
