"""The palette experiment: separation of palette pairs and random pairs (paper, Section 4.3)."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from itertools import combinations

import numpy as np

from alpha_audit.color import (
    DELTA_E_TOLERANCE,
    composite_extended,
    delta_e_2000,
    hex_to_linear,
    to_8bit,
)
from alpha_audit.model import Theme
from alpha_audit.reproduce.experiments.collisions import pair_collisions
from alpha_audit.reproduce.experiments.common import Progress, check_alphas, noop
from alpha_audit.reproduce.grids import PAPER_SEED, VIBRANT, random_source_pairs

__all__ = ["PaletteResult", "palette_separation"]


@dataclass(frozen=True)
class PaletteResult:
    """Separation of palette pairs and of random pairs (paper, Section 4.3).

    ``smaller[a]``: palette pair x canvas combinations whose CIEDE2000 at
    alpha ``a`` is below that at alpha 1 by more than the tolerance;
    ``collisions[a]``: those with identical 8-bit outputs.  The per-canvas
    tuples follow the theme's canvas order.  ``random_collisions[a]`` counts
    colliding random pair x canvas combinations.
    """

    theme: str
    palette: tuple[str, ...]
    alphas: tuple[float, ...]
    combinations: int
    smaller: dict[float, int]
    collisions: dict[float, int]
    smaller_per_canvas: dict[float, tuple[int, ...]]
    collisions_per_canvas: dict[float, tuple[int, ...]]
    random_pairs: int
    seed: int
    random_combinations: int
    random_alphas: tuple[float, ...]
    random_collisions: dict[float, int]


def palette_separation(
    theme: Theme,
    alphas: Iterable[float] = (1.1, 1.4),
    *,
    palette: Sequence[str] = VIBRANT,
    pairs: int = 65536,
    seed: int = PAPER_SEED,
    random_alphas: Iterable[float] = (1.0, 1.1, 1.4),
    progress: Progress = noop,
) -> PaletteResult:
    """CIEDE2000 and 8-bit collisions of palette pairs on every canvas, and of random pairs."""
    alphas = check_alphas(alphas)
    random_alphas = check_alphas(random_alphas)
    colours = np.array([hex_to_linear(c) for c in palette])
    first, second = (np.array(ix) for ix in zip(*combinations(range(len(palette)), 2), strict=True))
    backgrounds = theme.backgrounds
    bg = backgrounds[:, np.newaxis, :]
    base = delta_e_2000(colours[first], colours[second])[np.newaxis, :]
    smaller, collide = {}, {}
    for a in alphas:
        out_1 = composite_extended(colours[first][np.newaxis], bg, a)
        out_2 = composite_extended(colours[second][np.newaxis], bg, a)
        smaller[a] = np.count_nonzero(delta_e_2000(out_1, out_2) < base - DELTA_E_TOLERANCE, axis=1)
        collide[a] = np.all(to_8bit(out_1) == to_8bit(out_2), axis=-1).sum(axis=1)
    progress(0.2)
    random = pair_collisions(backgrounds, np.array(random_alphas), random_source_pairs(pairs, seed))
    progress(0.8)
    return PaletteResult(
        theme=theme.name,
        palette=tuple(palette),
        alphas=alphas,
        combinations=first.size * backgrounds.shape[0],
        smaller={a: int(v.sum()) for a, v in smaller.items()},
        collisions={a: int(v.sum()) for a, v in collide.items()},
        smaller_per_canvas={a: tuple(int(x) for x in v) for a, v in smaller.items()},
        collisions_per_canvas={a: tuple(int(x) for x in v) for a, v in collide.items()},
        random_pairs=pairs,
        seed=seed,
        random_combinations=pairs * backgrounds.shape[0],
        random_alphas=random_alphas,
        random_collisions={a: int(random[i].sum()) for i, a in enumerate(random_alphas)},
    )
