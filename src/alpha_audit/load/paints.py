"""The paints an SVG icon draws: colours, ``currentColor``, opacities, and what cannot be audited.

The audit used to push one manifest colour through the paper's formula; what
ships is each element's own fill and stroke.  This module reads them the way
the renderer does: the XML is parsed with defusedxml (entities and external
references refused, as cairosvg's ``unsafe=False`` parser does), and the CSS
cascade uses tinycss2 and cssselect2, the libraries cairosvg itself uses, so
a selector matches here exactly when it matches in the rendered mask.

Cascade per element, lowest first (SVG 2, section 6.6; CSS Cascade 4): the
inherited value, presentation attributes, ``<style>`` rules by specificity and
order, the ``style`` attribute, then the same two with ``!important``.
``fill``, ``stroke``, ``color``, ``fill-opacity``, ``stroke-opacity``,
``stroke-width`` and ``visibility`` inherit; ``opacity`` and ``display`` do not
(SVG 2, "Painting" and "Rendering Model").  Initial values: ``stroke: none``,
opacities 1 (SVG 2, section 13.2) and ``fill: currentColor``: SVG's own initial
fill is black, but a fill the SVG never sets is its host's (inline SVG inherits
CSS ``fill``), for which the manifest's colour stands.  ``currentColor`` takes the
element's ``color``; when the SVG never sets ``color`` that is the host page's
colour -- the manifest's -- and the paint follows the theme.

Supported: every selector cssselect2 supports (type, class, id, attribute,
descendant/child combinators, ``:not`` ...); dynamic pseudo-classes
(``:hover``) and pseudo-elements never match, as in the renderer.  Not
supported, reported as not audited: gradient and pattern paints (``url(...)``),
``context-fill``/``context-stroke``, ``<text>``, ``<image>``, ``<use>``,
``<foreignObject>``, markers and filters.  ``@media``, ``@import`` and
``var()`` are ignored, as cairosvg ignores them.

Group opacity is multiplied down the tree.  That is exact for one element;
for overlapping children of a translucent group it is the per-element
approximation (the group is composited once, so overlaps are not doubled).
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from collections.abc import Callable, Container, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal, cast

import cssselect2
import defusedxml
import defusedxml.ElementTree
import tinycss2
import tinycss2.color4

from alpha_audit.errors import SvgError

__all__ = [
    "CURRENT_COLOR",
    "MAX_DEPTH",
    "MAX_ELEMENTS",
    "MAX_ISOLATE_WORK",
    "MAX_MATCH_WORK",
    "Paint",
    "PaintGroup",
    "PaintKind",
    "SvgPaints",
    "Unaudited",
    "extract_paints",
    "isolate_each",
    "isolate_groups",
    "isolate_paints",
    "paints_and_isolates",
]

SVG_NS = "http://www.w3.org/2000/svg"
CURRENT_COLOR = "currentColor"
PaintKind = Literal["fill", "stroke"]

# Limits on the in-process parse of an untrusted file (already capped at
# MAX_SVG_BYTES by load.svg.read_svg).  Icons have tens of elements and a few
# rules; the product bounds cssselect2's matching work, the depth mirrors the
# render worker, whose recursion limit (2000 frames) stops cairosvg near 600.
MAX_ELEMENTS = 20_000
MAX_DEPTH = 500
MAX_MATCH_WORK = 2_000_000  # elements x selectors
MAX_ISOLATE_WORK = 100_000  # rendered elements x per-paint variants

_SHAPES = frozenset({"path", "rect", "circle", "ellipse", "line", "polyline", "polygon"})
_CONTAINERS = frozenset({"svg", "g", "a", "switch"})
# Never drawn where they stand (referenced, or metadata): their subtrees are skipped.
_NOT_RENDERED = frozenset(
    {
        "defs",
        "symbol",
        "clipPath",
        "mask",
        "marker",
        "pattern",
        "linearGradient",
        "radialGradient",
        "filter",
        "style",
        "title",
        "desc",
        "metadata",
        "script",
    }
)
_UNAUDITED_ELEMENTS = {
    "text": "text is drawn with the renderer's fonts; its paints are not audited",
    "image": "raster or external image; its colours are not audited",
    "use": "<use> copies another element; its paints are not audited",
    "foreignObject": "foreign content; not audited",
}
_INHERITED = ("fill", "stroke", "color", "fill-opacity", "stroke-opacity", "stroke-width")
_MARKERS = ("marker", "marker-start", "marker-mid", "marker-end")
# What a mask overrides, and which of those cairosvg inherits (it inherits every
# attribute but opacity, filter, display and a few geometric ones).
_INHERITED_MASK = frozenset(("fill", "stroke", "fill-opacity", "stroke-opacity", *_MARKERS))
_MASK_PROPERTIES = (*_INHERITED_MASK, "opacity", "filter")
_PROPERTIES = frozenset((*_INHERITED, "opacity", "display", "visibility", "filter", *_MARKERS))
_INITIAL = {
    # SVG's initial fill is black, but an icon whose SVG never sets one is painted by
    # its host (inline SVG inherits CSS `fill`: simple-icons, Material Symbols); the
    # manifest's colour stands for the host's.  A fill the SVG sets stays its own.
    "fill": "currentColor",
    "stroke": "none",
    "color": None,  # not set by the SVG: the host page's colour (the manifest's)
    "fill-opacity": "1",
    "stroke-opacity": "1",
    "stroke-width": "1",
    "visibility": "visible",
}


@dataclass(frozen=True)
class Paint:
    """One fill or stroke of one element.

    ``color`` is ``#rrggbb`` (a fixed colour: it will not follow the theme) or
    ``currentColor`` (the manifest colour).  ``opacity`` is effective: the
    product of ``opacity`` on the element and every ancestor, the
    ``fill-opacity`` or ``stroke-opacity``, and any alpha in the colour itself.
    """

    color: str
    kind: PaintKind
    opacity: float
    element: str
    line: int | None = None

    @property
    def fixed(self) -> bool:
        """Whether the colour is hard-coded rather than ``currentColor``."""
        return self.color != CURRENT_COLOR


@dataclass(frozen=True)
class Unaudited:
    """Something the SVG draws that the audit cannot judge, naming the element."""

    element: str
    line: int | None
    reason: str


@dataclass(frozen=True)
class PaintGroup:
    """Paints that draw the same colour at the same effective opacity (one audit row each)."""

    color: str
    opacity: float
    paints: tuple[Paint, ...]

    @property
    def key(self) -> tuple[str, float]:
        """``(color, opacity)``, what :func:`isolate_paints` keeps."""
        return (self.color, self.opacity)

    @property
    def fixed(self) -> bool:
        """Whether the colour is hard-coded rather than ``currentColor``."""
        return self.color != CURRENT_COLOR


@dataclass(frozen=True)
class SvgPaints:
    """Every visible paint of one SVG, in document order, and what was not audited."""

    paints: tuple[Paint, ...]
    unaudited: tuple[Unaudited, ...] = field(default=())

    def groups(self) -> tuple[PaintGroup, ...]:
        """Paints grouped by ``(color, opacity)``, in order of first appearance."""
        by_key: dict[tuple[str, float], list[Paint]] = {}
        for p in self.paints:
            by_key.setdefault((p.color, p.opacity), []).append(p)
        return tuple(PaintGroup(c, o, tuple(ps)) for (c, o), ps in by_key.items())


def extract_paints(svg: bytes, *, path: str | Path | None = None) -> SvgPaints:
    """The paints ``svg`` draws; raises :class:`SvgError` on bad XML or a limit.

    >>> svg = b'''<svg xmlns="http://www.w3.org/2000/svg" fill="none" stroke="currentColor">
    ...   <g opacity="0.5"><circle r="4" fill="#f00" fill-opacity="0.5"/></g></svg>'''
    >>> [(p.color, p.kind, p.opacity) for p in extract_paints(svg).paints]
    [('#ff0000', 'fill', 0.25), ('currentColor', 'stroke', 0.5)]
    """
    unaudited: list[Unaudited] = []
    return _paints_of(list(_walk(svg, path, unaudited)), unaudited)


def _paints_of(visited: Sequence[_Visited], unaudited: list[Unaudited]) -> SvgPaints:
    """The visible paints of walked elements, in document order."""
    paints = [p for element in visited for p in element.paints if p.opacity > 0.0]
    return SvgPaints(tuple(paints), tuple(unaudited))


def paints_and_isolates(
    svg: bytes, *, path: str | Path | None = None, max_groups: int | None = None
) -> tuple[SvgPaints, list[bytes]]:
    """:func:`extract_paints` and one :func:`isolate_paints` SVG per paint group.

    One parse and one cascade serve both (a check reads every icon this way);
    the SVGs follow :meth:`SvgPaints.groups`.  More than ``max_groups`` groups
    is an :class:`SvgError` raised before any SVG is written.
    """
    unaudited: list[Unaudited] = []
    visited = list(_walk(svg, path, unaudited))
    paints = _paints_of(visited, unaudited)
    groups = paints.groups()
    if max_groups is not None and len(groups) > max_groups:
        raise SvgError(
            f"draws {len(groups)} distinct paints (colour and opacity); at most "
            f"{max_groups} are audited per icon",
            path=path,
        )
    return paints, _isolate(visited, [_in_group(g.key) for g in groups], path)


# A colour drawn at full strength in the masks :func:`isolate_paints` makes.
_MASK_INK = "#000000"
# A paint every renderer reads as one opaque colour: left as it is in a mask.
_PLAIN_HEX = re.compile(r"#(?:[0-9a-fA-F]{3}){1,2}")


def isolate_paints(
    svg: bytes, keep: Callable[[Paint], bool], *, path: str | Path | None = None
) -> bytes:
    """``svg`` with only the paints ``keep`` accepts, drawn opaque; everything else unpainted.

    Rendering the result gives the geometric coverage of those paints (their
    opacity is audited separately): every element and group is drawn at
    opacity 1, kept paints opaque (``#000000`` unless already an opaque hex
    colour), other fills and strokes ``none``, and text, images, ``<use>``,
    markers and filters are not drawn.  Only the declarations that change
    something are appended to an element's ``style`` attribute, with
    ``!important``, the last word in the cascade, so ``<style>`` rules cannot
    undo them; geometry (``stroke-width``, transforms, clip paths) is untouched.
    """
    return isolate_each(svg, [keep], path=path)[0]


def isolate_groups(
    svg: bytes, groups: Sequence[PaintGroup], *, path: str | Path | None = None
) -> list[bytes]:
    """One :func:`isolate_paints` SVG per paint group, from one parse and one cascade."""
    return isolate_each(svg, [_in_group(g.key) for g in groups], path=path)


def _in_group(key: tuple[str, float]) -> Callable[[Paint], bool]:
    """Whether a paint belongs to the group with ``key`` (colour, opacity)."""
    return lambda p: (p.color, p.opacity) == key


def isolate_each(
    svg: bytes, keeps: Sequence[Callable[[Paint], bool]], *, path: str | Path | None = None
) -> list[bytes]:
    """:func:`isolate_paints` for several predicates; the work is bounded by
    :data:`MAX_ISOLATE_WORK` (rendered elements x variants)."""
    return _isolate(list(_walk(svg, path, [])), keeps, path)


def _isolate(
    visited: list[_Visited], keeps: Sequence[Callable[[Paint], bool]], path: str | Path | None
) -> list[bytes]:
    """One SVG per predicate from walked elements (their tree is rewritten in place)."""
    if len(visited) * len(keeps) > MAX_ISOLATE_WORK:
        raise SvgError(
            f"{len(keeps)} paints on {len(visited)} elements need more than "
            f"{MAX_ISOLATE_WORK} element renders; refused (resource limit)",
            path=path,
        )
    original = [v.node.get("style") for v in visited]
    out = []
    for keep in keeps:
        for v, style in zip(visited, original, strict=True):
            decls = _overrides(v, keep)
            if not decls:  # renders as it is: left byte for byte (a third of the render cost)
                if style is None:
                    v.node.attrib.pop("style", None)
                else:
                    v.node.set("style", style)
                continue
            own = [] if style is None else _kept_declarations(style, decls)
            v.node.set(
                "style", "; ".join([*own, *(f"{k}: {d} !important" for k, d in decls.items())])
            )
        # ElementTree writes the SVG namespace with a prefix (ns0:svg); the renderer
        # matches elements by namespace, not prefix, so the drawing is the same.
        out.append(ET.tostring(visited[0].node, encoding="utf-8"))
    return out


@dataclass
class _Visited:
    node: ET.Element
    paints: tuple[Paint, ...]
    hidden_kind: bool  # an element the audit does not judge (text, image, use ...)
    rendered: dict[str, str | None]  # the renderer's view of what a mask overrides


def _overrides(v: _Visited, keep: Callable[[Paint], bool]) -> dict[str, str]:
    """What one element needs so that only ``keep``'s paints draw, opaque, and nothing else.

    Only declarations that change the drawing: where the renderer already
    sees the value wanted (no opacity, filter or marker declared, a paint
    already ``none``, a kept paint already an opaque hex colour) nothing is
    written, since every declaration costs the renderer a CSS parse per
    render.  The test is on the renderer's own view (:func:`_cascade`), not
    on the validated values, so an invalid or unusual declaration is always
    overridden.
    """
    seen = v.rendered
    decls: dict[str, str] = {}
    if v.hidden_kind:
        decls["display"] = "none"
    for name in ("opacity", "filter", *_MARKERS):
        if seen[name] is not None and not (name != "opacity" and seen[name] == "none"):
            decls[name] = "1" if name == "opacity" else "none"
    # Paint only on shapes: a container's fill would be inherited by <mask>
    # and <clipPath> content defined under it, changing the geometry.
    for kind in ("fill", "stroke") if _local(v.node) in _SHAPES else ():
        paint = next((p for p in v.paints if p.kind == kind), None)
        value, opacity = seen[kind], seen[f"{kind}-opacity"]
        if paint is not None and paint.opacity > 0.0 and keep(paint):
            # An opaque hex colour draws full coverage as it is; currentColor,
            # translucency and the host's fill are made #000000 at opacity 1.
            if paint.opacity != 1.0 or value is None or not _PLAIN_HEX.fullmatch(value):
                decls[kind] = _MASK_INK
            if opacity is not None:
                decls[f"{kind}-opacity"] = "1"
        elif value != "none":
            decls[kind] = "none"
    return decls


def _kept_declarations(style: str, ours: Container[str]) -> list[str]:
    """An inline ``style``'s valid declarations, minus the properties we override."""
    return [
        f"{d.name}: {tinycss2.serialize(d.value).strip()}{' !important' if d.important else ''}"
        for d in tinycss2.parse_declaration_list(style, skip_comments=True, skip_whitespace=True)
        if d.type == "declaration" and d.lower_name not in ours
    ]


