"""Colour-vision deficiency simulation: Machado, Oliveira & Fernandes (2009), severity 1.

The matrices come from colour-science (``matrix_cvd_Machado2009``) and act on
linear RGB; results are clipped to [0, 1] per channel.  Machado's
physiological model shifts cone sensitivities; for tritan deficiencies that
shift is only an approximation (Machado et al. restrain the model from
modelling tritanopia proper, as colour-science warns), so tritan results are
indicative only (docs/model.md).
"""

from __future__ import annotations

import warnings
from functools import cache
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from alpha_audit.color.metrics import _colour

__all__ = ["DEFICIENCIES", "Deficiency", "cvd_matrix", "simulate_cvd"]

Deficiency = Literal["protanopia", "deuteranopia", "tritanopia"]
DEFICIENCIES: tuple[Deficiency, ...] = ("protanopia", "deuteranopia", "tritanopia")
# colour-science names the anomalies; severity 1 is the corresponding -opia.
_MACHADO_NAMES = {
    "protanopia": "Protanomaly",
    "deuteranopia": "Deuteranomaly",
    "tritanopia": "Tritanomaly",
}
_SEVERITY = 1.0


@cache
def cvd_matrix(deficiency: Deficiency) -> NDArray[np.float64]:
    """The 3x3 Machado (2009) matrix at severity 1; unknown names raise ValueError."""
    if deficiency not in _MACHADO_NAMES:
        raise ValueError(
            f"unknown colour-vision deficiency {deficiency!r}; use one of {', '.join(DEFICIENCIES)}"
        )
    with warnings.catch_warnings():
        # colour-science warns that the tritan matrix is an approximation; the docs say so.
        warnings.simplefilter("ignore")
        m = np.asarray(
            _colour().blindness.matrix_cvd_Machado2009(_MACHADO_NAMES[deficiency], _SEVERITY),
            dtype=np.float64,
        )
    m.setflags(write=False)
    return m


def simulate_cvd(linear: ArrayLike, deficiency: Deficiency) -> NDArray[np.float64]:
    """Linear sRGB as seen with ``deficiency``: ``clip(M @ c)``, channels last.

    Each matrix row sums to 1, so greys stay grey:

    >>> simulate_cvd([0.5, 0.5, 0.5], "protanopia").round(6).tolist()
    [0.5, 0.5, 0.5]
    """
    c = np.asarray(linear, dtype=np.float64)
    return np.clip(c @ cvd_matrix(deficiency).T, 0.0, 1.0)
