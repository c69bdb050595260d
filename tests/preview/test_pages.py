"""Sheets over the pixel budget: split into pages that cover every icon once, or refused."""

from __future__ import annotations

import itertools
import math
import warnings
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
from PIL import Image
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.color import composite_coverage, to_8bit
from alpha_audit.errors import UsageError
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.preview import (
    MAX_NEAR_SOURCE_COLORS,
    PIXEL_BUDGET,
    Layout,
    near_source_canvases,
    paginate,
    plan_sheets,
    render_sheet,
)
from alpha_audit.preview.figures import solid_rows

ROOT = Path(__file__).resolve().parents[2]
THEME = str(ROOT / "themes" / "paper16.yaml")
CANVASES = (Canvas("Paper", "#fbfbf8"), Canvas("Ink", "#17171a"), Canvas("Mist", "#c9d4e0"))


def _big_set(n: int, size: int, *, palette: bool = True) -> tuple[IconSet, dict]:
    """``n`` icons with random 8-bit coverage, own colours and two coefficients."""
    rng = np.random.default_rng(20261201)
    colours = [f"#{int(c):06x}" for c in rng.integers(0, 1 << 24, n)]
    icons = tuple(
        Icon(f"icon-{k:04d}", Path(f"{k}.svg"), colours[k], 1.0 if k % 3 else 1.2) for k in range(n)
    )
    masks = {(i.name, size): rng.integers(0, 256, (size, size)) / 255.0 for i in icons}
    pal = {"a": "#ee7733", "b": "#0077bb"} if palette else {}
    return IconSet("big", icons, palette=pal, sizes=(size,)), masks


def _rows(iconset, masks, canvases=CANVASES):
    return solid_rows(Theme("t", tuple(canvases)), iconset, masks)


def _render_pages(specs, iconset, masks, **options):
    drawn = _rows(iconset, masks, {c: None for s in specs for c in s.canvases})
    return [render_sheet(spec, iconset, drawn, **options) for spec in specs]


