"""``suggest``: the exact largest safe coefficient, its reports and ``--apply``.

:mod:`~alpha_audit.suggest.engine` answers the question from *events*
(:mod:`~alpha_audit.suggest.events`), :mod:`~alpha_audit.suggest.report`
renders the answer and :mod:`~alpha_audit.suggest.apply` writes it into a
manifest.  Importing the package loads only the engine.
"""

from __future__ import annotations

from alpha_audit.suggest.engine import (
    SEPARATION_GRID_STEP,
    CanvasLimit,
    ColorSuggestion,
    IconSuggestion,
    Limit,
    SafeAlpha,
    SuggestResult,
    largest_safe_alpha,
    suggest,
)

__all__ = [
    "SEPARATION_GRID_STEP",
    "CanvasLimit",
    "ColorSuggestion",
    "IconSuggestion",
    "Limit",
    "SafeAlpha",
    "SuggestResult",
    "largest_safe_alpha",
    "suggest",
]
