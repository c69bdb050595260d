"""Sweep figures drawn with Pillow (paper, Figures 3 and 6).

matplotlib is not a dependency of alpha-audit, and three line panels need
nothing it offers beyond axes, ticks and labels, so they are drawn directly
with Pillow (already a dependency): the figures are always produced and
deterministic for a given result.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import BinaryIO

import numpy as np
from numpy.typing import NDArray
from PIL import Image, ImageDraw, ImageFont

from alpha_audit.output import Output, write_files
from alpha_audit.reproduce.experiments import SweepResult

__all__ = ["FIGURES", "draw_axes", "draw_dotted", "figure_outputs", "sweep_figure", "write_figures"]

# File name -> alpha range, as in the paper (Figure 3: [1, 2]; Figure 6: [0, 2]).
FIGURES = {"sweep-1-2.png": (1.0, 2.0), "sweep-0-2.png": (0.0, 2.0)}
_PANELS = (
    ("mean_change", "(a) Mean change in contrast ratio"),
    ("decrease_share", "(b) Proportion of contrast decreases"),
    ("collision_rate", "(c) 8-bit colour-collision rate"),
)
_COLOURS = {"light": (204, 51, 17), "dark": (0, 119, 187)}  # Tol Vibrant red and blue
_PANEL_W, _PANEL_H = 420, 320
_LEFT, _RIGHT, _TOP, _BOTTOM = 70, 16, 34, 48
_FONT = ImageFont.load_default(size=13)
_SMALL = ImageFont.load_default(size=11)


def _nice_ticks(lo: float, hi: float, count: int = 5) -> list[float]:
    """Round tick values spanning ``[lo, hi]``."""
    if hi <= lo:
        hi = lo + 1.0
    raw = (hi - lo) / count
    magnitude = 10 ** np.floor(np.log10(raw))
    step = next(m * magnitude for m in (1, 2, 2.5, 5, 10) if m * magnitude >= raw)
    first = np.floor(lo / step) * step
    ticks = [first + i * step for i in range(int(np.ceil((hi - first) / step)) + 1)]
    return [float(t) for t in ticks]


def _label(value: float) -> str:
    return f"{value:.4g}" if abs(value) >= 1e-3 or value == 0 else f"{value:.1e}"


def draw_axes(
    draw: ImageDraw.ImageDraw,
    box: tuple[float, float, float, float],
    y_ticks: list[float],
    scale: tuple[Callable[[float], float], Callable[[float], float]],
    alpha_range: tuple[float, float],
) -> None:
    """A panel's value ticks with grid lines, and its alpha ticks and label
    (``scale``: alpha and value to pixels)."""
    x0, _, x1, y1 = box
    px, py = scale
    a_lo, a_hi = alpha_range
    for t in y_ticks:
        y = py(t)
        draw.line((x0 - 4, y, x0, y), fill="black")
        draw.line((x0 + 1, y, x1 - 1, y), fill=(230, 230, 230))
        draw.text((x0 - 6, y), _label(t), fill="black", font=_SMALL, anchor="rm")
    for t in _nice_ticks(a_lo, a_hi, 4):
        if a_lo - 1e-9 <= t <= a_hi + 1e-9:
            x = px(t)
            draw.line((x, y1, x, y1 + 4), fill="black")
            draw.text((x, y1 + 6), f"{t:g}", fill="black", font=_SMALL, anchor="mt")
    draw.text(((x0 + x1) / 2, y1 + 24), "alpha", fill="black", font=_FONT, anchor="mt")


def draw_dotted(draw: ImageDraw.ImageDraw, x: float, y0: float, y1: float) -> None:
    """A dotted vertical line: how the paper marks alpha = 0 and 1."""
    for y in range(int(y0), int(y1), 6):
        draw.line((x, y, x, min(y + 3, y1)), fill=(90, 90, 90))


def _panel(
    draw: ImageDraw.ImageDraw,
    origin: tuple[int, int],
    title: str,
    alphas: NDArray[np.float64],
    series: dict[str, NDArray[np.float64]],
    alpha_range: tuple[float, float],
) -> None:
    """One panel: axes, ticks, dotted alpha = 1 line, one polyline per group."""
    ox, oy = origin
    x0, x1 = ox + _LEFT, ox + _PANEL_W - _RIGHT
    y0, y1 = oy + _TOP, oy + _PANEL_H - _BOTTOM
    values = np.concatenate([np.asarray(v, dtype=float) for v in series.values()])
    y_ticks = _nice_ticks(float(values.min()), float(values.max()))
    y_lo, y_hi = y_ticks[0], y_ticks[-1]
    a_lo, a_hi = alpha_range

    def px(a: float) -> float:
        return x0 + (a - a_lo) / (a_hi - a_lo) * (x1 - x0)

    def py(v: float) -> float:
        return y1 - (v - y_lo) / (y_hi - y_lo) * (y1 - y0)

    draw.text((ox + _LEFT, oy + 8), title, fill="black", font=_FONT)
    draw.rectangle((x0, y0, x1, y1), outline="black")
    draw_axes(draw, (x0, y0, x1, y1), y_ticks, (px, py), alpha_range)
    if a_lo < 1.0 < a_hi:
        draw_dotted(draw, px(1.0), y0, y1)
    for i, (group, ys) in enumerate(series.items()):
        colour = _COLOURS.get(group, (0, 0, 0))
        points = [(px(a), py(v)) for a, v in zip(alphas, ys, strict=True)]
        draw.line(points, fill=colour, width=2)
        for x, y in points:
            draw.ellipse((x - 1.5, y - 1.5, x + 1.5, y + 1.5), fill=colour)
        lx, ly = x0 + 8, y0 + 8 + 16 * i
        draw.line((lx, ly + 6, lx + 18, ly + 6), fill=colour, width=2)
        draw.text((lx + 24, ly), group, fill="black", font=_SMALL)


def sweep_figure(result: SweepResult, alpha_range: tuple[float, float]) -> Image.Image:
    """Three panels (mean change, decreases, collisions) over ``alpha_range``."""
    alphas = np.asarray(result.alphas)
    keep = (alphas >= alpha_range[0] - 1e-9) & (alphas <= alpha_range[1] + 1e-9)
    image = Image.new("RGB", (_PANEL_W * len(_PANELS), _PANEL_H), "white")
    draw = ImageDraw.Draw(image)
    for i, (name, title) in enumerate(_PANELS):
        groups = getattr(result, name)
        series = {
            g: np.asarray(groups[g], dtype=np.float64)[keep]
            for g in ("light", "dark")
            if g in groups
        }
        _panel(draw, (i * _PANEL_W, 0), title, alphas[keep], series, alpha_range)
    return image


def figure_outputs(result: SweepResult, directory: str | Path) -> list[Output]:
    """``sweep-1-2.png`` and ``sweep-0-2.png`` as :class:`~alpha_audit.output.Output` items.

    Each figure is drawn and encoded while its temporary file is written.
    """

    def png(alpha_range: tuple[float, float]) -> Callable[[BinaryIO], None]:
        return lambda fh: sweep_figure(result, alpha_range).save(fh, format="PNG")

    return [Output(Path(directory) / name, png(r)) for name, r in FIGURES.items()]


def write_figures(
    result: SweepResult, directory: str | Path, *, overwrite: bool = False
) -> list[Path]:
    """Write both figures atomically (existing files only with ``overwrite``); their paths."""
    return write_files(figure_outputs(result, directory), overwrite=overwrite)
