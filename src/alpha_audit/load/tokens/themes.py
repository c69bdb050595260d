"""Themes and icon colours from design tokens, as the project config selects them.

The config's ``tokens:`` table names a token file and which token paths are
canvases and which are icon colours (glob patterns, ``*`` matching any
characters including dots), which mode (light/dark) each context is, the
gamut policy, and the ``$extensions`` key holding a colour's coefficient::

    tokens:
      file: tokens/system.resolver.json
      canvases: "color.bg.*"
      colors: "color.icon.*"
      modes: {light: light, "*dark*": dark}   # mode (glob) -> light|dark
      gamut: map
      alpha-extension: com.alpha-audit
      types: {"color.*": color}               # for sources without types

``modes:`` may instead list the modes to audit (``[default, "theme-g*"]``) or
be a table of lists: ``audit`` (globs of the modes to audit), ``light`` and
``dark`` (globs of the modes of each scheme) and ``groups`` (the Tokens
Studio theme groups combined into modes, one theme of each).

A coefficient lives in ``$extensions`` because DTCG's own ``alpha`` is
limited to 0-1: ``{"com.alpha-audit": {"alpha": 1.2}}`` (or the flat key
``"com.alpha-audit.alpha": 1.2``).  Without one, the manifest or ``--alpha``
decides, as today.
"""

from __future__ import annotations

import fnmatch
import json
import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np

from alpha_audit.color.css import ParsedColor, gamut_delta_e, map_parsed
from alpha_audit.constants import GamutPolicy
from alpha_audit.errors import InputError
from alpha_audit.load.theme import MAX_CANVASES
from alpha_audit.load.tokens import load_token_modes, token_color
from alpha_audit.load.tokens.model import ModeConditions, Token, TokenModes
from alpha_audit.model import Canvas, GamutAdjustment, Mode, Theme
from alpha_audit.ranges import ALPHA

__all__ = [
    "DEFAULT_ALPHA_EXTENSION",
    "GamutAdjustment",
    "TokenColor",
    "TokenConfig",
    "TokenMode",
    "TokenThemes",
    "TranslucentToken",
    "load_token_themes",
    "token_themes",
]

DEFAULT_ALPHA_EXTENSION = "com.alpha-audit"


@dataclass(frozen=True)
class TokenConfig:
    """The ``tokens:`` table of a project config (paths absolute)."""

    file: Path
    canvases: tuple[str, ...]
    colors: tuple[str, ...] = ()
    modes: dict[str, Mode] = field(default_factory=dict)  # mode glob -> light|dark
    modifier: str | None = None
    gamut: GamutPolicy = "error"
    alpha_extension: str = DEFAULT_ALPHA_EXTENSION
    format: str = "auto"
    root: Path | None = None
    audit: tuple[str, ...] = ()  # globs of the modes to audit; () every mode
    groups: tuple[str, ...] | None = None  # Tokens Studio groups combined; None: all
    types: dict[str, str] = field(default_factory=dict)  # path glob -> type (untyped sets)

    def mode_of(self, name: str) -> Mode | None:
        """``light`` or ``dark`` as the first ``modes`` glob matching ``name`` says."""
        return next((m for g, m in self.modes.items() if fnmatch.fnmatchcase(name, g)), None)


@dataclass(frozen=True)
class TokenColor:
    """An icon colour from a token: exact sRGB, its CSS form and its coefficient."""

    token: Token
    parsed: ParsedColor
    alpha: float | None

    @property
    def css(self) -> str:
        """Exact ``color(srgb ...)``: what a palette entry or an :class:`Icon` colour takes."""
        return self.parsed.css


@dataclass(frozen=True)
class TranslucentToken:
    """A selected canvas token with its own alpha below 1: a surface over the mode's canvas.

    ``parsed.alpha`` is the token's alpha and ``parsed.encoded`` its colour;
    ``mode`` the mode it belongs to.  It is audited as a layer
    (:class:`~alpha_audit.model.Canvas` ``over``) on the mode's first opaque canvas.
    """

    token: Token
    parsed: ParsedColor
    mode: str


