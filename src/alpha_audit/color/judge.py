"""The one judgement of a shown colour on a canvas (docs/model.md, "What ships is judged")."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from alpha_audit.color.metrics import contrast_ratio
from alpha_audit.color.srgb import shipped

__all__ = ["judged_contrast"]


def judged_contrast(shown: ArrayLike, canvas: ArrayLike) -> NDArray[np.float64]:
    """The one judgement of a shown colour on a canvas: WCAG 2.2 contrast of what ships.

    Both linear colours are taken to the 8-bit sRGB codes a screen shows
    (:func:`~alpha_audit.color.srgb.shipped`: encoded, rounded half to even)
    before the ratio: every verdict (rows, findings, ``pair``, fixes, a
    browser's measured paints and the model's predictions for them) calls this,
    so two formulas never disagree on one colour.  ``contrast_ratio`` of the
    float colours is the paper's maths, kept beside it as ``*_float``.

    >>> round(float(judged_contrast([0.5, 0.5, 0.5], [1.0, 1.0, 1.0])), 6)
    1.899124
    """
    return contrast_ratio(shipped(shown), shipped(canvas))
