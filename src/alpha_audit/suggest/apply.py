"""Write a coefficient into an icon-set manifest, touching nothing but the alpha values.

``suggest --apply`` uses this.  The manifest is not re-serialised: the YAML is
composed only to find where each ``alpha`` value sits (top level, in an
``icons:`` entry, in ``overrides:``), and those character spans are replaced.
Comments, order, quoting, spacing and line endings everywhere else stay byte
for byte.  The edited text is parsed again and must mean the same document
with only the alpha values changed, or nothing is written; an anchored alpha
(which an alias elsewhere would follow) is refused.  The file keeps its mode,
and a symbolic link keeps pointing at the edited file (its target must lie in
the project).
"""

from __future__ import annotations

import json
import os
import re
import stat
from collections.abc import Sequence, Sized
from dataclasses import dataclass, field, replace
from enum import StrEnum
from pathlib import Path, PurePosixPath
from typing import TYPE_CHECKING, Any

import yaml

from alpha_audit.errors import InputError
from alpha_audit.load.files import read_text_capped
from alpha_audit.load.yamldoc import MAX_YAML_BYTES
from alpha_audit.output import write_bytes
from alpha_audit.rows import with_alphas

if TYPE_CHECKING:
    from alpha_audit.color import GamutPolicy
    from alpha_audit.findings import Finding
    from alpha_audit.results import Limit, SuggestResult
    from alpha_audit.suggest.engine import SafeAlphas

__all__ = [
    "ApplyPlan",
    "ApplyScope",
    "Unsafe",
    "apply_alpha",
    "apply_suggestion",
    "describe_plan",
    "edit_alphas",
    "explicit_alpha_icons",
    "format_alpha",
    "plan_apply",
    "set_alpha",
]


def format_alpha(alpha: float, precision: int) -> str:
    """A coefficient as YAML: at most ``precision`` decimals, no trailing zeros.

    >>> format_alpha(1.25, 3), format_alpha(2.0, 3), format_alpha(1.0, 0), format_alpha(20.0, 0)
    ('1.25', '2.0', '1', '20')
    """
    text = f"{alpha:.{precision}f}"
    if "." not in text:  # precision 0: "20" must not lose its zero
        return text
    text = text.rstrip("0")
    return text + "0" if text.endswith(".") else text


def _value(node: yaml.MappingNode, key: str) -> yaml.Node | None:
    k: yaml.Node
    v: yaml.Node
    for k, v in node.value:
        if isinstance(k, yaml.ScalarNode) and k.value == key:
            return v
    return None


def set_alpha(text: str, value: str, path: str | Path | None = None) -> str:
    """``text`` with every alpha value replaced by ``value`` (and a top-level one added).

    Without a top-level ``alpha:`` the icons that use the default would keep
    1.0, so one is appended at the end of the document.  The set-wide case of
    :func:`edit_alphas`: the top level and every icon the manifest gives an
    alpha of its own.

    >>> print(set_alpha("# demo\\nalpha: 1.1  # was\\noverrides:\\n  a: {alpha: 1.3}\\n", "1.25"))
    # demo
    alpha: 1.25 # was
    overrides:
      a: {alpha: 1.25}
    <BLANKLINE>
    """
    explicit = explicit_alpha_icons(text, path)
    return edit_alphas(text, top=value, icons=dict.fromkeys(sorted(explicit), value), path=path)


def apply_alpha(
    path: str | Path, alpha: float, precision: int, *, root: str | Path | None = None
) -> bool:
    """Write ``alpha`` into the manifest at ``path``; returns whether the file changed.

    The file is replaced atomically and only when its text changes, keeping
    its mode.  If ``path`` is a symbolic link, the file it points to is edited
    (the link stays) when that file lies inside ``root`` (default: the working
    directory); otherwise the edit is refused.
    """
    given, target, text = _read_manifest(path, root)
    return _write_if_changed(target, text, set_alpha(text, format_alpha(alpha, precision), given))


def _read_manifest(path: str | Path, root: str | Path | None) -> tuple[Path, Path, str]:
    """The manifest as given, the file to edit (:func:`_edit_target`) and its text (capped)."""
    given = Path(path)
    target = _edit_target(given, root)
    return (
        given,
        target,
        read_text_capped(target, MAX_YAML_BYTES, InputError, "an icon-set manifest"),
    )


