"""The page people see, driven like a person would, in Chromium, Firefox and WebKitGTK.

These tests open the real ``--html`` page (not the validation hook) in every
engine of :mod:`alpha_audit.browser`, at a 1024 x 768 viewport, and read what
it shows: the tiles' pixels through the page's own 2D canvases
(``toDataURL``), the boxes and labels laid over them from the DOM.  Controls
are driven by setting their values and dispatching the events a person's
input fires (``input``, ``change``, ``click``).  Only the check that a label
is not hidden under the next tile looks at the composited screen, through the
driver's :meth:`~alpha_audit.browser.Browser.screenshot`.

Every icon's covered pixels must lie in its own box and within 1/255 of the
float64 CPU reference, every other pixel must be exactly its band's canvas
colour, and each label must name the icon whose pixels sit right above it.
"""

from __future__ import annotations

import base64
import io
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from alpha_audit import load_iconset, load_theme, rasterize_icons
from alpha_audit.browser import ENGINES, Browser
from alpha_audit.color import parse_color, srgb_decode, to_8bit
from alpha_audit.model import Icon, IconSet
from alpha_audit.preview.compose import composite_drawings, solid_drawing
from alpha_audit.preview.figures import solid_rows
from alpha_audit.preview.html import preview_html

ROOT = Path(__file__).resolve().parents[2]
TOLERANCE = 1  # 8-bit code, i.e. 1/255 per channel (paper, Section 4.4)
# A common laptop width; at this width both sets below are taller than llvmpipe's 16384 px
# and SwiftShader's 8192 px drawing-buffer limit, so the page must tile them.
VIEWPORT = (1024, 768)

COLLECT = """
(async () => {
  const stage = document.getElementById("stage");
  const frame = () => new Promise((r) => requestAnimationFrame(() => setTimeout(r, 0)));
  for (let i = 0; stage.dataset.pending !== "0" || !stage.dataset.generation; i++) {
    if (i > 600) throw new Error("the page did not settle");
    await frame();
  }
  await frame();
  const generation = stage.dataset.generation;
  const box = (el) => {
    const s = stage.getBoundingClientRect(), r = el.getBoundingClientRect();
    return { x: r.left - s.left, y: r.top - s.top, w: r.width, h: r.height };
  };
  const out = { tiles: [], hits: {}, labels: {}, bands: [] };
  for (const tile of document.querySelectorAll("#tiles .tile")) {
    tile.scrollIntoView({ block: "center" });
    for (let i = 0; tile.dataset.generation !== generation; i++) {
      if (i > 600) throw new Error("a tile was not painted");
      await frame();
    }
    out.tiles.push({ ...box(tile), width: tile.width, height: tile.height,
      png: tile.toDataURL("image/png") });
    for (const el of document.querySelectorAll(".tile-overlay .hit")) {
      out.hits[el.dataset.band + ":" + el.dataset.icon] = box(el);
    }
    for (const el of document.querySelectorAll(".tile-overlay .cr")) {
      out.labels[el.dataset.band + ":" + el.dataset.icon] = { ...box(el),
        name: el.querySelector(".name").textContent,
        value: el.querySelector(".value").textContent };
    }
  }
  for (const el of document.querySelectorAll("#overlay .band")) {
    out.bands.push({ ...box(el), hex: el.dataset.hex, name: el.dataset.canvas });
  }
  const stageBox = box(stage);
  out.width = stageBox.w; out.height = stageBox.h;
  return out;
})()
"""

LIMITS = """
(() => {
  const gl = document.createElement("canvas").getContext("webgl2");
  const v = gl.getParameter(gl.MAX_VIEWPORT_DIMS);
  return { w: Math.min(v[0], gl.getParameter(gl.MAX_TEXTURE_SIZE),
                       gl.getParameter(gl.MAX_RENDERBUFFER_SIZE)),
           h: Math.min(v[1], gl.getParameter(gl.MAX_TEXTURE_SIZE),
                       gl.getParameter(gl.MAX_RENDERBUFFER_SIZE)) };
})()
"""


def _decode_png(data: bytes) -> np.ndarray:
    with Image.open(io.BytesIO(data)) as image:
        return np.asarray(image.convert("RGB"))


def _decode_data_url(data_url: str) -> np.ndarray:
    return _decode_png(base64.b64decode(data_url.split(",", 1)[1]))


