"""SVG filters that do the audit's compositing: one ``<filter>`` per canvas (and coefficient).

``feComponentTransfer`` with ``type="linear"`` computes ``slope*C + intercept``
per channel on non-premultiplied colour, then clamps to [0, 1] (Filter
Effects 1, section 15.11).  With ``slope = a`` and ``intercept = (1 - a) Cb``
it is ``clip(Cb + a (Cs - Cb))`` for one canvas colour, in the colour space
``color-interpolation-filters`` names: ``linearRGB`` (``Cb`` in linear light)
for the ``linear`` pipeline, the paper's formula with its clip; ``sRGB``
(``Cb`` encoded) for ``css``, the browser's own blend.  The icon keeps its one
source colour and the filter does the rest.  Antialiased edges are then
blended by the browser in gamma-encoded sRGB, not in linear light, and
browsers keep linearRGB filter buffers in 8 bits, so dark channels come out
up to 18/255 off (docs/export.md measures it; the CSS colours are exact).
"""

from __future__ import annotations

import numpy as np

from alpha_audit.color import srgb_encode
from alpha_audit.export.escape import xml_attr, xml_id, xml_text
from alpha_audit.export.table import ExportTable, OneOwner

__all__ = ["filter_id", "render_svg"]


def filter_id(mode: str, canvas: str, alpha: float, distinct_alphas: int) -> str:
    """The filter's id: mode and canvas, plus the coefficient when a mode has several."""
    base = xml_id(f"alpha-{mode}-{canvas}")
    return base if distinct_alphas == 1 else xml_id(f"{base}-a{alpha!r}".replace(".", "_"))


def render_svg(table: ExportTable) -> str:
    """An SVG document of ``<filter>`` definitions (no drawing, nothing executable)."""
    lines = [
        '<svg xmlns="http://www.w3.org/2000/svg" width="0" height="0" aria-hidden="true">',
        "  <defs>",
    ]
    ids = OneOwner("SVG filter id")
    for mode in table.modes:
        alphas = sorted({c.alpha for c in mode.colors})
        space = "sRGB" if mode.pipeline == "css" else "linearRGB"
        for name in mode.names:
            for canvas in mode.canvases:
                behind = canvas.linear if mode.pipeline == "linear" else srgb_encode(canvas.linear)
                for a in alphas:
                    fid = filter_id(name, canvas.short, a, len(alphas))
                    ids.claim(fid, f"mode {name} on {canvas.token} at alpha {a!r}")
                    lines.append(
                        f'    <filter id={xml_attr(fid)} color-interpolation-filters="{space}" '
                        f'x="0" y="0" width="100%" height="100%">'
                    )
                    lines.append(
                        f"      <desc>{xml_text(canvas.token)} {canvas.hex}, alpha {a!r}</desc>"
                    )
                    lines.append("      <feComponentTransfer>")
                    for channel, cb in zip("RGB", np.asarray(behind).tolist(), strict=True):
                        intercept = (1 - a) * cb
                        lines.append(
                            f'        <feFunc{channel} type="linear" slope="{a!r}" '
                            f'intercept="{intercept!r}"/>'
                        )
                    lines.append("      </feComponentTransfer>")
                    lines.append("    </filter>")
    lines += ["  </defs>", "</svg>"]
    return "\n".join(lines) + "\n"
