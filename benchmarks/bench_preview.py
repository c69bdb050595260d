"""Benchmark: ``alpha-audit preview`` grid sheets, 300 real icons x 16 canvases x 2 alphas, 48 px.

Target (issue 5): all sixteen PNG sheets written in under 10 s on a 2-core
machine, for the whole process (start-up, SVG rasterisation, compositing,
labels, PNG encoding).  The baseline is the straightforward implementation,
measured in the same run on the same masks: composite each icon x canvas x
alpha with the colour package at every pixel, paste it with Pillow, label it,
and save with Pillow's default PNG settings.

    python benchmarks/bench_preview.py [--icons DIR]   # DIR: a folder of SVGs
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _icons import lucide_icons, make_project

REPO = Path(__file__).resolve().parents[1]
THEME = REPO / "themes/paper16.yaml"
ALPHAS = ("1", "1.1")
SIZE = 48
TARGET_S = 10.0


def ours(manifest: Path, out: Path) -> float:
    """The real command in a fresh process; returns wall seconds."""
    cli = Path(sys.executable).with_name("alpha-audit")
    command = [str(cli), "preview", str(THEME), str(manifest), "-o", str(out), "-s", str(SIZE)]
    for a in ALPHAS:
        command += ["-a", a]
    start = time.perf_counter()
    subprocess.run(command, check=True, capture_output=True)
    return time.perf_counter() - start


def straightforward(manifest: Path, out: Path) -> float:
    """Per-icon, per-pixel compositing and one paste per icon; returns seconds."""
    start = time.perf_counter()
    import numpy as np
    from PIL import Image, ImageDraw, ImageFont

    from alpha_audit import load_iconset, load_theme, rasterize_icons
    from alpha_audit.color import composite_coverage, composite_extended, contrast_ratio, to_8bit

    theme = load_theme(THEME)
    iconset = load_iconset(manifest)
    masks = rasterize_icons([(i.name, i.file) for i in iconset.icons], [SIZE]).masks
    font = ImageFont.load_default(size=12)
    cell, cols = SIZE + 16, 20
    rows = -(-len(iconset.icons) // cols)
    for canvas in theme.canvases:
        b = np.array(canvas.linear)
        fill = tuple(int(v) for v in to_8bit(b))
        sheet = Image.new("RGB", (cols * cell + 48, len(ALPHAS) * rows * (cell + 16) + 48), fill)
        draw = ImageDraw.Draw(sheet)
        for r, a in enumerate(float(x) for x in ALPHAS):
            for k, icon in enumerate(iconset.icons):
                s = np.array(icon.linear)
                block = to_8bit(composite_coverage(s, b, a, masks[(icon.name, SIZE)]))
                x = 24 + (k % cols) * cell
                y = 24 + (r * rows + k // cols) * (cell + 16)
                sheet.paste(Image.fromarray(block, "RGB"), (x, y))
                cr = float(contrast_ratio(composite_extended(s, b, a), b))
                draw.text((x, y + SIZE + 2), f"{cr:.2f}", font=font, fill=(0, 0, 0))
        sheet.save(out / f"{canvas.name}.png")
    return time.perf_counter() - start


def rasterize_only(manifest: Path) -> float:
    """The SVG rasterisation both implementations share; returns seconds."""
    from alpha_audit import load_iconset, rasterize_icons

    iconset = load_iconset(manifest)
    start = time.perf_counter()
    rasterize_icons([(i.name, i.file) for i in iconset.icons], [SIZE])
    return time.perf_counter() - start


def main() -> None:
    os.environ["ALPHA_AUDIT_NO_CACHE"] = "1"  # every run renders, as before the render cache
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--icons", type=Path, help="folder of SVG icons (default: lucide-static)")
    args = parser.parse_args()
    icons = sorted(args.icons.glob("*.svg"))[:300] if args.icons else lucide_icons(300)
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        manifest = make_project(root / "project", icons, sizes=(SIZE,))
        (root / "ours").mkdir()
        (root / "base").mkdir()
        t_ours = ours(manifest, root / "ours")
        sheets = sorted((root / "ours").glob("*.png"))
        megabytes = sum(p.stat().st_size for p in sheets) / 1e6
        t_base = straightforward(manifest, root / "base")
        t_raster = rasterize_only(manifest)
    print(
        f"preview: {len(icons)} icons x 16 canvases x {len(ALPHAS)} alphas at {SIZE} px -> "
        f"{len(sheets)} sheets ({megabytes:.1f} MB)"
    )
    print(f"  alpha-audit preview (whole process, cold): {t_ours:.2f} s  (target < {TARGET_S} s)")
    print(f"  straightforward implementation:            {t_base:.2f} s")
    print(f"  ratio: {t_base / t_ours:.1f}x faster")
    print(
        f"  (both include SVG rasterisation, {t_raster:.2f} s in-process; without it: "
        f"{t_ours - t_raster:.2f} s vs {t_base - t_raster:.2f} s, "
        f"{(t_base - t_raster) / max(t_ours - t_raster, 1e-9):.1f}x)"
    )
    if t_ours >= TARGET_S:
        raise SystemExit(f"too slow: {t_ours:.2f} s >= {TARGET_S} s")


if __name__ == "__main__":
    main()
