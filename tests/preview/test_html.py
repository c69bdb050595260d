"""The preview page is one self-contained file whose masks round-trip exactly."""

from __future__ import annotations

import base64
import json
import re
from pathlib import Path

import numpy as np

from alpha_audit import load_iconset, load_theme, rasterize_icons
from alpha_audit.preview.html import mask_atlas, preview_html

ROOT = Path(__file__).resolve().parents[2]


def test_page_is_self_contained_and_masks_round_trip():
    theme = load_theme(ROOT / "themes" / "paper16.yaml")
    iconset = load_iconset(ROOT / "examples" / "vibrant" / "iconset.yaml")
    masks = rasterize_icons([(i.name, i.file) for i in iconset.icons], [16, 48]).masks
    page = preview_html(theme, iconset, masks, sizes=[16, 48])
    assert "default-src 'none'" in page  # CSP: no network, no external files
    assert not re.search(r"""(src|href)\s*=\s*["'](?!data:)""", page)
    assert "__ALPHA_AUDIT_" not in page
    data = json.loads(re.search(r'id="alpha-audit-data">(.*?)</script>', page, re.S).group(1))
    for size in (16, 48):
        atlas = data["atlases"][str(size)]
        codes = np.frombuffer(base64.b64decode(atlas["data"]), dtype=np.uint8)
        codes = codes.reshape(atlas["height"], atlas["width"])
        for k, icon in enumerate(data["icons"]):
            r, c = divmod(k, atlas["columns"])
            block = codes[r * size : (r + 1) * size, c * size : (c + 1) * size]
            assert np.array_equal(block / 255.0, masks[(icon["name"], size)])


def test_atlas_layout():
    cols, atlas = mask_atlas([np.full((4, 4), k / 255) for k in range(5)], 4)
    assert cols == 3 and atlas.shape == (8, 12)
    assert atlas[4, 4] == 4 and atlas[0, 8] == 2
