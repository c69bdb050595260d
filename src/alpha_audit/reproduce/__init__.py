"""The paper's numerical evaluation ("Opacity Is Not Just Opacity", Section 4 and Appendix A).

Library API: :func:`full_gamut`, :func:`broad_grid`, :func:`sweep` and
:func:`palette_separation` return frozen dataclasses of unrounded numbers and
work on any theme.  Never imported by the audit path.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from alpha_audit.reproduce.experiments import (
        BroadGridResult,
        CanvasChange,
        ContrastChange,
        FullGamutResult,
        PaletteResult,
        SweepResult,
        broad_grid,
        full_gamut,
        palette_separation,
        sweep,
        sweep_alphas,
    )

__all__ = [
    "BroadGridResult",
    "CanvasChange",
    "ContrastChange",
    "FullGamutResult",
    "PaletteResult",
    "SweepResult",
    "broad_grid",
    "full_gamut",
    "palette_separation",
    "sweep",
    "sweep_alphas",
]


def __getattr__(name: str) -> Any:
    """The experiments on first use (PEP 562): the command line imports
    :mod:`alpha_audit.reproduce.experiment` without loading them."""
    if name in __all__:
        return getattr(importlib.import_module("alpha_audit.reproduce.experiments"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