def _hex_codes(hex_color: str) -> np.ndarray:
    return np.array([int(hex_color[i : i + 2], 16) for i in (1, 3, 5)], dtype=np.uint8)


def _canvas_hex(linear) -> str:
    return "#" + "".join(f"{int(v):02x}" for v in to_8bit(linear))


def _open_page(browser: Browser, page: Path) -> dict:
    """Open the page at the test viewport; wait for it to start; the GPU's tile limits."""
    browser.set_viewport(*VIEWPORT)
    browser.open(page.as_uri())
    browser.wait_for("Boolean(window.alphaAuditPreview)")
    ready = browser.evaluate("alphaAuditPreview.ready || alphaAuditPreview.error")
    assert ready is True, f"{browser.LABEL}: the page failed: {ready}"
    limits = browser.evaluate(LIMITS)
    assert isinstance(limits, dict)
    return limits


def _view(browser: Browser, limits: dict) -> dict:
    """Everything on screen: the stage's pixels assembled from its tiles, boxes and labels."""
    view = browser.evaluate(COLLECT)
    assert isinstance(view, dict)
    height, width = round(view["height"]), round(view["width"])
    image = np.zeros((height, width, 3), dtype=np.uint8)
    filled = np.zeros((height, width), dtype=bool)
    for tile in view["tiles"]:
        assert tile["width"] <= limits["w"] and tile["height"] <= limits["h"]
        pixels = _decode_data_url(tile["png"])
        y, x = round(tile["y"]), round(tile["x"])
        assert pixels.shape == (tile["height"], tile["width"], 3)
        image[y : y + pixels.shape[0], x : x + pixels.shape[1]] = pixels
        filled[y : y + pixels.shape[0], x : x + pixels.shape[1]] = True
    assert filled.all(), "part of the stage is in no tile"
    view["image"] = image
    return view


def _reference(iconset, stacks, size, linear, alpha, only=None):
    """The CPU reference (float64, rounded half to even) of each icon drawn as one mask."""
    keep = range(len(iconset.icons)) if only is None else [only]
    drawings = [solid_drawing(iconset.icons[k], {size: stacks[size][k]}) for k in keep]
    return composite_drawings(drawings, size, np.array(linear), alpha)


def _check_view(view, iconset, stacks, size, canvases, alpha):
    """Every icon in its own box, exactly the CPU reference; gutters flat; labels name icons."""
    image = view["image"]
    n = len(iconset.icons)
    assert [b["hex"] for b in view["bands"]] == [c[1] for c in canvases]
    assert set(view["hits"]) == {f"{b}:{k}" for b in range(len(canvases)) for k in range(n)}
    expected = np.array(image)  # what the stage must look like, built from the CPU reference
    for b, (linear, hex_color) in enumerate(canvases):
        band = view["bands"][b]
        y0, y1 = round(band["y"]), round(band["y"] + band["h"])
        expected[y0:y1] = _hex_codes(hex_color)
        cpu = _reference(iconset, stacks, size, linear, alpha)
        for k in range(n):
            hit = view["hits"][f"{b}:{k}"]
            x, y = round(hit["x"]), round(hit["y"])
            assert (round(hit["w"]), round(hit["h"])) == (size, size)
            assert y0 <= y and y + size <= y1, "an icon box outside its band"
            expected[y : y + size, x : x + size] = cpu[k]
    error = (np.maximum(image, expected) - np.minimum(image, expected)).max(axis=-1)
    covered = np.zeros(error.shape, dtype=bool)
    for key, hit in view["hits"].items():
        k = int(key.split(":")[1])
        x, y = round(hit["x"]), round(hit["y"])
        covered[y : y + size, x : x + size] |= stacks[size][k] > 0
    assert int(error[covered].max()) <= TOLERANCE
    assert int(error[~covered].max()) == 0, "a pixel outside every icon's coverage differs"
    # Each label names the icon whose pixels sit right above it (read from the pixels).
    by_name = {icon.name: k for k, icon in enumerate(iconset.icons)}
    for key, label in view["labels"].items():
        b = int(key.split(":")[0])
        k = by_name[label["name"]]
        x = round(label["x"]) + (round(label["w"]) - size) // 2
        y = round(label["y"]) - 2 - size
        cpu = _reference(iconset, stacks, size, canvases[b][0], alpha, only=k)[0]
        block = image[y : y + size, x : x + size].astype(np.int16)
        assert np.abs(block - cpu.astype(np.int16)).max() <= TOLERANCE, (
            f"label {label['name']} is not under it"
        )
    assert len(view["labels"]) == len(view["hits"])
    return expected


