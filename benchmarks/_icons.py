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


def lucide_icons(count: int | None = 300) -> list[Path]:
    """The first ``count`` lucide-static icons by file name, every one with None
    (downloads once)."""
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
    if count is not None and len(icons) < count:
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
        f"name: lucide-{len(icons)}\nicons: svg/*.svg\ncolor: cycle\nalpha: 1.1\n"
        f"sizes: {list(sizes)}\n"
        "palette: {orange: '#ee7733', blue: '#0077bb', cyan: '#33bbee', magenta: '#ee3377',"
        " red: '#cc3311', teal: '#009988', grey: '#bbbbbb'}\n"
    )
    return manifest


def _npm_package(name: str) -> Path:
    """``package/`` of an npm tarball unpacked under the cache (downloads once)."""
    folder = CACHE / name
    if not (folder / "package").is_dir():
        if shutil.which("npm") is None:
            raise SystemExit(f"benchmarks need npm to fetch {name} (apt-get install npm)")
        folder.mkdir(parents=True, exist_ok=True)
        out = subprocess.run(
            ["npm", "pack", name, "--silent"],
            cwd=folder,
            check=True,
            capture_output=True,
            text=True,
        ).stdout.split()[-1]
        with tarfile.open(folder / out) as tar:
            tar.extractall(folder, filter="data")
    return folder / "package"


def flag_icons(count: int | None = None) -> list[Path]:
    """flag-icons' 4x3 flags by file name (downloads once): several paints each."""
    flags = sorted((_npm_package("flag-icons") / "flags/4x3").glob("*.svg"))
    return flags[:count] if count is not None else flags


def simple_icons(count: int | None = None) -> list[tuple[Path, str]]:
    """simple-icons logos with their brand colour ``(svg, '#rrggbb')``, by slug order."""
    import json

    package = _npm_package("simple-icons")
    data = json.loads((package / "data/simple-icons.json").read_text())
    found = []
    for entry in sorted(data, key=lambda e: e.get("slug", "")):
        svg = package / "icons" / f"{entry.get('slug', '')}.svg"
        if svg.is_file():
            found.append((svg, "#" + entry["hex"].lower()))
    return found[:count] if count is not None else found


def canvases(count: int = 38) -> list[str]:
    """``count`` canvas colours: the bundled themes' canvases, then greys to fill up."""
    import yaml

    themes = Path(__file__).resolve().parents[1] / "themes"
    colors: list[str] = []
    for theme in sorted(themes.glob("*.yaml")):
        for canvas in yaml.safe_load(theme.read_text())["canvases"]:
            if canvas["color"].lower() not in colors:
                colors.append(canvas["color"].lower())
    grey = 0
    while len(colors) < count:
        value = f"#{grey:02x}{grey:02x}{grey:02x}"
        if value not in colors:
            colors.append(value)
        grey = (grey + 37) % 256
    return colors[:count]


def write_theme(path: Path, colors: list[str]) -> Path:
    """A theme file with one canvas per colour."""
    lines = ["name: bench", "canvases:"]
    lines += [f"  - {{name: c{k}, color: '{c}'}}" for k, c in enumerate(colors)]
    path.write_text("\n".join(lines) + "\n")
    return path


def make_brand_project(
    root: Path, logos: list[tuple[Path, str]], *, palette: list[str] | None = None
) -> Path:
    """A throwaway project of logos, each in its own brand colour (or ``palette`` in turn)."""
    (root / ".git").mkdir(parents=True, exist_ok=True)
    svg = root / "svg"
    svg.mkdir(exist_ok=True)
    lines = ["name: brands", "alpha: 1.1", "sizes: [24]", "icons:"]
    for k, (icon, color) in enumerate(logos):
        shutil.copy(icon, svg / icon.name)
        chosen = palette[k % len(palette)] if palette else color
        lines.append(f"  - {{file: svg/{icon.name}, color: '{chosen}'}}")
    manifest = root / "iconset.yaml"
    manifest.write_text("\n".join(lines) + "\n")
    return manifest


def run_measured(args: list[str]) -> tuple[float, int, int]:
    """Run a command under ``/usr/bin/time -v``: (seconds, peak RSS in MB, exit code)."""
    import re
    import time

    start = time.perf_counter()
    done = subprocess.run(
        ["/usr/bin/time", "-v", *args], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True
    )
    seconds = time.perf_counter() - start
    found = re.search(r"Maximum resident set size \(kbytes\): (\d+)", done.stderr)
    return seconds, int(found.group(1)) // 1024 if found else -1, done.returncode


def run_timed(args: list[str]) -> tuple[float, float, int, int]:
    """Like :func:`run_measured`, plus the CPU seconds (user + system) of the process and
    the children it waited for: (seconds, CPU seconds, peak RSS in MB, exit code)."""
    import re
    import time

    start = time.perf_counter()
    done = subprocess.run(
        ["/usr/bin/time", "-v", *args], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True
    )
    seconds = time.perf_counter() - start
    user = re.search(r"User time \(seconds\): ([\d.]+)", done.stderr)
    system = re.search(r"System time \(seconds\): ([\d.]+)", done.stderr)
    cpu = float(user.group(1)) + float(system.group(1)) if user and system else -1.0
    found = re.search(r"Maximum resident set size \(kbytes\): (\d+)", done.stderr)
    return seconds, cpu, int(found.group(1)) // 1024 if found else -1, done.returncode