def _parse(svg: bytes, path: str | Path | None) -> tuple[ET.Element, dict[int, int]]:
    """The XML tree and each element's start line (keyed by ``id``), under the limits."""
    lines: list[int] = []
    parser_box: list[defusedxml.ElementTree.DefusedXMLParser] = []

    class _LineBuilder(ET.TreeBuilder):
        def start(self, tag: Any, attrs: dict[Any, Any], /) -> ET.Element:
            if len(lines) >= MAX_ELEMENTS:
                raise SvgError(
                    f"has more than {MAX_ELEMENTS} elements; refused (resource limit)", path=path
                )
            lines.append(parser_box[0].parser.CurrentLineNumber)
            return super().start(tag, attrs)

    parser = defusedxml.ElementTree.DefusedXMLParser(target=_LineBuilder())
    parser_box.append(parser)
    try:
        parser.feed(svg)
        root = parser.close()
    except defusedxml.EntitiesForbidden as exc:
        raise SvgError(
            "declares XML entities, which are refused (entity expansion)", path=path
        ) from exc
    except (defusedxml.DTDForbidden, defusedxml.ExternalReferenceForbidden) as exc:
        raise SvgError("refers to an external DTD or entity, which is refused", path=path) from exc
    except (ET.ParseError, defusedxml.ElementTree.ParseError) as exc:
        line = exc.position[0] if getattr(exc, "position", None) else None
        reason = str(exc).split(":", 1)[0]
        raise SvgError(f"is not well-formed XML ({reason})", path=path, line=line) from exc
    return root, {id(e): n for e, n in zip(root.iter(), lines, strict=False)}


