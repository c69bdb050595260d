"""The interactive preview page: one self-contained HTML file drawing with WebGL2.

The page draws each icon as its audit rows do, in a fragment shader: the
icon's paint groups in painter's order, each with its own coverage mask (an
8-bit texture array), colour and opacity, under the rows' pipeline (linear:
the paper's expression, Appendix A.2, mixed in linear light; css: source-over
on encoded values); the coefficient is a uniform, the canvas colour is
supplied by the page, and the result goes to an opaque 8-bit canvas.  Labels
are the rows' size contrast, from each group's ``q50``.  Everything is
inlined (script, style, masks as base64), and a Content-Security-Policy
forbids any network access, so the file works from disk, from an e-mail
attachment or from a CI artefact.

``window.alphaAuditPreview.renderBatch`` is the hook the browser validation
test drives: it renders through the same shader and returns the pixels.
"""

from __future__ import annotations

import base64
import json
import math
import re
from collections.abc import Sequence
from importlib import resources

import numpy as np
from numpy.typing import NDArray

from alpha_audit.color import to_8bit
from alpha_audit.errors import UsageError
from alpha_audit.model import IconSet, Theme
from alpha_audit.preview.figures import PreviewRows
from alpha_audit.render.common import escape_html

__all__ = [
    "ATLAS_MAX_WIDTH",
    "MAX_PAGE_MASK_BYTES",
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
# The masks a page carries (base64 in the file: 4/3 of this), over every size: a
# browser opens a page of this size in a few seconds.
MAX_PAGE_MASK_BYTES = 48 * 2**20
_PLACEHOLDERS = ("__ALPHA_AUDIT_TITLE__", "__ALPHA_AUDIT_DATA__", "__ALPHA_AUDIT_SCRIPT__")
_PLACEHOLDER = re.compile("|".join(_PLACEHOLDERS))

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
// alpha-audit preview page: each icon's paint groups composited in a WebGL2 fragment shader,
// in painter's order: P = (o q) clip(Cb + a (Cs - Cb), 0, 1) + (1 - o q) P in linear sRGB
// ("Opacity Is Not Just Opacity", Appendix A.2), or source-over on encoded values (css).
// No network, no external files.
"""


def mask_atlas(masks: Sequence[NDArray[np.uint8]], size: int) -> tuple[int, int, NDArray[np.uint8]]:
    """Pack ``size x size`` coverage codes into pages of one 8-bit texture array.

    Returns ``(columns, rows, atlas)`` with ``atlas`` of shape ``(pages, rows
    * size, columns * size)``; slot ``k`` sits on page ``k // (columns * rows)``,
    then row-major, top-down.  Pages are at most :data:`ATLAS_MAX_WIDTH`
    square, the size WebGL2 guarantees for a texture.
    """
    n = len(masks)
    per_row = max(1, ATLAS_MAX_WIDTH // size)
    cols = max(1, min(math.ceil(math.sqrt(n)), per_row))
    rows = max(1, min(math.ceil(n / cols), per_row))
    pages = max(1, math.ceil(n / (cols * rows)))
    atlas = np.zeros((pages, rows * size, cols * size), dtype=np.uint8)
    for k, mask in enumerate(masks):  # one block copy per slot
        page, rest = divmod(k, cols * rows)
        r, c = divmod(rest, cols)
        atlas[page, r * size : (r + 1) * size, c * size : (c + 1) * size] = mask
    return cols, rows, atlas


def atlas_data(masks: Sequence[NDArray[np.uint8]], size: int) -> dict[str, object]:
    """One size's :func:`mask_atlas` as the page's renderer reads it (``DATA.atlases[size]``).

    ``masks`` are 8-bit coverage codes, one slot each, in the order the icons'
    ``first`` and ``layers`` count them (an icon without ``layers`` is one slot,
    its own index).
    """
    cols, rows, atlas = mask_atlas(masks, size)
    return {
        "columns": cols,
        "rows": rows,
        "pages": int(atlas.shape[0]),
        "width": int(atlas.shape[2]),
        "height": int(atlas.shape[1]),
        "data": base64.b64encode(atlas.tobytes()).decode("ascii"),
    }


def _hex(linear: tuple[float, float, float]) -> str:
    """``#rrggbb`` of a linear colour: the page's own notation, whatever the input wrote."""
    return "#" + "".join(f"{int(v):02x}" for v in to_8bit(linear))


def _check_page_bytes(slots: int, sizes: Sequence[int]) -> None:
    """Refuse a page whose masks would pass :data:`MAX_PAGE_MASK_BYTES`, before packing."""
    total = sum(slots * s * s for s in sizes)
    if total > MAX_PAGE_MASK_BYTES:
        raise UsageError(
            f"the page would carry {total / 2**20:,.1f} MiB of coverage masks ({slots:,} paint "
            f"groups x sizes {', '.join(map(str, sizes))} px), more than the "
            f"{MAX_PAGE_MASK_BYTES // 2**20} MiB a self-contained page holds; give fewer "
            "sizes or split the icon set"
        )


def preview_data(
    theme: Theme,
    iconset: IconSet,
    drawn: PreviewRows,
    *,
    sizes: Sequence[int],
    alpha: float | None = None,
) -> dict[str, object]:
    """Everything the page needs, as JSON-ready data (icons not drawn are left out).

    Each icon carries its paint groups in painter's order (``layers``: colour,
    opacity, ``q50`` per size for the labels, ``fixed`` when hard-coded) and
    ``first``, its first slot in every size's atlas.
    """
    sizes = sorted({int(s) for s in sizes})
    drawings = drawn.drawings
    icons = [
        i
        for i in iconset.icons
        if i.name in drawings and all(s in drawings[i.name].masks for s in sizes)
    ]
    _check_page_bytes(sum(len(drawings[i.name].layers) for i in icons), sizes)
    atlases = {
        str(size): atlas_data([mask for i in icons for mask in drawings[i.name].masks[size]], size)
        for size in sizes
    }
    q50 = drawn.q50(icons, sizes)
    alphas = [i.alpha for i in icons]
    usual = max(sorted(set(alphas)), key=alphas.count) if alphas else 1.0  # the set's usual one
    own = [s for s in iconset.sizes if s in sizes]  # the page opens at the set's own size
    entries = []
    first = 0
    for i in icons:
        d = drawings[i.name]
        entries.append(
            {
                "name": i.name,
                "hex": _hex(i.linear),
                "alpha": i.alpha,
                "linear": list(i.linear),
                "first": first,
                "fixed": d.fixed,
                "layers": [
                    {
                        "paint": layer.paint,
                        "hex": _hex(layer.source),
                        "linear": list(layer.source),
                        "opacity": layer.opacity,
                        "q50": {str(s): q50[i.name][g][s] for s in sizes},
                    }
                    for g, layer in enumerate(d.layers)
                ],
            }
        )
        first += len(d.layers)
    return {
        "schema": "alpha-audit.preview/2",
        "title": f"{iconset.name} on {theme.name}",
        "theme": theme.name,
        "threshold": theme.threshold,
        "pipeline": drawn.pipeline,
        "alpha": float(alpha if alpha is not None else usual),
        "canvases": [
            {"name": c.name, "hex": _hex(c.linear), "mode": c.mode, "linear": list(c.linear)}
            for c in theme.canvases
        ],
        "icons": entries,
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
    drawn: PreviewRows,
    *,
    sizes: Sequence[int],
    alpha: float | None = None,
) -> str:
    """The complete page as text; ``alpha`` is the slider's starting value."""
    data = preview_data(theme, iconset, drawn, sizes=sizes, alpha=alpha)
    # Inside <script> only "</" could end the element early; \u003c is the same JSON string.
    payload = json.dumps(data, separators=(",", ":"), allow_nan=False).replace("<", "\\u003c")
    script = page_script()
    page = asset("page.html")
    for marker in _PLACEHOLDERS:
        if marker not in page:
            raise AssertionError(f"page.html must contain {marker}")
    filled = {
        "__ALPHA_AUDIT_TITLE__": escape_html(data["title"]),
        "__ALPHA_AUDIT_SCRIPT__": script,
        "__ALPHA_AUDIT_DATA__": payload,
    }
    # One pass: a name that reads like a placeholder stays text (chained
    # replaces put the whole script into the title of a theme so named).
    return _PLACEHOLDER.sub(lambda m: filled[m.group()], page)
