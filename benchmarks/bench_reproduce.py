"""Benchmark of ``alpha-audit reproduce`` against a straightforward float64 implementation.

Run as ``python benchmarks/bench_reproduce.py`` (not a test).  In one process
it times the fast kernels and the straightforward chunked numpy float64
implementation (:mod:`alpha_audit.reproduce.reference`: per-combination
``srgb_decode``, ``composite_extended``, ``relative_luminance``,
``contrast_from_luminance``), checks that counts are identical and sums agree
to 1e-12 relative, and prints the times and ratios against the issue's targets
(2-core machine): full gamut one alpha < 1.0 s and >= 12x, broad grid both
alphas < 2.5 s, sweep < 3 s.  ``--quick`` skips the slow baselines.
"""

from __future__ import annotations

import argparse
import resource
import time
from pathlib import Path

import numpy as np

from alpha_audit.load.theme import load_theme
from alpha_audit.reproduce import broad_grid, full_gamut, palette_separation, sweep
from alpha_audit.reproduce.grids import encoded_levels
from alpha_audit.reproduce.reference import reference_broad_grid, reference_full_gamut

THEME = Path(__file__).resolve().parents[1] / "themes" / "paper16.yaml"


def timed(fn, *args, **kwargs):
    """(result, seconds) of one call."""
    start = time.perf_counter()
    result = fn(*args, **kwargs)
    return result, time.perf_counter() - start


def peak_mb() -> float:
    """Peak resident set size of this process (Linux reports KiB)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def check_full_gamut(fast, reference) -> None:
    """Identical counts, sums within 1e-12 relative, per canvas."""
    for i, canvas in enumerate(fast.canvases):
        c = canvas.change
        for key in ("increase", "decrease", "newly_reach"):
            assert getattr(c, key) == reference[key][i], (canvas.name, key)
        for key in ("sum_change", "sum_difference", "sum_exclusion"):
            want = reference[key][i]
            assert abs(getattr(c, key) - want) <= 1e-12 * abs(want), (canvas.name, key)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="skip the slow baselines")
    args = parser.parse_args()
    theme = load_theme(THEME)

    fg, t_fg = timed(full_gamut, theme, [1.1])
    print(f"full gamut, 1 alpha, {len(theme.canvases)} canvases: {t_fg:6.3f} s   (target < 1.0 s)")
    bg, t_bg = timed(broad_grid, [1.1, 1.4])
    print(f"broad grid, 2 alphas:                {t_bg:6.3f} s   (target < 2.5 s)")
    _, t_sw = timed(sweep, theme)
    print(f"sweep, 81 alphas with collisions:    {t_sw:6.3f} s   (target < 3 s)")
    _, t_pl = timed(palette_separation, theme)
    print(f"palette separation:                  {t_pl:6.3f} s")
    print(f"peak resident memory so far:         {peak_mb():6.0f} MB   (target < 1 GB)")
    if args.quick:
        return

    ref, t_ref = timed(
        reference_full_gamut, np.arange(256) / 255, theme.backgrounds, 1.1, controls=True
    )
    check_full_gamut(fg[0], ref)
    print(
        f"straightforward full gamut:          {t_ref:6.3f} s   ratio {t_ref / t_fg:5.1f}x "
        "(target >= 12x); counts identical, sums within 1e-12"
    )
    ref_bg = {}
    t_ref_bg = 0.0
    for a in (1.1, 1.4):
        ref_bg[a], t = timed(reference_broad_grid, encoded_levels(17), encoded_levels(33), a)
        t_ref_bg += t
    for r in bg:
        want = ref_bg[r.alpha]
        assert (r.increase, r.decrease, r.loss_le_0_25) == (
            want["increase"],
            want["decrease"],
            want["loss_le_0_25"],
        )
        assert r.max_loss == want["max_loss"]
    print(f"straightforward broad grid:          {t_ref_bg:6.3f} s   ratio {t_ref_bg / t_bg:5.1f}x")
    print(f"peak resident memory, with baselines: {peak_mb():5.0f} MB")


if __name__ == "__main__":
    main()
