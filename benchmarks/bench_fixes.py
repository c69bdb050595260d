"""Benchmark the fix for every finding (issue 13, item 5) on a failing set.

300 icons in 40 colours on 16 canvases at alpha 1.1, gated on below-threshold
and loss: nearly every colour fails somewhere.  Bar: every fix (largest safe
alpha, smallest alpha reaching the threshold per mode, nearest passing colour)
under 10 s on a 2-core machine.  For scale, the same run times the
straightforward versions for a few colours -- a 1e-4 alpha sweep, and a dense
OKLCH (L, C) grid at 0.0025 for the nearest colour -- prints the ratio and how
far the grid's best colour is from ours (ours should never be worse than the
grid by more than its step).  Run as a script:

    .venv/bin/python benchmarks/bench_fixes.py
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from alpha_audit.color import (
    composite_extended,
    contrast_ratio,
    delta_e_2000,
    linear_to_hex,
    shipped,
)
from alpha_audit.color.oklch import linear_to_oklch, oklch_to_linear
from alpha_audit.fixes import passes_everywhere, with_fixes
from alpha_audit.gate import evaluate
from alpha_audit.load.theme import load_theme
from alpha_audit.model import Icon, IconSet
from alpha_audit.policy import Policy
from alpha_audit.results import CheckReport, ColorFix
from alpha_audit.rows import audit
from alpha_audit.rules import Rule

ROOT = Path(__file__).resolve().parents[1]
POLICY = Policy(rules=frozenset({Rule.BELOW_THRESHOLD, Rule.LOSS}))


def iconset(n: int = 300, colours: int = 40) -> IconSet:
    rng = np.random.default_rng(13)
    palette = {f"c{k:02d}": linear_to_hex(rng.random(3)) for k in range(colours)}
    names = list(palette)
    icons = tuple(
        Icon(
            f"icon{i:03d}", f"icon{i:03d}.svg", palette[names[i % colours]], 1.1, names[i % colours]
        )
        for i in range(n)
    )
    return IconSet("bench", icons, palette)


def sweep_reaching(source, backgrounds, threshold: float, step: float = 1e-4) -> float | None:
    """The straightforward smallest alpha: composite at every grid point, judged as the
    fixes are, on what ships (the 8-bit colour on the 8-bit canvas)."""
    canvases = shipped(backgrounds)
    for a in np.arange(1.0, 2.0 + step / 2, step):
        shown = shipped(composite_extended(source, backgrounds, a))
        if np.all(contrast_ratio(shown, canvases) >= threshold):
            return float(a)
    return None


def grid_nearest(source, backgrounds, alphas, threshold: float, step: float = 0.0025):
    """The straightforward nearest colour: every (L, C) of the hue on a grid."""
    _, _, hue = linear_to_oklch(source)
    ll, cc = np.meshgrid(np.arange(0, 1 + step / 2, step), np.arange(0, 0.4 + step / 2, step))
    lin = oklch_to_linear(np.stack([ll.ravel(), cc.ravel(), np.full(ll.size, hue)], axis=-1))
    ok = passes_everywhere(lin, backgrounds, alphas, threshold, POLICY)
    if not ok.any():
        return None
    return float(delta_e_2000(np.clip(lin[ok], 0, 1), source).min())


def main() -> None:
    theme = load_theme(ROOT / "themes" / "paper16.yaml")
    icons = iconset()
    result = audit(theme, icons)
    report = CheckReport((result,), evaluate([result], POLICY))
    small = audit(theme, iconset(14, 2))
    with_fixes(CheckReport((small,), evaluate([small], POLICY)))  # warm up
    t0 = time.perf_counter()
    fixes = [f for f in with_fixes(report).fixes if isinstance(f, ColorFix)]
    ours = time.perf_counter() - t0
    colours = sorted({f.color for f in fixes})
    print(
        f"fixes for {len(icons.icons)} icons x {len(theme.canvases)} canvases: "
        f"{len(fixes)} (colour, canvas) fixes, {len(colours)} failing colours: {ours:.2f} s"
    )

    sample = [next(f for f in fixes if f.color == c) for c in colours[:4]]
    backgrounds = theme.backgrounds
    t_sweep = t_grid = 0.0
    worst_gap = 0.0
    for fix in sample:
        icon = next(i for i in icons.icons if i.name == fix.icons[0])
        src = np.array(icon.linear)
        same = [k for k, c in enumerate(theme.canvases) if c.mode == fix.mode]
        t0 = time.perf_counter()
        swept = sweep_reaching(src, backgrounds[same], result.threshold)
        t_sweep += time.perf_counter() - t0
        if fix.reach.alpha is not None and swept is not None:
            assert abs(swept - fix.reach.exact) <= 1e-4 + 1e-9, (swept, fix.reach.exact)
        t0 = time.perf_counter()
        best = grid_nearest(src, backgrounds, [icon.alpha], result.threshold)
        t_grid += time.perf_counter() - t0
        if best is not None and fix.nearest is not None:
            worst_gap = max(worst_gap, fix.nearest.delta_e - best)
    per_colour = ours / len(colours)
    straightforward = (t_sweep + t_grid) / len(sample)
    print(f"straightforward, per colour: {straightforward:.2f} s (1e-4 sweep + 0.0025 grid)")
    print(f"ours, per colour: {per_colour:.3f} s; ratio {straightforward / per_colour:.1f}x")
    print(f"  ours minus grid's best CIEDE2000 (8-bit hex vs continuous): <= {worst_gap:.3f}")
    print("bar: every fix < 10 s ->", "PASS" if ours < 10.0 else "FAIL")


if __name__ == "__main__":
    main()
