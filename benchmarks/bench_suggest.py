"""Benchmark ``suggest`` on 300 icons x 16 canvases with a 7-colour palette (issue 4).

Bar: set-wide + per colour + per icon under 2 s on a 2-core machine.  For
scale, the same run times a straightforward 1e-4 sweep (``audit`` + ``gate``
at every alpha, stopping at the first failure) for the set-wide answer, and
for one colour and one icon, and prints the ratio.  Run as a script:

    .venv/bin/python benchmarks/bench_suggest.py
"""

from __future__ import annotations

import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from alpha_audit.gate import evaluate
from alpha_audit.load.theme import load_theme
from alpha_audit.model import Icon, IconSet
from alpha_audit.policy import Policy
from alpha_audit.rows import audit
from alpha_audit.suggest import suggest

ROOT = Path(__file__).resolve().parents[1]
VIBRANT = {  # Paul Tol's Vibrant palette, as in examples/vibrant
    "orange": "#ee7733",
    "blue": "#0077bb",
    "cyan": "#33bbee",
    "magenta": "#ee3377",
    "red": "#cc3311",
    "teal": "#009988",
    "grey": "#bbbbbb",
}


def iconset(n: int = 300) -> IconSet:
    names = list(VIBRANT)
    icons = tuple(
        Icon(
            f"icon{i:03d}",
            f"icon{i:03d}.svg",
            VIBRANT[names[i % 7]],
            1.2 if i % 25 == 0 else 1.1,
            names[i % 7],
        )
        for i in range(n)
    )
    return IconSet("bench", icons, VIBRANT)


def sweep(theme, icons: IconSet, policy: Policy, moving: set[str], step: float = 1e-4) -> float:
    """First unsafe alpha on a grid, the straightforward way (audit + gate per alpha)."""
    for a in np.arange(1.0, 2.0 + step / 2, step):
        moved = tuple(replace(i, alpha=float(a)) if i.name in moving else i for i in icons.icons)
        gate = evaluate([audit(theme, replace(icons, icons=moved))], policy)
        if any(set(f.icons) & moving for f in gate.failures):
            return float(a)
    return 2.0


def main() -> None:
    theme = load_theme(ROOT / "themes" / "paper16.yaml")
    icons = iconset()
    policy = Policy()
    suggest(audit(theme, icons), policy)  # warm imports and caches
    t0 = time.perf_counter()
    result = suggest(audit(theme, icons), policy)
    exact = time.perf_counter() - t0
    size = f"{len(icons.icons)} icons x {len(theme.canvases)} canvases x 7 colours"
    print(f"suggest (set-wide + per colour + per icon), {size}: {exact:.3f} s")
    limit = result.overall.limit
    why = "nothing" if limit is None else f"{limit.rule.value} on {limit.canvas} at {limit.at:.6f}"
    print(f"  set-wide a* = {result.alpha} ({why})")

    everyone = {i.name for i in icons.icons}
    t0 = time.perf_counter()
    swept = sweep(theme, icons, policy, everyone)
    set_wide = time.perf_counter() - t0
    print(f"1e-4 sweep, set-wide only: {set_wide:.1f} s (first unsafe {swept:.4f})")
    t0 = time.perf_counter()
    sweep(theme, icons, policy, {"icon000"})
    one = time.perf_counter() - t0
    # A colour or an icon that never breaks sweeps the whole grid: 10,001 audits.
    scenarios = 1 + len(result.per_color) + len(result.per_icon)
    estimate = set_wide + (scenarios - 1) * one
    print(f"1e-4 sweep, one icon: {one:.1f} s")
    print(f"  all {scenarios} questions ~ {estimate:.0f} s (extrapolated from the two above)")
    print(f"ratio sweep/exact: set-wide alone {set_wide / exact:.0f}x")
    print(f"  all questions ~{estimate / exact:.0f}x (extrapolated)")
    print("bar: suggest < 2 s ->", "PASS" if exact < 2.0 else "FAIL")


if __name__ == "__main__":
    main()