# Scroll a label into view, wait until it exists and two frames have been composited, and
# give its box in viewport coordinates (what a screenshot shows).
SHOW_LABEL = """
(async () => {
  const stage = document.getElementById("stage");
  window.scrollTo(0, stage.getBoundingClientRect().top + scrollY + %(top)s - 300);
  const frame = () => new Promise((r) => requestAnimationFrame(() => setTimeout(r, 0)));
  for (let i = 0; i < 600 && !document.querySelector(%(find)s); i++) await frame();
  for (let i = 0; i < 3; i++) await frame();
  const r = document.querySelector(%(find)s).getBoundingClientRect();
  return { x: r.left, y: r.top, w: r.width, h: r.height };
})()
"""


def _check_label_is_on_top(browser: Browser, view: dict) -> None:
    """A label whose icon starts in one tile but which hangs into the next one is visible."""
    seams = [round(t["y"]) for t in view["tiles"][1:]]
    key, seam = next(
        (k, seam)
        for k, label in view["labels"].items()
        for seam in seams
        if view["hits"][k]["y"] < seam and label["y"] + label["h"] - seam >= 14  # a text line
    )
    below = max(0.0, seam - view["labels"][key]["y"])  # look only at the part in the next tile
    b, k = key.split(":")
    find = f"\".cr[data-band='{b}'][data-icon='{k}']\""
    rect = browser.evaluate(SHOW_LABEL % {"top": view["hits"][key]["y"], "find": find})
    assert isinstance(rect, dict)
    shot = _decode_png(browser.screenshot())
    assert shot.shape[:2] == (VIEWPORT[1], VIEWPORT[0])
    x0, x1 = round(rect["x"]), round(rect["x"] + rect["w"])
    y0, y1 = round(rect["y"] + below), round(rect["y"] + rect["h"])
    assert 0 <= x0 < x1 <= VIEWPORT[0] and 0 <= y0 < y1 <= VIEWPORT[1]
    pixels = shot[y0:y1, x0:x1].reshape(-1, 3)
    assert len(np.unique(pixels, axis=0)) > 2, "a label is hidden under the next tile"


# Controls, driven as a person's input drives them: set the value, fire the event.
SET_VALUE = """
(() => {
  const el = document.getElementById(%(id)s);
  el.value = %(value)s;
  el.dispatchEvent(new Event(%(event)s, { bubbles: true }));
  return el.value;
})()
"""


def _set(browser: Browser, element: str, value: str, event: str) -> None:
    """Set control ``element`` to ``value`` and dispatch ``event`` on it, as a person's input."""
    quoted = {k: f'"{v}"' for k, v in (("id", element), ("value", value), ("event", event))}
    assert browser.evaluate(SET_VALUE % quoted) == value


@pytest.fixture(scope="module")
def many_icons(tmp_path_factory: pytest.TempPathFactory, generated_svgs):
    """300 generated icons at their own 24 px, rasterised once for every engine."""
    folder = tmp_path_factory.mktemp("real-page")
    theme = load_theme(ROOT / "themes" / "paper16.yaml")
    example = load_iconset(ROOT / "examples" / "vibrant" / "iconset.yaml")
    palette = list(example.palette.values())
    files = generated_svgs(folder, 300)
    icons = tuple(Icon(f.stem, f, palette[k % len(palette)], 1.0) for k, f in enumerate(files))
    size = 24
    iconset = IconSet("many", icons, palette=example.palette, sizes=(size,))
    rendered = rasterize_icons([(i.name, i.file) for i in iconset.icons], [size, 48])
    assert not rendered.problems
    stacks = {s: np.stack([rendered.masks[(i.name, s)] for i in icons]) for s in (size, 48)}
    page = folder / "preview.html"
    page.write_text(
        preview_html(theme, iconset, solid_rows(theme, iconset, rendered.masks), sizes=[size, 48]),
        encoding="utf-8",
    )
    return theme, iconset, stacks, size, page