@pytest.mark.parametrize("layout", [Layout.GRID, Layout.COMPARE])
def test_pages_cover_every_icon_once_and_stay_under_the_budget(layout):
    iconset, masks = _big_set(400, 24)
    budget = 600_000
    planned = plan_sheets(layout, CANVASES, [24], "t")
    specs = paginate(planned, iconset, alphas=[1.0, None], budget=budget)
    assert len(specs) > len(planned)  # the set does not fit one sheet at this budget
    names = [s.name for s in specs]
    assert len(set(names)) == len(names)
    sheets = _render_pages(specs, iconset, masks, alphas=[1.0, None])
    seen: Counter = Counter()
    for sheet in sheets:
        width, height = sheet.image.size
        assert width * height <= budget, sheet.spec.name
        assert sheet.spec.page is not None and sheet.spec.name.endswith(
            f"-{sheet.spec.page.number:0{len(str(sheet.spec.page.count))}d}.png"
        )
        seen.update((p.icon, p.canvas) for p in sheet.placements)
        pixels = np.asarray(sheet.image)
        for p in sheet.placements[:: max(1, len(sheet.placements) // 25)]:
            expected = to_8bit(
                composite_coverage(p.source, p.background, p.alpha, masks[(p.icon, p.size)])
            )
            assert np.array_equal(pixels[p.y : p.y + p.size, p.x : p.x + p.size], expected)
    # Every icon on every canvas, once in each of the two rows (alpha 1 and the set's own).
    assert set(seen) == {(i.name, c.name) for i in iconset.icons for c in CANVASES}
    assert set(seen.values()) == {2}


def test_a_sheet_that_fits_keeps_its_name_and_has_no_page():
    iconset, masks = _big_set(30, 16)
    planned = plan_sheets(Layout.GRID, CANVASES[:1], [16], "t")
    assert paginate(planned, iconset) == planned
    assert render_sheet(planned[0], iconset, _rows(iconset, masks)).spec.page is None


def test_pages_are_even_and_in_manifest_order():
    iconset, _ = _big_set(400, 24)
    specs = paginate(plan_sheets(Layout.GRID, CANVASES[:1], [24], "t"), iconset, budget=600_000)
    spans = [(s.page.first, s.page.stop) for s in specs]
    assert spans[0][0] == 0 and spans[-1][1] == 400
    assert all(a[1] == b[0] for a, b in itertools.pairwise(spans))
    sizes = [b - a for a, b in spans]
    assert max(sizes) - min(sizes) <= math.ceil(400 / len(spans))
    assert f"icons 1-{spans[0][1]} of 400" in specs[0].page.note


def test_swatches_without_a_palette_page_by_colour():
    iconset, masks = _big_set(300, 48, palette=False)
    specs = paginate(
        plan_sheets(Layout.SWATCHES, CANVASES[:1], [48], "t"), iconset, budget=2_000_000
    )
    assert len(specs) > 1
    seen: Counter = Counter()
    for sheet in _render_pages(specs, iconset, masks):
        assert sheet.image.size[0] * sheet.image.size[1] <= 2_000_000
        seen.update((p.source, p.alpha) for p in sheet.placements)
    assert len({source for source, _ in seen}) == len({i.color for i in iconset.icons})
    assert set(seen.values()) == {1}


def test_one_item_over_the_budget_is_refused_naming_the_sheet():
    iconset, _ = _big_set(3, 48)
    (spec,) = plan_sheets(Layout.GRID, CANVASES[:1], [48], "t")
    with pytest.raises(UsageError, match=r"t-grid-paper-48px\.png .* even with one icon"):
        paginate([spec], iconset, budget=20_000)


def test_drawing_a_sheet_over_the_budget_is_refused():
    iconset, masks = _big_set(1, 16)
    (spec,) = plan_sheets(Layout.GRID, CANVASES[:1], [16], "t")
    with pytest.raises(UsageError, match=f"more than the {PIXEL_BUDGET:,} px"):
        render_sheet(spec, iconset, _rows(iconset, masks), alphas=[1.0] * 200_000)


def test_near_source_canvases_are_bounded():
    palette = {f"c{k}": f"#{k:06x}" for k in range(MAX_NEAR_SOURCE_COLORS + 1)}
    with pytest.raises(UsageError, match=f"at most {MAX_NEAR_SOURCE_COLORS}"):
        near_source_canvases(palette)
    assert len(near_source_canvases(dict(list(palette.items())[:-1]))) == (
        MAX_NEAR_SOURCE_COLORS + 1
    )


def _write_set(folder: Path, n: int, *, palette: bool, size: int) -> Path:
    svg = (
        '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24">'
        '<circle cx="12" cy="12" r="9" fill="currentColor"/></svg>'
    )
    (folder / "svg").mkdir()
    lines = ["name: many", f"sizes: [{size}]"]
    if palette:
        lines += ["palette:", "  orange: '#ee7733'"]
    lines.append("icons:")
    for k in range(n):
        (folder / "svg" / f"i{k}.svg").write_text(svg)
        lines += [f"  - name: i{k}", f"    file: svg/i{k}.svg", f"    color: '#{k * 4099:06x}'"]
    manifest = folder / "iconset.yaml"
    manifest.write_text("\n".join(lines) + "\n")
    return manifest


def test_cli_splits_a_large_grid_into_pages_pillow_opens_without_warning(tmp_path):
    manifest = _write_set(tmp_path, 20, palette=True, size=1024)
    theme = tmp_path / "theme.yaml"
    theme.write_text("name: one\ncanvases:\n  - name: white\n    color: '#ffffff'\n")
    out = tmp_path / "out"
    result = CliRunner().invoke(
        app, ["preview", str(theme), str(manifest), "-o", str(out), "-s", "1024", "-a", "1"]
    )
    assert result.exit_code == 0, result.output
    names = sorted(p.name for p in out.iterdir())
    assert names == ["one-grid-white-1024px-1.png", "one-grid-white-1024px-2.png"]
    for name in names:
        with warnings.catch_warnings():
            warnings.simplefilter("error", Image.DecompressionBombWarning)
            with Image.open(out / name) as image:
                assert image.size[0] * image.size[1] <= PIXEL_BUDGET


def test_cli_refuses_near_source_for_thousands_of_colours_with_exit_2(tmp_path):
    manifest = _write_set(tmp_path, MAX_NEAR_SOURCE_COLORS + 6, palette=False, size=16)
    result = CliRunner().invoke(
        app,
        ["preview", THEME, str(manifest), "-o", str(tmp_path), "--near-source", "-l", "compare"],
    )
    assert result.exit_code == 2, result.output
    assert f"at most {MAX_NEAR_SOURCE_COLORS}" in result.output
    assert str(manifest) in result.output
    assert not list(tmp_path.glob("*.png"))
