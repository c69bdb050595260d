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
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.preview import (
    Blend,
    Layout,
    near_source_canvases,
    plan_sheets,
    render_sheet,
    write_sheet,
)
from alpha_audit.preview.compose import Drawing, Layer, composite_drawings
from alpha_audit.preview.figures import solid_rows

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


def _drawings(rng, n, groups, size, opacity=None):
    """``n`` random icons of ``groups`` currentColor-free paint groups each."""
    out = []
    for k in range(n):
        layers = tuple(
            Layer("#000000", tuple(rng.random(3)), 1.0 if opacity is None else opacity)
            for _ in range(groups)
        )
        masks = {size: tuple(rng.integers(0, 256, (size, size)).astype(np.uint8) for _ in layers)}
        out.append(Drawing(f"i{k}", layers, masks))
    return out


def test_lookup_path_equals_direct_evaluation():
    rng = np.random.default_rng(20260913)
    drawings = _drawings(rng, 40, 1, 9)
    sources = np.array([d.layers[0].source for d in drawings])
    masks = np.stack([d.masks[9][0] for d in drawings]) / 255.0
    background = rng.random(3)
    alphas = rng.uniform(-2, 2, 40)
    direct = to_8bit(
        composite_coverage(sources[:, None, None, :], background, alphas[:, None, None], masks)
    )
    assert np.array_equal(composite_drawings(drawings, 9, background, alphas), direct)


def _row_pixel(s, b, a, w, pipeline):
    """One channel of a paint's row at weight w = opacity x coverage, with the math module only.

    linear: encode(w clip(b + a (s - b)) + (1 - w) b); css: b' + a w (s' - b') on encoded values.
    """

    def encode(v):  # CSS Color 4 gam_sRGB
        return 1.055 * v ** (1 / 2.4) - 0.055 if v > 0.0031308 else 12.92 * v

    if pipeline == "css":
        return round(min(1.0, max(0.0, encode(b) + a * w * (encode(s) - encode(b)))) * 255)
    out = min(1.0, max(0.0, b + a * (s - b)))
    return round(encode(w * out + (1 - w) * b) * 255)  # round() is half to even


@pytest.mark.parametrize("pipeline", ["linear", "css"])
def test_a_pixel_one_group_covers_is_its_rows_formula(pipeline):
    # Three groups painted in order; where exactly one covers a pixel, the pixel is that
    # group's row at coverage q: composite_paint(Cs, Cb, a, o q) then 8 bits.
    rng = np.random.default_rng(5)
    size = 12
    layers = (
        Layer("#000000", tuple(rng.random(3)), 0.3),
        Layer("currentColor", tuple(rng.random(3)), 1.0),
        Layer("#000000", tuple(rng.random(3)), 0.7),
    )
    masks = np.zeros((3, size, size), dtype=np.uint8)
    cells = rng.integers(0, 3, (size, size))  # which group covers each pixel, alone
    for g in range(3):
        masks[g][cells == g] = rng.integers(0, 256, int((cells == g).sum()))
    drawing = Drawing("x", layers, {size: tuple(masks)})
    background = rng.random(3)
    a = 0.8 if pipeline == "css" else 1.3
    pixels = composite_drawings([drawing], size, background, a, pipeline)[0]
    for y, x in [(y, x) for y in range(0, size, 3) for x in range(0, size, 2)]:
        g = int(cells[y, x])
        w = layers[g].opacity * (int(masks[g][y, x]) / 255)
        want = [_row_pixel(layers[g].source[c], background[c], a, w, pipeline) for c in range(3)]
        assert pixels[y, x].tolist() == want, (y, x, g)


def test_groups_are_painted_in_order_in_linear_light():
    # A fully covered opaque group hides what is under it; a translucent one on top mixes
    # with the group below, not with the canvas.
    full = np.full((1, 1), 255, dtype=np.uint8)
    red, blue = (1.0, 0.0, 0.0), (0.0, 0.0, 1.0)
    white = np.ones(3)
    under = Drawing(
        "u", (Layer("#0000ff", blue, 1.0), Layer("#ff0000", red, 1.0)), {1: (full, full)}
    )
    assert composite_drawings([under], 1, white)[0, 0, 0].tolist() == [255, 0, 0]
    half = Drawing(
        "h", (Layer("#0000ff", blue, 1.0), Layer("#ff0000", red, 0.5)), {1: (full, full)}
    )
    assert (
        composite_drawings([half], 1, white)[0, 0, 0].tolist() == to_8bit([0.5, 0.0, 0.5]).tolist()
    )


