"""Run every benchmark in this folder (``make bench``), each in a process of its own.

A benchmark may set environment variables (``bench_brands.py`` turns the render
cache off); a process each keeps that from reaching the next one.  Every script
runs even when one fails; the exit code says whether any did.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).parent

if __name__ == "__main__":
    failed = []
    for script in sorted(HERE.glob("bench_*.py")):
        print(f"== {script.name}", flush=True)
        if subprocess.run([sys.executable, str(script)], check=False).returncode != 0:
            failed.append(script.name)
    if failed:
        raise SystemExit(f"failed: {', '.join(failed)}")
