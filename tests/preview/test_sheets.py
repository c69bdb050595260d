"""PNG sheets: every icon pixel recomputed from its mask, layouts, file handling."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from alpha_audit import load_iconset, load_theme, rasterize_icons
from alpha_audit.color import composite_coverage, to_8bit
from alpha_audit.errors import UsageError
from alpha_audit.model import Canvas, Icon, IconSet
from alpha_audit.preview import (
    Blend,
    Layout,
    composite_masks,
    near_source_canvases,
    plan_sheets,
    render_sheet,
    write_sheet,
)

ROOT = Path(__file__).resolve().parents[2]
THEME = ROOT / "themes" / "paper16.yaml"
ICONSET = ROOT / "examples" / "vibrant" / "iconset.yaml"


@pytest.fixture(scope="module")
def example():
    theme = load_theme(THEME)
    iconset = load_iconset(ICONSET)
    masks = rasterize_icons([(i.name, i.file) for i in iconset.icons], [16, 24, 48])
    assert not masks.problems
    return theme, iconset, masks.masks


def _scalar_pixel(s: float, b: float, a: float, q: float) -> int:
    """The paper's pixel for one channel, written out with the math module only."""

    def encode(v: float) -> float:  # linear -> encoded, CSS Color 4 gam_sRGB
        return 1.055 * v ** (1 / 2.4) - 0.055 if v > 0.0031308 else 12.92 * v

    out = min(1.0, max(0.0, b + a * (s - b)))
    return round(encode(q * out + (1 - q) * b) * 255)  # round() is half to even


def test_lookup_path_equals_direct_evaluation():
    rng = np.random.default_rng(20260913)
    masks = rng.integers(0, 256, size=(40, 9, 9)) / 255.0
    sources = rng.random((40, 3))
    background = rng.random(3)
    alphas = rng.uniform(-2, 2, 40)
    direct = to_8bit(
        composite_coverage(sources[:, None, None, :], background, alphas[:, None, None], masks)
    )
    assert np.array_equal(composite_masks(masks, sources, background, alphas), direct)


def test_arbitrary_coverage_takes_the_direct_path():
    rng = np.random.default_rng(7)
    masks = rng.random((5, 4, 4))  # not k / 255
    sources, background = rng.random((5, 3)), rng.random(3)
    direct = to_8bit(composite_coverage(sources[:, None, None, :], background, 1.3, masks))
    assert np.array_equal(composite_masks(masks, sources, background, 1.3), direct)


@pytest.mark.parametrize("blend", list(Blend))
def test_blends_at_full_coverage(blend):
    s, b = np.array([[0.8, 0.2, 0.5]]), np.array([0.3, 0.6, 0.5])
    expected = {
        Blend.EXTENDED: np.clip(b + 1.5 * (s - b), 0, 1),
        Blend.DIFFERENCE: np.abs(s - b),
        Blend.EXCLUSION: s + b - 2 * s * b,
    }[blend]
    got = composite_masks(np.ones((1, 2, 2)), s, b, 1.5, blend)
    assert np.array_equal(got[0, 0, 0], to_8bit(expected[0]))