def _stylesheet(
    root: ET.Element, elements: int, path: str | Path | None
) -> tuple[cssselect2.Matcher, cssselect2.Matcher]:
    """Normal and ``!important`` matchers of every ``<style type="text/css">``, like cairosvg."""
    normal, important = cssselect2.Matcher(), cssselect2.Matcher()
    selectors = 0
    for style in root.iter(f"{{{SVG_NS}}}style"):
        if style.get("type", "text/css") != "text/css" or not style.text:
            continue
        for rule in tinycss2.parse_stylesheet(style.text, skip_comments=True, skip_whitespace=True):
            if rule.type != "qualified-rule":  # @media, @import ...: ignored, as cairosvg does
                continue
            plain, strong = _declarations(rule.content)
            try:
                compiled = list(cssselect2.compile_selector_list(rule.prelude))
            except cssselect2.SelectorError:
                continue  # an invalid selector drops its rule (CSS Syntax 3)
            for selector in compiled:
                if selector.pseudo_element is not None or selector.never_matches:
                    continue
                selectors += 1
                if selectors * elements > MAX_MATCH_WORK:
                    raise SvgError(
                        f"has {selectors}+ CSS selectors on {elements} elements; refused "
                        f"(resource limit: {MAX_MATCH_WORK} selector x element matches)",
                        path=path,
                    )
                if plain:
                    normal.add_selector(selector, plain)
                if strong:
                    important.add_selector(selector, strong)
    return normal, important


