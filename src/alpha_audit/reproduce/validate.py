"""The WebGL2 preview page against the CPU reference, in any engine (paper, Section 4.4).

:func:`validate_page` opens the real ``--html`` page in a :class:`Browser`,
asks it (through the page's ``alphaAuditPreview.renderBatch`` hook) to render
every icon through its shader for each canvas, size and configuration, reads
the 8-bit pixels back and compares every pixel against
:func:`~alpha_audit.preview.compose.composite_drawings` in float64.  The paper reports at
most 1/255 on covered pixels over 388,800 instances in three browsers.
"""

from __future__ import annotations

import base64
import json
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TypedDict

import numpy as np
from numpy.typing import NDArray

from alpha_audit.browser.interface import Browser, BrowserError
from alpha_audit.model import IconSet, Theme
from alpha_audit.preview.compose import Blend, composite_drawings
from alpha_audit.preview.figures import PreviewRows
from alpha_audit.preview.html import preview_html

__all__ = [
    "PAPER_CONFIGURATIONS",
    "Configuration",
    "ConfigurationResult",
    "PageValidation",
    "validate_page",
]

# Bytes of pixels asked for per evaluate call: large enough to amortise the call, small
# enough that base64 text in the page and in our process stays a few tens of MB.
_BATCH_BYTES = 12 * 1024 * 1024


@dataclass(frozen=True)
class Configuration:
    """One way of drawing: the extended coefficient ``alpha``, or a control blend."""

    blend: Blend
    alpha: float = 1.0

    @property
    def label(self) -> str:
        """``alpha 1.1``, ``difference``, ``exclusion``."""
        if self.blend is Blend.EXTENDED:
            return f"alpha {self.alpha:g}"
        return str(self.blend)


# Paper, Appendix A.2: seven coefficients, then Difference and Exclusion as controls.
PAPER_CONFIGURATIONS = (
    *(Configuration(Blend.EXTENDED, a) for a in (0.6, 0.9, 1.0, 1.05, 1.1, 1.2, 1.4)),
    Configuration(Blend.DIFFERENCE),
    Configuration(Blend.EXCLUSION),
)


@dataclass(frozen=True)
class ConfigurationResult:
    """Instances (icon x canvas x size) drawn in one configuration and the largest errors.

    Errors are in 8-bit codes, the maximum over channels and pixels; ``covered``
    pixels have nonzero coverage, the rest must show the canvas itself.
    """

    configuration: Configuration
    instances: int
    max_error: int
    max_error_uncovered: int


@dataclass(frozen=True)
class PageValidation:
    """One engine's run of the page against the CPU reference."""

    engine: str
    version: str
    renderer: str
    icons: int
    canvases: int
    sizes: tuple[int, ...]
    results: tuple[ConfigurationResult, ...]

    @property
    def instances(self) -> int:
        """Rendering instances over every configuration."""
        return sum(r.instances for r in self.results)

    @property
    def max_error(self) -> int:
        """Largest error on covered pixels, 8-bit codes."""
        return max((r.max_error for r in self.results), default=0)

    @property
    def max_error_uncovered(self) -> int:
        """Largest error on uncovered pixels, 8-bit codes."""
        return max((r.max_error_uncovered for r in self.results), default=0)


class _Job(TypedDict):
    """One page render request (``_c``: its configuration, kept out of the request)."""

    canvas: int
    size: int
    blend: str
    alpha: float
    _c: Configuration


def _batches(jobs: list[_Job], icons: int) -> list[list[_Job]]:
    """Consecutive jobs grouped so that each group's pixels stay under ``_BATCH_BYTES``."""
    groups: list[list[_Job]] = []
    size = 0
    for job in jobs:
        nbytes = icons * job["size"] ** 2 * 3
        if not groups or size + nbytes > _BATCH_BYTES:
            groups.append([])
            size = 0
        groups[-1].append(job)
        size += nbytes
    return groups


def _empty(size: int) -> NDArray[np.uint8]:
    return np.zeros((size, size), dtype=np.uint8)


def validate_page(
    browser: Browser,
    theme: Theme,
    iconset: IconSet,
    drawn: PreviewRows,
    *,
    sizes: Sequence[int],
    configurations: Sequence[Configuration] = PAPER_CONFIGURATIONS,
    progress: Callable[[float], None] | None = None,
) -> PageValidation:
    """Render ``iconset`` on every canvas of ``theme`` in ``browser``; compare with the CPU.

    Every icon must be drawn (``drawn.drawings``) at every size, each paint
    group in its colour and opacity under ``drawn.pipeline``.
    ``progress(fraction)`` is called after each canvas.
    """
    sizes = tuple(sorted({int(s) for s in sizes}))
    icons = iconset.icons
    n = len(icons)
    browser.open_html(preview_html(theme, iconset, drawn, sizes=sizes), "preview.html")
    browser.wait_for("Boolean(window.alphaAuditPreview)")
    info = browser.evaluate(
        "({ready: alphaAuditPreview.ready, error: alphaAuditPreview.error || null,"
        " renderer: alphaAuditPreview.renderer || '', icons: alphaAuditPreview.icons})"
    )
    assert isinstance(info, dict)
    if not info["ready"]:
        raise BrowserError(f"{browser.LABEL}: the WebGL2 page failed: {info['error']}")
    if info["icons"] != n:
        raise BrowserError(f"{browser.LABEL}: the page has {info['icons']} icons, expected {n}")
    drawings = [drawn.drawings[i.name] for i in icons]
    covered = {
        s: np.stack([np.any(np.stack([*d.masks[s], _empty(s)]) > 0, axis=0) for d in drawings])
        for s in sizes
    }
    worst = {c: [0, 0, 0] for c in configurations}  # instances, covered, uncovered
    for j, canvas in enumerate(theme.canvases):
        background = np.array(canvas.linear)
        jobs: list[_Job] = [
            {"canvas": j, "size": s, "blend": str(c.blend), "alpha": c.alpha, "_c": c}
            for s in sizes
            for c in configurations
        ]
        for batch in _batches(jobs, n):
            request = [{k: v for k, v in job.items() if k != "_c"} for job in batch]
            raw = browser.evaluate(f"alphaAuditPreview.renderBatch({json.dumps(request)})")
            pixels = np.frombuffer(base64.b64decode(str(raw)), dtype=np.uint8)
            offset = 0
            for job in batch:
                s, config = job["size"], job["_c"]
                count = n * s * s * 3
                if offset + count > pixels.size:
                    raise BrowserError(f"{browser.LABEL}: the page returned too few pixels")
                gpu = pixels[offset : offset + count].reshape(n, s, s, 3).astype(np.int16)
                offset += count
                cpu = composite_drawings(
                    drawings, s, background, config.alpha, drawn.pipeline, config.blend
                ).astype(np.int16)
                error = np.abs(gpu - cpu).max(axis=-1)
                entry = worst[config]
                entry[0] += n
                entry[1] = max(entry[1], int(error[covered[s]].max(initial=0)))
                entry[2] = max(entry[2], int(error[~covered[s]].max(initial=0)))
            if offset != pixels.size:
                raise BrowserError(f"{browser.LABEL}: the page returned too many pixels")
        if progress is not None:
            progress(1.0 / len(theme.canvases))
    return PageValidation(
        engine=browser.NAME,
        version=browser.version,
        renderer=str(info["renderer"]),
        icons=n,
        canvases=len(theme.canvases),
        sizes=sizes,
        results=tuple(ConfigurationResult(c, *worst[c]) for c in configurations),
    )
