"""The interactive preview page: one self-contained HTML file drawing with WebGL2.

The page evaluates the paper's expression in a fragment shader (Appendix A.2):
the coefficient is a uniform, coverage comes from a mask texture, the canvas
colour is supplied by the page, and the result is sRGB-encoded onto an opaque
canvas.  Everything is inlined (script, style, masks as base64), and a
Content-Security-Policy forbids any network access, so the file works from
disk, from an e-mail attachment or from a CI artefact.

``window.alphaAuditPreview.renderBatch`` is the hook the browser validation
test drives: it renders through the same shader and returns the pixels.
"""

from __future__ import annotations

import base64
import html
import json
import math
from collections.abc import Mapping, Sequence
from importlib import resources

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import to_8bit
from alpha_audit.errors import UsageError
from alpha_audit.model import IconSet, Theme

__all__ = [
    "ATLAS_MAX_WIDTH",
    "RENDERER_ASSET",
    "SCRIPT_ASSETS",
    "asset",
    "atlas_data",
    "mask_atlas",
    "page_script",
    "preview_data",
    "preview_html",
    "scoped_script",
]

# WebGL2 guarantees MAX_TEXTURE_SIZE >= 2048 (OpenGL ES 3.0, table 6.28);
# keeping atlases this narrow leaves height for thousands of icons.
ATLAS_MAX_WIDTH = 2048
_PLACEHOLDERS = ("__ALPHA_AUDIT_TITLE__", "__ALPHA_AUDIT_DATA__", "__ALPHA_AUDIT_SCRIPT__")

# The WebGL2 shader and its renderer (context, program, atlas textures, draw calls): the
# one copy, shipped in this page and in reproduce's runtime page, which times it.
RENDERER_ASSET = "page_shader.js"
# The page's script, in the order it runs: one function scope, one file each per concern.
SCRIPT_ASSETS = (
    "page_data.js",  # the embedded data and the page's fixed choices
    "page_colour.js",  # float64 colour maths for labels and contrast
    RENDERER_ASSET,  # the WebGL2 shader and renderer
    "page_layout.js",  # state, layout and drawing
    "page_ui.js",  # tooltip and controls
    "page_start.js",  # the validation hook and start-up
)
_PAGE_HEADING = """\
// alpha-audit preview page: the paper's compositing expression in a WebGL2 fragment shader.
// Pixel = encode(q * clip(Cb + a (Cs - Cb), 0, 1) + (1 - q) * Cb) in linear sRGB
// ("Opacity Is Not Just Opacity", Appendix A.2). No network, no external files.
"""


