"""Benchmark: closest pair of 2,788 brand colours (CIEDE2000) on 38 canvases.

Issue 10: the all-pairs separation column needed 3.3 GiB for this set.  The
pruned search (:mod:`alpha_audit.color.nearest`) is compared with the
chunked brute force over every pair in the same run; both must name the same
pair at the same distance on every canvas.

    python benchmarks/bench_separation.py
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _icons import canvases, simple_icons


def main() -> None:
    import numpy as np

    from alpha_audit.color import composite_extended, delta_e_2000_lab, hex_to_linear, linear_to_lab
    from alpha_audit.color.nearest import closest_pair_brute_force, closest_pair_delta_e_2000

    colors = sorted({c for _, c in simple_icons()})
    backgrounds = np.array([hex_to_linear(c) for c in canvases(38)])
    sources = np.array([hex_to_linear(c) for c in colors])
    lab = linear_to_lab(composite_extended(sources[:, None], backgrounds[None], 1.1))  # (k, m, 3)

    start = time.perf_counter()
    pruned = [closest_pair_delta_e_2000(lab[:, j]) for j in range(lab.shape[1])]
    fast = time.perf_counter() - start

    start = time.perf_counter()
    brute = [
        closest_pair_brute_force(
            lambda i, j, c=j: delta_e_2000_lab(lab[i, c], lab[j, c]), lab.shape[0]
        )
        for j in range(lab.shape[1])
    ]
    slow = time.perf_counter() - start
    same = pruned == brute
    print(f"separation, {len(colors)} colours x {lab.shape[1]} canvases: pruned {fast:.2f} s")
    print(f"chunked brute force over every pair:                     {slow:.2f} s")
    print(f"ratio: {slow / fast:.0f}x   same pair and distance on every canvas: {same}")
    if not same:
        raise SystemExit("pruned and brute-force closest pairs differ")


if __name__ == "__main__":
    main()
