"""Fonts for PNG labels that draw any name: never a tofu box.

Pillow's bundled font covers ASCII only, so an icon or canvas named
``Ωμέγα`` or ``日本語`` would come out as boxes.  ASCII keeps the bundled
font (so sheets look the same everywhere); every other character is drawn
with the first installed font whose character map has it -- read exactly
with fontTools, not guessed from rendered pixels -- preferring wide-coverage
families (DejaVu, Noto, Droid Sans Fallback, ...), runs sharing one baseline.
A character no installed font has is written as ``<U+XXXX>``: readable and
honest instead of a box.

Fonts are only read from the usual system font folders (bounded scan), never
downloaded, and nothing from the input ever names a font file.
"""

from __future__ import annotations

import math
import os
import sys
from functools import cache
from pathlib import Path

from PIL import ImageDraw, ImageFont

__all__ = [
    "MAX_FONT_FILES",
    "draw_text",
    "font_dirs",
    "font_for_char",
    "runs",
    "text_metrics",
    "text_width",
]

MAX_FONT_FILES = 4000  # a scan bound: a typical Linux desktop has a few hundred
_SUFFIXES = (".ttf", ".otf", ".ttc")
# Wide coverage first (file stems, case-insensitive); the rest follow sorted by path.
_PREFERRED = (
    "dejavusans",
    "notosans-regular",
    "notosanscjk-regular",
    "notosanscjksc-regular",
    "droidsansfallbackfull",
    "droidsansfallback",
    "liberationsans-regular",
    "arialuni",
    "arial unicode",
    "segoeui",
    "arial",
    "helvetica",
    "notosansmono-regular",
    "dejavusansmono",
)


def font_dirs() -> tuple[Path, ...]:
    """Where fonts are installed on Linux, macOS and Windows (existing folders only)."""
    home = Path.home()
    candidates = [
        home / ".local/share/fonts",
        home / ".fonts",
        Path("/usr/local/share/fonts"),
        Path("/usr/share/fonts"),
        Path("/Library/Fonts"),
        Path("/System/Library/Fonts"),
        home / "Library/Fonts",
    ]
    if sys.platform == "win32":  # pragma: no cover - not on the CI machine
        candidates.append(Path(os.environ.get("WINDIR", r"C:\Windows")) / "Fonts")
    return tuple(p for p in candidates if p.is_dir())


@cache
def _installed() -> tuple[Path, ...]:
    """Installed font files, preferred families first; at most :data:`MAX_FONT_FILES`."""
    found: list[Path] = []
    for folder in font_dirs():
        for root, _dirs, files in os.walk(folder):
            found.extend(Path(root) / f for f in files if f.lower().endswith(_SUFFIXES))
            if len(found) >= MAX_FONT_FILES:
                break
    rank = {stem: k for k, stem in enumerate(_PREFERRED)}
    return tuple(
        sorted(found[:MAX_FONT_FILES], key=lambda p: (rank.get(p.stem.lower(), len(rank)), str(p)))
    )


@cache
def _cmap(path: Path) -> frozenset[int]:
    """Code points ``path`` has glyphs for (empty when it cannot be read)."""
    from fontTools.ttLib import TTFont  # only when a name needs it

    try:
        with TTFont(path, lazy=True, fontNumber=0) as font:
            return frozenset(font.getBestCmap() or {})
    except Exception:
        return frozenset()


def font_for_char(char: str) -> Path | None:
    """The first installed font (preferred families first) that has ``char``."""
    code = ord(char)
    return next((path for path in _installed() if code in _cmap(path)), None)


@cache
def _truetype(path: Path, size: int) -> ImageFont.FreeTypeFont:
    return ImageFont.truetype(str(path), size=size)


# Pillow's bundled font at a given size and installed TrueType fonts are both FreeType.
Font = ImageFont.FreeTypeFont


def runs(font: Font, text: str) -> list[tuple[Font, str]]:
    """``text`` cut into runs, each with a font that has every character of it.

    ASCII (and whitespace) stays in ``font`` (Pillow's bundled one); every
    other character goes to the first installed font that has it; one no
    installed font has becomes ``<U+XXXX>`` in ``font``.  This is per-character
    font fallback, as browsers do it, so mixed names (``日本 #ffffff``) work.

    >>> from PIL import ImageDraw, ImageFont
    >>> bundled = ImageFont.load_default(size=12)
    >>> [(f is bundled, s) for f, s in runs(bundled, "alert 2")]
    [(True, 'alert 2')]
    """
    size = int(getattr(font, "size", 12))
    out: list[tuple[Font, str]] = []
    for char in text:
        chosen: Font = font
        shown = char
        if not (char.isascii() or char.isspace()):
            path = font_for_char(char)
            if path is None:
                shown = f"<U+{ord(char):04X}>"
            else:
                chosen = _truetype(path, size)
        if out and out[-1][0] is chosen:
            out[-1] = (chosen, out[-1][1] + shown)
        else:
            out.append((chosen, shown))
    return out


def text_width(font: Font, text: str) -> int:
    """Width in pixels of ``text`` drawn with fallback (:func:`runs`)."""
    return math.ceil(sum(f.getlength(s) for f, s in runs(font, text)))


def text_metrics(font: Font, text: str) -> tuple[int, int]:
    """(ascent, descent) covering every run of ``text``."""
    metrics = [f.getmetrics() for f, _ in runs(font, text)] or [font.getmetrics()]
    return max(a for a, _ in metrics), max(d for _, d in metrics)


def draw_text(
    draw: ImageDraw.ImageDraw,
    xy: tuple[int, int],
    text: str,
    font: Font,
    fill: str | tuple[int, ...],
) -> int:
    """Draw ``text`` with its top at ``xy`` (runs share one baseline); return its width."""
    ascent, _ = text_metrics(font, text)
    x, baseline = float(xy[0]), xy[1] + ascent
    for f, s in runs(font, text):
        draw.text((x, baseline), s, font=f, fill=fill, anchor="ls")
        x += f.getlength(s)
    return text_width(font, text)