@pytest.mark.parametrize("layout", list(Layout))
def test_every_icon_pixel_is_the_papers_expression(example, layout):
    theme, iconset, masks = example
    canvases = (theme.canvases[0], theme.canvases[4], theme.canvases[10])
    for spec in plan_sheets(layout, canvases, [16, 48], "t"):
        sheet = render_sheet(spec, iconset, masks, alphas=[1.0, None, -1.0, 1.4])
        pixels = np.asarray(sheet.image)
        assert sheet.placements
        for p in sheet.placements:
            q = masks[(p.icon, p.size)] if p.icon else np.ones((p.size, p.size))
            expected = to_8bit(composite_coverage(p.source, p.background, p.alpha, q))
            block = pixels[p.y : p.y + p.size, p.x : p.x + p.size]
            assert np.array_equal(block, expected), (spec.name, p)
        # ...and a sample of pixels with scalar maths only, independent of numpy.
        for p in sheet.placements[:: max(1, len(sheet.placements) // 7)]:
            q = masks[(p.icon, p.size)] if p.icon else np.ones((p.size, p.size))
            for y, x in [(p.size // 2, p.size // 2), (0, 0), (p.size // 3, p.size - 2)]:
                want = [
                    _scalar_pixel(p.source[k], p.background[k], p.alpha, float(q[y, x]))
                    for k in range(3)
                ]
                assert pixels[p.y + y, p.x + x].tolist() == want


@pytest.mark.parametrize("layout", list(Layout))
def test_blocks_are_disjoint_inside_the_sheet_and_labels_exist(example, layout):
    theme, iconset, masks = example
    (spec,) = plan_sheets(layout, theme.canvases[:1], [24], "t")[:1]
    sheet = render_sheet(spec, iconset, masks)
    width, height = sheet.image.size
    covered = np.zeros((height, width), dtype=int)
    for p in sheet.placements:
        assert p.x >= 0 and p.x + p.size <= width and p.y >= 0 and p.y + p.size <= height
        covered[p.y : p.y + p.size, p.x : p.x + p.size] += 1
    assert covered.max() == 1
    pixels = np.asarray(sheet.image).reshape(-1, 3)
    gutter = pixels[covered.reshape(-1) == 0]
    assert len(np.unique(gutter, axis=0)) > 2  # text was drawn somewhere outside the icons


def test_grid_rows_default_to_one_and_the_sets_own(example):
    theme, iconset, masks = example
    (spec,) = plan_sheets(Layout.GRID, theme.canvases[:1], [24], "t")
    sheet = render_sheet(spec, iconset, masks)
    alphas = sorted({p.alpha for p in sheet.placements})
    assert alphas == [1.0, 1.1, 1.18]
    assert len(sheet.placements) == 2 * len(iconset.icons)


def test_grid_wraps_to_the_width(example):
    theme, iconset, masks = example
    (spec,) = plan_sheets(Layout.GRID, theme.canvases[:1], [48], "t")
    sheet = render_sheet(spec, iconset, masks, alphas=[1.0], max_width=400)
    assert sheet.image.size[0] <= 560  # header text may set the width, icons wrap
    assert len({p.y for p in sheet.placements}) > 1


def test_swatches_cover_the_palette(example):
    theme, iconset, masks = example
    (spec,) = plan_sheets(Layout.SWATCHES, theme.canvases[:1], [48], "t")
    sheet = render_sheet(spec, iconset, masks, alphas=[1.0, 2.0])
    assert len(sheet.placements) == 2 * len(iconset.palette)
    assert all(p.icon is None for p in sheet.placements)


def test_plan_names_are_predictable_and_distinct():
    canvases = [Canvas("Paper", "#fff"), Canvas("paper", "#eee"), Canvas("Ink 2", "#000")]
    grid = [s.name for s in plan_sheets(Layout.GRID, canvases, [24], "My Theme")]
    assert grid == [
        "my-theme-grid-paper-24px.png",
        "my-theme-grid-paper-2-24px.png",
        "my-theme-grid-ink-2-24px.png",
    ]
    assert [s.name for s in plan_sheets(Layout.COMPARE, canvases, [16, 48], "x")] == [
        "x-compare-16px.png",
        "x-compare-48px.png",
    ]
    assert [s.name for s in plan_sheets(Layout.SWATCHES, canvases[:1], [16], "x")] == [
        "x-swatches-paper.png"
    ]


def test_write_refuses_to_overwrite(tmp_path, example):
    theme, iconset, masks = example
    (spec,) = plan_sheets(Layout.GRID, theme.canvases[:1], [16], "t")
    sheet = render_sheet(spec, iconset, masks)
    path = write_sheet(sheet, tmp_path)
    assert np.array_equal(np.asarray(Image.open(path)), np.asarray(sheet.image))
    with pytest.raises(UsageError, match="already exists; pass `overwrite=True`"):
        write_sheet(sheet, tmp_path)
    write_sheet(sheet, tmp_path, overwrite=True)
    assert [p.name for p in tmp_path.iterdir()] == [spec.name]  # no temporary files left
    umask = os.umask(0o022)
    os.umask(umask)
    assert path.stat().st_mode & 0o777 == 0o666 & ~umask  # an ordinary file, not mkstemp's 0600


def test_near_source_canvases_follow_the_paper():
    vibrant = load_iconset(ICONSET).palette
    canvases = near_source_canvases(vibrant)
    names = [c.name for c in canvases]
    # Warm to cool hues, then grey, then dark grey (paper, Appendix A.3 figures).
    assert names == [
        "near-red",
        "near-orange",
        "near-teal",
        "near-cyan",
        "near-blue",
        "near-magenta",
        "near-grey",
        "dark-grey",
    ]
    for canvas in canvases[:-1]:
        source = vibrant[canvas.name.removeprefix("near-")]
        for k in range(3):
            code = int(source[1 + 2 * k : 3 + 2 * k], 16)
            mixed = int(canvas.color[1 + 2 * k : 3 + 2 * k], 16)
            assert abs(mixed - (0.9 * code + 25.5)) <= 0.5


def test_sheets_render_icons_without_a_mask_as_absent():
    icons = IconSet(
        "s", (Icon("a", Path("a.svg"), "#ee7733", 1.1), Icon("b", Path("b.svg"), "red", 1))
    )
    masks = {("a", 8): np.full((8, 8), 1.0)}
    (spec,) = plan_sheets(Layout.GRID, [Canvas("w", "#fff")], [8], "t")
    sheet = render_sheet(spec, icons, masks, alphas=[1.0])
    assert [p.icon for p in sheet.placements] == ["a"]