@dataclass(frozen=True)
class TokenMode:
    """One mode: its theme (opaque canvases from tokens), icon colours and translucent surfaces."""

    name: str
    theme: Theme
    colors: dict[str, TokenColor]
    translucent: dict[str, TranslucentToken] = field(default_factory=dict)

    def theme_palette(self) -> dict[str, str]:
        """``{token path: exact colour}`` of this mode's icon colours."""
        return {path: c.css for path, c in self.colors.items()}


@dataclass(frozen=True)
class TokenThemes:
    """Every mode of a token source, with the colours the gamut policy moved."""

    source: Path
    kind: str
    gamut: GamutPolicy
    modes: tuple[TokenMode, ...]
    adjusted: tuple[GamutAdjustment, ...] = ()
    notes: tuple[str, ...] = ()  # one line each for stderr: modes found, tokens skipped
    # Modes audited as another: a CSS state computing the same values, or a mode
    # whose selected colours equal an earlier one's (name -> the audited mode).
    aliases: dict[str, str] = field(default_factory=dict)
    # Modes not audited: no selected token set in them, or not listed in modes.audit.
    skipped: tuple[str, ...] = ()
    # For a CSS source: the browser state of every mode and alias (what a page sets).
    conditions: dict[str, ModeConditions] = field(default_factory=dict)

    @property
    def themes(self) -> tuple[Theme, ...]:
        """One :class:`Theme` per mode (named after the mode)."""
        return tuple(m.theme for m in self.modes)

    def palette(self, mode: str | None = None) -> dict[str, str]:
        """``{token path: colour}`` of one mode (default: the first), for a manifest's palette."""
        chosen = self.modes[0] if mode is None else next(m for m in self.modes if m.name == mode)
        return chosen.theme_palette()


def _matches(path: str, patterns: Sequence[str]) -> bool:
    return any(fnmatch.fnmatchcase(path, p) for p in patterns)


def _alpha(token: Token, key: str) -> float | None:
    ext = token.extensions
    raw: Any = None
    if isinstance(ext.get(key), dict):
        raw = ext[key].get("alpha")
    elif f"{key}.alpha" in ext:
        raw = ext[f"{key}.alpha"]
    elif isinstance(ext.get(key), int | float):
        raw = ext[key]
    if raw is None:
        return None
    if isinstance(raw, bool) or not isinstance(raw, int | float) or not math.isfinite(raw):
        raise InputError(
            f"$extensions {key} alpha must be a finite number, got {raw!r:.40}",
            path=token.alias_file or token.file,
            line=token.alias_line or token.line,
            key=token.path,
        )
    if not ALPHA.allows(raw):
        raise InputError(
            ALPHA.refusal(f"$extensions {key} alpha {raw}"),
            path=token.alias_file or token.file,
            line=token.alias_line or token.line,
            key=token.path,
        )
    return float(raw)


def _selection(source: TokenModes, config: TokenConfig) -> dict[str, tuple[bool, bool]]:
    """``{path: (is canvas, is icon colour)}`` of every selected path, each glob tried once."""
    out: dict[str, tuple[bool, bool]] = {}
    seen: set[str] = set()
    for tokens in source.modes.values():
        for path in tokens:
            if path in seen:
                continue
            seen.add(path)
            is_canvas, is_color = _matches(path, config.canvases), _matches(path, config.colors)
            if is_canvas or is_color:
                out[path] = (is_canvas, is_color)
    return out


def _color_key(value: Any) -> str | None:
    """``value`` as a key for parsing each colour once, or None when it is too large to be
    one (a string, or an object of scalars and one list of three): that value is parsed,
    to be refused, without first serialising thousands of JSON values per mode.
    """
    if isinstance(value, str):
        return json.dumps(value)
    if not isinstance(value, dict) or len(value) > 4:
        return None
    for item in value.values():
        if isinstance(item, dict) or (
            isinstance(item, list)
            and (len(item) > 3 or any(isinstance(i, list | dict) for i in item))
        ):
            return None
    return json.dumps(value, sort_keys=True)


