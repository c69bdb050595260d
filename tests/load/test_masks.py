"""Masks are kept as 8-bit codes and read back as exactly k / 255 in float64."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from alpha_audit.load.svg import CoverageMasks, rasterize, rasterize_icons

SVG = (
    b'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24">'
    b'<circle cx="12" cy="12" r="7"/></svg>'
)


def test_lookup_is_codes_over_255_in_float64() -> None:
    codes = np.arange(256, dtype=np.uint8).reshape(16, 16)
    masks = CoverageMasks({("a", 16): codes})
    mask = masks[("a", 16)]
    assert mask.dtype == np.float64
    assert np.array_equal(mask * 255.0, codes.astype(np.float64))
    assert masks.codes(("a", 16)).nbytes == 256  # one byte a pixel
    assert list(masks) == [("a", 16)] and len(masks) == 1


def test_sandboxed_masks_equal_in_process_rasterisation(tmp_path: Path) -> None:
    (tmp_path / "c.svg").write_bytes(SVG)
    result = rasterize_icons([("c", tmp_path / "c.svg")], [16, 33])
    for size in (16, 33):
        assert result.masks.codes(("c", size)).dtype == np.uint8
        assert np.array_equal(result.masks[("c", size)], rasterize(SVG, size))
