"""OKLCH (Ottosson's Oklab in polar form) of linear sRGB, and back.

Oklab itself is colour-science's (``XYZ_to_Oklab`` / ``Oklab_to_XYZ``); the
XYZ step uses the same exact CSS Color 4 matrix as CIELAB in
:mod:`alpha_audit.color.metrics`, so both spaces see one linear sRGB.
Hue is in radians, in ``(-pi, pi]``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from alpha_audit.color.metrics import LINEAR_SRGB_TO_XYZ, _colour

__all__ = ["linear_to_oklch", "oklch_to_linear"]

_XYZ_TO_LINEAR_SRGB = np.linalg.inv(LINEAR_SRGB_TO_XYZ)


def linear_to_oklch(linear: ArrayLike) -> NDArray[np.float64]:
    """OKLCH ``(L, C, h)`` of linear sRGB, channels last, hue in radians.

    >>> lch = linear_to_oklch([1.0, 1.0, 1.0])
    >>> round(float(lch[0]), 4), bool(lch[1] < 1e-3)
    (1.0, True)
    """
    xyz = np.asarray(linear, dtype=np.float64) @ LINEAR_SRGB_TO_XYZ.T
    lab = np.asarray(_colour().XYZ_to_Oklab(xyz), dtype=np.float64)
    chroma = np.hypot(lab[..., 1], lab[..., 2])
    hue = np.arctan2(lab[..., 2], lab[..., 1])
    return np.stack([lab[..., 0], chroma, hue], axis=-1)


def oklch_to_linear(oklch: ArrayLike) -> NDArray[np.float64]:
    """Linear sRGB of OKLCH ``(L, C, h)`` (not clipped: out of gamut leaves [0, 1]).

    >>> lin = oklch_to_linear(linear_to_oklch([0.2, 0.5, 0.7]))
    >>> np.allclose(lin, [0.2, 0.5, 0.7])
    True
    """
    lch = np.asarray(oklch, dtype=np.float64)
    lab = np.stack(
        [lch[..., 0], lch[..., 1] * np.cos(lch[..., 2]), lch[..., 1] * np.sin(lch[..., 2])],
        axis=-1,
    )
    xyz = np.asarray(_colour().Oklab_to_XYZ(lab), dtype=np.float64)
    return xyz @ _XYZ_TO_LINEAR_SRGB.T