def _edit_target(given: Path, root: str | Path | None) -> Path:
    """The file to edit: ``given``, or the file its link points at inside ``root``."""
    if not given.is_symlink():
        return given
    try:
        target = given.resolve(strict=True)
    except (OSError, RuntimeError) as exc:  # dangling, or a loop of links
        raise InputError("is a link that leads to no file; not editing it", path=given) from exc
    base = Path(root if root is not None else Path.cwd()).resolve()
    if not target.is_relative_to(base):
        raise InputError(
            f"is a link to {target}, outside the project {base}; not editing it", path=given
        )
    return target


def _write_if_changed(target: Path, text: str, edited: str) -> bool:
    """Replace ``target`` atomically with ``edited`` (mode kept) when it differs from ``text``."""
    if edited == text:
        return False
    mode = stat.S_IMODE(os.stat(target).st_mode)
    write_bytes(target, edited.encode("utf-8"), overwrite=True, mode=mode)
    return True


# -- per colour and per icon ---------------------------------------------------

_PLAIN_KEY = re.compile(r"[A-Za-z0-9_][A-Za-z0-9_.-]*")


class ApplyScope(StrEnum):
    """What ``suggest --apply`` writes: the set-wide value, or per colour / per icon overrides."""

    SET = "set"
    COLOUR = "colour"
    ICON = "icon"


@dataclass
class _Manifest:
    """Where the alpha values and overrides sit in a manifest's text (composed once).

    Every ``alpha`` value (top level, ``icons:`` entries, ``overrides:``) must be
    a plain scalar without an anchor, or the manifest is not edited at all.
    """

    text: str
    path: str | Path | None = None
    top: yaml.ScalarNode | None = field(init=False, default=None)
    explicit: dict[str, list[tuple[int, int]]] = field(init=False, default_factory=dict)
    overrides_key: yaml.Node | None = field(init=False, default=None)
    overrides: yaml.Node | None = field(init=False, default=None)
    entries: dict[str, yaml.Node] = field(init=False, default_factory=dict)
    palette: dict[str, yaml.Node] = field(init=False, default_factory=dict)

    def __post_init__(self) -> None:
        try:
            root = yaml.compose(self.text, Loader=yaml.SafeLoader)
            events = list(yaml.parse(self.text, Loader=yaml.SafeLoader))
        except yaml.YAMLError as exc:
            raise InputError(f"cannot edit this manifest: {exc}", path=self.path) from exc
        if not isinstance(root, yaml.MappingNode):
            raise InputError("cannot edit this manifest: not a mapping", path=self.path)
        anchored = {
            e.start_mark.index
            for e in events
            if isinstance(e, yaml.NodeEvent) and e.anchor is not None and e.start_mark is not None
        }
        top = _value(root, "alpha")
        self.top = self._checked(top, anchored) if top is not None else None
        icons = _value(root, "icons")
        if isinstance(icons, yaml.SequenceNode):
            for item in icons.value:
                span = self._alpha_span(item, anchored)
                if span is None:
                    continue
                name, file = _value(item, "name"), _value(item, "file")
                label = name.value if isinstance(name, yaml.ScalarNode) else None
                if label is None and isinstance(file, yaml.ScalarNode):
                    label = PurePosixPath(file.value.replace("\\", "/")).stem
                if label is not None:
                    self.explicit.setdefault(label, []).append(span)
        for key, node in root.value:
            if isinstance(key, yaml.ScalarNode) and key.value == "overrides":
                self.overrides_key, self.overrides = key, node
        palette, overrides = _entries(_value(root, "palette")), _entries(self.overrides)
        self.palette, self.entries = dict(palette), dict(overrides)
        for _, node in palette:
            self._alpha_span(node, anchored)
        for key_name, node in overrides:
            span = self._alpha_span(node, anchored)
            if span is not None:
                self.explicit.setdefault(key_name, []).append(span)

    def _alpha_span(self, node: yaml.Node, anchored: set[int]) -> tuple[int, int] | None:
        """Where the alpha of the mapping ``node`` sits, checked; ``None`` without one."""
        alpha = _value(node, "alpha") if isinstance(node, yaml.MappingNode) else None
        return None if alpha is None else _span(self._checked(alpha, anchored))

    def _checked(self, node: yaml.Node, anchored: set[int]) -> yaml.ScalarNode:
        """``node`` as an editable alpha value, or why not."""
        line = node.start_mark.line + 1
        if not isinstance(node, yaml.ScalarNode):
            raise InputError(
                f"cannot edit this manifest: alpha on line {line} is not a plain number",
                path=self.path,
            )
        if node.start_mark.index in anchored:
            raise InputError(
                f"cannot edit this manifest: alpha on line {line} carries an anchor that "
                "other values may follow; write the number itself there",
                path=self.path,
            )
        return node