def _declarations(tokens: object) -> tuple[list[tuple[str, str]], list[tuple[str, str]]]:
    """``(normal, important)`` ``(name, value)`` pairs of the properties this module reads."""
    normal: list[tuple[str, str]] = []
    important: list[tuple[str, str]] = []
    for d in tinycss2.parse_declaration_list(tokens, skip_comments=True, skip_whitespace=True):
        if d.type == "declaration" and d.lower_name in _PROPERTIES:
            (important if d.important else normal).append(
                (d.lower_name, tinycss2.serialize(d.value).strip())
            )
    return normal, important


def _describe(node: ET.Element) -> str:
    tag = _local(node)
    for attr in ("id", "class"):
        if value := node.get(attr):
            return f'<{tag} {attr}="{_printable(value)}">'
    return f"<{tag}>"


def _printable(text: str, limit: int = 60) -> str:
    """Untrusted names shown literally: no control characters, bounded length."""
    clean = "".join(ch if ch.isprintable() else "?" for ch in text)
    return clean if len(clean) <= limit else clean[: limit - 1] + "…"


def _local(node: ET.Element) -> str:
    tag = node.tag if isinstance(node.tag, str) else ""
    return tag.rsplit("}", 1)[-1]


def _in_svg_namespace(node: ET.Element) -> bool:
    tag = node.tag if isinstance(node.tag, str) else ""
    return not tag.startswith("{") or tag.startswith(f"{{{SVG_NS}}}")


