"""Theme files: named canvases (light and dark) and a contrast threshold."""

from __future__ import annotations

from pathlib import Path

from alpha_audit import ranges
from alpha_audit.bundled import bundled_theme, bundled_themes
from alpha_audit.color import NON_TEXT_THRESHOLD, GamutPolicy
from alpha_audit.errors import InputError
from alpha_audit.load.fields import (
    check_keys,
    read_color,
    read_gamut,
    read_mapping,
    read_name,
    read_number,
    read_pipeline,
)
from alpha_audit.load.paths import PathRefused, contain_argument
from alpha_audit.load.yamldoc import YamlDoc, load_yaml
from alpha_audit.model import Canvas, GamutAdjustment, Theme

__all__ = ["MAX_CANVASES", "load_bundled_themes", "load_theme", "theme_from_doc"]

MAX_CANVASES = 4096
_THEME_KEYS = ("name", "threshold", "canvases", "description", "source", "pipeline", "gamut")
_CANVAS_KEYS = ("name", "color", "mode", "over")
MAX_LAYERS = 8  # canvases stacked on one another (a surface, a hover tint ...)


def load_theme(path: str | Path, *, gamut: GamutPolicy | None = None) -> Theme:
    """Load and validate a theme YAML file.

    ``gamut`` (the project's policy: ``--gamut``, else the config's) wins over
    the file's own ``gamut:`` key; with neither, a colour outside sRGB is an
    error.

    >>> theme = load_theme("themes/paper16.yaml")  # doctest: +SKIP
    """
    try:
        contain_argument(path)  # before a byte is read
    except PathRefused as err:
        raise InputError(str(err), path=path) from err
    return theme_from_doc(load_yaml(path), gamut=gamut)


def load_bundled_themes() -> tuple[tuple[str, Theme], ...]:
    """Every bundled theme as ``(name, loaded theme)``, in name order."""
    return tuple((name, load_theme(bundled_theme(name))) for name in bundled_themes())


def read_layer_color(
    doc: YamlDoc, keys: tuple[str | int, ...], value: object, gamut: GamutPolicy
) -> tuple[str, float]:
    """A layer's colour and its own alpha (``rgb(9 105 218 / 0.08)``, ``#0969da14`` ...)."""
    from alpha_audit.color import parse_css_color
    from alpha_audit.errors import ColorSyntaxError

    if not isinstance(value, str):
        raise doc.error(keys, f"expected a colour string, got {type(value).__name__}")
    try:
        parsed = parse_css_color(value, gamut=gamut, allow_alpha=True)
    except ColorSyntaxError as exc:
        raise doc.error(keys, exc.message) from exc
    if not 0.0 < parsed.alpha <= 1.0:
        raise doc.error(keys, f"a layer's alpha must be above 0, got {parsed.alpha:g}")
    return parsed.css, parsed.alpha


def _check_layers(doc: YamlDoc, canvases: list[Canvas]) -> None:
    """Every layer is over a canvas of the theme, with no loop and at most MAX_LAYERS deep."""
    by_name = {c.name: (i, c) for i, c in enumerate(canvases)}
    for i, canvas in enumerate(canvases):
        depth, seen, at = 0, {canvas.name}, canvas
        while at.over is not None:
            keys = ("canvases", i, "over")
            if at.over not in by_name:
                raise doc.error(keys, f"{at.over!r} names no canvas of this theme")
            at = by_name[at.over][1]
            depth += 1
            if at.name in seen or depth > MAX_LAYERS:
                raise doc.error(
                    keys, f"layers over {canvas.over!r} loop or stack deeper than {MAX_LAYERS}"
                )
            seen.add(at.name)


def theme_from_doc(doc: YamlDoc, *, gamut: GamutPolicy | None = None) -> Theme:
    """Validate a parsed theme document (``gamut`` as in :func:`load_theme`)."""
    data = read_mapping(doc, (), doc.data, "a theme")
    check_keys(doc, (), data, _THEME_KEYS)
    name = read_name(doc, ("name",), data.get("name", doc.path.stem))
    own = read_gamut(doc, ("gamut",), data["gamut"]) if "gamut" in data else "error"
    policy: GamutPolicy = gamut or own
    adjusted: list[GamutAdjustment] = []
    threshold = NON_TEXT_THRESHOLD
    if "threshold" in data:
        threshold = read_number(
            doc, ("threshold",), data["threshold"], allowed=ranges.CONTRAST_RATIO
        )
    raw = data.get("canvases")
    if not isinstance(raw, list) or not raw:
        raise doc.error(
            ("canvases",),
            "expected a non-empty list of canvases "
            '({name: ..., color: "#rrggbb", mode: light|dark})',
        )
    if len(raw) > MAX_CANVASES:
        raise doc.error(("canvases",), f"{len(raw)} canvases; at most {MAX_CANVASES} are allowed")
    canvases: list[Canvas] = []
    seen: dict[str, int] = {}
    for i, item in enumerate(raw):
        keys = ("canvases", i)
        item = read_mapping(doc, keys, item, "a canvas")
        check_keys(doc, keys, item, _CANVAS_KEYS)
        if "color" not in item:
            raise doc.error(keys, 'canvas has no color; add color: "#rrggbb"')
        over = item.get("over")
        opacity = 1.0
        if over is not None:
            # A translucent layer over another canvas: its colour carries its alpha.
            over = read_name(doc, (*keys, "over"), over)
            color, opacity = read_layer_color(doc, (*keys, "color"), item["color"], policy)
        else:
            color = read_color(
                doc, (*keys, "color"), item["color"], gamut=policy, adjusted=adjusted, owner=name
            )
        cname = read_name(doc, (*keys, "name"), item.get("name", color))
        if cname in seen:
            raise doc.error(
                (*keys, "name"),
                f"duplicate canvas name {cname!r} "
                f"(also canvases[{seen[cname]}]); names must be unique",
            )
        seen[cname] = i
        mode = item.get("mode")
        if mode is not None and mode not in ("light", "dark"):
            raise doc.error((*keys, "mode"), f"{mode!r} is not a mode; use light or dark (or omit)")
        canvases.append(Canvas(cname, color, mode, line=doc.line(keys), over=over, opacity=opacity))
    _check_layers(doc, canvases)
    pipeline = read_pipeline(doc, ("pipeline",), data["pipeline"]) if "pipeline" in data else None
    return Theme(
        name,
        tuple(canvases),
        threshold,
        path=doc.path,
        pipeline=pipeline,
        adjusted=tuple(adjusted),
    )
