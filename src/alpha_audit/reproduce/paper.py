"""The paper's printed numbers, with the number of decimals it prints them to.

Source: "Opacity Is Not Just Opacity", Section 4 (Table 1 and text of 4.2 and
4.3) and the abstract.  Each entry says whether our reproduction is
*comparable in digits*: only the broad grid depends on nothing the paper
leaves out.  The full-gamut, palette and random-pair figures depend on the
paper's sixteen canvases (unpublished; ``themes/paper16.yaml`` is our own
choice) and on its random-pair construction (unspecified), so they are
comparable in method only.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["PAPER", "PaperValue", "matches_printed"]


@dataclass(frozen=True)
class PaperValue:
    """One printed number: value, decimals printed, and whether ours should match it."""

    value: float
    decimals: int
    comparable: bool
    where: str


def _v(value: float, decimals: int, comparable: bool, where: str) -> PaperValue:
    return PaperValue(value, decimals, comparable, where)


_TABLE1 = "Table 1"
_S42 = "Section 4.2"
_S43 = "Section 4.3"

PAPER: dict[str, dict[str, dict[str, PaperValue]]] = {
    "broad_grid": {
        "1.1": {
            "increase_pct": _v(90.3672, 4, True, _TABLE1),
            "decrease_pct": _v(9.3318, 4, True, _TABLE1),
            "max_loss": _v(0.4655, 4, True, _S42),
            "loss_le_0_25_pct": _v(99.34, 2, True, _S42),
            "worst_contrast_1.0": _v(10.2773, 4, True, _S42),
            "worst_contrast_1.1": _v(9.8118, 4, True, _S42),
        },
        "1.4": {
            "increase_pct": _v(86.7022, 4, True, _TABLE1),
            "decrease_pct": _v(12.9968, 4, True, _TABLE1),
            "max_loss": _v(1.6394, 4, True, _S42),
            "loss_le_0_25_pct": _v(81.53, 2, True, _S42),
            "worst_contrast_1.0": _v(10.2773, 4, True, _S42),
            "worst_contrast_1.4": _v(8.6379, 4, True, _S42),
        },
    },
    "full_gamut": {
        "1.1": {
            "increase_pct": _v(99.8145, 4, False, "abstract, Table 1"),
            "decrease_pct": _v(0.1853, 4, False, _TABLE1),
            "mean_change": _v(0.9783, 4, False, _S42),
            "mean_difference_change": _v(-1.3050, 4, False, _S42),
            "mean_exclusion_change": _v(-1.3104, 4, False, _S42),
            "newly_reach_pct": _v(4.8346, 4, False, "abstract, Section 4.2"),
        },
        "1.4": {
            "increase_pct": _v(99.6132, 4, False, _TABLE1),
            "decrease_pct": _v(0.3867, 4, False, _TABLE1),
        },
    },
    "palette": {
        "1.1": {
            "smaller": _v(32, 0, False, _S43),
            "collisions": _v(0, 0, False, _S43),
            "random_collisions": _v(617, 0, False, _S43),
        },
        "1.4": {
            "smaller": _v(88, 0, False, _S43),
            "collisions": _v(8, 0, False, _S43),
            "random_collisions": _v(15098, 0, False, _S43),
        },
        "counts": {
            # Number of combinations: comparable when the theme has 16 canvases.
            "combinations": _v(336, 0, True, _S43),
            "random_combinations": _v(1048576, 0, True, _S43),
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