def _typed(token: Token, config: TokenConfig) -> Token:
    """``token`` with the type the config's ``types`` gives an untyped token.

    A source without types (Style Dictionary output, whose ``type`` may sit in
    ``attributes`` or nowhere) is typed from the config, a glob per type, never
    guessed; an untyped token the config does not type is refused naming the key.
    """
    if token.type != "unknown" or token.value is None or token.problem is None:
        return token  # typed, or broken for another reason (an alias to nothing)
    paths = (token.path, *token.chain)
    found = next(
        (t for g, t in config.types.items() for p in paths if fnmatch.fnmatchcase(p, g)), None
    )
    if found is None:
        raise InputError(
            f"{token.problem}; or type it in the config: tokens: {{types: "
            f'{{"{token.path}": color}}}} (a glob per type)',
            path=token.file,
            line=token.line,
            key=token.path,
        )
    return replace(token, type=found, problem=None)


def _parse_all(
    source: TokenModes, config: TokenConfig
) -> tuple[dict[str, ParsedColor], list[tuple[str, str, str, Token, bool, bool]]]:
    """Every selected token's distinct value parsed once, and the selection in order.

    Modes share most colours (aliases of one palette), so each distinct value
    is converted once; under ``map`` the values are parsed as ``clip`` (cheap)
    and the ones outside sRGB are then gamut-mapped in one vectorised batch.
    A translucent value is parsed with its alpha (:func:`token_themes` decides).
    """
    parse_as: GamutPolicy = "clip" if config.gamut == "map" else config.gamut
    chosen = _selection(source, config)
    seen: dict[str, ParsedColor] = {}
    selected: list[tuple[str, str, str, Token, bool, bool]] = []
    for name, tokens in source.modes.items():
        for path, token in tokens.items():
            if path not in chosen:
                continue
            is_canvas, is_color = chosen[path]
            token = _typed(token, config)
            key = _color_key(token.value)
            if key is None or key not in seen or token.type != "color" or token.problem is not None:
                parsed = token_color(token, gamut=parse_as, allow_alpha=True)
                key = key or json.dumps(token.value, sort_keys=True)  # not reached: no colour
                seen[key] = parsed
            selected.append((name, path, key, token, is_canvas, is_color))
    if config.gamut == "map":
        seen = dict(zip(seen, map_parsed(list(seen.values())), strict=True))
    return seen, selected


def token_themes(source: TokenModes, config: TokenConfig) -> TokenThemes:
    """Build a theme and icon colours per mode from resolved tokens.

    A translucent canvas token (a surface or hover layer: alpha below 1) is a
    layer over the mode's first opaque canvas (composited in the audit's
    pipeline), kept in :attr:`TokenMode.translucent` too, and a note says so.  A
    translucent icon colour is an error (the coefficient belongs in
    ``$extensions``).  A CSS mode whose selected colours equal an earlier
    mode's is audited once, with a note.
    """
    source, not_listed = _chosen_modes(source, config)
    seen, selected = _parse_all(source, config)
    modes: list[TokenMode] = []
    adjusted: list[tuple[str, Token, ParsedColor]] = []
    notes: list[str] = list(source.notes)
    if not_listed:
        notes.append(_names_note(not_listed, "not listed in the config's modes.audit"))
    aliases = {a: m for a, m in source.aliases.items() if m in source.modes}
    by_mode: dict[str, list[tuple[str, str, Token, bool, bool]]] = {n: [] for n in source.modes}
    for name, *entry in selected:
        by_mode[name].append(tuple(entry))  # type: ignore[arg-type]  # the 4 fields after name
    chosen = {path for _, path, *_ in selected}
    for path in sorted(chosen & set(source.skipped)):
        notes.append(
            f"{path}: also set at {source.skipped[path]}, which is no colour mode; "
            "that value is not audited"
        )
    modes, unset = _audited_modes(source, by_mode, seen, config, adjusted, aliases, notes)
    if unset:
        notes.append(_names_note(unset, f"no token matching canvases {', '.join(config.canvases)}"))
    if not modes:
        raise InputError(
            f"no mode has an opaque token matching canvases {', '.join(config.canvases)} "
            f"(modes: {', '.join(list(source.modes)[:8])})",
            path=source.source,
        )
    audited = {m.name for m in modes}
    aliases = {a: aliases.get(m, m) for a, m in aliases.items() if aliases.get(m, m) in audited}
    moved = _gamut_moves(adjusted, config)
    skipped = (*not_listed, *unset, *(a for a in source.aliases if a not in aliases))
    return TokenThemes(
        source.source,
        source.kind,
        config.gamut,
        tuple(modes),
        moved,
        tuple(notes),
        aliases=aliases,
        skipped=tuple(skipped),
        conditions=dict(source.conditions),
    )