def _entries(node: yaml.Node | None) -> list[tuple[str, yaml.Node]]:
    """A mapping's entries with a scalar key, in order; none when ``node`` is no mapping."""
    if not isinstance(node, yaml.MappingNode):
        return []
    return [(k.value, v) for k, v in node.value if isinstance(k, yaml.ScalarNode)]


def _span(node: yaml.Node) -> tuple[int, int]:
    return node.start_mark.index, node.end_mark.index


def explicit_alpha_icons(text: str, path: str | Path | None = None) -> frozenset[str]:
    """Icons whose alpha the manifest sets one by one (an ``icons:`` entry or ``overrides:``).

    >>> sorted(explicit_alpha_icons("icons:\\n  - {file: a.svg, alpha: 1}\\n  - b.svg\\n"
    ...     "overrides:\\n  c: {alpha: 1.2}\\n  d: {color: red}\\n"))
    ['a', 'c']
    """
    return frozenset(_Manifest(text, path).explicit)


def _key(name: str) -> str:
    """A mapping key as YAML: plain when safe, else a JSON (= YAML double-quoted) string."""
    plain = _PLAIN_KEY.fullmatch(name) and name.lower() not in (
        "true",
        "false",
        "null",
        "yes",
        "no",
    )
    return name if plain else json.dumps(name, ensure_ascii=False)


def _eol(text: str) -> str:
    """The file's own line ending (CRLF when most lines use it)."""
    return "\r\n" if text.count("\r\n") * 2 > text.count("\n") else "\n"


def _line_end(text: str, index: int) -> int:
    end = text.find("\n", index)
    end = len(text) if end < 0 else end
    return end - 1 if end > 0 and text[end - 1] == "\r" else end  # before a CRLF


def _content_end(node: yaml.Node) -> int:
    """Where ``node``'s own text ends.

    A block collection's end mark is the *next* token, which for a nested
    entry sits on its sibling's line (``  b: ...``): the end is that of its
    last value instead, recursively.
    """
    while (
        isinstance(node, yaml.MappingNode | yaml.SequenceNode)
        and node.value
        and not (node.flow_style)
    ):
        last = node.value[-1]
        node = last[1] if isinstance(node, yaml.MappingNode) else last
    return int(node.end_mark.index)


def _replacement(text: str, start: int, end: int, value: str) -> tuple[int, int, str]:
    """Replace ``text[start:end]`` by ``value``, keeping a following comment in its column."""
    # The value may close flow collections before the comment: `{alpha: 1.2}   # why`.
    match = re.match(r"([}\]]*)( +)#", text[end:])
    if match is None:
        return start, end, value
    closing, gap = match.group(1), match.group(2)
    spaces = len(gap) - (len(value) - (end - start))
    return start, end + len(closing) + len(gap), value + closing + " " * max(1, spaces)


