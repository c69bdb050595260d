"""A Tailwind v4 ``@theme`` block: the first mode's colours, other modes as overrides.

Tailwind generates utilities only for ``--color-*`` properties declared in
``@theme``; names not starting with ``color.`` are put under ``color-``.
The other modes override the same properties under ``[data-theme="<mode>"]``,
the form alpha-audit's Tailwind reader takes back.
"""

from __future__ import annotations

from alpha_audit.export.css import css_properties
from alpha_audit.export.escape import css_comment, css_string
from alpha_audit.export.table import ExportMode, ExportTable

__all__ = ["render_tailwind"]


def _props(mode: ExportMode) -> list[tuple[str, str]]:
    return css_properties(mode, prefix="color.")


def render_tailwind(table: ExportTable) -> str:
    """``@theme { --color-...: #rrggbb; }`` plus per-mode overrides (aliases included)."""
    first, *rest = table.modes
    lines = [f"/* alpha-audit export, mode {css_comment(first.name)} in @theme */", "@theme {"]
    lines.extend(f"  {p}: {v};" for p, v in _props(first))
    lines.append("}")
    if first.aliases:  # the same values, for a page that names the alias
        lines.append(", ".join(f"[data-theme={css_string(a)}]" for a in first.aliases) + " {")
        lines.extend(f"  {p}: {v};" for p, v in _props(first))
        lines.append("}")
    for mode in rest:
        lines.append(", ".join(f"[data-theme={css_string(n)}]" for n in mode.names) + " {")
        lines.extend(f"  {p}: {v};" for p, v in _props(mode))
        lines.append("}")
    return "\n".join(lines) + "\n"
