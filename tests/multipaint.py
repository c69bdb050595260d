"""A small set whose icons draw their own paints: what previews must draw as the rows do."""

from __future__ import annotations

from pathlib import Path

SVGS = {
    # A hard-coded red stroke: drawn red, never in the manifest's blue.
    "red": '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24"><path d="M4 4 L20 20'
    ' M20 4 L4 20" stroke="#ff0000" stroke-width="3" fill="none"/></svg>',
    # A black disc at opacity 0.3: seen as a light grey, contrast 1.4 on white.
    "disc": '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24"><circle cx="12" cy="12"'
    ' r="10" fill="#000000" opacity="0.3"/></svg>',
    # Two colours: a currentColor square under a fixed yellow disc (painter's order).
    "two": '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24"><rect x="2" y="2"'
    ' width="20" height="20" fill="currentColor"/><circle cx="12" cy="12" r="6"'
    ' fill="#ffcc00"/></svg>',
    # All three at once: a currentColor stroke, a red stroke and a 0.3 disc.
    "mixed": '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24"><circle cx="12"'
    ' cy="12" r="9" fill="#000000" opacity="0.3"/><path d="M3 12 H21" stroke="currentColor"'
    ' stroke-width="2"/><path d="M12 3 V21" stroke="#ff0000" stroke-width="2.5"/></svg>',
}
THEME = """name: t
canvases:
  - {name: white, color: "#ffffff"}
  - {name: dark, color: "#1e1e1e"}
"""


def write_multipaint(folder: Path, alpha: float = 1.0) -> tuple[Path, Path]:
    """Write the SVGs, a manifest (blue, ``alpha``, sizes 24 and 48) and a theme; return both."""
    lines = ["name: multipaint", "sizes: [24, 48]", "icons:"]
    for name, svg in SVGS.items():
        (folder / f"{name}.svg").write_text(svg)
        lines.append(f'  - {{name: {name}, file: {name}.svg, color: "#0969da", alpha: {alpha}}}')
    manifest = folder / "iconset.yaml"
    manifest.write_text("\n".join(lines) + "\n")
    theme = folder / "theme.yaml"
    theme.write_text(THEME)
    return theme, manifest
