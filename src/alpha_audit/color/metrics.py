"""Luminance, WCAG contrast ratio and CIEDE2000 on linear sRGB.

Channels are on the last axis; the leading shape is kept.
"""

from __future__ import annotations

import sys
import threading
import warnings
from functools import cache
from types import ModuleType

import numpy as np
from numpy.typing import ArrayLike, NDArray

from alpha_audit.constants import LUMINANCE_WEIGHTS

__all__ = [
    "contrast_from_luminance",
    "contrast_ratio",
    "delta_e_2000",
    "delta_e_2000_lab",
    "linear_to_lab",
    "relative_luminance",
]


# CSS Color 4, 10.2: linear sRGB -> CIE XYZ (D65), exact rational entries.
# colour-science's rounded sRGB matrix moves CIEDE2000 by > 0.1 on some
# near-opposite-hue pairs, so the exact one is used.
LINEAR_SRGB_TO_XYZ = np.array(
    [
        [506752 / 1228815, 87881 / 245763, 12673 / 70218],
        [87098 / 409605, 175762 / 245763, 12673 / 175545],
        [7918 / 409605, 87881 / 737289, 1001167 / 1053270],
    ]
)
# CSS Color 4 D65 white, as chromaticity (x, y) = (0.3127, 0.3290).
D65_XY = np.array([0.3127, 0.3290])


@cache
def _colour() -> ModuleType:
    """colour-science, imported on first use: its package import costs ~0.3 s."""
    with _IMPORTING:
        # colour-science announces its optional SciPy/Matplotlib features at import.
        # A narrow filter, not catch_warnings(): that swaps the process-wide filters
        # and would hide the main thread's warnings while this runs in the background.
        warnings.filterwarnings(
            "ignore", message=r'"\w+" related API features are not available', module=r"colour\."
        )
        import colour

    return colour


_IMPORTING = threading.Lock()  # one import at a time, so the cache fills once


def preload_colour() -> None:
    """Start importing colour-science in a background thread and return at once.

    For a caller about to wait on something else (the render workers): the
    import, a third of a small check's own CPU time, then runs while this
    process would sit idle, and the first colour-science call finds it done
    (or waits for it, never imports twice).
    """
    if "colour" not in sys.modules:
        threading.Thread(target=_colour, name="alpha-audit-colour-import", daemon=True).start()


def relative_luminance(linear: ArrayLike) -> NDArray[np.float64]:
    """WCAG relative luminance ``0.2126 R + 0.7152 G + 0.0722 B`` of linear sRGB.

    Summed left to right so that table-driven fast paths reproduce it bit for bit.

    >>> float(relative_luminance([1.0, 1.0, 1.0]))
    1.0
    """
    c = np.asarray(linear, dtype=np.float64)
    wr, wg, wb = LUMINANCE_WEIGHTS
    return wr * c[..., 0] + wg * c[..., 1] + wb * c[..., 2]


def contrast_from_luminance(y1: ArrayLike, y2: ArrayLike) -> NDArray[np.float64]:
    """WCAG contrast ratio ``(max + 0.05) / (min + 0.05)`` of two luminances.

    >>> float(contrast_from_luminance(1.0, 0.0))
    21.0
    """
    a = np.asarray(y1, dtype=np.float64)
    b = np.asarray(y2, dtype=np.float64)
    return (np.maximum(a, b) + 0.05) / (np.minimum(a, b) + 0.05)


def contrast_ratio(linear1: ArrayLike, linear2: ArrayLike) -> NDArray[np.float64]:
    """WCAG contrast ratio of two linear sRGB colours (symmetric, >= 1)."""
    return contrast_from_luminance(relative_luminance(linear1), relative_luminance(linear2))


def linear_to_lab(linear: ArrayLike) -> NDArray[np.float64]:
    """CIELAB (D65) of linear sRGB via the CSS Color 4 XYZ matrix."""
    c = np.asarray(linear, dtype=np.float64)
    xyz = c @ LINEAR_SRGB_TO_XYZ.T
    return np.asarray(_colour().XYZ_to_Lab(xyz, D65_XY), dtype=np.float64)


def delta_e_2000_lab(lab1: ArrayLike, lab2: ArrayLike) -> NDArray[np.float64]:
    """CIEDE2000 of two CIELAB colours (colour-science's implementation)."""
    return np.asarray(_colour().difference.delta_E_CIE2000(lab1, lab2), dtype=np.float64)


def delta_e_2000(linear1: ArrayLike, linear2: ArrayLike) -> NDArray[np.float64]:
    """CIEDE2000 colour difference of two linear sRGB colours.

    >>> round(float(delta_e_2000([1.0, 1.0, 1.0], [0.0, 0.0, 0.0])), 6)
    100.0
    """
    return delta_e_2000_lab(linear_to_lab(linear1), linear_to_lab(linear2))