def _audited_modes(
    source: TokenModes,
    by_mode: dict[str, list[tuple[str, str, Token, bool, bool]]],
    seen: dict[str, ParsedColor],
    config: TokenConfig,
    adjusted: list[tuple[str, Token, ParsedColor]],
    aliases: dict[str, str],
    notes: list[str],
) -> tuple[list[TokenMode], list[str]]:
    """A theme and icon colours per mode, and the modes with no selected canvas.

    Layer notes and the notes on CSS modes audited once (recorded in ``aliases``)
    are added to ``notes``; gamut adjustments to ``adjusted``.
    """
    modes: list[TokenMode] = []
    unset: list[str] = []
    same_as: dict[str, list[str]] = {}
    distinct: dict[tuple[Any, ...], str] = {}
    total_canvases = 0
    for name, entries in by_mode.items():
        canvases, colors, translucent, layers = _mode_tokens(
            name, entries, seen, config, source.kind, adjusted
        )
        if not canvases:
            _no_canvas(name, layers, config, source.source)
            unset.append(name)  # the mode sets no selected canvas: nothing to audit on
            continue
        if layers:
            canvases += [replace(layer, over=canvases[0].name) for layer in layers]
            notes.append(_layers_note(name, canvases[0].name, layers, source.kind))
        signature = (
            tuple((c.name, c.color, c.mode) for c in canvases),
            tuple((p, c.parsed.encoded, c.alpha) for p, c in colors.items()),
        )
        # CSS rules name modes loosely (any class or data attribute that sets a
        # property), so a sheet's identical modes are audited once; a format
        # that names its modes (Resolver, Figma, Tokens Studio) keeps them all.
        if source.kind == "css" and signature in distinct:
            aliases[name] = distinct[signature]
            same_as.setdefault(distinct[signature], []).append(name)
            continue
        distinct[signature] = name
        total_canvases += len(canvases)
        if total_canvases > MAX_CANVASES:
            raise InputError(
                f"more than {MAX_CANVASES} canvases over {len(distinct)} modes; at most "
                f"{MAX_CANVASES} (the cap on a theme's canvases)",
                path=source.source,
            )
        theme = Theme(name, tuple(canvases), path=source.source)
        modes.append(TokenMode(name, theme, colors, translucent))
    for first, names in same_as.items():
        notes.append(_names_note(names, f"the same selected colours as mode {first}"))
    return modes, unset


def _no_canvas(name: str, layers: Sequence[Canvas], config: TokenConfig, source: Path) -> None:
    """A mode with no opaque canvas: an error when it has translucent ones (nothing says what
    they are drawn over), else nothing to audit on (the caller notes it)."""
    if layers:
        shown = ", ".join(f"{c.name} (alpha {c.opacity:.3g})" for c in layers[:2])
        raise InputError(
            f"mode {name!r}: the tokens matching canvases {', '.join(config.canvases)} "
            f"are translucent ({shown}) and nothing says what they are drawn over; "
            "add the opaque canvas below them to canvases, or leave the mode out "
            "(tokens: {modes: {audit: [...]}})",
            path=source,
        )


def _layers_note(name: str, base: str, layers: Sequence[Canvas], kind: str) -> str:
    """What a mode's translucent canvases are audited as."""
    shown = ", ".join(f"{c.name} ({c.opacity:.3g})" for c in layers[:3])
    more = f" and {len(layers) - 3} more" if len(layers) > 3 else ""
    how = " as a browser draws them" if kind == "css" else ""
    return f"mode {name}: translucent canvases {shown}{more} audited as layers over {base}{how}"


