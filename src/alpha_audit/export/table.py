"""What ``export`` writes: every icon colour's displayed output per mode and canvas.

The numbers are the audit's own rows: each mode's icon colours are audited on
its canvases (:func:`~alpha_audit.rows.audit`, each colour a ``currentColor``
paint, the ``linear`` pipeline whose extended coefficient only an exported
colour can ship), and every exported hex is that row's ``output``.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from alpha_audit.errors import InputError, UsageError
from alpha_audit.load.tokens.themes import GamutAdjustment, TokenThemes
from alpha_audit.model import Icon, IconSet
from alpha_audit.rows import audit

__all__ = [
    "ExportCanvas",
    "ExportColor",
    "ExportMode",
    "ExportTable",
    "OneOwner",
    "export_table",
    "exported_paths",
]


@dataclass(frozen=True)
class ExportCanvas:
    """A canvas of one mode: token path, short name for exported names, colour."""

    token: str
    short: str
    hex: str
    linear: tuple[float, float, float]


@dataclass(frozen=True)
class ExportColor:
    """One icon colour of one mode with its displayed output on each canvas."""

    token: str
    source: str
    alpha: float
    outputs: tuple[str, ...]  # "#rrggbb" per canvas, in the mode's canvas order


@dataclass(frozen=True)
class ExportMode:
    """One mode (a Resolver context, Figma mode, ...) and its light/dark kind."""

    name: str
    kind: str | None
    canvases: tuple[ExportCanvas, ...]
    colors: tuple[ExportColor, ...]


@dataclass(frozen=True)
class ExportTable:
    """Everything every export format needs; renderers are pure functions of it."""

    source: str
    gamut: str
    modes: tuple[ExportMode, ...]
    adjusted: tuple[GamutAdjustment, ...] = ()
    notes: tuple[str, ...] = ()  # how the token source became modes, tokens not audited


def _hex(codes: np.ndarray) -> str:
    r, g, b = (int(c) for c in codes)
    return f"#{r:02x}{g:02x}{b:02x}"


def _short_names(paths: list[str]) -> list[str]:
    """Canvas paths without their common leading groups (``color.bg.canvas`` -> ``canvas``)."""
    split = [p.split(".") for p in paths]
    common = 0
    while all(len(s) > common + 1 for s in split) and len({s[common] for s in split}) == 1:
        common += 1
    if len(paths) == 1:
        common = len(split[0]) - 1
    return [".".join(s[common:]) for s in split]


def export_table(
    themes: TokenThemes, *, alpha: float | None = None, default_alpha: float | None = None
) -> ExportTable:
    """Composite every icon colour on every canvas of every mode.

    ``alpha`` overrides every colour's coefficient (``--alpha``);
    ``default_alpha`` applies to colours whose token carries none.
    """
    modes = []
    for mode in themes.modes:
        icons = []
        for path, color in mode.colors.items():
            a = (
                alpha
                if alpha is not None
                else (color.alpha if color.alpha is not None else default_alpha)
            )
            if a is None:
                raise UsageError(
                    f"icon colour {path} (mode {mode.name}) has no coefficient: add "
                    f"$extensions {{com.alpha-audit: {{alpha: ...}}}} to the token, alpha: to the "
                    "project config (an icon manifest's alpha: is per icon, not per colour) "
                    "or pass `alpha`"
                )
            icons.append(Icon(path, Path(path), color.css, float(a), path))
        result = audit(mode.theme, IconSet(mode.name, tuple(icons)))
        canvases = result.theme.canvases  # layers flattened as the audit drew them
        shorts = _short_names([c.name for c in canvases])
        codes = result.output_codes  # (colours, canvases, 3): the rows' outputs
        out_colors = [
            ExportColor(
                e.icon.name,
                e.icon.color,
                float(result.alpha[p]),
                tuple(_hex(codes[p, j]) for j in range(len(canvases))),
            )
            for p, e in enumerate(result.entries)
        ]
        modes.append(
            ExportMode(
                name=mode.name,
                kind=canvases[0].mode if len({c.mode for c in canvases}) == 1 else None,
                canvases=tuple(
                    ExportCanvas(c.name, s, c.color, c.linear)
                    for c, s in zip(canvases, shorts, strict=True)
                ),
                colors=tuple(out_colors),
            )
        )
    return ExportTable(
        themes.source.name, themes.gamut, tuple(modes), themes.adjusted, themes.notes
    )


class OneOwner:
    """Output names and what each was made from: two sources meeting in one name are an error.

    Every export format turns untrusted names into its own names (properties,
    ids, file names); where two meet, one would silently overwrite the other,
    so the error names both.

    >>> ids = OneOwner("SVG filter id")
    >>> ids.claim("a_b", "mode a b")
    >>> ids.claim("a_b", "mode a_b")
    Traceback (most recent call last):
    ...
    alpha_audit.errors.InputError: mode a b and mode a_b both become the SVG filter id a_b; \
rename one so that each keeps its own
    """

    def __init__(self, what: str) -> None:
        self.what = what
        self.owners: dict[str, str] = {}

    def claim(self, name: str, owner: str) -> None:
        """Record ``name`` as made from ``owner``; another owner of it is an error."""
        first = self.owners.setdefault(name, owner)
        if first != owner:
            raise InputError(
                f"{first} and {owner} both become the {self.what} {name}; "
                "rename one so that each keeps its own"
            )


def exported_paths(mode: ExportMode) -> list[tuple[str, ExportColor, ExportCanvas, str]]:
    """``(token path, colour, canvas, hex)`` of every output of a mode, each path once.

    ``<color>.on.<canvas>`` can meet another colour's path (``a`` on ``b.on.c``
    and ``a.on.b`` on ``c``): an error naming both, never one value lost.
    """
    owners = OneOwner(f"exported token path (mode {mode.name})")
    out = []
    for color in mode.colors:
        for canvas, hex_ in zip(mode.canvases, color.outputs, strict=True):
            path = exported_path(color.token, canvas, mode)
            owners.claim(path, f"{color.token} on {canvas.token}")
            out.append((path, color, canvas, hex_))
    return out


def exported_path(color: str, canvas: ExportCanvas, mode: ExportMode) -> str:
    """Token path of a colour's output on a canvas: ``<color>`` with one canvas, else
    ``<color>.on.<canvas>``."""
    return color if len(mode.canvases) == 1 else f"{color}.on.{canvas.short}"


def property_name(path: str) -> str:
    """CSS custom property of a token path: dots to dashes (``--color-icon-ok``)."""
    return "--" + path.replace(".", "-")
