"""Benchmark: check and suggest on simple-icons logos, each in its brand colour.

Issue 10: on the 3,470 logos (2,788 colours) x 38 canvases ``check`` died at
10.9 GB; ``suggest`` on 300 logos (271 colours) took 5 min 16 s and 10.3 GB.
Targets, measured in this run (whole process, ``/usr/bin/time -v``):

- check, all logos in their own colours x 38 canvases: at most 3x the time
  of the same logos in 8 colours, and under a 3 GB address-space cap;
- suggest on the same set (every logo in its own colour): at most 3x check
  (issue 23; it was 13x on the 3,470 logos), peak under 1 GB.

    python benchmarks/bench_brands.py           # every logo
    BENCH_LOGOS=1000 python benchmarks/bench_brands.py
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _icons import canvases, make_brand_project, run_measured, simple_icons, write_theme

EIGHT = ["#ee7733", "#0077bb", "#33bbee", "#ee3377", "#cc3311", "#009988", "#bbbbbb", "#000000"]
CAP_KB = 3_000_000  # ulimit -v, in kB


def _capped(args: list[str]) -> list[str]:
    return ["sh", "-c", f'ulimit -v {CAP_KB} && exec "$@"', "sh", *args]


def main() -> None:
    os.environ["ALPHA_AUDIT_NO_CACHE"] = "1"  # every run renders, as before the render cache
    cli = str(Path(sys.executable).with_name("alpha-audit"))
    count = int(os.environ.get("BENCH_LOGOS", "0")) or None
    logos = simple_icons(count)
    colours = len({c for _, c in logos})
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        theme = write_theme(root / "theme.yaml", canvases(38))
        own = make_brand_project(root / "own", logos)
        eight = make_brand_project(root / "eight", logos, palette=EIGHT)
        check = [cli, "check", str(theme), "--format", "json", "--exit-zero"]
        t8, m8, rc8 = run_measured(_capped([*check, str(eight)]))
        tn, mn, rcn = run_measured(_capped([*check, str(own)]))
        print(
            f"check, {len(logos)} logos x 38 canvases, 8 colours: {t8:6.2f} s {m8:5d} MB exit {rc8}"
        )
        print(f"check, same logos, {colours} own colours: {tn:6.2f} s {mn:5d} MB exit {rcn}")
        print(f"own/8: {tn / t8:.2f}x  target <= 3x -> {'PASS' if tn <= 3 * t8 else 'FAIL'}")

        ts, ms, rcs = run_measured(
            _capped([cli, "suggest", str(theme), str(own), "--format", "json"])
        )
        print(f"suggest, same logos, own colours: {ts:6.2f} s {ms:5d} MB exit {rcs}")
        ok = ts <= 3 * tn and ms < 1024
        print(f"suggest/check: {ts / tn:.2f}x  target <= 3x, < 1 GB -> {'PASS' if ok else 'FAIL'}")


if __name__ == "__main__":
    main()
