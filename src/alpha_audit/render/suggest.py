"""Reports for ``alpha-audit suggest``: pure functions of a :class:`SuggestResult`.

``table`` (rich, fixed width), ``json`` (schema ``alpha-audit.suggest/3``,
documented in ``docs/suggest.md``) and ``markdown`` (a pull-request comment).
Output order is stable: canvases in theme order, colours in palette order,
icons in manifest order.  A big set (more than :data:`MAX_ROWS` colours, groups
or icons) is summarised in the table and the comment: the colours and groups
with the smallest answers first, and per colour its worst icon; the JSON
document always has every answer.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from rich.console import Group, RenderableType
from rich.text import Text

from alpha_audit.render.common import (
    RenderOptions,
    dumps,
    escape_markdown,
    fitted_table,
    name_column,
    names_and,
    number_column,
    policy_limits,
    shorten_names,
    to_text,
)
from alpha_audit.results import (
    ColorSuggestion,
    GroupSuggestion,
    IconSuggestion,
    Limit,
    SafeAlpha,
    SuggestResult,
)

__all__ = [
    "MAX_ROWS",
    "SCHEMA",
    "render_json",
    "render_markdown",
    "render_table",
    "suggest_document",
]

SCHEMA = "alpha-audit.suggest/3"
_MAX_NAMES = 3  # icon names shown per cell in table and markdown; JSON has all
# Rows per section of the table and the comment before it is summarised (Lucide's
# 1,500 icons were 16,468 lines): the worst answers first, the rest in the JSON.
MAX_ROWS = 25


def _limit(limit: Limit | None) -> dict[str, Any] | None:
    if limit is None:
        return None
    return {
        "rule": limit.rule.value,
        "icons": list(limit.icons),
        "canvas": limit.canvas,
        "at": limit.at,
        "attained": limit.attained,
        # null: found exactly from events; else bracketed on this grid, bisected to 1e-9.
        "grid": limit.grid,
        # The two roles a confusion or cvd-confusion limit pulls together; else empty.
        "roles": list(limit.roles),
    }


def _safe(safe: SafeAlpha) -> dict[str, Any]:
    return {"alpha": safe.alpha, "exact": safe.exact, "limited_by": _limit(safe.limit)}


def suggest_document(result: SuggestResult) -> dict[str, Any]:
    """The JSON document (``alpha-audit.suggest/3``) as plain data."""
    policy = result.policy
    return {
        "schema": SCHEMA,
        "theme": result.theme.name,
        "iconset": result.iconset.name,
        "policy": {"rules": sorted(r.value for r in policy.rules), **policy_limits(policy)},
        "threshold": result.threshold,
        "alpha_max": result.alpha_max,
        "precision": result.precision,
        **_safe(result.overall),
        "per_canvas": [
            {"canvas": c.canvas, "alpha": c.alpha, "limited_by": _limit(c.limit)}
            for c in result.overall.per_canvas
        ],
        "per_color": [
            {"color": c.color, "source": c.source, "icons": list(c.icons), **_safe(c.safe)}
            for c in result.per_color
        ],
        "per_group": [
            {
                "colors": list(g.colors),
                "confused": list(g.confused),
                "icons": list(g.icons),
                **_safe(g.safe),
            }
            for g in result.per_group
        ],
        "per_icon": [
            {"icon": i.icon, "color": i.color, "configured": i.configured, **_safe(i.safe)}
            for i in result.per_icon
        ],
        "left_out": list(result.left_out),
    }


def _alpha(value: float | None, precision: int) -> str:
    return "none" if value is None else f"{value:.{precision}f}"


def _names(icons: tuple[str, ...]) -> str:
    return shorten_names(icons, _MAX_NAMES)


def _why(limit: Limit | None, alpha_max: float) -> str:
    if limit is None:
        return f"nothing breaks up to {alpha_max:g}"
    where = "at" if limit.attained else "just above"
    how = "" if limit.grid is None else f", bracketed on a {limit.grid:g} grid, bisected to 1e-9"
    who = names_and(limit.roles) if limit.roles else _names(limit.icons)
    return f"{limit.rule.value} on {limit.canvas} {where} {limit.at:.6f} ({who}{how})"


def _headline(result: SuggestResult) -> str:
    p = result.precision
    rules = ", ".join(sorted(r.value for r in result.policy.rules))
    alpha = result.overall.alpha
    if not result.overall.per_canvas:  # the set-wide question was not asked (--only)
        return (
            f"Largest safe alphas for {result.iconset.name} on {result.theme.name} "
            f"(policy: {rules}; the set-wide answer not asked)"
        )
    if alpha is None:
        return f"No safe alpha for {result.iconset.name} on {result.theme.name}: " + _why(
            result.overall.limit, result.alpha_max
        )
    return (
        f"Largest safe alpha for {result.iconset.name} on {result.theme.name}: "
        f"{_alpha(alpha, p)} (policy: {rules}; "
        f"{_why(result.overall.limit, result.alpha_max)})"
    )


def _worst_first(alpha: float | None) -> tuple[bool, float]:
    """Sort key: no safe alpha first, then the smallest answer."""
    return (alpha is not None, alpha if alpha is not None else 0.0)


@dataclass(frozen=True)
class _Shown:
    """What a big set's table and comment show: the worst answers, and what they leave out."""

    colors: tuple[ColorSuggestion, ...]
    groups: tuple[GroupSuggestion, ...]
    icons: tuple[IconSuggestion, ...]
    notes: tuple[str, ...]


