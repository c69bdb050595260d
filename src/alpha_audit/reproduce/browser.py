"""The paper's output validation in real browsers (Section 4.4 and Appendix A.2).

The first 300 SVGs of a directory, ordered by the SHA-256 of their path,
rasterised at 16, 24 and 48 px and coloured with the seven Vibrant colours in
turn, are drawn by the WebGL2 preview page on every canvas of the theme in the
nine configurations (seven coefficients, Difference, Exclusion), in every
installed engine, and compared pixel by pixel with the float64 CPU reference
(:func:`alpha_audit.reproduce.validate.validate_page`).  The paper reports
388,800 instances over three browsers (300 x 3 x 16 x 9 = 129,600 each) with
every covered pixel within 1/255.
"""

from __future__ import annotations

import hashlib
import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from alpha_audit.browser import ENGINES, engine_class, installed_engines
from alpha_audit.errors import UsageError
from alpha_audit.load.svg import rasterize_icons
from alpha_audit.model import Icon, IconSet, Theme
from alpha_audit.preview.figures import solid_rows
from alpha_audit.reproduce.grids import VIBRANT
from alpha_audit.reproduce.validate import PAPER_CONFIGURATIONS, PageValidation, validate_page

__all__ = [
    "PAPER_ICONS",
    "PAPER_INSTANCES",
    "PAPER_MAX_ERROR",
    "PAPER_SIZES",
    "BrowserValidationResult",
    "browser_validation",
    "load_validation_icons",
    "select_icons",
]

# Paper, Section 4.4 and Appendix A.2.
PAPER_ICONS = 300
PAPER_SIZES = (16, 24, 48)
PAPER_INSTANCES = 388_800  # over three browsers
PAPER_MAX_ERROR = 1  # 8-bit codes: 1/255 on covered pixels


def _path_key(root: Path, path: Path) -> str:
    """SHA-256 of the file's path relative to ``root`` (POSIX, UTF-8): machine-independent."""
    return hashlib.sha256(path.relative_to(root).as_posix().encode("utf-8")).hexdigest()


def select_icons(directory: Path, count: int = PAPER_ICONS) -> list[Path]:
    """The first ``count`` ``*.svg`` files under ``directory`` by SHA-256 of their path.

    Paths are relative to ``directory`` so that the choice is the same on every
    machine; files whose real location is outside ``directory`` (symlinks out)
    are left out.
    """
    root = Path(directory)
    if not root.is_dir():
        raise UsageError(f"`icons` {root} is not a directory of SVG files")
    real_root = root.resolve()
    # os.walk skips directories it cannot read or that vanish while walking, and does
    # not follow directory symlinks; file symlinks leading out of the root are dropped.
    files = [
        path
        for folder, _, names in os.walk(root)
        for name in names
        if name.endswith(".svg")
        and (path := Path(folder) / name).is_file()
        and path.resolve().is_relative_to(real_root)
    ]
    if not files:
        raise UsageError(f"`icons` {root} holds no *.svg files")
    return sorted(files, key=lambda p: _path_key(root, p))[:count]


def load_validation_icons(
    directory: Path, sizes: Sequence[int], count: int = PAPER_ICONS
) -> tuple[IconSet, Mapping[tuple[str, int], NDArray[np.float64]], int]:
    """The selected icons coloured with Vibrant in turn, their masks, and how many failed.

    Icons that cannot be rasterised are left out (and counted), the rest keep
    their colour from the cycle over the selection.
    """
    root = Path(directory)
    files = select_icons(root, count)
    icons = tuple(
        Icon(f.relative_to(root).with_suffix("").as_posix(), f, VIBRANT[k % len(VIBRANT)], 1.0)
        for k, f in enumerate(files)
    )
    rendered = rasterize_icons([(i.name, i.file) for i in icons], sizes)
    ok = tuple(i for i in icons if rendered.ok(i.name))
    if not ok:
        raise UsageError(f"`icons` {root}: none of the selected SVG files could be rasterised")
    palette = {f"vibrant{k + 1}": c for k, c in enumerate(VIBRANT)}
    iconset = IconSet(root.name or "icons", ok, palette=palette, sizes=tuple(sizes))
    return iconset, rendered.masks, len(icons) - len(ok)


@dataclass(frozen=True)
class BrowserValidationResult:
    """Per engine, instances and maximum errors per configuration (see :class:`PageValidation`)."""

    icons: int
    failed_icons: int
    sizes: tuple[int, ...]
    canvases: int
    engines: tuple[PageValidation, ...]
    missing: tuple[str, ...]

    @property
    def instances(self) -> int:
        """Instances over every engine (the paper's 388,800)."""
        return sum(e.instances for e in self.engines)

    @property
    def max_error(self) -> int:
        """Largest covered-pixel error over every engine, 8-bit codes."""
        return max((e.max_error for e in self.engines), default=0)


def run_engines(
    engines: Iterable[str] | None,
) -> tuple[list[str], tuple[str, ...]]:
    """The engines to run (``None``: every installed one) and the registered ones missing.

    Raises :class:`UsageError` when none can run, naming how to install them.
    """
    found = installed_engines()
    wanted = list(engines) if engines else list(ENGINES)
    for name in wanted:
        engine_class(name)  # unknown names: a UsageError listing the valid ones
    present = [n for n in wanted if n in found]
    missing = tuple(n for n in wanted if n not in found)
    if not present:
        hints = "; ".join(f"{ENGINES[n].LABEL}: {ENGINES[n].INSTALL_HINT}" for n in missing)
        raise UsageError(f"no browser engine installed ({hints})")
    return present, missing


def browser_validation(
    theme: Theme,
    icons: Path,
    *,
    engines: Iterable[str] | None = None,
    count: int = PAPER_ICONS,
    sizes: Sequence[int] = PAPER_SIZES,
    progress: Callable[[float], None] | None = None,
) -> BrowserValidationResult:
    """Validate the preview page in each installed engine (or those named in ``engines``)."""
    present, missing = run_engines(engines)
    sizes = tuple(sorted({int(s) for s in sizes}))
    iconset, masks, failed = load_validation_icons(Path(icons), sizes, count)
    drawn = solid_rows(theme, iconset, masks, sizes)
    results = []
    for name in present:
        with ENGINES[name]() as browser:

            def step(fraction: float) -> None:
                if progress is not None:
                    progress(fraction / len(present))

            results.append(
                validate_page(
                    browser,
                    theme,
                    iconset,
                    drawn,
                    sizes=sizes,
                    configurations=PAPER_CONFIGURATIONS,
                    progress=step,
                )
            )
    return BrowserValidationResult(
        icons=len(iconset.icons),
        failed_icons=failed,
        sizes=sizes,
        canvases=len(theme.canvases),
        engines=tuple(results),
        missing=missing,
    )
