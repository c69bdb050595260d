"""The allowed range of every number a user sets, stated once for files, flags and the library.

A theme's ``threshold:``, a config's ``threshold:`` and ``--threshold`` mean one
thing, so one :class:`NumberRange` says what they accept and one sentence says
it when a value is refused: the YAML readers (:func:`alpha_audit.load.fields.read_number`),
the command line (:func:`alpha_audit.cli.options.in_range`) and
:class:`alpha_audit.policy.Policy` all ask the range here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from alpha_audit.constants import THRESHOLD_RANGE, THRESHOLD_WHAT

__all__ = [
    "ALPHA",
    "ALPHA_MAX",
    "COMBINATIONS",
    "CONTRAST_LOSS",
    "CONTRAST_RATIO",
    "DEFAULT_COMBINATIONS",
    "DELTA_E",
    "ICON_SIZE",
    "LOSS_TOLERANCE",
    "MAX_ICON_SIZE",
    "MAX_PRECISION",
    "PAGE_SECONDS",
    "PRECISION",
    "WORKERS",
    "NumberRange",
]


@dataclass(frozen=True)
class NumberRange:
    """A closed interval of finite numbers and the words that describe it to a user.

    >>> CONTRAST_RATIO.allows(3.0), CONTRAST_RATIO.allows(float("nan")), 25.0 in CONTRAST_RATIO
    (True, False, False)
    >>> CONTRAST_RATIO.refusal("--threshold 25")
    '--threshold 25 is out of range; expected a contrast ratio between 1 and 21'
    """

    low: float
    high: float
    what: str  # completes "expected ...": "a contrast ratio between 1 and 21"

    def allows(self, value: float) -> bool:
        """Whether ``value`` is finite and within ``[low, high]`` (NaN and infinities never are)."""
        return math.isfinite(value) and self.low <= value <= self.high

    def __contains__(self, value: object) -> bool:
        return isinstance(value, int | float) and self.allows(float(value))

    def refusal(self, shown: str) -> str:
        """The one sentence refusing a value, ``shown`` as the user wrote it (flag or key first)."""
        return f"{shown} is out of range; expected {self.what}"


# WCAG 2.2 contrast ratios run from 1 (a colour on itself) to 21 (black on white):
# thresholds and --min-size-contrast are contrast ratios, nothing else means anything.
CONTRAST_RATIO = NumberRange(*THRESHOLD_RANGE, THRESHOLD_WHAT)
# A contrast loss is a difference of two ratios, so it never exceeds 21 - 1; 21 keeps
# the limit a round "anything".
CONTRAST_LOSS = NumberRange(0.0, 21.0, "a contrast loss between 0 and 21")
# A relative contrast loss (loss / contrast at alpha 1): 1 would tolerate every loss.
LOSS_TOLERANCE = NumberRange(0.0, 1.0, "a relative tolerance between 0 and 1")
# Paint rows x canvases one check audits (the resource bound a config may raise):
# at least one; 10^9 rows would need hundreds of GB whatever the bound says.
COMBINATIONS = NumberRange(1, 1_000_000_000, "whole paint x canvas rows, 1 to 1,000,000,000")
# The bound by default: each row is a JSON row of about 600 bytes and a few
# microseconds of work (docs/ci.md measures memory against it).
DEFAULT_COMBINATIONS = 250_000
# CIEDE2000 between sRGB colours stays well under 200 (black-white is 100, the widest
# hue pairs ~125): a larger --min-delta-e or --max-drift can only be a typo.
DELTA_E = NumberRange(0.0, 200.0, "a CIEDE2000 difference between 0 and 200")
# Any finite coefficient is valid maths (the paper allows a outside [0, 1]); beyond
# +-100 every colour clips to a primary and the value is a typo.
ALPHA = NumberRange(-100.0, 100.0, "a finite coefficient between -100 and 100")
# suggest searches [1, alpha-max]: 1 is its reference, the top is ALPHA's.
ALPHA_MAX = NumberRange(1.0, ALPHA.high, f"a coefficient between 1 and {ALPHA.high:g}")
# Rasters are size x size float64 per icon and canvas: 1024 px keeps one at 8 MiB.
MAX_ICON_SIZE = 1024
ICON_SIZE = NumberRange(1, MAX_ICON_SIZE, f"whole pixels 1-{MAX_ICON_SIZE}")
# suggest rounds its exact answer down to this many decimals; float64 holds ~15-16
# significant digits, so 9 decimals stay exact for coefficients up to 100.
MAX_PRECISION = 9
PRECISION = NumberRange(0, MAX_PRECISION, f"0-{MAX_PRECISION} decimals")
# render: browser pages in parallel (each a browser process of a few hundred MB).
WORKERS = NumberRange(1, 16, "whole pages in parallel, 1-16")
# render: seconds one page and state may take (a hung page is a problem, not a hang).
PAGE_SECONDS = NumberRange(1, 600, "seconds between 1 and 600")