def _summarised(result: SuggestResult) -> _Shown:
    """Every answer of a small set; of a big one, the worst per section and per colour.

    Sections of at most :data:`MAX_ROWS` rows are shown whole, in their stable
    order.  A longer one keeps its smallest answers; icons keep the worst icon
    of each colour (the colours with the smallest first).
    """
    notes: list[str] = []

    def worst(rows: tuple[Any, ...], what: str, alpha: Any) -> tuple[Any, ...]:
        if len(rows) <= MAX_ROWS:
            return rows
        kept = tuple(sorted(rows, key=lambda r: _worst_first(alpha(r)))[:MAX_ROWS])
        notes.append(f"{len(rows) - len(kept)} more {what} with larger answers: see --format json")
        return kept

    colors = worst(result.per_color, "colours", lambda c: c.safe.alpha)
    groups = worst(result.per_group, "groups of roles", lambda g: g.safe.alpha)
    icons = result.per_icon
    if len(icons) > MAX_ROWS:
        per_colour: dict[str, IconSuggestion] = {}
        for i in icons:
            best = per_colour.get(i.color)
            if best is None or _worst_first(i.safe.alpha) < _worst_first(best.safe.alpha):
                per_colour[i.color] = i
        chosen = sorted(per_colour.values(), key=lambda i: _worst_first(i.safe.alpha))
        kept = tuple(chosen[:MAX_ROWS])
        notes.append(
            f"icons: the worst of each colour shown ({len(kept)} of {len(icons)} icons in "
            f"{len(per_colour)} colours); every icon is in --format json"
        )
        icons = kept
    return _Shown(colors, groups, icons, tuple(notes))


