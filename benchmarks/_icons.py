"""Real third-party icons for benchmarks, fetched from the npm registry on demand.

Never committed: ``npm pack`` downloads into a cache folder outside the repo.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import tarfile
from pathlib import Path

CACHE = Path(os.environ.get("ALPHA_AUDIT_BENCH_CACHE", Path.home() / ".cache/alpha-audit-bench"))


def lucide_icons(count: int = 300) -> list[Path]:
    """The first ``count`` lucide-static icons by file name (downloads once)."""
    folder = CACHE / "lucide-static"
    if not (folder / "package/icons").is_dir():
        if shutil.which("npm") is None:
            raise SystemExit("benchmarks need npm to fetch lucide-static (apt-get install npm)")
        folder.mkdir(parents=True, exist_ok=True)
        out = subprocess.run(
            ["npm", "pack", "lucide-static", "--silent"],
            cwd=folder,
            check=True,
            capture_output=True,
            text=True,
        ).stdout.split()[-1]
        with tarfile.open(folder / out) as tar:
            tar.extractall(folder, filter="data")
    icons = sorted((folder / "package/icons").glob("*.svg"))[:count]
    if len(icons) < count:
        raise SystemExit(f"only {len(icons)} lucide icons found in {folder}")
    return icons


def make_project(root: Path, icons: list[Path], sizes: tuple[int, ...] = (16, 24, 48)) -> Path:
    """A throwaway project: copies ``icons`` under ``root`` with a Vibrant manifest."""
    (root / ".git").mkdir(parents=True, exist_ok=True)
    svg = root / "svg"
    svg.mkdir(exist_ok=True)
    for icon in icons:
        shutil.copy(icon, svg / icon.name)
    manifest = root / "iconset.yaml"
    manifest.write_text(
        "name: lucide-300\nicons: svg/*.svg\ncolor: cycle\nalpha: 1.1\n"
        f"sizes: {list(sizes)}\n"
        "palette: {orange: '#ee7733', blue: '#0077bb', cyan: '#33bbee', magenta: '#ee3377',"
        " red: '#cc3311', teal: '#009988', grey: '#bbbbbb'}\n"
    )
    return manifest
