"""PNG labels draw any Unicode name with a font that has it (never a tofu box)."""

from __future__ import annotations

import numpy as np
import pytest
from fontTools.ttLib import TTFont
from PIL import ImageFont

from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.preview import Layout, plan_sheets, render_sheet
from alpha_audit.preview.figures import solid_rows
from alpha_audit.preview.fonts import font_for_char, runs, text_width

BUNDLED = ImageFont.load_default(size=14)
NAMES = ["Ωμέγα", "Привет", "日本語のアイコン", "مرحبا", "naïve café", "✓ check"]


def _has(font: ImageFont.FreeTypeFont, char: str) -> bool:
    """Independent check: the font file's own character map (fontTools)."""
    with TTFont(font.path, lazy=True, fontNumber=0) as tt:
        return ord(char) in (tt.getBestCmap() or {})


@pytest.mark.parametrize("name", NAMES)
def test_every_character_is_drawn_by_a_font_that_has_it(name: str) -> None:
    pieces = runs(BUNDLED, f"{name} #ffffff")
    assert "".join(s for _, s in pieces).replace("<U+", "").count("#ffffff") == 1
    for font, text in pieces:
        if font is BUNDLED:
            assert text.isascii()  # Pillow's bundled font: ASCII only
            continue
        for char in text:
            assert char.isspace() or _has(font, char), (name, char, font.path)


@pytest.mark.skipif(font_for_char("Ω") is None, reason="no system font with Greek installed")
def test_names_are_drawn_not_placeholders_when_a_font_has_them() -> None:
    shown = "".join(s for _, s in runs(BUNDLED, "Ωμέγα"))
    assert shown == "Ωμέγα"
    assert text_width(BUNDLED, "Ωμέγα") > 0


def test_a_character_no_font_has_is_written_as_its_code_point() -> None:
    # U+10FFFD is a private-use noncharacter no font maps.
    assert "".join(s for _, s in runs(BUNDLED, "a\U0010fffdb")) == "a<U+10FFFD>b"


def _grid(name: str) -> np.ndarray:
    canvas = Canvas("paper", "#ffffff")
    iconset = IconSet("s", (Icon(name, "x.svg", "#0077bb", 1.0),))
    mask = np.zeros((24, 24))
    mask[4:20, 4:20] = 1.0
    (spec,) = plan_sheets(Layout.GRID, [canvas], [24], "t")
    drawn = solid_rows(Theme("t", (canvas,)), iconset, {(name, 24): mask})
    sheet = render_sheet(spec, iconset, drawn, alphas=[1.0])
    return np.asarray(sheet.image)


def test_grid_sheets_name_their_icons() -> None:
    a, b = _grid("alert"), _grid("bell")
    assert a.shape == b.shape
    diff = np.argwhere(np.any(a != b, axis=-1))
    assert diff.size  # the names differ, so the sheets do
    # ... and only below the icon's ratio label, in the cell: the icon itself is the same.
    icon_bottom = 24 + 30 + 22 + 22 + 14 + 28 + 24  # margins, header, row label, icon
    assert diff[:, 0].min() > icon_bottom


def _glyph(font: ImageFont.FreeTypeFont | ImageFont.ImageFont, char: str) -> bytes:
    return bytes(font.getmask(char))


@pytest.mark.parametrize("char", ["Ω", "П", "日", "م"])
def test_no_tofu_the_chosen_glyph_is_not_the_missing_glyph(char: str) -> None:
    missing = "\U0010fffd"  # no font has it: what a font draws for a missing glyph
    # The problem: Pillow's bundled font draws these as its missing-glyph box.
    assert _glyph(BUNDLED, char) == _glyph(BUNDLED, missing)
    ((font, text),) = runs(BUNDLED, char)
    if text.startswith("<U+"):
        pytest.skip(f"no installed font has {char!r}")
    assert _glyph(font, char) != _glyph(font, missing)
    assert np.count_nonzero(np.frombuffer(_glyph(font, char), dtype=np.uint8)) > 0


def test_unicode_icon_name_is_drawn_in_the_sheet() -> None:
    assert np.any(_grid("Ωμέγα") != _grid("x"))
