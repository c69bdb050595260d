"""The paper's printed numbers, with the number of decimals it prints them to.

Source: "Opacity Is Not Just Opacity", Section 4 (Table 1 and text of 4.2 and
4.3) and the abstract.  Each value names the *setup* it depends on
(:class:`Setup`); a run whose setup is the paper's must give the printed
digits, and :mod:`alpha_audit.reproduce.compare` says, per run, which are.
The paper's sixteen canvases are the bundled theme :data:`PAPER_THEME`
(from the authors' public evaluation protocol, see ``themes/paper16.yaml``).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

__all__ = [
    "PAPER",
    "PAPER_THEME",
    "WORST_BACKGROUND",
    "WORST_SOURCE",
    "PaperValue",
    "Setup",
    "alpha_key",
    "matches_printed",
]

PAPER_THEME = "paper16"
"""The bundled theme holding the paper's sixteen canvases."""


class Setup(enum.StrEnum):
    """What a printed value depends on besides the engine (paper, Section 4.1, Appendix A.1).

    ``BROAD_GRID``: the 17**3 x 33**3 grids.  ``FULL_GAMUT``: all 256**3
    sources on the paper's sixteen canvases.  ``PALETTE``: Tol's Vibrant
    pairs on those canvases.  ``RANDOM_PAIRS``: 65,536 pairs from
    ``default_rng(20260913)`` on those canvases.
    """

    BROAD_GRID = "broad-grid"
    FULL_GAMUT = "full-gamut"
    PALETTE = "palette"
    RANDOM_PAIRS = "random-pairs"


@dataclass(frozen=True)
class PaperValue:
    """One printed number: value, decimals printed, what it depends on, where it is printed."""

    value: float
    decimals: int
    setup: Setup
    where: str


def alpha_key(alpha: float) -> str:
    """Key of a coefficient in :data:`PAPER` and in JSON: ``str(float)``.

    >>> alpha_key(1.1), alpha_key(1)
    ('1.1', '1.0')
    """
    return str(float(alpha))


_TABLE1 = "Table 1"
_S42 = "Section 4.2"
_S43 = "Section 4.3"


def _broad(value: float, decimals: int, where: str) -> PaperValue:
    return PaperValue(value, decimals, Setup.BROAD_GRID, where)


def _gamut(value: float, where: str) -> PaperValue:
    return PaperValue(value, 4, Setup.FULL_GAMUT, where)


def _count(value: int, setup: Setup) -> PaperValue:
    return PaperValue(value, 0, setup, _S43)


PAPER: dict[str, dict[str, dict[str, PaperValue]]] = {
    "broad_grid": {
        "1.1": {
            "increase_pct": _broad(90.3672, 4, _TABLE1),
            "decrease_pct": _broad(9.3318, 4, _TABLE1),
            "max_loss": _broad(0.4655, 4, _S42),
            "loss_le_0_25_pct": _broad(99.34, 2, _S42),
            "worst_contrast_1.0": _broad(10.2773, 4, _S42),
            "worst_contrast_1.1": _broad(9.8118, 4, _S42),
        },
        "1.4": {
            "increase_pct": _broad(86.7022, 4, _TABLE1),
            "decrease_pct": _broad(12.9968, 4, _TABLE1),
            "max_loss": _broad(1.6394, 4, _S42),
            "loss_le_0_25_pct": _broad(81.53, 2, _S42),
            "worst_contrast_1.0": _broad(10.2773, 4, _S42),
            "worst_contrast_1.4": _broad(8.6379, 4, _S42),
        },
    },
    "full_gamut": {
        "1.1": {
            "increase_pct": _gamut(99.8145, "abstract, Table 1"),
            "decrease_pct": _gamut(0.1853, _TABLE1),
            "mean_change": _gamut(0.9783, _S42),
            "mean_difference_change": _gamut(-1.3050, _S42),
            "mean_exclusion_change": _gamut(-1.3104, _S42),
            "newly_reach_pct": _gamut(4.8346, "abstract, Section 4.2"),
        },
        "1.4": {
            "increase_pct": _gamut(99.6132, _TABLE1),
            "decrease_pct": _gamut(0.3867, _TABLE1),
        },
    },
    "palette": {
        # "collisions increase from 617 to 15,098": read as alpha 1.1 -> 1.4.
        "1.1": {
            "smaller": _count(32, Setup.PALETTE),
            "collisions": _count(0, Setup.PALETTE),
            "random_collisions": _count(617, Setup.RANDOM_PAIRS),
        },
        "1.4": {
            "smaller": _count(88, Setup.PALETTE),
            "collisions": _count(8, Setup.PALETTE),
            "random_collisions": _count(15098, Setup.RANDOM_PAIRS),
        },
        "counts": {
            "combinations": _count(336, Setup.PALETTE),
            "random_combinations": _count(1048576, Setup.RANDOM_PAIRS),
        },
    },
}
# Paper, Section 4.2: the worst broad-grid combination, encoded sRGB.
WORST_SOURCE = (0.0, 0.0, 0.8125)
WORST_BACKGROUND = (1.0, 1.0, 0.0)


def matches_printed(ours: float, printed: PaperValue) -> bool:
    """Whether ``ours`` rounds to the printed value at the printed number of decimals.

    >>> matches_printed(90.36716395, PAPER["broad_grid"]["1.1"]["increase_pct"])
    True
    """
    return round(ours, printed.decimals) == round(printed.value, printed.decimals)
