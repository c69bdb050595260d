from .experiments import (
    BroadGridResult as BroadGridResult,
    CanvasChange as CanvasChange,
    ContrastChange as ContrastChange,
    FullGamutResult as FullGamutResult,
    PaletteResult as PaletteResult,
    SweepResult as SweepResult,
    broad_grid as broad_grid,
    full_gamut as full_gamut,
    palette_separation as palette_separation,
    sweep as sweep,
    sweep_alphas as sweep_alphas,
)