def test_several_groups_take_the_same_path_as_one():
    # An icon of one group equals the same group drawn under a group that covers nothing.
    rng = np.random.default_rng(11)
    (one,) = _drawings(rng, 1, 1, 7, opacity=0.6)
    empty = np.zeros((7, 7), dtype=np.uint8)
    two = Drawing(
        "y", (Layer("#000000", (0.2, 0.3, 0.4), 1.0), *one.layers), {7: (empty, *one.masks[7])}
    )
    background = rng.random(3)
    for pipeline in ("linear", "css"):
        a = 0.9
        assert np.array_equal(
            composite_drawings([one], 7, background, a, pipeline),
            composite_drawings([two], 7, background, a, pipeline),
        )


def test_css_refuses_alpha_times_opacity_above_one():
    rng = np.random.default_rng(1)
    with pytest.raises(ValueError, match="css"):
        composite_drawings(_drawings(rng, 1, 1, 2), 2, np.ones(3), 1.5, "css")


@pytest.mark.parametrize("blend", list(Blend))
def test_blends_at_full_coverage(blend):
    s, b = np.array([0.8, 0.2, 0.5]), np.array([0.3, 0.6, 0.5])
    expected = {
        Blend.EXTENDED: np.clip(b + 1.5 * (s - b), 0, 1),
        Blend.DIFFERENCE: np.abs(s - b),
        Blend.EXCLUSION: s + b - 2 * s * b,
    }[blend]
    full = np.full((2, 2), 255, dtype=np.uint8)
    drawing = Drawing("x", (Layer("currentColor", tuple(s), 1.0),), {2: (full,)})
    got = composite_drawings([drawing], 2, b, 1.5, blend=blend)
    assert np.array_equal(got[0, 0, 0], to_8bit(expected))


def _rows(theme, iconset, masks):
    return solid_rows(theme, iconset, masks)


@pytest.mark.parametrize("layout", list(Layout))
def test_every_icon_pixel_is_the_papers_expression(example, layout):
    theme, iconset, masks = example
    canvases = (theme.canvases[0], theme.canvases[4], theme.canvases[10])
    for spec in plan_sheets(layout, canvases, [16, 48], "t"):
        sheet = render_sheet(
            spec, iconset, _rows(theme, iconset, masks), alphas=[1.0, None, -1.0, 1.4]
        )
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
    sheet = render_sheet(spec, iconset, _rows(theme, iconset, masks))
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
    sheet = render_sheet(spec, iconset, _rows(theme, iconset, masks))
    alphas = sorted({p.alpha for p in sheet.placements})
    assert alphas == [1.0, 1.1, 1.18]
    assert len(sheet.placements) == 2 * len(iconset.icons)


def test_grid_wraps_to_the_width(example):
    theme, iconset, masks = example
    (spec,) = plan_sheets(Layout.GRID, theme.canvases[:1], [48], "t")
    sheet = render_sheet(spec, iconset, _rows(theme, iconset, masks), alphas=[1.0], max_width=400)
    assert sheet.image.size[0] <= 560  # header text may set the width, icons wrap
    assert len({p.y for p in sheet.placements}) > 1


def test_swatches_cover_the_palette(example):
    theme, iconset, masks = example
    (spec,) = plan_sheets(Layout.SWATCHES, theme.canvases[:1], [48], "t")
    sheet = render_sheet(spec, iconset, _rows(theme, iconset, masks), alphas=[1.0, 2.0])
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
    sheet = render_sheet(spec, iconset, _rows(theme, iconset, masks))
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
    theme = Theme("t", (Canvas("w", "#fff"),))
    (spec,) = plan_sheets(Layout.GRID, theme.canvases, [8], "t")
    sheet = render_sheet(spec, icons, _rows(theme, icons, masks), alphas=[1.0])
    assert [p.icon for p in sheet.placements] == ["a"]