def mask_atlas(masks: Sequence[NDArray[np.float64]], size: int) -> tuple[int, NDArray[np.uint8]]:
    """Pack ``size x size`` coverage masks row-major into one 8-bit atlas.

    Returns ``(columns, atlas)``; icon ``k`` sits at row ``k // columns``,
    column ``k % columns``, top-down.  Cairo masks are ``k / 255`` exactly, so
    the codes round-trip without loss.
    """
    n = len(masks)
    cols = max(1, min(math.ceil(math.sqrt(n)), ATLAS_MAX_WIDTH // size))
    rows = max(1, math.ceil(n / cols))
    if rows * size > ATLAS_MAX_WIDTH * 8:
        raise UsageError(f"too many icons for one {size} px texture atlas ({n})")
    atlas = np.zeros((rows * size, cols * size), dtype=np.uint8)
    for k, mask in enumerate(masks):  # one block copy per icon
        r, c = divmod(k, cols)
        codes = np.rint(np.clip(np.asarray(mask, dtype=np.float64), 0.0, 1.0) * 255.0)
        atlas[r * size : (r + 1) * size, c * size : (c + 1) * size] = codes
    return cols, atlas


def atlas_data(masks: Sequence[NDArray[np.float64]], size: int) -> dict[str, object]:
    """One size's :func:`mask_atlas` as the page's renderer reads it (``DATA.atlases[size]``)."""
    cols, atlas = mask_atlas(masks, size)
    return {
        "columns": cols,
        "width": int(atlas.shape[1]),
        "height": int(atlas.shape[0]),
        "data": base64.b64encode(atlas.tobytes()).decode("ascii"),
    }


def _hex(linear: tuple[float, float, float]) -> str:
    """``#rrggbb`` of a linear colour: the page's own notation, whatever the input wrote."""
    return "#" + "".join(f"{int(v):02x}" for v in to_8bit(linear))


def preview_data(
    theme: Theme,
    iconset: IconSet,
    masks: Mapping[tuple[str, int], NDArray[np.float64]],
    *,
    sizes: Sequence[int],
    alpha: float | None = None,
) -> dict[str, object]:
    """Everything the page needs, as JSON-ready data (icons lacking a mask are left out)."""
    sizes = sorted({int(s) for s in sizes})
    icons = [i for i in iconset.icons if all((i.name, s) in masks for s in sizes)]
    atlases = {
        str(size): atlas_data([masks[(i.name, size)] for i in icons], size) for size in sizes
    }
    alphas = [i.alpha for i in icons]
    usual = max(sorted(set(alphas)), key=alphas.count) if alphas else 1.0  # the set's usual one
    own = [s for s in iconset.sizes if s in sizes]  # the page opens at the set's own size
    return {
        "schema": "alpha-audit.preview/1",
        "title": f"{iconset.name} on {theme.name}",
        "theme": theme.name,
        "threshold": theme.threshold,
        "alpha": float(alpha if alpha is not None else usual),
        "canvases": [
            {"name": c.name, "hex": _hex(c.linear), "mode": c.mode, "linear": list(c.linear)}
            for c in theme.canvases
        ],
        "icons": [
            {"name": i.name, "hex": _hex(i.linear), "alpha": i.alpha, "linear": list(i.linear)}
            for i in icons
        ],
        "sizes": sizes,
        "size": max(own) if own else max(sizes, default=0),
        "atlases": atlases,
    }


def asset(name: str, package: str = "alpha_audit.preview") -> str:
    """The text of a script or page asset shipped in ``package``."""
    return resources.files(package).joinpath(name).read_text(encoding="utf-8")


def scoped_script(heading: str, parts: Sequence[str]) -> str:
    """``parts`` (asset texts) joined inside one strict function scope, ``heading`` first.

    One scope, so later parts use what earlier ones declare (``Renderer``)
    and nothing leaks onto ``window`` but what a part puts there; inlined in
    a ``<script>`` element, so a closing script tag is refused.
    """
    script = heading + '"use strict";\n(() => {\n' + "".join(parts) + "})();\n"
    if "</script" in script.lower():
        raise AssertionError("an inlined script must not contain a closing script tag")
    return script


def page_script() -> str:
    """The page's script: :data:`SCRIPT_ASSETS` joined inside one strict function scope."""
    return scoped_script(_PAGE_HEADING, [asset(name) for name in SCRIPT_ASSETS])


def preview_html(
    theme: Theme,
    iconset: IconSet,
    masks: Mapping[tuple[str, int], NDArray[np.float64]],
    *,
    sizes: Sequence[int],
    alpha: float | None = None,
) -> str:
    """The complete page as text; ``alpha`` is the slider's starting value."""
    data = preview_data(theme, iconset, masks, sizes=sizes, alpha=alpha)
    # Inside <script> only "</" could end the element early; \u003c is the same JSON string.
    payload = json.dumps(data, separators=(",", ":"), allow_nan=False).replace("<", "\\u003c")
    script = page_script()
    page = asset("page.html")
    for marker in _PLACEHOLDERS:
        if marker not in page:
            raise AssertionError(f"page.html must contain {marker}")
    return (
        page.replace("__ALPHA_AUDIT_TITLE__", html.escape(str(data["title"])))
        .replace("__ALPHA_AUDIT_SCRIPT__", script)
        .replace("__ALPHA_AUDIT_DATA__", payload)
    )
