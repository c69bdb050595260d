"""The paper's runtime measurement across signed coefficients (Section 4.4, Appendix A.3).

300 icons at 48 px are drawn by the preview page's own shader on a
1280 x 960 canvas whose background alternates between a warm light and a cool
dark colour frame by frame; each frame ends in a synchronous one-pixel
readback.  Per engine: two warm-up sweeps, then 25 rounds over 161
coefficients in [-2, 2] at step 0.025, each round in a seeded Fisher-Yates
order (the same orders in every engine); ``performance.now()`` times blocks
of 20 frames, and the block mean is the time per frame.  Reported per
coefficient: the median of the block means and the empirical 10th-90th
percentile band.

On software GL (Mesa llvmpipe, SwiftShader) absolute times are not the
paper's GPU times; the claim under test is relative: no sustained increase
outside [0, 1] compared with the conventional transparency interval.
"""

from __future__ import annotations

import html
import json
import random
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from PIL import Image, ImageDraw

from alpha_audit.browser import ENGINES, Browser
from alpha_audit.browser.interface import BrowserError
from alpha_audit.color.srgb import srgb_decode
from alpha_audit.output import Output
from alpha_audit.preview.compose import mask_codes
from alpha_audit.preview.html import RENDERER_ASSET, asset, atlas_data, scoped_script
from alpha_audit.reproduce.browser import PAPER_ICONS, load_validation_icons, run_engines
from alpha_audit.reproduce.experiments import sweep_alphas
from alpha_audit.reproduce.figures import _FONT, _SMALL, _nice_ticks, draw_axes, draw_dotted
from alpha_audit.reproduce.grids import PAPER_SEED

__all__ = [
    "BACKGROUNDS",
    "RUNTIME_FIGURE",
    "EngineTiming",
    "RuntimeResult",
    "RuntimeSettings",
    "runtime",
    "runtime_figure",
    "runtime_figure_output",
    "runtime_script",
]

# The paper's backgrounds are "warm light" and "cool dark" without values; these are ours
# (encoded sRGB): a cream and a slate blue.
BACKGROUNDS = {"warm light": "#faf3e0", "cool dark": "#1c2633"}
CANVAS = (1280, 960)  # Appendix A.3
RUNTIME_FIGURE = "runtime.png"  # what ``reproduce --out`` calls the figure
ICON_SIZE = 48  # Appendix A.3
_HEADING = """\
// alpha-audit runtime page: the preview's own renderer and shader, timed (paper, Section 4.4,
// Appendix A.3). No network, no external files.
"""


@dataclass(frozen=True)
class RuntimeSettings:
    """The measurement's design; :meth:`paper` is Appendix A.3, :meth:`quick` for tests."""

    alphas: tuple[float, ...]
    warmups: int
    rounds: int
    frames: int
    icons: int = PAPER_ICONS
    seed: int = PAPER_SEED

    @classmethod
    def paper(cls) -> RuntimeSettings:
        """161 coefficients in [-2, 2] step 0.025, 2 warm-up sweeps, 25 rounds of 20 frames."""
        return cls(sweep_alphas(-2.0, 2.0, 0.025), warmups=2, rounds=25, frames=20)

    @classmethod
    def quick(cls) -> RuntimeSettings:
        """9 coefficients in [-2, 2] step 0.5, 1 warm-up, 3 rounds of 4 frames."""
        return cls(sweep_alphas(-2.0, 2.0, 0.5), warmups=1, rounds=3, frames=4)


@dataclass(frozen=True)
class EngineTiming:
    """One engine's block means, ``samples[round][k]`` in ms per frame at ``alphas[k]``."""

    engine: str
    version: str
    renderer: str
    alphas: tuple[float, ...]
    samples: tuple[tuple[float, ...], ...]

    def _per_alpha(self, q: float) -> tuple[float, ...]:
        return tuple(float(v) for v in np.percentile(np.asarray(self.samples), q, axis=0))

    @property
    def median(self) -> tuple[float, ...]:
        """Median of the block means per coefficient (ms per frame)."""
        return self._per_alpha(50)

    @property
    def p10(self) -> tuple[float, ...]:
        """10th percentile of the block means per coefficient."""
        return self._per_alpha(10)

    @property
    def p90(self) -> tuple[float, ...]:
        """90th percentile of the block means per coefficient."""
        return self._per_alpha(90)

    def _interval_median(self, inside: bool) -> float:
        a = np.asarray(self.alphas)
        keep = ((a >= 0) & (a <= 1)) == inside
        return float(np.median(np.asarray(self.median)[keep])) if keep.any() else float("nan")

    @property
    def outside_vs_inside(self) -> float:
        """Median over coefficients outside [0, 1] of the medians, over the same inside [0, 1].

        1 means no difference; the paper's claim is that this stays near 1.
        """
        return self._interval_median(False) / self._interval_median(True)

    @property
    def worst_vs_inside(self) -> float:
        """The largest per-coefficient median outside [0, 1], over the inside median."""
        a = np.asarray(self.alphas)
        outside = np.asarray(self.median)[(a < 0) | (a > 1)]
        worst = float(outside.max()) if outside.size else float("nan")
        return worst / self._interval_median(True)


