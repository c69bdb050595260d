"""The exports in a browser: CSS custom properties and SVG filters, in every engine.

Each icon colour of each mode is drawn on each canvas twice: filled with the
exported CSS property (under the mode's ``[data-theme]`` rule) and filled with
its source colour through the exported ``<filter>``.  The viewport's
screenshot (the driver's, since only the compositor knows these pixels) must
show ``check``'s output within 1/255 per channel on fully covered pixels.
Half-covered edge pixels are compared with the browser's blend in
gamma-encoded sRGB: within 1/255 through the CSS property; through the filter
within 3/255, because engines run ``linearRGB`` filters on 8-bit premultiplied
buffers (docs/export.md, "Edges", has the measurements).  Either way the edges
are the browser's gamma-space blend, not the paper's linear one.
"""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from alpha_audit.browser import ENGINES
from alpha_audit.color import composite_extended, srgb_decode, srgb_encode, to_8bit
from alpha_audit.export import export_project, render_export
from alpha_audit.export.svg import filter_id
from alpha_audit.load.config import load_config

ROOT = Path(__file__).resolve().parents[2]
CELL = 24  # px; the icon is a square inset in its cell, its left edge at x = 3.5
TOLERANCE = 1
# Half-covered pixels through the filter, 8-bit codes off the gamma-space blend of check's
# output: measured 3 in Chromium 156 and WebKitGTK 2.50, 1 in Firefox 153 (docs/export.md).
FILTER_EDGE_TOLERANCE = 3


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


@pytest.fixture(scope="module")
def export_page():
    """The example design system's export table and the page drawing it both ways."""
    table = export_project(load_config(ROOT / "examples/tokens/alpha-audit.yaml"))
    html, expected = _page(table)
    return table, html, expected


def _codes(hex_color: str) -> np.ndarray:
    return np.array([int(hex_color[i : i + 2], 16) for i in (1, 3, 5)])