def edit_alphas(
    text: str,
    *,
    top: str | None = None,
    icons: dict[str, str] | None = None,
    palette: dict[str, str] | None = None,
    path: str | Path | None = None,
) -> str:
    """``text`` with the top-level alpha, each icon's in ``icons`` and each colour's set.

    A palette colour in ``palette`` gets an alpha of its own: a plain entry
    (``red: "#cc3311"``) becomes ``red: {color: "#cc3311", alpha: 1.1}``, an
    entry written as a mapping gains or changes its ``alpha``.

    An icon whose alpha the manifest already sets (``icons:`` entry or
    ``overrides:``) has that value replaced; otherwise its ``overrides:`` entry
    gains an ``alpha`` (flow or block style, as written), or a new entry
    ``name: {alpha: ...}`` is added after the last one, at the same indent
    and with its value in the column the other entries use.  Comments, order,
    quoting and everything else stay byte for byte; a comment after a
    replaced value keeps its column.  ``None``/absent: left alone.  This is
    the only editor of manifests (:func:`set_alpha` is its set-wide case):
    the edited text is parsed again and must mean exactly the requested
    alphas, or :class:`InputError` says to edit by hand.

    >>> text = ("alpha: 1.1   # default\\noverrides:\\n"
    ...         "  alert:  {color: red}\\n  ok:     {alpha: 1}\\n")
    >>> print(edit_alphas(text, top="1.25", icons={"alert": "1.3", "new": "1.4"}), end="")
    alpha: 1.25  # default
    overrides:
      alert:  {color: red, alpha: 1.3}
      ok:     {alpha: 1}
      new:    {alpha: 1.4}
    """
    m = _Manifest(text, path)
    eol = _eol(text)
    edits: list[tuple[int, int, str]] = []
    appended: list[str] = []
    if top is not None:
        if m.top is not None:
            edits.append(_replacement(text, *_span(m.top), top))
        else:
            appended.append(f"alpha: {top}")
    for name, value in (palette or {}).items():
        node = m.palette.get(name)
        if node is None:
            raise InputError(f"cannot edit this manifest: no palette entry {name!r}", path=path)
        edits.append(_mapping_alpha(text, node, value, eol))
    new_entries: list[tuple[str, str]] = []
    for name, value in (icons or {}).items():
        if name in m.explicit:
            edits.extend(_replacement(text, s, e, value) for s, e in m.explicit[name])
            continue
        node = m.entries.get(name)
        if node is None:
            new_entries.append((name, value))
        elif isinstance(node, yaml.MappingNode) and (node.flow_style or node.value):
            edits.append(_mapping_alpha(text, node, value, eol))
        else:  # `alert:` with nothing (or ~): becomes a flow mapping
            start, end = _span(node)
            edits.append((start, end, f"{'' if text[start - 1] == ' ' else ' '}{{alpha: {value}}}"))
    if new_entries:
        _add_entries(text, m, new_entries, edits, appended, eol)
    out, pos = [], 0
    for start, end, value in sorted(edits, key=lambda e: (e[0], e[1])):
        out += [text[pos:start], value]
        pos = max(pos, end)
    out.append(text[pos:])
    edited = "".join(out)
    if appended:
        newline = "" if edited.endswith("\n") or not edited else eol
        edited += newline + eol.join(appended) + eol
    _check_edit(text, edited, top, icons or {}, palette or {}, path)
    return edited


def _mapping_alpha(text: str, node: yaml.Node, value: str, eol: str) -> tuple[int, int, str]:
    """The edit giving the entry at ``node`` (a scalar colour or a mapping) ``alpha: value``."""
    if isinstance(node, yaml.ScalarNode):
        start, end = _span(node)
        return start, end, f"{{color: {text[start:end]}, alpha: {value}}}"
    assert isinstance(node, yaml.MappingNode)
    alpha = _value(node, "alpha")
    if alpha is not None:
        return _replacement(text, *_span(alpha), value)
    if node.flow_style:
        close = node.end_mark.index - 1  # the closing brace
        return close, close, f"{', ' if node.value else ''}alpha: {value}"
    indent = node.value[0][0].start_mark.column
    at = _line_end(text, _content_end(node) - 1)
    return at, at, eol + " " * indent + f"alpha: {value}"


