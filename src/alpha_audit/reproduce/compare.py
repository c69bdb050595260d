"""The paper's printed figures beside a run's, and which of them the run must match.

A printed value is *comparable in digits* when the run computed it with the
paper's setup (:class:`~alpha_audit.reproduce.paper.Setup`): its grids, its
sixteen canvases (the bundled ``paper16``), Tol's Vibrant palette and 65,536
random pairs from seed 20260913.  Then ours must round to the printed value;
otherwise the report says why the setup differs and never calls it a match.
Computed once here, rendered by :mod:`alpha_audit.reproduce.report`.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

from alpha_audit.model import Theme
from alpha_audit.reproduce.grids import PAPER_SEED, VIBRANT
from alpha_audit.reproduce.paper import (
    PAPER,
    PAPER_THEME,
    PaperValue,
    Setup,
    alpha_key,
    matches_printed,
)
from alpha_audit.reproduce.run import Reproduction, Settings

__all__ = ["Comparison", "comparisons", "is_paper_canvases", "setup_differences"]


@dataclass(frozen=True)
class Comparison:
    """One printed value beside ours.

    ``differs`` says why this run cannot be held to the printed digits (its
    setup is not the paper's, or it did not compute the value); ``None`` when
    it can.
    """

    experiment: str
    group: str
    name: str
    printed: PaperValue
    ours: float | None
    differs: str | None

    @property
    def comparable(self) -> bool:
        """Computed with the paper's setup: ours must give the printed digits."""
        return self.differs is None

    @property
    def matches(self) -> bool | None:
        """Whether ours rounds to the printed value; ``None`` when not comparable."""
        if self.ours is None or not self.comparable:
            return None
        return matches_printed(self.ours, self.printed)


@cache
def _paper_backgrounds() -> tuple[tuple[float, ...], ...]:
    from alpha_audit.bundled import bundled_theme
    from alpha_audit.load.theme import load_theme

    return tuple(sorted(c.linear for c in load_theme(bundled_theme(PAPER_THEME)).canvases))


def is_paper_canvases(theme: Theme) -> bool:
    """Whether ``theme``'s canvases are the paper's sixteen, in any order and under any names."""
    return tuple(sorted(c.linear for c in theme.canvases)) == _paper_backgrounds()


def setup_differences(run: Reproduction) -> dict[Setup, str | None]:
    """Per setup, how this run's differs from the paper's (``None``: it is the paper's)."""
    paper = Settings.paper()
    canvases = (
        []
        if is_paper_canvases(run.theme)
        else [f"canvases of theme {run.theme.name!r}, not the paper's sixteen ({PAPER_THEME})"]
    )
    reasons: dict[Setup, list[str] | None] = dict.fromkeys(Setup)  # None: not run
    if run.broad_grid:
        s, b = run.broad_grid[0].source_levels, run.broad_grid[0].background_levels
        paper_grid = (paper.source_levels, paper.background_levels)
        reasons[Setup.BROAD_GRID] = (
            []
            if (s, b) == paper_grid
            else [f"a {s}^3 x {b}^3 grid, not {paper_grid[0]}^3 x {paper_grid[1]}^3"]
        )
    if run.full_gamut:
        levels, paper_levels = run.full_gamut[0].levels, paper.full_gamut_levels
        sources = [] if levels == paper_levels else [f"{levels}^3 sources, not {paper_levels}^3"]
        reasons[Setup.FULL_GAMUT] = [*sources, *canvases]
    if (p := run.palette) is not None:
        vibrant = [] if tuple(p.palette) == VIBRANT else ["not Tol's Vibrant"]
        reasons[Setup.PALETTE] = [*vibrant, *canvases]
        pairs = (
            []
            if p.random_pairs == paper.pairs
            else [f"{p.random_pairs:,} random pairs, not {paper.pairs:,}"]
        )
        seed = [] if p.seed == PAPER_SEED else [f"seed {p.seed}, not {PAPER_SEED}"]
        reasons[Setup.RANDOM_PAIRS] = [*pairs, *seed, *canvases]
    return {
        setup: "not run" if why is None else "; ".join(why) or None
        for setup, why in reasons.items()
    }


def _ours(run: Reproduction, experiment: str, group: str, name: str) -> float | None:
    """This run's value of one printed quantity, or ``None`` if it was not computed."""
    if experiment == "broad_grid" and run.broad_grid:
        for r in run.broad_grid:
            if alpha_key(r.alpha) == group:
                if name.startswith("worst_contrast_"):
                    return r.worst_contrast.get(float(name.removeprefix("worst_contrast_")))
                value: float = getattr(r, name)
                return value
    if experiment == "full_gamut" and run.full_gamut:
        for g in run.full_gamut:
            if alpha_key(g.alpha) == group:
                total: float = getattr(g.total, name)
                return total
    if experiment == "palette" and run.palette is not None:
        p = run.palette
        if group == "counts":
            count: int = getattr(p, name)
            return count
        per_alpha = {
            "smaller": p.smaller,
            "collisions": p.collisions,
            "random_collisions": p.random_collisions,
        }[name]
        for a, n in per_alpha.items():
            if alpha_key(a) == group:
                return n
    return None


def comparisons(run: Reproduction) -> tuple[Comparison, ...]:
    """Every printed value of :data:`~alpha_audit.reproduce.paper.PAPER` beside this run's."""
    differences = setup_differences(run)
    rows = []
    for experiment, groups in PAPER.items():
        for group, values in groups.items():
            for name, printed in values.items():
                ours = _ours(run, experiment, group, name)
                differs = differences[printed.setup] if ours is not None else "not computed"
                rows.append(Comparison(experiment, group, name, printed, ours, differs))
    return tuple(rows)
