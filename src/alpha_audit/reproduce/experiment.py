"""The names of the experiments ``alpha-audit reproduce`` can run.

Kept apart from :mod:`alpha_audit.reproduce.run` so the command line can
offer them as choices without loading the experiments themselves.
"""

from __future__ import annotations

import enum

__all__ = ["Experiment"]


class Experiment(enum.StrEnum):
    """The four numerical experiments, in the paper's order, then the two in browsers."""

    FULL_GAMUT = "full-gamut"
    BROAD_GRID = "broad-grid"
    SWEEP = "sweep"
    PALETTE = "palette"
    BROWSER = "browser"
    RUNTIME = "runtime"