def test_the_real_page_tiles_labels_and_controls(engine, many_icons):
    name, installation = engine
    theme, iconset, stacks, size, page = many_icons
    all_canvases = [(c.linear, _canvas_hex(c.linear)) for c in theme.canvases]

    with ENGINES[name](installation, timeout=120) as browser:
        limits = _open_page(browser, page)
        # It opens at the set's own size (24 px), not at the page's other size.
        pressed = "document.querySelector('#sizes [aria-pressed=true]').textContent"
        assert browser.evaluate(pressed) == f"{size} px"

        # All sixteen canvases: a stage taller than any one drawing buffer.
        browser.evaluate("document.getElementById('all').click()")
        view = _view(browser, limits)
        assert view["height"] > limits["h"] and len(view["tiles"]) > 1
        before = _check_view(view, iconset, stacks, size, all_canvases, 1.0)
        _check_label_is_on_top(browser, view)

        # Moving the slider repaints exactly the icon pixels whose CPU output changes.
        _set(browser, "alpha-range", "1.4", "input")
        moved = _view(browser, limits)
        after = _check_view(moved, iconset, stacks, size, all_canvases, 1.4)
        changed_gpu = np.any(moved["image"] != view["image"], axis=-1)
        changed_cpu = np.any(after != before, axis=-1)
        wobble = np.any(moved["image"] != after, axis=-1) | np.any(view["image"] != before, axis=-1)
        assert changed_cpu.any()
        assert not np.any(changed_gpu & ~changed_cpu & ~wobble)
        assert not np.any(changed_cpu & ~changed_gpu & ~wobble)

        # Switching to one canvas shows that canvas only, at the slider's alpha.
        browser.evaluate("document.getElementById('all').click()")
        _set(browser, "canvas", "5", "change")
        single = _view(browser, limits)
        _check_view(single, iconset, stacks, size, all_canvases[5:6], 1.4)
        picker = "document.getElementById('custom').value"
        assert browser.evaluate(picker) == all_canvases[5][1]

        # The free colour picker shows the colour it is set to, and the canvas is that colour.
        _set(browser, "custom", "#123456", "input")
        custom = _view(browser, limits)
        assert browser.evaluate(picker) == "#123456"
        assert "#123456" in str(browser.evaluate("document.getElementById('custom-option').text"))
        linear = tuple(float(v) for v in srgb_decode(parse_color("#123456")))
        _check_view(custom, iconset, stacks, size, [(linear, "#123456")], 1.4)


@pytest.fixture(scope="module")
def three_thousand(tmp_path_factory: pytest.TempPathFactory):
    """3,000 synthetic icons at 48 px and their page, made once for every engine.

    Masks are random 8-bit coverage with a fully covered one-pixel frame, so any icon
    sliced, shifted or drawn into the wrong cell shows; no SVG rasterising is needed.
    """
    size, n = 48, 3000
    rng = np.random.default_rng(3000)
    theme = load_theme(ROOT / "themes" / "paper16.yaml")
    masks = {}
    icons = []
    for k in range(n):
        q = rng.integers(0, 256, (size, size)) / 255.0
        q[[0, -1], :] = 1.0
        q[:, [0, -1]] = 1.0
        name = f"i{k:04d}"
        masks[(name, size)] = q
        icons.append(Icon(name, Path(f"{name}.svg"), f"#{int(rng.integers(0, 1 << 24)):06x}", 1))
    iconset = IconSet("three-thousand", tuple(icons), sizes=(size,))
    page = tmp_path_factory.mktemp("three-thousand") / "big.html"
    page.write_text(
        preview_html(theme, iconset, solid_rows(theme, iconset, masks), sizes=[size]),
        encoding="utf-8",
    )
    stacks = {size: np.stack([masks[(i.name, size)] for i in icons])}
    return theme, iconset, stacks, size, page


def test_three_thousand_icons_at_48px_each_whole_in_its_own_cell(engine, three_thousand):
    """The issue's set size: 3,000 icons at 48 px on one canvas, every icon whole in its cell.

    It runs at full size in every engine (15 to 35 s each on two busy cores): the stage,
    over 20,000 px tall, exceeds both SwiftShader's and llvmpipe's drawing-buffer limits.
    """
    name, installation = engine
    theme, iconset, stacks, size, page = three_thousand
    canvas = theme.canvases[0]
    with ENGINES[name](installation, timeout=120) as browser:
        limits = _open_page(browser, page)
        view = _view(browser, limits)
    assert view["height"] > limits["h"]
    _check_view(view, iconset, stacks, size, [(canvas.linear, _canvas_hex(canvas.linear))], 1.0)
