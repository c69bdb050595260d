"""The WebGL2 page against the CPU reference, in headless Chromium (paper, Section 4.4).

The test writes the real ``--html`` page, opens it in the system's Chromium,
asks the page to render the icon set through its shader for every canvas,
sizes 16/24/48 and the paper's nine configurations (plus alpha = -1), reads
the pixels back and compares every pixel with nonzero coverage against
:func:`~alpha_audit.preview.composite_masks`.  The paper reports at most
1/255 over 388,800 instances in three browsers; we require the same bound.

Chromium is driven over ``--remote-debugging-pipe`` (the DevTools protocol as
NUL-terminated JSON on fds 3 and 4) with the standard library only.  Set
``ALPHA_AUDIT_BROWSER_ICONS=/path/to/svgs`` to validate up to 300 icons of a
real set instead of the bundled ones.
"""

from __future__ import annotations

import base64
import contextlib
import fcntl
import json
import os
import select
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pytest

from alpha_audit import load_iconset, load_theme, rasterize_icons
from alpha_audit.color import parse_color, srgb_decode, to_8bit
from alpha_audit.model import Icon, IconSet
from alpha_audit.preview import Blend, composite_masks
from alpha_audit.preview.html import preview_html

ROOT = Path(__file__).resolve().parents[2]
SIZES = (16, 24, 48)
# Paper, Appendix A.2: seven coefficients, Difference and Exclusion; we add reverse scaling.
CONFIGS = [
    *((Blend.EXTENDED, a) for a in (0.6, 0.9, 1.0, 1.05, 1.1, 1.2, 1.4, -1.0)),
    (Blend.DIFFERENCE, 1.0),
    (Blend.EXCLUSION, 1.0),
]
MIN_INSTANCES = 10_000
TOLERANCE = 1  # 8-bit code, i.e. 1/255 per channel
INSTALL_HINT = (
    "no Chromium for the WebGL2 validation: install Debian's package "
    "(`sudo apt-get install -y chromium`, or `make browser` as root), "
    "or point ALPHA_AUDIT_CHROMIUM at a system Chromium/Chrome binary"
)
CHROMIUM_FLAGS = [
    "--headless",
    "--no-sandbox",  # root in CI containers cannot use the setuid sandbox
    "--disable-gpu",
    "--use-angle=swiftshader",  # WebGL2 on the CPU: no GPU on CI machines
    "--enable-unsafe-swiftshader",
    "--disable-quic",
    "--no-first-run",
    "--no-default-browser-check",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-extensions",
    "--mute-audio",
    "--remote-debugging-pipe",
]


def find_chromium() -> str | None:
    """``$ALPHA_AUDIT_CHROMIUM`` or a system Chromium/Chrome on ``PATH``."""
    configured = os.environ.get("ALPHA_AUDIT_CHROMIUM")
    if configured:
        return configured if Path(configured).is_file() else None
    for name in ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable"):
        if found := shutil.which(name):
            return found
    return None


