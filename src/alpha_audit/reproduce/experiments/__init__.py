"""The paper's four numerical experiments as a library API (Section 4, Appendix A).

Each function returns frozen dataclasses of *unrounded* counts and sums;
percentages and means are derived properties.  They work on any theme, so a
design-system team can ask "which share of all colours gains contrast on our
canvases at 1.2?" with ``full_gamut(load_theme("ours.yaml"), [1.2])``.

One module per experiment: :mod:`.gamut` (full gamut), :mod:`.broad` (the broad grid),
:mod:`.alpha_sweep` (the coefficient sweep) and :mod:`.separation` (palette
separation); :mod:`.collisions` and :mod:`.common` hold what they share.
Nothing here prints.
"""

from alpha_audit.reproduce.experiments.alpha_sweep import SweepResult, sweep, sweep_alphas
from alpha_audit.reproduce.experiments.broad import BroadGridResult, broad_grid
from alpha_audit.reproduce.experiments.collisions import pair_collisions
from alpha_audit.reproduce.experiments.gamut import (
    CanvasChange,
    ContrastChange,
    FullGamutResult,
    full_gamut,
)
from alpha_audit.reproduce.experiments.separation import PaletteResult, palette_separation

__all__ = [
    "BroadGridResult",
    "CanvasChange",
    "ContrastChange",
    "FullGamutResult",
    "PaletteResult",
    "SweepResult",
    "broad_grid",
    "full_gamut",
    "pair_collisions",
    "palette_separation",
    "sweep",
    "sweep_alphas",
]
