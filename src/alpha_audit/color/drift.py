"""What alpha does to a colour: CIEDE2000 drift and OKLCH hue shift.

Drift compares the source colour with the displayed one (same leading shape,
channels last, linear sRGB); it is zero at ``a = 1`` on an opaque paint and
grows as the coefficient pushes the colour towards or away from the canvas.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from alpha_audit.color.metrics import delta_e_2000
from alpha_audit.color.oklch import linear_to_oklch

__all__ = ["ACHROMATIC_CHROMA", "color_drift", "hue_shift", "oklch_degrees"]

# At or below this OKLab chroma the hue is powerless (missing).  CSS Color 4's
# sample code (conversions.js, OKLab_to_OKLCH) uses 0.000004 with its own
# XYZ -> LMS matrix, which maps D65 white exactly to a = b = 0; colour-science's
# XYZ_to_Oklab uses Ottosson's original matrix, which leaves exact greys with
# chroma up to 1.3e-4.  4e-4 lies above every grey and below every 8-bit colour
# one code away from grey (chroma >= 1.0e-3, #fffefe); tests/color says so.
ACHROMATIC_CHROMA = 4e-4


def oklch_degrees(linear: ArrayLike) -> NDArray[np.float64]:
    """OKLCH ``(L, C, h in degrees [0, 360))`` of linear sRGB; ``h`` is NaN when achromatic.

    The conversion is :func:`alpha_audit.color.oklch.linear_to_oklch` (one home
    for OKLab); here the hue is in degrees and powerless for greys (CSS Color 4).
    CSS Color 4 lists sRGB red as ``oklch(62.8% 0.2577 29.23)``, this gives hue
    29.227 (Ottosson's matrix was fitted to a slightly different XYZ; 0.007
    degrees is far below any hue difference the audit reports).

    >>> [round(float(v), 2) for v in oklch_degrees([1.0, 0.0, 0.0])]
    [0.63, 0.26, 29.23]
    """
    lch = linear_to_oklch(linear)
    hue = np.degrees(lch[..., 2]) % 360.0
    hue = np.where(lch[..., 1] <= ACHROMATIC_CHROMA, np.nan, hue)
    return np.stack([lch[..., 0], lch[..., 1], hue], axis=-1)


def hue_shift(source: ArrayLike, displayed: ArrayLike) -> NDArray[np.float64]:
    """Signed OKLCH hue change ``displayed - source`` in degrees, in [-180, 180).

    NaN where either colour is achromatic (its hue is powerless, CSS Color 4):
    a grey has no hue to shift, and a colour pushed to black or white has lost
    its hue altogether, which :func:`color_drift` measures.

    >>> float(hue_shift([1.0, 0.0, 0.0], [1.0, 0.0, 0.0]))
    0.0
    """
    h1 = oklch_degrees(source)[..., 2]
    h2 = oklch_degrees(displayed)[..., 2]
    return (h2 - h1 + 180.0) % 360.0 - 180.0


def color_drift(source: ArrayLike, displayed: ArrayLike) -> NDArray[np.float64]:
    """CIEDE2000 between the source colour and the displayed colour.

    >>> float(color_drift([0.2, 0.4, 0.6], [0.2, 0.4, 0.6]))
    0.0
    """
    return delta_e_2000(source, displayed)