class DevTools:
    """A minimal Chrome DevTools Protocol client over ``--remote-debugging-pipe``."""

    def __init__(self, binary: str, timeout: float = 60.0) -> None:
        self.timeout = timeout
        self.profile = tempfile.mkdtemp(prefix="alpha-audit-chromium-")
        commands_r, commands_w = os.pipe()
        replies_r, replies_w = os.pipe()
        # Move the child's ends above 3 and 4 so that placing them there cannot collide.
        child_r = fcntl.fcntl(commands_r, fcntl.F_DUPFD, 10)
        child_w = fcntl.fcntl(replies_w, fcntl.F_DUPFD, 10)
        os.close(commands_r)
        os.close(replies_w)
        trampoline = (
            "import os, sys; os.dup2(int(sys.argv[1]), 3); os.dup2(int(sys.argv[2]), 4); "
            "os.close(int(sys.argv[1])); os.close(int(sys.argv[2])); "
            "os.execv(sys.argv[3], sys.argv[3:])"
        )
        self.process = subprocess.Popen(
            [
                *(sys.executable, "-c", trampoline, str(child_r), str(child_w), binary),
                *CHROMIUM_FLAGS,
                f"--user-data-dir={self.profile}",
            ],
            pass_fds=(child_r, child_w),
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        os.close(child_r)
        os.close(child_w)
        self.writer = os.fdopen(commands_w, "wb")
        self.reader = replies_r
        self.buffer = b""
        self.next_id = 0
        self.session: str | None = None

    def _messages(self, deadline: float):
        while True:
            while b"\0" in self.buffer:
                raw, self.buffer = self.buffer.split(b"\0", 1)
                yield json.loads(raw)
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([self.reader], [], [], left)[0]:
                raise TimeoutError("Chromium did not answer in time")
            chunk = os.read(self.reader, 1 << 20)
            if not chunk:
                raise ConnectionError("Chromium closed the DevTools pipe")
            self.buffer += chunk

    def call(self, method: str, params: dict | None = None, *, session: bool = True) -> dict:
        self.next_id += 1
        message = {"id": self.next_id, "method": method, "params": params or {}}
        if session and self.session:
            message["sessionId"] = self.session
        self.writer.write(json.dumps(message).encode() + b"\0")
        self.writer.flush()
        for reply in self._messages(time.monotonic() + self.timeout):
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply["result"]
        raise AssertionError("unreachable")

    def open(self, url: str) -> None:
        target = self.call("Target.createTarget", {"url": "about:blank"}, session=False)
        attached = self.call(
            "Target.attachToTarget", {"targetId": target["targetId"], "flatten": True}
        )
        self.session = attached["sessionId"]
        self.call("Page.navigate", {"url": url})

    def evaluate(self, expression: str):
        reply = self.call(
            "Runtime.evaluate",
            {"expression": expression, "returnByValue": True, "awaitPromise": True},
        )
        if "exceptionDetails" in reply:
            raise RuntimeError(f"page error: {reply['exceptionDetails']}")
        return reply["result"].get("value")

    def close(self) -> None:
        with contextlib.suppress(OSError, TimeoutError, ConnectionError, RuntimeError):
            self.call("Browser.close", session=False)
        try:
            self.process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()
        with contextlib.suppress(OSError):
            self.writer.close()
        os.close(self.reader)
        shutil.rmtree(self.profile, ignore_errors=True)


@pytest.fixture(scope="module")
def chromium():
    binary = find_chromium()
    if binary is None:
        if os.environ.get("CI"):
            pytest.fail(INSTALL_HINT, pytrace=False)
        pytest.skip(INSTALL_HINT)
    return binary


def _generated_svgs(folder: Path, count: int) -> list[Path]:
    """Deterministic stroked and filled shapes at sub-pixel positions: many coverage levels."""
    rng = np.random.default_rng(20260913)
    files = []
    for k in range(count):
        parts = []
        for _ in range(3):
            kind = rng.integers(0, 4)
            x, y = rng.uniform(2, 22, 2).round(2)
            w = rng.choice([1.0, 1.5, 2.0, 2.5])
            if kind == 0:
                r = round(float(rng.uniform(2, 9)), 2)
                parts.append(f'<circle cx="{x}" cy="{y}" r="{r}" stroke-width="{w}"/>')
            elif kind == 1:
                pts = " ".join(f"{a:.2f},{b:.2f}" for a, b in rng.uniform(1, 23, (4, 2)))
                parts.append(f'<polyline points="{pts}" stroke-width="{w}"/>')
            elif kind == 2:
                angle = round(float(rng.uniform(0, 90)), 1)
                parts.append(
                    f'<rect x="{x - 4}" y="{y - 3}" width="8" height="6" rx="1.5" '
                    f'transform="rotate({angle} {x} {y})" fill="currentColor" stroke="none"/>'
                )
            else:
                cx, cy = rng.uniform(4, 20, 2).round(2)
                parts.append(
                    f'<path d="M{x} {y} Q{cx} {cy} {24 - x} {24 - y}" stroke-width="{w}"/>'
                )
        svg = (
            '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24" fill="none" '
            'stroke="currentColor" stroke-linecap="round" stroke-linejoin="round">'
            + "".join(parts)
            + "</svg>"
        )
        path = folder / f"shape-{k:02d}.svg"
        path.write_text(svg)
        files.append(path)
    return files


def _icon_set(folder: Path) -> IconSet:
    """The bundled Vibrant icons plus generated shapes (or a real set from the environment)."""
    example = load_iconset(ROOT / "examples" / "vibrant" / "iconset.yaml")
    palette = list(example.palette.values())
    real = os.environ.get("ALPHA_AUDIT_BROWSER_ICONS")
    files = sorted(Path(real).glob("*.svg"))[:300] if real else _generated_svgs(folder, 24)
    extra = tuple(Icon(f.stem, f, palette[k % len(palette)], 1.0) for k, f in enumerate(files))
    icons = extra if real else (*example.icons, *extra)
    return IconSet("validation", icons, palette=example.palette, sizes=SIZES)


COLLECT = """
LIMITS = """


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
  return JSON.stringify(out);
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


def _decode_png(data_url: str) -> np.ndarray:
    from io import BytesIO

    from PIL import Image

    raw = base64.b64decode(data_url.split(",", 1)[1])
    with Image.open(BytesIO(raw)) as image:
        return np.asarray(image.convert("RGB"))


def _hex_codes(hex_color: str) -> np.ndarray:
    return np.array([int(hex_color[i : i + 2], 16) for i in (1, 3, 5)], dtype=np.uint8)


def _view(devtools: DevTools, limits: dict) -> dict:
    """Everything on screen: the stage's pixels assembled from its tiles, boxes and labels."""
    view = json.loads(devtools.evaluate(COLLECT))
    height, width = round(view["height"]), round(view["width"])
    image = np.zeros((height, width, 3), dtype=np.uint8)
    filled = np.zeros((height, width), dtype=bool)
    for tile in view["tiles"]:
        assert tile["width"] <= limits["w"] and tile["height"] <= limits["h"]
        pixels = _decode_png(tile["png"])
        y, x = round(tile["y"]), round(tile["x"])
        assert pixels.shape == (tile["height"], tile["width"], 3)
        image[y : y + pixels.shape[0], x : x + pixels.shape[1]] = pixels
        filled[y : y + pixels.shape[0], x : x + pixels.shape[1]] = True
    assert filled.all(), "part of the stage is in no tile"
    view["image"] = image
    return view


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
        cpu = composite_masks(stacks[size], iconset.sources, np.array(linear), alpha)
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
        cpu = composite_masks(
            stacks[size][k : k + 1], iconset.sources[k : k + 1], np.array(canvases[b][0]), alpha
        )[0]
        block = image[y : y + size, x : x + size].astype(np.int16)
        assert np.abs(block - cpu.astype(np.int16)).max() <= TOLERANCE, (
            f"label {label['name']} is not under it"
        )
    assert len(view["labels"]) == len(view["hits"])
    return expected


def _check_label_is_on_top(devtools: DevTools, view: dict) -> None:
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
    find = f".cr[data-band='{b}'][data-icon='{k}']"
    top = view["hits"][key]["y"]
    rect = devtools.evaluate(
        "(async () => { const stage = document.getElementById('stage');"
        f" window.scrollTo(0, stage.getBoundingClientRect().top + scrollY + {top} - 300);"
        f' for (let i = 0; i < 600 && !document.querySelector("{find}"); i++)'
        " await new Promise((r) => requestAnimationFrame(() => setTimeout(r, 0)));"
        f' const r = document.querySelector("{find}").getBoundingClientRect();'
        " return {x: r.left + scrollX, y: r.top + scrollY, w: r.width, h: r.height}; })()"
    )
    time.sleep(0.3)
    shot = devtools.call(
        "Page.captureScreenshot",
        {
            "format": "png",
            "clip": {
                "x": rect["x"],
                "y": rect["y"] + below,
                "width": rect["w"],
                "height": rect["h"] - below,
                "scale": 1,
            },
        },
    )
    pixels = _decode_png("data:image/png;base64," + shot["data"]).reshape(-1, 3)
    assert len(np.unique(pixels, axis=0)) > 2, "a label is hidden under the next tile"


def test_the_real_page_tiles_labels_and_controls(chromium, tmp_path):
    theme = load_theme(ROOT / "themes" / "paper16.yaml")
    example = load_iconset(ROOT / "examples" / "vibrant" / "iconset.yaml")
    palette = list(example.palette.values())
    files = _generated_svgs(tmp_path, 300)
    icons = tuple(Icon(f.stem, f, palette[k % len(palette)], 1.0) for k, f in enumerate(files))
    size = 24
    iconset = IconSet("many", icons, palette=example.palette, sizes=(size,))
    rendered = rasterize_icons([(i.name, i.file) for i in iconset.icons], [size, 48])
    assert not rendered.problems
    stacks = {s: np.stack([rendered.masks[(i.name, s)] for i in icons]) for s in (size, 48)}
    page = tmp_path / "preview.html"
    page.write_text(
        preview_html(theme, iconset, rendered.masks, sizes=[size, 48]), encoding="utf-8"
    )
    all_canvases = [
        (c.linear, "#" + "".join(f"{int(v):02x}" for v in to_8bit(c.linear)))
        for c in theme.canvases
    ]

    devtools = DevTools(chromium, timeout=120)
    try:
        devtools.open(page.as_uri())
        devtools.call(
            "Emulation.setDeviceMetricsOverride",
            {"width": 1280, "height": 900, "deviceScaleFactor": 1, "mobile": False},
        )
        deadline = time.monotonic() + 60
        while not devtools.evaluate("Boolean(window.alphaAuditPreview)"):
            assert time.monotonic() < deadline, "the page did not start"
            time.sleep(0.05)
        assert devtools.evaluate("alphaAuditPreview.ready"), devtools.evaluate(
            "alphaAuditPreview.error"
        )
        limits = devtools.evaluate(LIMITS)
        # It opens at the set's own size (24 px), not at the page's other size.
        pressed = "document.querySelector('#sizes [aria-pressed=true]').textContent"
        assert devtools.evaluate(pressed) == f"{size} px"

        # All sixteen canvases: a stage taller than any one drawing buffer.
        devtools.evaluate("document.getElementById('all').click()")
        view = _view(devtools, limits)
        assert view["height"] > limits["h"] and len(view["tiles"]) > 1
        before = _check_view(view, iconset, stacks, size, all_canvases, 1.0)
        _check_label_is_on_top(devtools, view)

        # Moving the slider repaints exactly the icon pixels whose CPU output changes.
        devtools.evaluate(
            "(() => { const r = document.getElementById('alpha-range'); r.value = '1.4';"
            " r.dispatchEvent(new Event('input', {bubbles: true})); })()"
        )
        moved = _view(devtools, limits)
        after = _check_view(moved, iconset, stacks, size, all_canvases, 1.4)
        changed_gpu = np.any(moved["image"] != view["image"], axis=-1)
        changed_cpu = np.any(after != before, axis=-1)
        wobble = np.any(moved["image"] != after, axis=-1) | np.any(view["image"] != before, axis=-1)
        assert changed_cpu.any()
        assert not np.any(changed_gpu & ~changed_cpu & ~wobble)
        assert not np.any(changed_cpu & ~changed_gpu & ~wobble)

        # Switching to one canvas shows that canvas only, at the slider's alpha.
        devtools.evaluate("document.getElementById('all').click()")
        devtools.evaluate(
            "(() => { const s = document.getElementById('canvas'); s.value = '5';"
            " s.dispatchEvent(new Event('change', {bubbles: true})); })()"
        )
        single = _view(devtools, limits)
        _check_view(single, iconset, stacks, size, all_canvases[5:6], 1.4)
        picker = "document.getElementById('custom').value"
        assert devtools.evaluate(picker) == all_canvases[5][1]

        # The free colour picker shows the colour it is set to, and the canvas is that colour.
        devtools.evaluate(
            "(() => { const c = document.getElementById('custom'); c.value = '#123456';"
            " c.dispatchEvent(new Event('input', {bubbles: true})); })()"
        )
        custom = _view(devtools, limits)
        assert devtools.evaluate(picker) == "#123456"
        assert "#123456" in devtools.evaluate("document.getElementById('custom-option').text")
        linear = tuple(float(v) for v in srgb_decode(parse_color("#123456")))
        _check_view(custom, iconset, stacks, size, [(linear, "#123456")], 1.4)
    finally:
        devtools.close()


def test_three_thousand_icons_at_48px_each_whole_in_its_own_cell(chromium, tmp_path):
    """The issue's set size: 3,000 icons at 48 px on one canvas, every icon whole in its cell.

    Masks are synthetic (no SVG rasterising needed for the page): random 8-bit coverage with a
    fully covered one-pixel frame, so any icon sliced, shifted or drawn into the wrong cell
    shows.
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
    page = tmp_path / "big.html"
    page.write_text(preview_html(theme, iconset, masks, sizes=[size]), encoding="utf-8")
    stacks = {size: np.stack([masks[(i.name, size)] for i in icons])}
    canvas = theme.canvases[0]
    hex_color = "#" + "".join(f"{int(v):02x}" for v in to_8bit(canvas.linear))
    devtools = DevTools(chromium, timeout=120)
    try:
        devtools.open(page.as_uri())
        devtools.call(
            "Emulation.setDeviceMetricsOverride",
            {"width": 1280, "height": 900, "deviceScaleFactor": 1, "mobile": False},
        )
        deadline = time.monotonic() + 60
        while not devtools.evaluate("Boolean(window.alphaAuditPreview)"):
            assert time.monotonic() < deadline, "the page did not start"
            time.sleep(0.05)
        assert devtools.evaluate("alphaAuditPreview.ready")
        limits = devtools.evaluate(LIMITS)
        view = _view(devtools, limits)
        assert view["height"] > limits["h"]
        _check_view(view, iconset, stacks, size, [(canvas.linear, hex_color)], 1.0)
    finally:
        devtools.close()