def _mode_tokens(
    name: str,
    entries: Sequence[tuple[str, str, Token, bool, bool]],
    seen: dict[str, ParsedColor],
    config: TokenConfig,
    kind: str,
    adjusted: list[tuple[str, Token, ParsedColor]],
) -> tuple[list[Canvas], dict[str, TokenColor], dict[str, TranslucentToken], list[Canvas]]:
    """One mode's opaque canvases, icon colours, translucent tokens and translucent canvas
    layers (their ``over`` set by the caller); colours moved into the gamut are added to
    ``adjusted``.  A translucent icon colour is an error."""
    canvases: list[Canvas] = []
    colors: dict[str, TokenColor] = {}
    translucent: dict[str, TranslucentToken] = {}
    layers: list[Canvas] = []
    for path, key, token, is_canvas, is_color in entries:
        parsed = seen[key]
        # The canvas this token is (a translucent one is a layer: see below).
        canvas = partial(
            Canvas,
            path,
            parsed.css,
            config.mode_of(name),
            line=token.line,
            file=token.file,
            span=token.span,
        )
        if parsed.alpha < 1.0:
            if is_color:
                raise InputError(
                    f"{parsed.text[:60]!r} is translucent (alpha {parsed.alpha:.4g}); an "
                    "icon colour is opaque and its coefficient lives in $extensions",
                    path=token.file,
                    line=token.line,
                    key=path,
                )
            translucent[path] = TranslucentToken(token, parsed, name)
            if is_canvas:  # a surface or hover layer: audited over the mode's canvas
                layers.append(
                    canvas(
                        over="",  # set below: the mode's first opaque canvas
                        opacity=parsed.alpha,
                        # A sheet's surface is painted by the browser, whatever
                        # pipeline draws the icons.
                        blend="css" if kind == "css" else None,
                    )
                )
            continue
        if parsed.adjusted:
            adjusted.append((name, token, parsed))
        if is_canvas:
            canvases.append(canvas())
        if is_color:
            colors[path] = TokenColor(token, parsed, _alpha(token, config.alpha_extension))
    return canvases, colors, translucent, layers


def _gamut_moves(
    adjusted: Sequence[tuple[str, Token, ParsedColor]], config: TokenConfig
) -> tuple[GamutAdjustment, ...]:
    """Each colour moved into the gamut, with its CIEDE2000 (one batched call)."""
    delta_e = gamut_delta_e([p for _, _, p in adjusted]) if adjusted else np.zeros(0)
    moved = tuple(
        GamutAdjustment(
            mode=name,
            token=token.path,
            text=parsed.text,
            policy=config.gamut,
            output=_hex(parsed),
            delta_e=float(de),
            file=token.file,
            line=token.line,
        )
        for (name, token, parsed), de in zip(adjusted, delta_e, strict=True)
    )
    return moved


def _names_note(names: Sequence[str], why: str) -> str:
    """One note for many modes: ``modes a, b and 3 more: why``."""
    shown = ", ".join(names[:6]) + (f" and {len(names) - 6} more" if len(names) > 6 else "")
    return f"mode {shown}: {why}" if len(names) == 1 else f"modes {shown}: {why}"


def _chosen_modes(source: TokenModes, config: TokenConfig) -> tuple[TokenModes, list[str]]:
    """``source`` with only the modes ``config.audit`` lists, and the names left out.

    A mode is listed when a glob matches its name or an alias's; a glob that
    matches nothing is an error (a typo would silently audit nothing).
    """
    if not config.audit:
        return source, []
    names = {m: [m, *(a for a, t in source.aliases.items() if t == m)] for m in source.modes}
    for glob in config.audit:
        if not any(fnmatch.fnmatchcase(n, glob) for ns in names.values() for n in ns):
            raise InputError(
                f"tokens.modes: {glob!r} matches no mode of {source.source.name}; modes: "
                f"{', '.join(list(source.modes)[:12])}",
                path=source.source,
            )
    kept = [m for m, ns in names.items() if any(_matches(n, config.audit) for n in ns)]
    left = [m for m in source.modes if m not in kept]
    modes = {m: source.modes[m] for m in kept}
    return replace(source, modes=modes, default=kept[0]), left


def _hex(parsed: ParsedColor) -> str:
    r, g, b = (int(v) for v in np.rint(parsed.array * 255))
    return f"#{r:02x}{g:02x}{b:02x}"


def load_token_themes(config: TokenConfig) -> TokenThemes:
    """Load ``config.file`` and build its themes and icon colours."""
    source = load_token_modes(
        config.file,
        root=config.root,
        modifier=config.modifier,
        format=config.format,
        groups=config.groups,
    )
    return token_themes(source, config)
