"""Benchmark: ``alpha-audit check`` on all of Lucide x 17 canvases x 3 sizes, cold and warm.

Against a competent single-process script measured in the same run (issues 23
and 31): it renders each icon at each size with cairosvg (``svg2png``, alpha
read back with Pillow) and computes each icon x canvas pair's contrast with
numpy.  Every run is a whole process (interpreter start and imports included),
timed best of ``ROUNDS`` with the three kinds interleaved, as an installed
package runs: with its bytecode compiled (a first untimed run of each writes it
even where ``PYTHONDONTWRITEBYTECODE`` is set).  CPU time (user + system, render
workers included) and peak memory from ``/usr/bin/time -v``.  On a machine
shared with other work the wall-clock ratios follow the load; the CPU-time
ratios do not.

Targets (issue 31): cold (empty render cache) at least 1.5x the script, warm
(the cache filled by an earlier run) at least 4x.

    python benchmarks/bench_check.py [ROUNDS [ICONS]]
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _icons import lucide_icons, make_project, run_timed

REPO = Path(__file__).resolve().parents[1]
THEME = REPO / "themes/paper16.yaml"  # 16 canvases; a 17th (mid grey) is added below

# What a competent user writes: one process, cairosvg per icon and size, numpy per pair.
SCRIPT = """
import sys
from io import BytesIO
from pathlib import Path

import cairosvg
import numpy as np
import yaml
from PIL import Image

theme = yaml.safe_load(Path(sys.argv[1]).read_text())
spec = yaml.safe_load(Path(sys.argv[2]).read_text())
palette = list(spec["palette"].values())
files = sorted((Path(sys.argv[2]).parent / "svg").glob("*.svg"))


def linear(hex_color):
    c = np.array([int(hex_color[i : i + 2], 16) for i in (1, 3, 5)]) / 255
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


canvases = np.array([linear(c["color"]) for c in theme["canvases"]])
weights = np.array([0.2126, 0.7152, 0.0722])
y_canvas = canvases @ weights
contrast = []
for i, file in enumerate(files):
    data = file.read_bytes()
    for size in spec["sizes"]:
        png = cairosvg.svg2png(bytestring=data, output_width=size, output_height=size)
        alpha = np.asarray(Image.open(BytesIO(png)).convert("RGBA"))[..., 3]
        assert alpha.any()
    source = linear(palette[i % len(palette)])
    shown = np.clip(canvases + spec["alpha"] * (source - canvases), 0, 1) @ weights
    contrast.append((np.maximum(shown, y_canvas) + 0.05) / (np.minimum(shown, y_canvas) + 0.05))
print(len(contrast), float(np.mean(contrast)))
"""


def seventeen(folder: Path) -> Path:
    """paper16 plus a mid-grey canvas: the issue's 17 canvases."""
    text = THEME.read_text().rstrip("\n") + "\n  - {name: grey50, color: '#808080'}\n"
    path = folder / "theme17.yaml"
    path.write_text(text)
    return path


def load() -> str:
    return "load average " + ", ".join(f"{x:.2f}" for x in os.getloadavg())


def main() -> None:
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    icons = lucide_icons(int(sys.argv[2]) if len(sys.argv) > 2 else None)
    os.environ.pop("PYTHONDONTWRITEBYTECODE", None)  # bytecode as an installed package has it
    cli = str(Path(sys.executable).with_name("alpha-audit"))
    before = load()
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        manifest = make_project(root / "project", icons)
        theme = seventeen(root)
        script = root / "straightforward.py"
        script.write_text(SCRIPT)
        check = [cli, "check", str(theme), str(manifest), "--format", "json", "--exit-zero"]
        warm_cache = root / "warm-cache"
        os.environ["ALPHA_AUDIT_CACHE_DIR"] = str(warm_cache)
        run_timed(check)  # fills the warm cache
        run_timed([sys.executable, str(script), str(theme), str(manifest)])  # its bytecode
        base, cold, warm = [], [], []
        for k in range(rounds):
            base.append(run_timed([sys.executable, str(script), str(theme), str(manifest)]))
            os.environ["ALPHA_AUDIT_CACHE_DIR"] = str(root / f"cold-cache-{k}")  # empty
            cold.append(run_timed(check))
            os.environ["ALPHA_AUDIT_CACHE_DIR"] = str(warm_cache)
            warm.append(run_timed(check))
    after = load()
    if any(code != 0 for *_, code in base + cold + warm):
        raise SystemExit("a run failed")
    (b, b_cpu, b_mb), (c, c_cpu, c_mb), (w, w_cpu, w_mb) = (
        (min(r[0] for r in runs), min(r[1] for r in runs), max(r[2] for r in runs))
        for runs in (base, cold, warm)
    )
    print(f"{len(icons)} lucide icons x 17 canvases x 3 sizes, whole process, best of {rounds}:")
    for label, t, cpu, mb in (
        ("straightforward script (cairosvg + numpy)", b, b_cpu, b_mb),
        ("check, cold (empty render cache)", c, c_cpu, c_mb),
        ("check, warm (cache filled)", w, w_cpu, w_mb),
    ):
        print(f"  {label + ':':44} {t:5.2f} s  {cpu:5.2f} s CPU  {mb:4d} MB")
    print(
        f"  cold: {b / c:.2f}x (CPU {b_cpu / c_cpu:.2f}x; "
        f"target >= 1.5x: {'PASS' if b >= 1.5 * c else 'FAIL'})"
    )
    print(
        f"  warm: {b / w:.2f}x (CPU {b_cpu / w_cpu:.2f}x; "
        f"target >= 4x: {'PASS' if b >= 4 * w else 'FAIL'})"
    )
    print(f"  machine: {before} before, {after} after (2 cores shared)")


if __name__ == "__main__":
    main()