def _add_entries(
    text: str,
    m: _Manifest,
    entries: list[tuple[str, str]],
    edits: list[tuple[int, int, str]],
    appended: list[str],
    eol: str,
) -> None:
    """New ``overrides:`` entries, placed and aligned like the existing ones."""
    node = m.overrides
    if isinstance(node, yaml.MappingNode) and node.flow_style:
        close = node.end_mark.index - 1
        body = ", ".join(f"{_key(n)}: {{alpha: {v}}}" for n, v in entries)
        edits.append((close, close, f"{', ' if node.value else ''}{body}"))
        return
    indent, column = 2, 0
    if isinstance(node, yaml.MappingNode) and node.value:
        first_key = node.value[0][0]
        indent = first_key.start_mark.column
        # Values aligned in one column (on their key's line) keep that column.
        columns = {
            v.start_mark.column
            for k, v in node.value
            if v.start_mark.line == k.start_mark.line and not isinstance(v, yaml.ScalarNode)
        }
        column = columns.pop() if len(columns) == 1 else 0
        at = _line_end(text, _content_end(node) - 1)
    elif m.overrides_key is not None:
        assert node is not None
        start, end = _span(node)
        if end > start:  # `overrides: ~` or `null`: drop the scalar
            edits.append((start, end, ""))
        at = _line_end(text, m.overrides_key.end_mark.index)
    else:
        at = -1
    lines = []
    for name, value in entries:
        head = " " * indent + f"{_key(name)}:"
        lines.append(head + " " * max(1, column - len(head)) + f"{{alpha: {value}}}")
    if at >= 0:
        edits.append((at, at, "".join(eol + line for line in lines)))
    else:
        appended.append("overrides:")
        appended.extend(lines)


@dataclass(frozen=True)
class Unsafe:
    """Colours (or icons) ``--apply`` found no safe alpha for (left at their alpha), and what
    stops them at 1."""

    names: tuple[str, ...]
    limit: Limit | None


@dataclass(frozen=True)
class ApplyPlan:
    """What ``suggest --apply`` will write, and whether the gate passes with it.

    ``top`` is the new set-wide alpha (``None``: unchanged), ``icons`` the
    per-icon alphas, ``palette`` the palette colours' own alphas, ``kept`` the
    icons whose explicit choice is left alone and ``unsafe`` the groups with no
    safe alpha from 1, left at their alpha.  ``alphas`` is every icon's alpha as
    planned and ``failures`` the gate's failing findings with them (empty: it
    passes, and only then is the manifest written).
    """

    scope: ApplyScope
    top: float | None
    icons: dict[str, float]
    kept: tuple[str, ...] = ()
    unsafe: tuple[Unsafe, ...] = ()
    palette: dict[str, float] = field(default_factory=dict)
    failures: tuple[Finding, ...] = ()
    alphas: dict[str, float] = field(default_factory=dict)

    @property
    def passes(self) -> bool:
        """Whether the gate passes on the manifest as planned (the only one ever written)."""
        return not self.failures


def plan_apply(
    result: SuggestResult,
    scope: ApplyScope | str,
    explicit: frozenset[str],
    *,
    replace_explicit: bool = False,
) -> ApplyPlan:
    """Turn a suggestion into edits, never touching an icon in ``explicit`` unless asked.

    ``set``: the set-wide alpha; with explicit icons kept, it is recomputed
    with those icons fixed at their own alpha (so it stays safe with them).
    ``colour``: one alpha per group of colours, one group after the other, each
    with the groups before it at their new alpha, so the answers hold together
    (each alone would assume the rest unchanged).  The groups are suggest's
    groups of confused roles (:attr:`~alpha_audit.results.SuggestResult.per_group`),
    then every other colour alone; each grows into the group its joint answer
    needs (:meth:`~alpha_audit.suggest.engine.SafeAlphas.joint`: the roles it
    pulls under the floor, the colours that leave it no safe alpha), so a colour
    that cannot move alone moves with the colours that hold it.  A palette
    colour's answer is written once, as the colour's own alpha (``palette: {red:
    {color: ..., alpha: ...}}``); other alphas per icon where they differ from
    what the icon has now.  ``icon``: each icon's answer in turn, an icon with
    none moving with its colour's group.  The plan then runs the gate on the
    same rows with the planned alphas (``failures``).
    """
    scope = ApplyScope(scope)
    iconset = result.iconset
    names = [i.name for i in iconset.icons]
    kept = () if replace_explicit else tuple(n for n in names if n in explicit)
    alphas = {i.name: i.alpha for i in iconset.icons}
    original = dict(alphas)
    top: float | None = None
    unsafe: list[Unsafe] = []
    palette: dict[str, float] = {}
    if scope is ApplyScope.SET:
        top = _plan_set(result, kept, alphas, unsafe)
        wanted = {n: alphas[n] for n in names if n in explicit and n not in kept}
    else:
        if scope is ApplyScope.COLOUR:
            palette = _plan_colours(result, kept, alphas, unsafe)
        else:
            _plan_icons(result, kept, alphas, unsafe)
        p = result.precision
        by_colour = {i.name: i.color_name for i in iconset.icons}
        wanted = {
            n: alphas[n]
            for n in names
            if format_alpha(alphas[n], p) != format_alpha(original[n], p)
            # A palette colour's own alpha sets every icon that has none of its own.
            and not (by_colour[n] in palette and n not in explicit)
        }
    failures = _failures(result, alphas)
    return ApplyPlan(scope, top, wanted, kept, tuple(unsafe), palette, failures, alphas)


