"""The generated SVG shapes several browser tests draw (``generated_svgs``).

The ``engine`` fixture (each installed engine; a missing one skips, or fails on
CI) is in tests/conftest.py, shared with tests/pages.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest


def _generated_svgs(folder: Path, count: int) -> list[Path]:
    """Deterministic stroked and filled shapes at sub-pixel positions: many coverage levels."""
    rng = np.random.default_rng(20260913)
    files = []
    for k in range(count):
        parts = []
        for _ in range(3):
            kind = rng.integers(0, 4)
            x, y = rng.uniform(2, 22, 2).round(2)
            w = rng.choice([1.0, 1.5, 2.0, 2.5])
            if kind == 0:
                r = round(float(rng.uniform(2, 9)), 2)
                parts.append(f'<circle cx="{x}" cy="{y}" r="{r}" stroke-width="{w}"/>')
            elif kind == 1:
                pts = " ".join(f"{a:.2f},{b:.2f}" for a, b in rng.uniform(1, 23, (4, 2)))
                parts.append(f'<polyline points="{pts}" stroke-width="{w}"/>')
            elif kind == 2:
                angle = round(float(rng.uniform(0, 90)), 1)
                parts.append(
                    f'<rect x="{x - 4}" y="{y - 3}" width="8" height="6" rx="1.5" '
                    f'transform="rotate({angle} {x} {y})" fill="currentColor" stroke="none"/>'
                )
            else:
                cx, cy = rng.uniform(4, 20, 2).round(2)
                parts.append(
                    f'<path d="M{x} {y} Q{cx} {cy} {24 - x} {24 - y}" stroke-width="{w}"/>'
                )
        svg = (
            '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24" fill="none" '
            'stroke="currentColor" stroke-linecap="round" stroke-linejoin="round">'
            + "".join(parts)
            + "</svg>"
        )
        path = folder / f"shape-{k:02d}.svg"
        path.write_text(svg)
        files.append(path)
    return files


@pytest.fixture(scope="session")
def generated_svgs() -> Callable[[Path, int], list[Path]]:
    """``make(folder, count)``: write ``count`` generated 24 x 24 SVG shapes into ``folder``."""
    return _generated_svgs
