"""The preview page is one self-contained file carrying each paint group's mask exactly."""

from __future__ import annotations

import base64
import json
import re
from pathlib import Path

import numpy as np
import pytest

from alpha_audit import load_iconset, load_theme
from alpha_audit.errors import UsageError
from alpha_audit.load.paint_masks import paint_masks
from alpha_audit.preview import html as page_html
from alpha_audit.preview.figures import preview_rows
from alpha_audit.preview.html import mask_atlas, preview_html
from multipaint import write_multipaint

ROOT = Path(__file__).resolve().parents[2]


def _page_data(page: str) -> dict:
    return json.loads(re.search(r'id="alpha-audit-data">(.*?)</script>', page, re.S).group(1))


def test_page_is_self_contained_and_group_masks_round_trip(tmp_path):
    theme_path, manifest = write_multipaint(tmp_path)
    theme, iconset = load_theme(theme_path), load_iconset(manifest)
    masks = paint_masks([(i.name, i.file) for i in iconset.icons], [16, 48], cache=False)
    drawn = preview_rows(theme, iconset, masks, [16, 48])
    page = preview_html(theme, iconset, drawn, sizes=[16, 48])
    assert "default-src 'none'" in page  # CSP: no network, no external files
    assert not re.search(r"""(src|href)\s*=\s*["'](?!data:)""", page)
    assert "__ALPHA_AUDIT_" not in page
    data = _page_data(page)
    assert data["pipeline"] == "linear"
    by_name = {i["name"]: i for i in data["icons"]}
    assert [layer["hex"] for layer in by_name["red"]["layers"]] == ["#ff0000"]
    assert by_name["red"]["fixed"] and by_name["disc"]["fixed"]
    assert [layer["opacity"] for layer in by_name["disc"]["layers"]] == [pytest.approx(0.3)]
    assert len(by_name["mixed"]["layers"]) == 3
    for size in (16, 48):
        atlas = data["atlases"][str(size)]
        codes = np.frombuffer(base64.b64decode(atlas["data"]), dtype=np.uint8)
        codes = codes.reshape(atlas["pages"], atlas["height"], atlas["width"])
        per_page = atlas["columns"] * atlas["rows"]
        for icon in data["icons"]:
            for g, mask in enumerate(masks.icons[icon["name"]].masks[size]):
                page_no, rest = divmod(icon["first"] + g, per_page)
                r, c = divmod(rest, atlas["columns"])
                block = codes[page_no, r * size : (r + 1) * size, c * size : (c + 1) * size]
                assert np.array_equal(block, mask)


def test_atlas_layout():
    cols, rows, atlas = mask_atlas([np.full((4, 4), k, dtype=np.uint8) for k in range(5)], 4)
    assert (cols, rows) == (3, 2) and atlas.shape == (1, 8, 12)
    assert atlas[0, 4, 4] == 4 and atlas[0, 0, 8] == 2


def test_atlas_pages_hold_at_most_the_guaranteed_texture_size():
    cols, rows, atlas = mask_atlas([np.full((512, 512), k, dtype=np.uint8) for k in range(20)], 512)
    assert (cols, rows) == (4, 4) and atlas.shape == (2, 2048, 2048)
    assert atlas[1, 0, 512] == 17


def test_a_page_over_the_mask_budget_is_refused_before_packing(monkeypatch):
    monkeypatch.setattr(page_html, "MAX_PAGE_MASK_BYTES", 1000)
    with pytest.raises(UsageError, match=r"MiB of coverage masks .* fewer sizes"):
        page_html._check_page_bytes(4, [16, 48])


@pytest.mark.parametrize(
    "title",
    ["__ALPHA_AUDIT_SCRIPT__", "__ALPHA_AUDIT_DATA__", "</title><script>alert(1)</script>\u202e"],
)
def test_a_name_is_text_in_the_page_even_when_it_reads_like_a_placeholder(tmp_path, title):
    import dataclasses
    import html

    theme_path, manifest = write_multipaint(tmp_path)
    theme, iconset = load_theme(theme_path), load_iconset(manifest)
    theme = dataclasses.replace(theme, name=title)
    masks = paint_masks([(i.name, i.file) for i in iconset.icons], [16], cache=False)
    page = preview_html(theme, iconset, preview_rows(theme, iconset, masks, [16]), sizes=[16])
    # One script and one data block: a theme named like a placeholder once pulled the whole
    # script into the page's title and heading (chained str.replace).
    assert page.count("<script") == 2 and page.count('"use strict"') == 1
    shown = re.search(r'<h1 id="title">(.*?)</h1>', page, re.S).group(1)
    assert "<" not in shown and "\u202e" not in shown
    assert title.split("\u202e")[0] in html.unescape(shown)
    assert title in _page_data(page)["title"]  # the data keeps the name as it is
