"""Numbers and names of the colour maths that need no numpy (it imports nothing).

The command line shows them in ``--help`` (the default threshold, the range a
threshold may take, the gamut policies) and reads them here, so ``alpha-audit
--help`` starts without numpy or colour-science; :mod:`alpha_audit.color`
exports them with the maths that uses them.
"""

from __future__ import annotations

from typing import Literal, get_args

__all__ = [
    "CONTRAST_TOLERANCE",
    "DEFAULT_GAMUT",
    "DELTA_E_TOLERANCE",
    "GAMUT_POLICIES",
    "LUMINANCE_WEIGHTS",
    "NON_TEXT_THRESHOLD",
    "THRESHOLD_RANGE",
    "THRESHOLD_WHAT",
    "GamutPolicy",
]

# WCAG 2.2, "relative luminance" (the Rec. 709 / sRGB Y row, rounded to 4 places).
LUMINANCE_WEIGHTS = (0.2126, 0.7152, 0.0722)
# WCAG 2.2 SC 1.4.11 Non-text Contrast.
NON_TEXT_THRESHOLD = 3.0
# WCAG 2.2 contrast ratios run from 1 (a colour on itself) to 21 (black on white):
# the only thresholds that mean anything, for themes, configs and --threshold alike.
THRESHOLD_RANGE = (1.0, 21.0)
THRESHOLD_WHAT = "a contrast ratio between 1 and 21"
# Paper, Appendix A.1: contrast changes within 1e-10 are "unchanged",
# CIEDE2000 decreases within 1e-9 are not decreases.
CONTRAST_TOLERANCE = 1e-10
DELTA_E_TOLERANCE = 1e-9

# What to do with a colour outside sRGB (alpha_audit.color.css.parse_css_color).
GamutPolicy = Literal["clip", "map", "error"]
GAMUT_POLICIES: tuple[GamutPolicy, ...] = get_args(GamutPolicy)
# ``pair``'s: what a browser draws on an sRGB screen today (alpha_audit.pair).
DEFAULT_GAMUT: GamutPolicy = "clip"
