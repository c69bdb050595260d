"""The paper's numerical evaluation ("Opacity Is Not Just Opacity", Section 4 and Appendix A).

Library API: :func:`full_gamut`, :func:`broad_grid`, :func:`sweep` and
:func:`palette_separation` return frozen dataclasses of unrounded numbers and
work on any theme.  Never imported by the audit path.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from alpha_audit.lazy import lazy_exports

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

# The experiments load on first use: the CLI imports reproduce.experiment without them.
__getattr__ = lazy_exports(__name__, dict.fromkeys(__all__, "alpha_audit.reproduce.experiments"))