@dataclass(frozen=True)
class RuntimeResult:
    """Timings per engine, with the design they were measured under."""

    settings: RuntimeSettings
    icons: int
    distinct_icons: int
    engines: tuple[EngineTiming, ...]
    missing: tuple[str, ...]


def runtime_script() -> str:
    """The timing page's script: the preview page's renderer, then the timing loop.

    Timing the very code people see, not a copy: :data:`RENDERER_ASSET` (the
    preview's WebGL2 set-up, shader and draw calls) is inlined as shipped,
    and ``runtime.js`` only drives it.
    """
    return scoped_script(
        _HEADING, [asset(RENDERER_ASSET), asset("runtime.js", "alpha_audit.reproduce")]
    )


def _page(icons_dir: Path, settings: RuntimeSettings) -> tuple[str, int, int]:
    """The timing page as HTML, the number of draws per frame and of distinct icons."""
    iconset, masks, _ = load_validation_icons(icons_dir, (ICON_SIZE,), settings.icons)
    icons = iconset.icons
    n = len(icons)
    backgrounds = []
    for hex_colour in BACKGROUNDS.values():
        codes = [int(hex_colour[i : i + 2], 16) for i in (1, 3, 5)]
        linear = [float(v) for v in srgb_decode(np.array(codes) / 255.0)]
        backgrounds.append({"codes": codes, "linear": linear})
    # The fields the preview's Renderer reads (``atlases``, ``icons``), as html.py writes them.
    data = {
        "width": CANVAS[0],
        "height": CANVAS[1],
        "size": ICON_SIZE,
        "atlases": {
            str(ICON_SIZE): atlas_data(
                [_codes(masks[(i.name, ICON_SIZE)]) for i in iconset.icons], ICON_SIZE
            )
        },
        "icons": [{"linear": list(i.linear)} for i in icons],
        # Fewer distinct icons than draws: cycle them, so each frame still draws the design's 300.
        "draws": [k % n for k in range(settings.icons)],
        "backgrounds": backgrounds,
    }
    payload = json.dumps(data, separators=(",", ":")).replace("<", "\\u003c")
    script = runtime_script()
    page = (
        "<!doctype html><html><head><meta charset='utf-8'>"
        "<meta http-equiv='Content-Security-Policy' content=\"default-src 'none'; "
        "script-src 'unsafe-inline'\">"
        f"<title>{html.escape('alpha-audit runtime')}</title></head><body>"
        f"<canvas id='gl'></canvas>"
        f"<script type='application/json' id='alpha-audit-runtime'>{payload}</script>"
        f"<script>{script}</script></body></html>"
    )
    return page, settings.icons, n


def _codes(mask: NDArray[np.float64]) -> NDArray[np.uint8]:
    """A cairo coverage mask (values k / 255) as the 8-bit codes the atlas holds."""
    codes = mask_codes(mask)
    if codes is None:
        raise ValueError("a coverage mask must hold values k / 255")
    return codes


def _round_orders(settings: RuntimeSettings) -> list[list[int]]:
    """One permutation of the coefficient indices per round, seeded: equal in every engine.

    ``random.shuffle`` is the Fisher-Yates (Durstenfeld) shuffle.
    """
    rng = random.Random(settings.seed)
    orders = []
    for _ in range(settings.rounds):
        order = list(range(len(settings.alphas)))
        rng.shuffle(order)
        orders.append(order)
    return orders


def _time_engine(browser: Browser, page: str, settings: RuntimeSettings,
                 step: Callable[[float], None]) -> EngineTiming:  # fmt: skip
    browser.open_html(page, "runtime.html")
    info = browser.wait_for("window.alphaAuditRuntime")
    assert isinstance(info, dict)
    if not info.get("ready"):
        raise BrowserError(f"{browser.LABEL}: the runtime page failed: {info.get('error')}")
    alphas = list(settings.alphas)
    # A sweep's budget: generous for software GL (about 10 ms per frame).
    budget = 60.0 + len(alphas) * settings.frames * 0.05
    for _ in range(settings.warmups):
        browser.evaluate(f"alphaAuditRuntime.sweep({json.dumps(alphas)}, {settings.frames})",
                         timeout=budget)  # fmt: skip
    samples = []
    for order in _round_orders(settings):
        means = browser.evaluate(
            f"alphaAuditRuntime.sweep({json.dumps([alphas[k] for k in order])}, {settings.frames})",
            timeout=budget,
        )
        assert isinstance(means, list) and len(means) == len(order)
        row = [0.0] * len(alphas)
        for k, mean in zip(order, means, strict=True):
            row[k] = float(mean)  # type: ignore[arg-type]  # page JSON; float() refuses non-numbers
        samples.append(tuple(row))
        step(1.0 / settings.rounds)
    return EngineTiming(browser.NAME, browser.version, str(info.get("renderer", "")),
                        settings.alphas, tuple(samples))  # fmt: skip


