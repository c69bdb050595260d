"""Benchmark: multicolour icons cost what their paints cost (issue 23, item 3).

Every paint group of every icon is measured at 16, 24 and 48 px through the
render workers (``measure_paints``, no cache), for 271 flag-icons flags (4x3;
about five paint groups each, heraldry included) and 300 single-paint Lucide
icons.  Target: a flag's paint group costs at most 3x a Lucide icon's.

Also measured in the same run, on the first flags, in one process: the
straightforward way (each paint group's whole SVG, its other paints unpainted,
parsed and drawn once per size) against this one (the group's own shapes only,
one parse for all sizes), with every mask compared.

    python benchmarks/bench_multicolour.py [ROUNDS]
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _icons import flag_icons, lucide_icons

SIZES = (16, 24, 48)


def _cpu() -> float:
    """CPU seconds of this process and of the children it reaped (the render workers)."""
    import resource

    own, kids = (
        resource.getrusage(who) for who in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN)
    )
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


def measured(files: list[Path], rounds: int) -> tuple[float, float, int]:
    """Best wall time and CPU time (workers included) of measuring every paint group of
    ``files``, and the group count."""
    from alpha_audit.load.paint_masks import measure_paints
    from alpha_audit.load.sandbox import RenderLimits

    icons = [(f.stem, f) for f in files]
    best, best_cpu, groups = float("inf"), float("inf"), 0
    for _ in range(rounds):
        start, cpu = time.perf_counter(), _cpu()
        result = measure_paints(icons, SIZES, cache=False, limits=RenderLimits(timeout=60.0))
        best = min(best, time.perf_counter() - start)
        best_cpu = min(best_cpu, _cpu() - cpu)
        groups = sum(len(i.coverage) for i in result.icons.values())
        # flags with more than MAX_PAINT_GROUPS paints are refused (the audit's rule)
        if any("distinct paints" not in p.message for p in result.problems):
            raise SystemExit(f"problems: {result.problems[:3]}")
    return best, best_cpu, groups


def straightforward_against_ours(files: list[Path]) -> tuple[float, float, int]:
    """In one process: seconds the straightforward way, seconds this way, masks compared."""
    from alpha_audit.load import paints
    from alpha_audit.load._svg_worker import read_paints, render_alpha, render_alphas

    data = [f.read_bytes() for f in files]
    start = time.perf_counter()
    ours = []
    for svg in data:
        _, variants, refused, _ = read_paints(svg, 32)
        if refused is None:
            ours.append([render_alphas(v, SIZES) for v in variants])
    fast = time.perf_counter() - start
    real = paints._prunable
    paints._prunable = lambda document: set()  # every group's SVG is the whole drawing
    try:
        start = time.perf_counter()
        plain = []
        for svg in data:
            try:
                _, variants = paints.paints_and_isolates(svg, max_groups=32)
            except paints.SvgError:
                continue
            plain.append([[render_alpha(v, size) for size in SIZES] for v in variants])
        slow = time.perf_counter() - start
    finally:
        paints._prunable = real
    if ours != plain:
        raise SystemExit("masks differ between the two ways")
    return slow, fast, sum(len(g) * len(SIZES) for g in ours)


def main() -> None:
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 2
    before = ", ".join(f"{x:.2f}" for x in os.getloadavg())
    flags = flag_icons()
    lucide = lucide_icons(300)
    f_time, f_cpu, f_groups = measured(flags, rounds)
    l_time, l_cpu, l_groups = measured(lucide, rounds)
    slow, fast, masks = straightforward_against_ours(flags[:25])
    after = ", ".join(f"{x:.2f}" for x in os.getloadavg())
    print(f"every paint group at {SIZES} px, render workers, best of {rounds} (CPU: workers too):")
    for label, t, cpu, n in (
        (f"{len(flags)} flags, {f_groups} paint groups", f_time, f_cpu, f_groups),
        (f"{len(lucide)} lucide icons, {l_groups} groups", l_time, l_cpu, l_groups),
    ):
        print(
            f"  {label + ':':36} {t:6.2f} s {1000 * t / n:6.1f} ms a group; "
            f"{cpu:6.2f} s CPU {1000 * cpu / n:6.1f} ms a group"
        )
    ratio, wall_ratio = (
        (f_cpu / f_groups) / (l_cpu / l_groups),
        (f_time / f_groups) / (l_time / l_groups),
    )
    verdict = "PASS" if ratio <= 3 else "FAIL"
    print(
        f"  a flag's group costs {ratio:.2f}x a lucide icon's in CPU time "
        f"({wall_ratio:.2f}x in wall time; target <= 3x: {verdict})"
    )
    print(
        f"first 25 flags in one process, {masks} masks identical: straightforward {slow:.2f} s, "
        f"these {fast:.2f} s ({slow / fast:.1f}x)"
    )
    print(f"  machine: load average {before} before, {after} after (2 cores shared)")


if __name__ == "__main__":
    main()