def render_table(result: SuggestResult, options: RenderOptions) -> str:
    """Headline, then per canvas, per colour and per icon tables at ``options.width``."""
    p, a_max = result.precision, result.alpha_max
    parts: list[RenderableType] = [Text(_headline(result))]

    def table(
        title: str, first: str, rows: list[list[str]], *, with_canvas: bool = True
    ) -> RenderableType:
        """Alphas and where they break never cut (render.common.fitted_table); names wrap."""
        columns = [
            name_column(first, min_width=9),  # "■ #rrggbb" or a colour name and its hex
            number_column("alpha"),
            name_column("limited by", min_width=6),
            number_column("unsafe at"),
            *([name_column("on canvas", min_width=8)] if with_canvas else []),
            name_column("icons", min_width=6, shrink_first=True),
        ]
        return fitted_table(columns, rows, title=title, padding=(0, 0))

    def cells(limit: Limit | None, *, with_canvas: bool = True) -> list[str]:
        """Rule, where it first breaks, canvas and icons; blank when nothing breaks."""
        if limit is None:
            return [f"nothing up to {a_max:g}", "", *([""] if with_canvas else []), ""]
        at = f"{limit.at:.6f}" if limit.attained else f">{limit.at:.6f}"
        rule = f"{limit.rule.value} ({names_and(limit.roles)})" if limit.roles else limit.rule.value
        return [rule, at, *([limit.canvas] if with_canvas else []),
                _names(limit.icons)]  # fmt: skip

    canvases = table(
        "Per canvas (every icon moves together)",
        "canvas",
        [
            [c.canvas, _alpha(c.alpha, p), *cells(c.limit, with_canvas=False)]
            for c in result.overall.per_canvas
        ],
        with_canvas=False,
    )
    shown = _summarised(result)
    colors = table(
        "Per colour (the others keep their alpha)",
        "colour",
        [[f"{c.color} {c.source}", _alpha(c.safe.alpha, p), *cells(c.safe.limit)]
         for c in shown.colors],
    )  # fmt: skip
    groups = table(
        "Per group of roles that pull each other under the floor (all move)",
        "colours",
        [[names_and(g.colors), _alpha(g.safe.alpha, p), *cells(g.safe.limit)]
         for g in shown.groups],
    )  # fmt: skip
    icons = table(
        "Per icon (the others keep their alpha)",
        "icon",
        [[i.icon, _alpha(i.safe.alpha, p), *cells(i.safe.limit)] for i in shown.icons],
    )
    if result.overall.per_canvas:
        parts.append(canvases)
    parts += [t for t, rows in ((colors, shown.colors), (groups, shown.groups),
                               (icons, shown.icons)) if rows]  # fmt: skip
    parts += [Text(note) for note in shown.notes]
    if result.left_out:
        parts.append(Text(_left_out(result)))
    return to_text(Group(*parts), options)


def _left_out(result: SuggestResult) -> str:
    n = len(result.left_out)
    return (
        f"{n} icon{'s' if n != 1 else ''} could not be rendered and are left out, as check "
        f"leaves them out: {_names(result.left_out)}"
    )


def render_markdown(result: SuggestResult, options: RenderOptions) -> str:
    """A pull-request comment: headline and one Markdown table per question."""
    p, a_max = result.precision, result.alpha_max
    lines = [
        f"### alpha-audit suggest: {escape_markdown(result.iconset.name)}",
        "",
        escape_markdown(_headline(result)),
    ]

    def section(title: str, first: str, rows: list[tuple[str, float | None, Limit | None]]) -> None:
        if not rows:
            return
        lines.extend(["", f"**{title}**", "", f"| {first} | alpha | limited by |", "|---|--:|---|"])
        for name, alpha, limit in rows:
            why = escape_markdown(_why(limit, a_max))
            lines.append(f"| {escape_markdown(name)} | {_alpha(alpha, p)} | {why} |")

    section(
        "Per canvas", "canvas", [(c.canvas, c.alpha, c.limit) for c in result.overall.per_canvas]
    )
    shown = _summarised(result)
    section("Per colour", "colour", [(c.color, c.safe.alpha, c.safe.limit) for c in shown.colors])
    section(
        "Per group of roles (all move)",
        "colours",
        [(names_and(g.colors), g.safe.alpha, g.safe.limit) for g in shown.groups],
    )
    section("Per icon", "icon", [(i.icon, i.safe.alpha, i.safe.limit) for i in shown.icons])
    if shown.notes:
        lines += ["", *(escape_markdown(note) for note in shown.notes)]
    if result.left_out:
        lines += ["", escape_markdown(_left_out(result))]
    return "\n".join(lines) + "\n"


def render_json(result: SuggestResult, options: RenderOptions) -> str:
    """The ``alpha-audit.suggest/2`` document (``options`` change nothing)."""
    return dumps(suggest_document(result))
