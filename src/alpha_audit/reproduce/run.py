"""Run a selection of the experiments with the paper's (or quick) settings."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import Any

from alpha_audit.errors import UsageError
from alpha_audit.model import Theme
from alpha_audit.reproduce.browser import BrowserValidationResult, browser_validation
from alpha_audit.reproduce.experiment import Experiment
from alpha_audit.reproduce.experiments import (
    BroadGridResult,
    FullGamutResult,
    PaletteResult,
    SweepResult,
    broad_grid,
    full_gamut,
    palette_separation,
    sweep,
    sweep_alphas,
)
from alpha_audit.reproduce.runtime import RuntimeResult, RuntimeSettings, runtime

__all__ = [
    "BROWSER_EXPERIMENTS",
    "DEFAULT_EXPERIMENTS",
    "Experiment",
    "Reproduction",
    "Settings",
    "reproduce",
]


# Run when nothing is selected; the browser experiments need engines and icons, so they
# run only when asked for.
DEFAULT_EXPERIMENTS = frozenset(
    {Experiment.FULL_GAMUT, Experiment.BROAD_GRID, Experiment.SWEEP, Experiment.PALETTE}
)
BROWSER_EXPERIMENTS = frozenset({Experiment.BROWSER, Experiment.RUNTIME})


@dataclass(frozen=True)
class Settings:
    """Grid sizes; :meth:`paper` are the paper's, :meth:`quick` small ones for tests."""

    full_gamut_levels: int
    source_levels: int
    background_levels: int
    sweep_levels: int
    sweep_step: float
    pairs: int

    @classmethod
    def paper(cls) -> Settings:
        """256**3 sources, 17**3 x 33**3 broad grid, 65**3 sweep step 0.025, 65,536 pairs."""
        return cls(256, 17, 33, 65, 0.025, 65536)

    @classmethod
    def quick(cls) -> Settings:
        """Small grids: 33**3 sources, 5**3 x 9**3 broad grid, 17**3 sweep step 0.1, 4,096 pairs."""
        return cls(33, 5, 9, 17, 0.1, 4096)


@dataclass(frozen=True)
class Reproduction:
    """Results of one run; experiments not selected are ``None``."""

    theme: Theme
    settings: Settings
    quick: bool
    alphas: tuple[float, ...]
    full_gamut: tuple[FullGamutResult, ...] | None = None
    broad_grid: tuple[BroadGridResult, ...] | None = None
    sweep: SweepResult | None = None
    palette: PaletteResult | None = None
    browser: BrowserValidationResult | None = None
    runtime: RuntimeResult | None = None


def reproduce(
    theme: Theme,
    only: Iterable[Experiment] = (),
    *,
    alphas: Iterable[float] = (1.1, 1.4),
    quick: bool = False,
    icons: Path | None = None,
    engines: Iterable[str] | None = None,
    progress: Callable[[Experiment, float], None] | None = None,
) -> Reproduction:
    """Run the selected experiments (all when ``only`` is empty) on ``theme``.

    ``alphas`` apply to the full gamut, broad grid and palette experiments;
    the sweep always covers [0, 2].  The browser experiments (run only when
    selected) draw the SVGs of ``icons`` in each installed engine, or in
    ``engines``.  ``progress(experiment, fraction)`` reports completed fractions.
    """
    selected = set(only) or set(DEFAULT_EXPERIMENTS)
    if selected & BROWSER_EXPERIMENTS and icons is None:
        names = " and ".join(sorted(e.value for e in selected & BROWSER_EXPERIMENTS))
        raise UsageError(f"experiment {names} needs `icons` (a directory of SVG icons)")
    alphas = tuple(float(a) for a in alphas)
    if not alphas:
        raise UsageError("`alphas` is empty; give at least one coefficient")
    settings = Settings.quick() if quick else Settings.paper()
    runs: dict[Experiment, Callable[[Callable[[float], None]], object]] = {
        Experiment.FULL_GAMUT: lambda step: full_gamut(
            theme, alphas, levels=settings.full_gamut_levels, progress=step
        ),
        Experiment.BROAD_GRID: lambda step: broad_grid(
            alphas,
            source_levels=settings.source_levels,
            background_levels=settings.background_levels,
            progress=step,
        ),
        Experiment.SWEEP: lambda step: sweep(
            theme,
            sweep_alphas(0.0, 2.0, settings.sweep_step),
            levels=settings.sweep_levels,
            pairs=settings.pairs,
            progress=step,
        ),
        Experiment.PALETTE: lambda step: palette_separation(
            theme, alphas, pairs=settings.pairs, progress=step
        ),
        Experiment.BROWSER: lambda step: browser_validation(
            theme, icons or Path(), engines=engines, progress=step
        ),
        Experiment.RUNTIME: lambda step: runtime(
            icons or Path(),
            settings=RuntimeSettings.quick() if quick else RuntimeSettings.paper(),
            engines=engines,
            progress=step,
        ),
    }
    report = progress or (lambda _experiment, _fraction: None)
    results: dict[str, Any] = {  # in the paper's order
        e.value.replace("-", "_"): runs[e](partial(report, e)) for e in Experiment if e in selected
    }
    return Reproduction(theme, settings, quick, alphas, **results)
