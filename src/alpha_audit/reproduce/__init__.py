"""The paper's numerical evaluation ("Opacity Is Not Just Opacity", Section 4 and Appendix A).

Library API: :func:`full_gamut`, :func:`broad_grid`, :func:`sweep` and
:func:`palette_separation` return frozen dataclasses of unrounded numbers and
work on any theme.  Never imported by the audit path.
"""

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