def _engine(result: SuggestResult, alphas: dict[str, float]) -> SafeAlphas:
    """The suggest engine on the rows with the alphas planned so far."""
    from alpha_audit.suggest.engine import SafeAlphas

    return SafeAlphas(
        with_alphas(result.audit, alphas),
        result.policy,
        alpha_max=result.alpha_max,
        precision=result.precision,
    )


def _colour_of(result: SuggestResult) -> dict[str, str]:
    return {i.name: i.color_name or i.color for i in result.iconset.icons}


def _plan_set(
    result: SuggestResult, kept: tuple[str, ...], alphas: dict[str, float], unsafe: list[Unsafe]
) -> float | None:
    """The set-wide alpha for every icon not kept (``None``: none), written into ``alphas``."""
    names = [i.name for i in result.iconset.icons]
    movable = [n for n in names if n not in kept]
    top: float | None = None
    if movable:
        safe = result.overall if len(movable) == len(names) else _engine(result, alphas)(movable)
        top = safe.alpha
        if top is None and result.alpha is not None:
            # [1, a] is not all safe with the explicit icons held (a pair of one
            # held icon and a moving one can be confused at a = 1), but the
            # set-wide answer itself may be: take it when the gate says so.
            trial = {**alphas, **dict.fromkeys(movable, result.alpha)}
            top = result.alpha if not _failures(result, trial) else None
        if top is None:
            unsafe.append(Unsafe(("the set",), safe.limit))
    for n in movable:
        alphas[n] = top if top is not None else alphas[n]
    return top


def _plan_colours(
    result: SuggestResult, kept: tuple[str, ...], alphas: dict[str, float], unsafe: list[Unsafe]
) -> dict[str, float]:
    """One alpha per group of colours in turn, written into ``alphas``; the palette's alphas."""
    iconset, colour_of = result.iconset, _colour_of(result)
    names = [i.name for i in iconset.icons]
    moved: dict[str, float] = {}
    colours = [*iconset.palette, *colour_of.values()]
    units = [g.colors for g in result.per_group] + [(c,) for c in dict.fromkeys(colours)]
    done: set[str] = set()
    for unit in units:
        seed = [c for c in unit if c not in done]
        if not seed:
            continue
        group, safe = _engine(result, alphas).joint(seed, held=kept, grow=False)
        done.update(group)
        movable = [n for n in names if colour_of[n] in group and n not in kept]
        if not movable:
            continue
        if safe.alpha is None:  # left as they are; the colours placed before stay
            unsafe.append(Unsafe(tuple(seed), safe.limit))
            continue
        alphas.update(dict.fromkeys(movable, safe.alpha))
        moved.update(dict.fromkeys(group, safe.alpha))
    return {c: a for c, a in moved.items() if c in iconset.palette}


def _plan_icons(
    result: SuggestResult, kept: tuple[str, ...], alphas: dict[str, float], unsafe: list[Unsafe]
) -> None:
    """Each icon's answer in turn, written into ``alphas``; one with none moves with its colour."""
    colour_of = _colour_of(result)
    names = [i.name for i in result.iconset.icons]
    placed: set[str] = set()
    for name in names:
        if name in kept or name in placed:
            continue
        engine = _engine(result, alphas)
        safe, movable = engine([name]), [name]
        if safe.alpha is None:  # not alone: with the colours that hold it
            group, safe = engine.joint([colour_of[name]], held=kept, grow=False)
            movable = [n for n in names if colour_of[n] in group and n not in kept]
        placed.update(movable)
        if safe.alpha is None:
            unsafe.append(Unsafe(tuple(movable), safe.limit))
            continue
        alphas.update(dict.fromkeys(movable, safe.alpha))


