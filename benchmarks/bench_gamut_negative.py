"""Benchmark: the full 8-bit gamut (16.7 M sources) x paper16 at alpha = -0.5.

Issue 10: a negative coefficient fell back to the straightforward path.  It
now counts from the per-channel tables (``kernels.change_counts_any_order``);
the straightforward chunked implementation is measured in the same run and
both must give the same counts on every canvas.

    python benchmarks/bench_gamut_negative.py
"""

from __future__ import annotations

import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
ALPHA = -0.5


def main() -> None:
    from alpha_audit.load.theme import load_theme
    from alpha_audit.reproduce.experiments import full_gamut
    from alpha_audit.reproduce.grids import encoded_levels
    from alpha_audit.reproduce.reference import reference_full_gamut

    theme = load_theme(REPO / "themes/paper16.yaml")
    start = time.perf_counter()
    (fast,) = full_gamut(theme, [ALPHA])
    t_fast = time.perf_counter() - start
    start = time.perf_counter()
    ref = reference_full_gamut(
        encoded_levels(256), theme.backgrounds, ALPHA, threshold=theme.threshold, controls=False
    )
    t_ref = time.perf_counter() - start
    same = all(
        [getattr(c.change, key) for c in fast.canvases] == ref[key].tolist()
        for key in ("increase", "decrease", "newly_reach")
    )
    m = len(theme.canvases)
    print(f"full gamut, 256^3 sources x {m} canvases, alpha {ALPHA}: {t_fast:.2f} s")
    print(f"straightforward chunked float64:                    {t_ref:.2f} s")
    print(f"ratio: {t_ref / t_fast:.1f}x   same counts on every canvas: {same}")
    if not same:
        raise SystemExit("table counts differ from the straightforward counts")


if __name__ == "__main__":
    main()