def _number(value: str | None) -> float | None:
    """An ``<alpha-value>`` (number or percentage), clamped to [0, 1]; None when invalid."""
    if value is None:
        return None
    text = value.strip()
    try:
        number = float(text[:-1]) / 100 if text.endswith("%") else float(text)
    except ValueError:
        return None
    if number != number:  # NaN
        return None
    return min(1.0, max(0.0, number))


def _length_is_zero(value: str | None) -> bool:
    if value is None:
        return False
    text = value.strip().lower()
    for unit in ("px", "pt", "pc", "mm", "cm", "in", "em", "ex", "%"):
        if text.endswith(unit):
            text = text[: -len(unit)]
            break
    try:
        return float(text) == 0.0
    except ValueError:
        return False


def _valid(name: str, value: str) -> bool:
    """Whether a declared value is usable; invalid ones are ignored (CSS Syntax 3)."""
    if value.strip().lower() == "inherit":
        return True
    if name in ("fill", "stroke"):
        return _paint_value(value)[0] != "invalid"
    if name == "color":
        return tinycss2.color4.parse_color(value) is not None
    if name in ("opacity", "fill-opacity", "stroke-opacity"):
        return _number(value) is not None
    return True


def _paint_value(value: str) -> tuple[str, object]:
    """Classify a ``<paint>`` value.

    ``('none', None)``, ``('current', None)``, ``('color', (hex, alpha))``,
    ``('server', url)``, ``('context', keyword)``, ``('space', name)`` for a
    colour outside sRGB notation (``lab()``, ``color(display-p3 ...)``), or
    ``('invalid', None)``.  Colours are CSS Color 4 (tinycss2), so
    ``rebeccapurple``, ``#rgba`` and ``rgb(r g b / a)`` all parse.
    """
    text = value.strip()
    lowered = text.lower()
    if lowered == "none":
        return ("none", None)
    if lowered in ("context-fill", "context-stroke"):
        return ("context", lowered)
    tokens = [
        t
        for t in tinycss2.parse_component_value_list(text)
        if t.type not in ("whitespace", "comment")
    ]
    if tokens and tokens[0].type == "url":
        return ("server", tokens[0].value)
    if tokens and tokens[0].type == "function" and tokens[0].lower_name == "url":
        return ("server", tinycss2.serialize(tokens[0].arguments).strip("'\" "))
    return _color_value(text)


