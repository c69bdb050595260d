"""What ``export`` writes: every icon colour's displayed output per mode and canvas.

The numbers are ``check``'s own rows: each theme (a YAML theme or a design-token
mode) is audited with its icon sets exactly as ``check`` audits it
(:func:`~alpha_audit.pipeline.audit_pair`: the manifest's and the project's
alpha, the pipeline in force), each icon its manifest colour as a
``currentColor`` paint at opacity 1, and every exported hex is that row's
``output``.  :func:`export_table` only names and groups those rows.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass

from alpha_audit.color import Pipeline, pack_8bit
from alpha_audit.errors import InputError, UsageError
from alpha_audit.load.tokens.themes import GamutAdjustment
from alpha_audit.rows import AuditResult

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
    """One icon colour of one mode with its displayed output on each canvas.

    ``token`` is its name: the palette entry (or design token) the icons name,
    else the icon's own name (a colour written on the icon, or an icon whose alpha
    differs from the rest of its palette entry's); ``icons`` the icons drawn in it.
    """

    token: str
    source: str
    alpha: float
    outputs: tuple[str, ...]  # "#rrggbb" per canvas, in the mode's canvas order
    icons: tuple[str, ...] = ()


@dataclass(frozen=True)
class ExportMode:
    """One mode (a YAML theme, a Resolver context, Figma mode, ...) and its light/dark kind.

    ``pipeline`` is the one its colours were composited under; ``aliases`` are
    other modes with exactly these colours (audited once, written for each).
    """

    name: str
    kind: str | None
    canvases: tuple[ExportCanvas, ...]
    colors: tuple[ExportColor, ...]
    pipeline: Pipeline = "linear"
    aliases: tuple[str, ...] = ()

    @property
    def names(self) -> tuple[str, ...]:
        """The mode's own name, then its aliases: every name a page may ask for."""
        return (self.name, *self.aliases)


@dataclass(frozen=True)
class ExportTable:
    """Everything every export format needs; renderers are pure functions of it.

    ``gamut`` is the project's gamut policy (``None``: each file's own).
    """

    source: str
    gamut: str | None
    modes: tuple[ExportMode, ...]
    adjusted: tuple[GamutAdjustment, ...] = ()
    notes: tuple[str, ...] = ()  # how the token source became modes, tokens not audited


def _short_names(paths: list[str]) -> list[str]:
    """Canvas paths without their common leading groups (``color.bg.canvas`` -> ``canvas``)."""
    split = [p.split(".") for p in paths]
    common = 0
    while all(len(s) > common + 1 for s in split) and len({s[common] for s in split}) == 1:
        common += 1
    if len(paths) == 1:
        common = len(split[0]) - 1
    return [".".join(s[common:]) for s in split]


def _named_rows(result: AuditResult) -> dict[str, list[int]]:
    """``{exported name: row indices}`` of one audit's rows, in first-row order.

    A palette entry's (or design token's) icons share its name at the alpha most
    of them carry (on a tie, the alpha most icons of the set carry: the set-wide
    one, not an icon's override); an icon at another alpha, or with a colour of its
    own, is named after the icon.
    """
    everywhere = Counter(e.icon.alpha for e in result.entries)
    alphas: dict[str, Counter[float]] = {}
    for e in result.entries:
        if e.icon.color_name is not None:
            alphas.setdefault(e.icon.color_name, Counter())[e.icon.alpha] += 1

    def usual(counts: Counter[float]) -> float:
        return max(counts, key=lambda a: (counts[a], everywhere[a]))

    kept = {role: usual(counts) for role, counts in alphas.items()}
    named: dict[str, list[int]] = {}
    for p, e in enumerate(result.entries):
        role = e.icon.color_name
        name = role if role is not None and e.icon.alpha == kept[role] else e.icon.name
        named.setdefault(name, []).append(p)
    return named


def _hex(packed: int) -> str:
    return f"#{packed:06x}"


def _colors(result: AuditResult) -> list[ExportColor]:
    """The exported colours of one audit: each named group's row outputs, per canvas."""
    packed = pack_8bit(result.output_codes)  # (rows, canvases): the rows' 8-bit outputs
    out = []
    for name, rows in _named_rows(result).items():
        first = rows[0]
        e = result.entries[first]
        out.append(
            ExportColor(
                name,
                e.icon.color,
                float(result.alpha[first]),
                tuple(_hex(int(c)) for c in packed[first].tolist()),
                tuple(dict.fromkeys(result.entries[p].icon.name for p in rows)),
            )
        )
    return out


def export_table(
    results: Sequence[AuditResult],
    *,
    source: str,
    gamut: str | None = None,
    adjusted: Sequence[GamutAdjustment] = (),
    notes: Sequence[str] = (),
    aliases: Sequence[tuple[str, str]] = (),
) -> ExportTable:
    """The export of ``check``'s audits: one mode per theme, its colours from every icon set.

    ``results`` are audits of manifest colours (no SVG read, so every row is an icon's
    ``currentColor`` paint at opacity 1); ``aliases`` are ``(mode, the mode it equals)``.
    Two icon sets naming one colour differently on one theme are an error naming both,
    and so is a theme composited under two pipelines.
    """
    by_theme: dict[str, list[AuditResult]] = {}
    for r in results:
        by_theme.setdefault(r.theme.name, []).append(r)
    also: dict[str, list[str]] = {}
    for alias, same_as in aliases:
        also.setdefault(same_as, []).append(alias)
    modes = []
    for name, audits in by_theme.items():
        pipelines = sorted({r.pipeline for r in audits})
        if len(pipelines) > 1:
            raise UsageError(
                f"theme {name} is audited under pipelines {' and '.join(pipelines)} by its "
                "icon sets, and export writes one colour per theme and canvas; give one "
                "`pipeline` in the project config"
            )
        canvases = audits[0].theme.canvases  # layers flattened as the audit drew them
        shorts = _short_names([c.name for c in canvases])
        colors: dict[str, ExportColor] = {}
        owner: dict[str, str] = {}
        for r in audits:
            for color in _colors(r):
                first = colors.setdefault(color.token, color)
                same = (first.source, first.alpha, first.outputs)
                if (color.source, color.alpha, color.outputs) != same:
                    raise InputError(
                        f"colour {color.token} is {first.source} at alpha {first.alpha:g} in "
                        f"{owner[color.token]} and {color.source} at alpha {color.alpha:g} in "
                        f"{r.iconset.name} (theme {name}); export writes one colour per name, "
                        "so rename one"
                    )
                owner.setdefault(color.token, r.iconset.name)
                if first is not color:
                    icons = tuple(dict.fromkeys((*first.icons, *color.icons)))
                    colors[color.token] = ExportColor(
                        first.token, first.source, first.alpha, first.outputs, icons
                    )
        modes.append(
            ExportMode(
                name=name,
                kind=canvases[0].mode if len({c.mode for c in canvases}) == 1 else None,
                canvases=tuple(
                    ExportCanvas(c.name, s, c.color, c.linear)
                    for c, s in zip(canvases, shorts, strict=True)
                ),
                colors=tuple(colors.values()),
                pipeline=pipelines[0],
                aliases=tuple(also.get(name, ())),
            )
        )
    return ExportTable(source, gamut, tuple(modes), tuple(adjusted), tuple(notes))


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
