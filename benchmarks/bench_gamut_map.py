"""Benchmark: CSS Color 4 gamut mapping of 2,541 out-of-sRGB colours, vectorised vs coloraide.

``alpha_audit.color.gamut.map_to_srgb`` maps every colour in one batch; the
straightforward implementation is coloraide's per-colour
``fit("srgb", method="minde-chroma", pspace="oklch", jnd=0.02)``, measured in
the same run on the same colours (display-p3, rec2020 and OKLCH colours drawn
at random, kept only when outside sRGB).  Both must agree within 1e-9 per
encoded channel.

    python benchmarks/bench_gamut_map.py
"""

from __future__ import annotations

import time

import numpy as np

N = 2541  # out-of-gamut colours, the size of the design system that took ~10 s
TOLERANCE = 1e-9


def _colors(n: int) -> list:
    from coloraide import Color

    rng = np.random.default_rng(2541)
    out = []
    while len(out) < n:
        kind = len(out) % 3
        if kind == 0:
            c = Color("display-p3", list(rng.random(3)))
        elif kind == 1:
            c = Color("rec2020", list(rng.random(3)))
        else:
            c = Color(
                "oklch", [rng.uniform(0.05, 0.95), rng.uniform(0.05, 0.4), rng.uniform(0, 360)]
            )
        if not c.convert("srgb").in_gamut(tolerance=0):
            out.append(c)
    return out


def main() -> None:
    from alpha_audit.color.gamut import map_to_srgb

    colors = _colors(N)
    unmapped = np.array([c.convert("srgb", norm=False).coords(nans=False) for c in colors])
    start = time.perf_counter()
    ours = map_to_srgb(unmapped)
    t_ours = time.perf_counter() - start
    start = time.perf_counter()
    ref = np.array(
        [
            c.clone()
            .fit("srgb", method="minde-chroma", pspace="oklch", jnd=0.02)
            .convert("srgb")
            .coords(nans=False)
            for c in colors
        ]
    )
    t_ref = time.perf_counter() - start
    worst = float(np.max(np.abs(ours - np.clip(ref, 0, 1))))
    print(f"gamut map, {N} out-of-sRGB colours, vectorised: {t_ours:.3f} s")
    print(f"coloraide minde-chroma, one colour at a time:   {t_ref:.3f} s")
    print(f"ratio: {t_ref / t_ours:.1f}x   largest channel difference: {worst:.1e}")
    if worst > TOLERANCE:
        raise SystemExit(f"vectorised mapping differs from coloraide by {worst:.1e}")


if __name__ == "__main__":
    main()
