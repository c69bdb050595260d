"""The independent truth the page-audit tests compare against (importable: ``pythonpath = tests``).

Written from the specifications, never with alpha-audit's maths: WCAG 2.2's relative
luminance and contrast ratio of 8-bit sRGB codes, and CSS source-over on encoded
sRGB kept to 8 bits (Compositing 1, as browsers composite).
"""

from __future__ import annotations

import re

import numpy as np


def luminance(codes: np.ndarray) -> float:
    """WCAG 2.2 relative luminance of 8-bit sRGB codes."""
    c = np.asarray(codes, dtype=float) / 255.0
    linear = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    return float(linear @ np.array([0.2126, 0.7152, 0.0722]))


def ratio(a: np.ndarray, b: np.ndarray) -> float:
    """WCAG 2.2 contrast ratio of two 8-bit sRGB colours."""
    la, lb = luminance(a), luminance(b)
    return (max(la, lb) + 0.05) / (min(la, lb) + 0.05)


def over(top: np.ndarray, alpha: float, below: np.ndarray) -> np.ndarray:
    """Source-over of an sRGB colour at ``alpha`` on an opaque one, on encoded values, 8-bit."""
    return np.floor(np.asarray(below) + alpha * (np.asarray(top) - below) + 0.5)


def within_a_code(drawn: np.ndarray, behind: np.ndarray) -> tuple[float, float]:
    """Least and greatest contrast with each colour moved by up to one code per channel."""
    ld = [luminance(np.clip(drawn + s, 0, 255)) for s in (-1, 1)]
    lb = [luminance(np.clip(behind + s, 0, 255)) for s in (-1, 1)]
    pairs = [(max(a, b) + 0.05) / (min(a, b) + 0.05) for a in ld for b in lb]
    overlap = max(ld[0], lb[0]) <= min(ld[1], lb[1])
    return (1.0 if overlap else min(pairs)), max(pairs)


def css_colour(text: str) -> tuple[np.ndarray, float]:
    """``#rrggbb`` or ``rgb(r g b / a)`` (as a minifier writes them) -> 8-bit codes, alpha."""
    text = text.strip()
    if re.fullmatch(r"#[0-9a-fA-F]{6}", text):
        return np.array([int(text[i : i + 2], 16) for i in (1, 3, 5)], dtype=float), 1.0
    found = re.fullmatch(r"rgba?\(\s*(\d+)[\s,]+(\d+)[\s,]+(\d+)\s*(?:[/,]\s*([\d.]+))?\s*\)", text)
    if found is None:
        raise ValueError(f"not a colour this helper reads: {text!r}")
    alpha = float(found.group(4)) if found.group(4) else 1.0
    return np.array([float(found.group(k)) for k in (1, 2, 3)]), alpha


def hex_codes(text: str) -> np.ndarray:
    """``#rrggbb`` -> 8-bit codes."""
    return css_colour(text)[0]
