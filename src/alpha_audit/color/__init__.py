"""Pure numpy colour maths: sRGB, extended compositing, luminance, contrast, CIEDE2000."""

from alpha_audit.color.composite import (
    composite_coverage,
    composite_extended,
    composite_raw,
    difference_blend,
    exclusion_blend,
)
from alpha_audit.color.metrics import (
    CONTRAST_TOLERANCE,
    DELTA_E_TOLERANCE,
    LUMINANCE_WEIGHTS,
    NON_TEXT_THRESHOLD,
    THRESHOLD_RANGE,
    THRESHOLD_WHAT,
    contrast_from_luminance,
    contrast_ratio,
    delta_e_2000,
    delta_e_2000_lab,
    linear_to_lab,
    relative_luminance,
)
from alpha_audit.color.srgb import (
    from_8bit,
    hex_to_linear,
    linear_to_hex,
    parse_color,
    srgb_decode,
    srgb_encode,
    to_8bit,
)

__all__ = [
    "CONTRAST_TOLERANCE",
    "DELTA_E_TOLERANCE",
    "LUMINANCE_WEIGHTS",
    "NON_TEXT_THRESHOLD",
    "THRESHOLD_RANGE",
    "THRESHOLD_WHAT",
    "composite_coverage",
    "composite_extended",
    "composite_raw",
    "contrast_from_luminance",
    "contrast_ratio",
    "delta_e_2000",
    "delta_e_2000_lab",
    "difference_blend",
    "exclusion_blend",
    "from_8bit",
    "hex_to_linear",
    "linear_to_hex",
    "linear_to_lab",
    "parse_color",
    "relative_luminance",
    "srgb_decode",
    "srgb_encode",
    "to_8bit",
]