def _failures(result: SuggestResult, alphas: dict[str, float]) -> tuple[Finding, ...]:
    """The gate's failing findings on the same rows with these alphas (the same policy)."""
    from alpha_audit.gate import evaluate

    return tuple(evaluate([with_alphas(result.audit, alphas)], result.policy).failures)


def apply_suggestion(
    path: str | Path,
    result: SuggestResult,
    scope: ApplyScope | str,
    *,
    replace_explicit: bool = False,
    root: str | Path | None = None,
    gamut: GamutPolicy | None = None,
) -> tuple[ApplyPlan, bool]:
    """Plan (:func:`plan_apply`) and write a suggestion into the manifest at ``path``,
    only if the gate passes with what would be written.

    Returns the plan and whether the file changed.  The edited text is read back
    by the manifest loader ``check`` uses (``gamut`` as the project's) and the
    gate run on the same rows with the alphas it holds
    (:attr:`ApplyPlan.failures`); when it fails, nothing is written and the plan
    says why (:func:`describe_plan`).  The file is handled as :func:`apply_alpha`
    handles it (capped read, a link edited at its target inside ``root``, mode
    kept, atomic write), and the edit must mean exactly the planned alphas.
    """
    given, target, text = _read_manifest(path, root)
    explicit = explicit_alpha_icons(text, given)
    plan = plan_apply(result, scope, explicit, replace_explicit=replace_explicit)
    p = result.precision
    top = None if plan.top is None else format_alpha(plan.top, p)
    icons = {n: format_alpha(a, p) for n, a in plan.icons.items()}
    palette = {c: format_alpha(a, p) for c, a in plan.palette.items()}
    edited = edit_alphas(text, top=top, icons=icons, palette=palette, path=given)
    written = _read_back(edited, given, gamut)
    audited = {n: a for n, a in written.items() if n in plan.alphas}
    if audited != plan.alphas:  # what check reads is the truth (the plan's gate ran on this)
        plan = replace(plan, alphas=audited, failures=_failures(result, audited))
    if not plan.passes:
        return plan, False
    return plan, _write_if_changed(target, text, edited)


def _read_back(text: str, path: Path, gamut: GamutPolicy | None) -> dict[str, float]:
    """Each icon's alpha in manifest ``text`` (at ``path``), read as ``check`` reads it."""
    from alpha_audit.load.iconset import find_project_root, iconset_from_doc
    from alpha_audit.load.yamldoc import parse_yaml

    root = find_project_root(path.absolute().parent)
    iconset = iconset_from_doc(parse_yaml(text, path), root=root, gamut=gamut)
    return {i.name: i.alpha for i in iconset.icons}


def _icon_entry_name(item: Any) -> str | None:
    """The icon name an ``icons:`` mapping entry gives (``name:``, else the file's stem)."""
    if not isinstance(item, dict):
        return None
    name = item.get("name")
    if isinstance(name, str):
        return name
    file = item.get("file")
    return PurePosixPath(file.replace("\\", "/")).stem if isinstance(file, str) else None