def runtime(
    icons: Path,
    *,
    settings: RuntimeSettings | None = None,
    engines: Iterable[str] | None = None,
    progress: Callable[[float], None] | None = None,
) -> RuntimeResult:
    """Time the preview shader over ``settings.alphas`` in each installed engine."""
    settings = settings or RuntimeSettings.paper()
    present, missing = run_engines(engines)
    page, draws, distinct = _page(Path(icons), settings)
    timings = []
    for name in present:

        def step(fraction: float) -> None:
            if progress is not None:
                progress(fraction / len(present))

        with ENGINES[name](timeout=120) as browser:
            timings.append(_time_engine(browser, page, settings, step))
    return RuntimeResult(settings, draws, distinct, tuple(timings), missing)


# ------------------------------------------------------------------------------ figure

_PANEL_W, _PANEL_H = 420, 320
_LEFT, _RIGHT, _TOP, _BOTTOM = 70, 16, 34, 48
# Tol Vibrant blue, orange, teal for Chromium, Firefox, WebKit (the paper's order).
_ENGINE_COLOURS = {"chromium": (0, 119, 187), "firefox": (238, 119, 51), "webkit": (0, 153, 136)}


def _runtime_panel(draw: ImageDraw.ImageDraw, ox: int, timing: EngineTiming) -> None:
    x0, x1 = ox + _LEFT, ox + _PANEL_W - _RIGHT
    y0, y1 = _TOP, _PANEL_H - _BOTTOM
    alphas = np.asarray(timing.alphas)
    lo, mid, hi = (np.asarray(v) for v in (timing.p10, timing.median, timing.p90))
    ticks = _nice_ticks(float(lo.min()), float(hi.max()))
    t_lo, t_hi = ticks[0], ticks[-1]
    a_lo, a_hi = float(alphas.min()), float(alphas.max())
    a_hi = a_hi if a_hi > a_lo else a_lo + 1.0

    def px(a: float) -> float:
        return x0 + (a - a_lo) / (a_hi - a_lo) * (x1 - x0)

    def py(v: float) -> float:
        return y1 - (v - t_lo) / (t_hi - t_lo) * (y1 - y0)

    colour = _ENGINE_COLOURS.get(timing.engine, (0, 0, 0))
    band = tuple(int(255 - (255 - c) * 0.3) for c in colour)
    draw.text((x0, 8), f"{ENGINES[timing.engine].LABEL}", fill="black", font=_FONT)
    draw_axes(draw, (x0, y0, x1, y1), ticks, (px, py), (a_lo, a_hi))
    polygon = [(px(a), py(v)) for a, v in zip(alphas, hi, strict=True)]
    polygon += [(px(a), py(v)) for a, v in zip(alphas[::-1], lo[::-1], strict=True)]
    if len(polygon) >= 3:
        draw.polygon(polygon, fill=band)
    draw.text((ox + 4, y0 - 14), "ms per frame", fill="black", font=_SMALL)
    for boundary in (0.0, 1.0):
        if a_lo <= boundary <= a_hi:
            draw_dotted(draw, px(boundary), y0, y1)
    draw.line([(px(a), py(v)) for a, v in zip(alphas, mid, strict=True)], fill=colour, width=2)
    draw.rectangle((x0, y0, x1, y1), outline="black")  # last: the band must not cover it


def runtime_figure_output(result: RuntimeResult, path: Path) -> Output:
    """The figure as an :class:`~alpha_audit.output.Output` for the one writer."""
    return Output(path, lambda fh: runtime_figure(result).save(fh, format="PNG"))


def runtime_figure(result: RuntimeResult) -> Image.Image:
    """One panel per engine: median line, 10th-90th percentile band, dotted alpha = 0 and 1."""
    panels = max(1, len(result.engines))
    image = Image.new("RGB", (_PANEL_W * panels, _PANEL_H), "white")
    draw = ImageDraw.Draw(image)
    for i, timing in enumerate(result.engines):
        _runtime_panel(draw, i * _PANEL_W, timing)
    return image
