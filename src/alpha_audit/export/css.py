"""CSS custom properties: one block per mode, plus ``light-dark()`` for light + dark."""

from __future__ import annotations

from alpha_audit.export.escape import css_comment, css_ident, css_name, css_string
from alpha_audit.export.table import ExportMode, ExportTable, OneOwner, exported_paths

__all__ = [
    "DEFAULT_SELECTOR",
    "css_properties",
    "header",
    "mode_properties",
    "mode_selector",
    "render_css",
]

DEFAULT_SELECTOR = '[data-theme="<mode>"]'


def css_properties(mode: ExportMode, prefix: str = "") -> list[tuple[str, str]]:
    """``(property, hex)`` for every colour and canvas of a mode, in stable order.

    A token path becomes a property by dots to dashes (``prefix`` first when
    the path does not start with it), so ``a.b-c`` and ``a-b.c`` would both
    be ``--a-b-c``: two paths that meet in one property are an error naming
    both, never one value silently written over the other.
    """
    out = []
    owners = OneOwner(f"CSS property (mode {mode.name})")
    for path, _color, _canvas, hex_ in exported_paths(mode):
        if prefix and not path.startswith(prefix):
            path = prefix + path
        prop = "--" + css_name(path.replace(".", "-"))
        owners.claim(prop, f"token {path}")
        out.append((prop, hex_))
    return out


def mode_properties(mode: ExportMode) -> list[tuple[str, str]]:
    """``(property, hex)`` of a mode's colours (:func:`css_properties` without a prefix)."""
    return css_properties(mode)


def _selector(template: str, mode: str) -> str:
    quoted = css_string(mode)
    if '"<mode>"' in template:
        return template.replace('"<mode>"', quoted)
    return template.replace("<mode>", css_ident(mode))


def header(table: ExportTable) -> str:
    """What a CSS export says it was made from (a comment: nothing in it is read)."""
    gamut = "" if table.gamut is None else f" (gamut: {table.gamut})"
    return f"/* alpha-audit export from {css_comment(table.source)}{gamut} */"


def mode_selector(template: str, mode: ExportMode) -> str:
    """The selector list of a mode and its aliases (each name where ``<mode>`` is)."""
    return ", ".join(_selector(template, name) for name in mode.names)


def render_css(table: ExportTable, *, selector: str = DEFAULT_SELECTOR) -> str:
    """One rule per mode under ``selector`` (``<mode>`` is replaced by the mode name and
    by each of its aliases).

    With exactly one light and one dark mode, a ``:root`` rule with
    ``light-dark(<light>, <dark>)`` values and ``color-scheme: light dark``
    follows (CSS Color 5, ``light-dark()``).
    """
    lines = [header(table)]
    for mode in table.modes:
        lines.append(f"{mode_selector(selector, mode)} {{")
        lines.extend(f"  {prop}: {value};" for prop, value in mode_properties(mode))
        lines.append("}")
    kinds = [m.kind for m in table.modes]
    if len(table.modes) == 2 and sorted(k or "" for k in kinds) == ["dark", "light"]:
        light = dict(mode_properties(table.modes[kinds.index("light")]))
        dark = dict(mode_properties(table.modes[kinds.index("dark")]))
        lines.append(":root {")
        lines.append("  color-scheme: light dark;")
        lines.extend(
            f"  {prop}: light-dark({light[prop]}, {dark[prop]});" for prop in light if prop in dark
        )
        lines.append("}")
    return "\n".join(lines) + "\n"