def _check_edit(
    before: str,
    after: str,
    top: str | None,
    icons: dict[str, str],
    palette: dict[str, str],
    path: str | Path | None,
) -> None:
    """Refuse an edit that does not parse, or means more than the planned alpha values."""
    data = yaml.safe_load(before)
    expected = dict(data) if isinstance(data, dict) else data
    if isinstance(expected, dict):
        if top is not None:
            expected["alpha"] = float(top)
        if palette:
            colours = dict(expected.get("palette") or {})
            for colour, value in palette.items():
                entry = colours.get(colour)
                entry = dict(entry) if isinstance(entry, dict) else {"color": entry}
                colours[colour] = {**entry, "alpha": float(value)}
            expected["palette"] = colours
        entries = expected.get("icons")
        listed: set[str] = set()
        if isinstance(entries, list):
            new_entries = []
            for item in entries:
                name = _icon_entry_name(item)
                if (
                    name is not None
                    and name in icons
                    and isinstance(item, dict)
                    and "alpha" in item
                ):
                    item = dict(item, alpha=float(icons[name]))
                    listed.add(name)
                new_entries.append(item)
            expected["icons"] = new_entries
        overrides = dict(expected.get("overrides") or {})
        for name, value in icons.items():
            entry = overrides.get(name)
            if name in listed and not (isinstance(entry, dict) and "alpha" in entry):
                continue
            overrides[name] = dict(entry or {}, alpha=float(value))
        if overrides or "overrides" in expected:
            expected["overrides"] = overrides
    try:
        got = yaml.safe_load(after)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f" at line {mark.line + 1}" if mark is not None else ""
        problem = getattr(exc, "problem", None) or "a syntax error"
        raise InputError(
            "cannot edit this manifest safely: the edit would not be valid YAML "
            f"({problem}{where}); set the alphas by hand",
            path=path,
        ) from exc
    if got != expected:
        raise InputError(
            "cannot edit this manifest safely: the edit would change more than the alpha "
            "values (flow style, an indented top level or a document end marker?); "
            "set the alphas by hand",
            path=path,
        )


def describe_plan(plan: ApplyPlan, path: str | Path, changed: bool, precision: int) -> str:
    """One status line saying what ``--apply`` wrote and kept, or why it wrote nothing.

    >>> describe_plan(ApplyPlan(ApplyScope.ICON, None, {"a": 1.25}, ("b",)), "m.yaml", True, 3)
    'wrote alpha for 1 icon (a: 1.25) in m.yaml; kept the explicit alpha of 1 icon (b)'
    """
    if not plan.passes:
        return f"wrote nothing to {path}: " + "; ".join(_why_not(plan))
    parts = []
    if plan.top is not None:
        verb = "wrote" if changed else "already has"
        parts.append(f"{verb} alpha {format_alpha(plan.top, precision)} in {path}")
    if plan.palette:
        shown = ", ".join(f"{c}: {format_alpha(a, precision)}" for c, a in plan.palette.items())
        parts.append(f"wrote alpha for {_count(plan.palette, 'colour')} ({shown}) in {path}")
    if plan.icons:
        shown = ", ".join(f"{n}: {format_alpha(a, precision)}" for n, a in plan.icons.items())
        parts.append(f"wrote alpha for {_count(plan.icons, 'icon')} ({shown}) in {path}")
    if not parts:
        parts.append(f"nothing to change in {path}")
    if plan.kept:
        names = ", ".join(plan.kept)
        parts.append(f"kept the explicit alpha of {_count(plan.kept, 'icon')} ({names})")
    parts += [f"left {u}" for u in _unsafe(plan)]
    return "; ".join(parts)


def _count(items: Sized, noun: str) -> str:
    return f"{len(items)} {noun}{'s' * (len(items) != 1)}"


def _some(names: Sequence[str]) -> str:
    """The first three names, and how many more."""
    return ", ".join(names[:3]) + (f" +{len(names) - 3} more" if len(names) > 3 else "")


def _unsafe(plan: ApplyPlan) -> list[str]:
    """Each group with no safe alpha from 1, and what stops it there."""
    out = []
    for u in plan.unsafe:
        what = ", ".join(u.names) + (" at their alpha" if len(u.names) > 1 else " at its alpha")
        limit = u.limit
        if limit is None:
            out.append(what)
            continue
        who = " and ".join(limit.roles) if limit.roles else _some(limit.icons)
        out.append(
            f"{what} (no safe alpha from 1: {limit.rule.value} on {limit.canvas} at alpha "
            f"{limit.at:g}, {who})"
        )
    return out


def _why_not(plan: ApplyPlan) -> list[str]:
    """Why the plan is not written: the gate's first failure, and each group with no safe
    alpha (left at its alpha)."""
    f = plan.failures[0]
    held = f" with the explicit alpha of {', '.join(plan.kept)} kept" if plan.kept else ""
    out = [
        f"the gate would still fail{held} ({len(plan.failures)} finding(s); first "
        f"{f.rule.value} of {_some(f.icons)}: {f.message})"
    ]
    return out + [f"left {u}" for u in _unsafe(plan)]
