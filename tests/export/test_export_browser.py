"""The exports in a browser: CSS custom properties and SVG filters in headless Chromium.

Each icon colour of each mode is drawn on each canvas twice: filled with the
exported CSS property (under the mode's ``[data-theme]`` rule) and filled with
its source colour through the exported ``<filter>``.  The screenshot's fully
covered pixels must equal ``check``'s output within 1/255 per channel.
Half-covered edge pixels are compared with the browser's blend in
gamma-encoded sRGB (docs/export.md says exported icons get the browser's
edges, not the paper's).
"""

from __future__ import annotations

import base64
import importlib.util
import io
import time
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from alpha_audit.color import srgb_decode, srgb_encode
from alpha_audit.export import export_table, render_export
from alpha_audit.export.svg import filter_id
from alpha_audit.load.config import load_config
from alpha_audit.load.tokens.themes import load_token_themes

ROOT = Path(__file__).resolve().parents[2]
CELL = 24  # px; the icon is a full-cell square with a 4 px inset
TOLERANCE = 1


def _harness():
    spec = importlib.util.spec_from_file_location(
        "browser_harness", ROOT / "tests/preview/test_browser.py"
    )
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    # No colour management: CSS and SVG colours reach the framebuffer as sRGB codes.
    module.CHROMIUM_FLAGS = [*module.CHROMIUM_FLAGS, "--force-color-profile=srgb"]
    return module


def _page(table) -> tuple[str, list[tuple[int, int, str, str]]]:
    css = render_export(table, "css")["colors.css"]
    svg = render_export(table, "svg")["filters.svg"]
    cells, expected = [], []
    row = 0
    for mode in table.modes:
        alphas = sorted({c.alpha for c in mode.colors})
        for color in mode.colors:
            for k, (canvas, out) in enumerate(zip(mode.canvases, color.outputs, strict=True)):
                prop = "--" + (
                    color.token if len(mode.canvases) == 1 else f"{color.token}.on.{canvas.short}"
                ).replace(".", "-")
                fid = filter_id(mode.name, canvas.short, color.alpha, len(alphas))
                for col, icon in enumerate(
                    (
                        f'<rect x="3.5" y="4" width="16.5" height="16" style="fill: var({prop})"/>',
                        f'<rect x="3.5" y="4" width="16.5" height="16" fill="{color.source}" '
                        f'filter="url(#{fid})"/>',
                    )
                ):
                    x, y = (2 * k + col) * CELL, row * CELL
                    cells.append(
                        f'<div data-theme="{mode.name}" style="position:absolute;left:{x}px;'
                        f'top:{y}px;width:{CELL}px;height:{CELL}px;background:{canvas.hex}">'
                        f'<svg width="{CELL}" height="{CELL}" viewBox="0 0 {CELL} {CELL}">'
                        f"{icon}</svg></div>"
                    )
                    expected.append((x + CELL // 2, y + CELL // 2, out, canvas.hex))
            row += 1
    html = (
        "<!doctype html><html><head><style>html,body{margin:0}"
        f"{css}</style></head><body>{svg}{''.join(cells)}</body></html>"
    )
    return html, expected


def test_exported_css_and_svg_filters_render_the_audit_outputs(tmp_path):
    harness = _harness()
    binary = harness.find_chromium()
    if binary is None:
        pytest.skip(harness.INSTALL_HINT)
    themes = load_token_themes(load_config(ROOT / "examples/tokens/alpha-audit.yaml").tokens)
    table = export_table(themes)
    html, expected = _page(table)
    page = tmp_path / "export.html"
    page.write_text(html, encoding="utf-8")
    devtools = harness.DevTools(binary)
    try:
        devtools.open(page.as_uri())
        deadline = time.monotonic() + 30
        while devtools.evaluate("document.readyState") != "complete":
            assert time.monotonic() < deadline
            time.sleep(0.05)
        width = max(e[0] for e in expected) + CELL
        height = max(e[1] for e in expected) + CELL
        devtools.call(
            "Emulation.setDeviceMetricsOverride",
            {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": False},
        )
        shot = devtools.call("Page.captureScreenshot", {"format": "png"})
    finally:
        devtools.close()
    image = np.asarray(Image.open(io.BytesIO(base64.b64decode(shot["data"]))).convert("RGB"))
    worst = 0
    edge_error = {0: 0, 1: 0}  # column 0: CSS property, column 1: SVG filter
    linear_gap = 255
    for x, y, out, bg in expected:
        want = np.array([int(out[i : i + 2], 16) for i in (1, 3, 5)])
        page = np.array([int(bg[i : i + 2], 16) for i in (1, 3, 5)])
        # the 8 x 8 centre of the square: fully covered pixels only
        got = image[y - 4 : y + 4, x - 4 : x + 4].reshape(-1, 3).astype(int)
        worst = max(worst, int(np.abs(got - want).max()))
        # The left edge (x = 3.5 in the cell) covers its pixel column by half: the browser
        # blends it onto the page in gamma-encoded sRGB, not in linear light.
        edge = image[y - 4 : y + 4, x - CELL // 2 + 3].astype(int)
        column = (x // CELL) % 2
        error = int(np.ceil(np.abs(edge - (want + page) / 2).max() - 1e-9))
        edge_error[column] = max(edge_error[column], error)
        linear = 255 * srgb_encode((srgb_decode(want / 255) + srgb_decode(page / 255)) / 2)
        if np.abs(linear - (want + page) / 2).max() > 20:  # where the two blends are far apart
            linear_gap = min(linear_gap, int(np.abs(edge - linear).max()))
    assert len(expected) == 2 * sum(len(m.colors) * len(m.canvases) for m in table.modes)
    assert worst <= TOLERANCE, f"max error {worst}/255"
    assert edge_error[0] <= TOLERANCE, f"CSS edges {edge_error[0]}/255 off the sRGB blend"
    # Through the filter, half-covered edge pixels land up to 3 codes off (measured in
    # Chromium 156; plausibly its 8-bit premultiplied linearRGB intermediates).
    assert edge_error[1] <= 3, f"filter edges {edge_error[1]}/255 off the sRGB blend"
    assert linear_gap > 15  # the edges are the browser's gamma blend, not the paper's linear one
    print(
        f"export in Chromium: {len(expected)} squares, max error {worst}/255 covered; "
        f"half-covered edges vs the gamma-space blend: CSS {edge_error[0]}/255, "
        f"filter {edge_error[1]}/255; >= {linear_gap}/255 from a linear-light blend"
    )