def _color_value(text: str) -> tuple[str, object]:
    """A CSS colour as ``('color', (hex, alpha))``, ``('current', None)``, ``('space', name)``
    or ``('invalid', None)``."""
    parsed = tinycss2.color4.parse_color(text)
    if parsed is None:
        return ("invalid", None)
    if parsed == "currentcolor":
        return ("current", None)
    assert isinstance(parsed, tinycss2.color4.Color)
    try:
        srgb = parsed.to("srgb")
    except NotImplementedError:
        return ("space", parsed.space)
    # CSS Color 4: out-of-range sRGB channels are clamped when drawn.
    r, g, b = (round(min(1.0, max(0.0, c)) * 255) for c in srgb.coordinates)
    return ("color", (f"#{r:02x}{g:02x}{b:02x}", float(srgb.alpha)))


def _cascade(
    wrapper: cssselect2.ElementWrapper,
    parent: dict[str, str | None],
    parent_raw: dict[str, str | None],
    matchers: tuple[cssselect2.Matcher, cssselect2.Matcher],
) -> tuple[dict[str, str | None], dict[str, str | None]]:
    """Computed values of the properties this module reads, and the renderer's view.

    The second dict is what cairosvg itself will use for the properties a
    mask overrides (:data:`_MASK_PROPERTIES`): the last value declared in the
    same cascade order, valid or not (it does not validate), inherited the
    same way, ``None`` where nothing is declared.
    """
    node = wrapper.etree_element
    computed: dict[str, str | None] = {name: parent[name] for name in _INHERITED}
    computed["visibility"] = parent["visibility"]
    computed.update({"opacity": "1", "display": "inline", "filter": None})
    computed.update(dict.fromkeys(_MARKERS))
    inline_normal, inline_important = _declarations(node.get("style", ""))
    layers: list[list[tuple[str, str]]] = [
        [(name, node.get(name)) for name in _PROPERTIES if node.get(name) is not None]
    ]
    normal, important = matchers
    layers += [rule[-1] for rule in normal.match(wrapper)]
    layers.append(inline_normal)
    layers += [rule[-1] for rule in important.match(wrapper)]
    layers.append(inline_important)
    raw = {name: parent_raw[name] if name in _INHERITED_MASK else None for name in parent_raw}
    for declarations in layers:
        for name, value in declarations:
            if name in raw:
                text = value.strip()
                raw[name] = parent_raw[name] if text == "inherit" else text
            if not _valid(name, value):
                continue
            if value.strip().lower() == "inherit":
                computed[name] = parent.get(name, _INITIAL.get(name))
            elif name == "color" and tinycss2.color4.parse_color(value) == "currentcolor":
                computed[name] = parent["color"]  # color: currentColor means inherit
            else:
                computed[name] = value.strip()
    return computed, raw