def test_exported_css_and_svg_filters_render_the_audit_outputs(engine, export_page, capsys):
    name, installation = engine
    table, html, expected = export_page
    width = max(e[0] for e in expected) + CELL
    height = max(e[1] for e in expected) + CELL
    with ENGINES[name](installation) as browser:
        # WebKitGTK's windows are never narrower than about 450 px: the page is smaller.
        browser.set_viewport(max(width, 480), max(height, 240))
        browser.open_html(html)
        image = np.asarray(Image.open(io.BytesIO(browser.screenshot())).convert("RGB"))
        version = browser.version
    assert image.shape[0] >= height and image.shape[1] >= width
    worst = {0: 0, 1: 0}  # fully covered; column 0: CSS property, column 1: SVG filter
    edge_error = {0: 0, 1: 0}
    linear_gap = 255
    for x, y, out, bg in expected:
        want, page = _codes(out), _codes(bg)
        column = (x // CELL) % 2
        # the 8 x 8 centre of the square: fully covered pixels only
        got = image[y - 4 : y + 4, x - 4 : x + 4].reshape(-1, 3).astype(int)
        worst[column] = max(worst[column], int(np.abs(got - want).max()))
        # The left edge (x = 3.5 in the cell) covers its pixel column by half: the browser
        # blends it onto the page in gamma-encoded sRGB, not in linear light.
        edge = image[y - 4 : y + 4, x - CELL // 2 + 3].astype(int)
        error = int(np.ceil(np.abs(edge - (want + page) / 2).max() - 1e-9))
        edge_error[column] = max(edge_error[column], error)
        linear = 255 * srgb_encode((srgb_decode(want / 255) + srgb_decode(page / 255)) / 2)
        if np.abs(linear - (want + page) / 2).max() > 20:  # where the two blends are far apart
            linear_gap = min(linear_gap, int(np.abs(edge - linear).max()))
    with capsys.disabled():
        print(
            f"\nexports in {version}: {len(expected)} squares; fully covered: CSS "
            f"{worst[0]}/255, filter {worst[1]}/255; half-covered edges vs the gamma-space "
            f"blend: CSS {edge_error[0]}/255, filter {edge_error[1]}/255; "
            f">= {linear_gap}/255 from a linear-light blend"
        )
    assert len(expected) == 2 * sum(len(m.colors) * len(m.canvases) for m in table.modes)
    assert max(worst.values()) <= TOLERANCE, f"fully covered pixels {worst}/255 off"
    assert edge_error[0] <= TOLERANCE, f"CSS edges {edge_error[0]}/255 off the sRGB blend"
    assert edge_error[1] <= FILTER_EDGE_TOLERANCE, (
        f"filter edges {edge_error[1]}/255 off the sRGB blend"
    )
    assert linear_gap > 15  # the edges are the browser's gamma blend, not the paper's linear one


# Every engine keeps a linearRGB filter's intermediates in 8 bits per channel, so both the
# source channel going in and the output coming out snap to 256 linear levels: sRGB steps of
# 13 codes near black, still about 2 at sRGB 75 (docs/export.md, "Edges and dark channels").
# Measured over every grey source code and every filter of the example: within 1/255 where
# source and output channel are both at least 160 (Chromium 156, WebKitGTK 2.50) or 110
# (Firefox 153), and at most 18/255 (13/255 in Firefox) anywhere.
FILTER_EXACT_FROM = 170
FILTER_WORST = 18


def test_exported_filters_over_every_source_code(engine, export_page, capsys):
    """Each exported filter on all 256 grey source codes, fully covered, against float64.

    This is what the example's colours do not show: through a filter, dark channels are
    not ``check``'s output.  The CSS custom properties are (the test above).
    """
    name, installation = engine
    table, _html, _expected = export_page
    filters = render_export(table, "svg")["filters.svg"]
    rows, wanted = [], []
    for mode in table.modes:
        alphas = sorted({c.alpha for c in mode.colors})
        for canvas in mode.canvases:
            for a in alphas:
                fid = filter_id(mode.name, canvas.short, a, len(alphas))
                y = 4 * len(rows)
                rows.append(
                    "".join(
                        f'<rect x="{4 * k}" y="{y}" width="4" height="4" '
                        f'fill="rgb({k},{k},{k})" filter="url(#{fid})"/>'
                        for k in range(256)
                    )
                )
                source = srgb_decode(np.repeat(np.arange(256)[:, None], 3, axis=1) / 255)
                wanted.append(to_8bit(composite_extended(source, np.array(canvas.linear), a)))
    height = 4 * len(rows)
    html = (
        "<!doctype html><html><head><style>html,body{margin:0;background:#000}</style>"
        f"</head><body>{filters}"
        f'<svg width="1024" height="{height}" style="position:absolute;left:0;top:0">'
        f"{''.join(rows)}</svg></body></html>"
    )
    with ENGINES[name](installation) as browser:
        browser.set_viewport(1024, max(height, 240))
        browser.open_html(html)
        image = np.asarray(Image.open(io.BytesIO(browser.screenshot())).convert("RGB"))
        version = browser.version
    got = image[2:height:4, 2:1024:4].astype(int)  # each cell's inner pixel
    want = np.stack(wanted).astype(int)  # (filters, 256, 3)
    error = np.abs(got - want)
    source = np.arange(256)[None, :, None]
    exact = (source >= FILTER_EXACT_FROM) & (want >= FILTER_EXACT_FROM)
    with capsys.disabled():
        print(
            f"\nexported filters in {version}: {want.shape[0]} filters x 256 source codes; "
            f"source and output channel >= {FILTER_EXACT_FROM}: max error "
            f"{int(error[exact].max())}/255; anywhere: max {int(error.max())}/255, "
            f"{(error > 1).mean():.1%} of channels more than 1/255 off"
        )
    assert exact.sum() > 1000  # the bright corner is not empty
    assert int(error[exact].max()) <= TOLERANCE
    assert int(error.max()) <= FILTER_WORST