def _walk(svg: bytes, path: str | Path | None, unaudited: list[Unaudited]) -> Iterator[_Visited]:
    """Every rendered SVG element with its paints, in document order; unaudited ones noted."""
    root, lines = _parse(svg, path)
    if _local(root) != "svg" or not _in_svg_namespace(root):
        raise SvgError("has no <svg> root element; not an SVG file", path=path)
    total = len(lines)
    matchers = _stylesheet(root, total, path)
    ids = {e.get("id"): e for e in root.iter() if e.get("id")}
    wrapper_root = cssselect2.ElementWrapper.from_xml_root(root)
    initial: dict[str, str | None] = {**_INITIAL, "opacity": "1"}
    nothing: dict[str, str | None] = dict.fromkeys(_MASK_PROPERTIES)
    # (wrapper, parent computed values, the renderer's view of them, product of
    # ancestors' opacity, depth, filtered above)
    stack: list[
        tuple[
            cssselect2.ElementWrapper,
            dict[str, str | None],
            dict[str, str | None],
            float,
            int,
            bool,
        ]
    ] = [(wrapper_root, initial, nothing, 1.0, 0, False)]
    while stack:
        wrapper, parent, parent_raw, group_opacity, depth, filtered = stack.pop()
        node = wrapper.etree_element
        if depth > MAX_DEPTH:
            raise SvgError(
                f"nests elements deeper than {MAX_DEPTH}; refused (resource limit)", path=path
            )
        tag = _local(node)
        if not _in_svg_namespace(node) or tag in _NOT_RENDERED:
            continue
        computed, raw = _cascade(wrapper, parent, parent_raw, matchers)
        if (computed["display"] or "").lower() == "none":
            continue
        line = lines.get(id(node))
        own_opacity = _number(computed["opacity"])
        opacity = group_opacity * (1.0 if own_opacity is None else own_opacity)
        if computed["filter"] and computed["filter"].lower() != "none" and not filtered:
            unaudited.append(
                Unaudited(_describe(node), line, "a filter may change its colours; not audited")
            )
            filtered = True
        if tag in _UNAUDITED_ELEMENTS:
            unaudited.append(Unaudited(_describe(node), line, _UNAUDITED_ELEMENTS[tag]))
            yield _Visited(node, (), True, raw)
            continue
        paints: tuple[Paint, ...] = ()
        if tag in _SHAPES:
            paints = tuple(_shape_paints(node, computed, opacity, line, ids, unaudited))
            if any(v and v.lower() != "none" for v in (computed[m] for m in _MARKERS)):
                unaudited.append(Unaudited(_describe(node), line, "markers are not audited"))
        elif tag not in _CONTAINERS:
            continue  # unknown SVG element: drawn as nothing by the renderer
        yield _Visited(node, paints, False, raw)
        children = list(wrapper.iter_children())
        if tag == "switch":
            children = children[:1]  # only the first child renders (cairosvg: no feature tests)
        for child in reversed(children):
            stack.append((child, computed, raw, opacity, depth + 1, filtered))


def _shape_paints(
    node: ET.Element,
    computed: dict[str, str | None],
    opacity: float,
    line: int | None,
    ids: dict[str | None, ET.Element],
    unaudited: list[Unaudited],
) -> Iterator[Paint]:
    if (computed["visibility"] or "visible").lower() in ("hidden", "collapse"):
        return
    description = _describe(node)
    for kind in ("fill", "stroke"):
        if kind == "fill" and _local(node) == "line":
            continue  # a line has no interior
        if kind == "stroke" and _length_is_zero(computed["stroke-width"]):
            continue
        value = computed[kind] or "none"
        sort, detail = _paint_value(value)
        if sort == "none":
            continue
        if sort == "server":
            target = ids.get(str(detail).lstrip("#"))
            what = _describe(target) if target is not None else f"url({_printable(str(detail))})"
            unaudited.append(
                Unaudited(description, line, f"{kind} is the paint server {what}; not audited")
            )
            continue
        if sort == "context":
            unaudited.append(Unaudited(description, line, f"{kind} is {detail}; not audited"))
            continue
        kind_opacity = _number(computed[f"{kind}-opacity"])
        effective = opacity * (1.0 if kind_opacity is None else kind_opacity)
        if sort == "current":
            if computed["color"] is None:
                yield Paint(CURRENT_COLOR, kind, effective, description, line)
                continue
            sort, detail = _color_value(computed["color"])
        if sort == "space":
            reason = f"{kind} is a {detail} colour, outside sRGB notation; not audited"
            unaudited.append(Unaudited(description, line, reason))
            continue
        # what remains is _color_value's ("color", (hex, alpha))
        hex_color, colour_alpha = cast(tuple[str, float], detail)
        yield Paint(hex_color, kind, effective * colour_alpha, description, line)
