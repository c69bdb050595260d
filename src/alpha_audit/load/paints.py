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

Every bound is checked before the work it bounds: the element count and depth as
the XML is parsed, the selector-matching work (:data:`MAX_MATCH_WORK`, counted
from each selector's shape and the tree's depth and width) before any element
is matched, the variants (:data:`MAX_ISOLATE_WORK`) before any is written.

Group opacity is multiplied down the tree.  That is exact for one element;
for overlapping children of a translucent group it is the per-element
approximation (the group is composited once, so overlaps are not doubled).
"""

from __future__ import annotations

import contextlib
import functools
import json
import re
import xml.etree.ElementTree as ET
from collections.abc import Callable, Container, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, cast

import cssselect2
import cssselect2.compiler
import cssselect2.parser
import defusedxml
import defusedxml.ElementTree
import tinycss2
import tinycss2.color4

from alpha_audit.errors import SvgError
from alpha_audit.paints import CURRENT_COLOR, Paint, SvgPaints, Unaudited

__all__ = [
    "MAX_DEPTH",
    "MAX_ELEMENTS",
    "MAX_ISOLATE_WORK",
    "MAX_MATCH_WORK",
    "MAX_SELECTORS",
    "decode_paints",
    "encode_paints",
    "extract_paints",
    "isolate_paints",
    "paints_and_isolates",
]

SVG_NS = "http://www.w3.org/2000/svg"

# Limits on the in-process parse of an untrusted file (already capped at
# MAX_SVG_BYTES by load.svg.read_svg).  Icons have tens of elements and a few
# rules.  The depth mirrors the render worker, whose recursion limit (2000
# frames) stops cairosvg near 600.  MAX_MATCH_WORK bounds the cascade: for
# every selector, the elements it may be tested on times an upper bound on the
# element tests one match makes (a descendant combinator may walk every
# ancestor, ``:has()`` every descendant ...) plus the declarations it applies;
# counted before any element is matched (each unit is about a microsecond).
MAX_ELEMENTS = 20_000
MAX_DEPTH = 500
MAX_SELECTORS = 5_000  # compiled selectors per file
MAX_MATCH_WORK = 1_000_000  # element tests + declarations applied, counted before matching
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
# attribute but opacity, filter, display and a few geometric ones); and ``color``,
# which a mask leaves alone but which says what ``currentColor`` draws.
_INHERITED_MASK = frozenset(
    ("fill", "stroke", "fill-opacity", "stroke-opacity", "color", *_MARKERS)
)
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


def extract_paints(svg: bytes, *, path: str | Path | None = None) -> SvgPaints:
    """The paints ``svg`` draws; raises :class:`SvgError` on bad XML or a limit.

    >>> svg = b'''<svg xmlns="http://www.w3.org/2000/svg" fill="none" stroke="currentColor">
    ...   <g opacity="0.5"><circle r="4" fill="#f00" fill-opacity="0.5"/></g></svg>'''
    >>> [(p.color, p.kind, p.opacity) for p in extract_paints(svg).paints]
    [('#ff0000', 'fill', 0.25), ('currentColor', 'stroke', 0.5)]
    """
    unaudited: list[Unaudited] = []
    return _paints_of(_read(svg, path, unaudited).visited, unaudited)


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
    document = _read(svg, path, unaudited)
    paints = _paints_of(document.visited, unaudited)
    groups = paints.groups()
    if max_groups is not None and len(groups) > max_groups:
        raise SvgError(
            f"draws {len(groups)} distinct paints (colour and opacity); at most "
            f"{max_groups} are audited per icon",
            path=path,
        )
    return paints, _isolate(document, [_in_group(g.key) for g in groups], path, svg)


def encode_paints(paints: SvgPaints) -> bytes:
    """``paints`` as compact JSON (what the render worker sends and the render cache keeps)."""
    doc = {
        "paints": [[p.color, p.kind, p.opacity, p.element, p.line] for p in paints.paints],
        "unaudited": [[u.element, u.line, u.reason] for u in paints.unaudited],
    }
    return json.dumps(doc, separators=(",", ":"), allow_nan=False).encode()


def decode_paints(value: bytes) -> SvgPaints | None:
    """:func:`encode_paints`'s JSON read back; None unless every field holds a value that
    reading an SVG could give (it comes from a cache file or a render process)."""
    try:
        doc = json.loads(value)
        paints = tuple(
            Paint(color, kind, float(opacity), element, line)
            for color, kind, opacity, element, line in doc["paints"]
        )
        unaudited = tuple(
            Unaudited(element, line, reason) for element, line, reason in doc["unaudited"]
        )
    except (ValueError, TypeError, KeyError, OverflowError, RecursionError):
        return None
    for p in paints:
        if not (
            (
                p.color == CURRENT_COLOR
                or (isinstance(p.color, str) and _HEX_COLOR.fullmatch(p.color))
            )
            and p.kind in ("fill", "stroke")
            and 0.0 < p.opacity <= 1.0
            and isinstance(p.element, str)
            and _line(p.line)
        ):
            return None
    for u in unaudited:
        if not (isinstance(u.element, str) and isinstance(u.reason, str) and _line(u.line)):
            return None
    return SvgPaints(paints, unaudited)


def _line(line: object) -> bool:
    return line is None or (type(line) is int and line >= 1)


_HEX_COLOR = re.compile(r"#[0-9a-f]{6}")


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
    markers and filters are not drawn (a ``<use>`` is left out or pointed at
    nothing: the renderer draws its target whatever its ``display``).  Only the
    declarations that change something are appended to an element's ``style`` attribute, with
    ``!important``, the last word in the cascade, so ``<style>`` rules cannot
    undo them; geometry (``stroke-width``, transforms, clip paths) is untouched.

    Shapes and groups that would draw nothing are left out of the SVG instead
    (the renderer would still parse and trace them), where that cannot change
    the drawing (:func:`_prunable`): each group's render then costs what its
    own elements cost, so a flag with fifteen colours renders about as fast as
    one drawn in one colour.
    """
    return _isolate(_read(svg, path, []), [keep], path, svg)[0]


def _in_group(key: tuple[str, float]) -> Callable[[Paint], bool]:
    """Whether a paint belongs to the group with ``key`` (colour, opacity)."""
    return lambda p: (p.color, p.opacity) == key


def _isolate(
    document: _Document,
    keeps: Sequence[Callable[[Paint], bool]],
    path: str | Path | None,
    svg: bytes,
) -> list[bytes]:
    """One SVG per predicate from a walked document (its tree is rewritten in place); the
    work is bounded by :data:`MAX_ISOLATE_WORK` (rendered elements x variants).

    A variant that changes nothing (every element already draws as the predicate
    wants, none is left out, no ``<use>`` is disarmed) is ``svg`` itself: the
    renderer parses it to the tree that writing the tree out would give.
    """
    visited = document.visited
    if len(visited) * len(keeps) > MAX_ISOLATE_WORK:
        raise SvgError(
            f"{len(keeps)} paints on {len(visited)} elements need more than "
            f"{MAX_ISOLATE_WORK} element renders; refused (resource limit)",
            path=path,
        )
    movable = _prunable(document)
    disarmed = _disarm_uses(document, {v.node for v in visited if v.node not in movable})
    original = [v.node.get("style") for v in visited]
    out = []
    for keep in keeps:
        left_out = _left_out(visited, movable, keep)
        changed = disarmed or bool(left_out)
        for v, style in zip(visited, original, strict=True):
            if v.node in left_out:
                continue  # not in this SVG: whatever it says does not matter
            decls = _overrides(v, keep)
            if not decls:  # renders as it is: left byte for byte (a third of the render cost)
                if style is None:
                    v.node.attrib.pop("style", None)
                else:
                    v.node.set("style", style)
                continue
            changed = True
            own = [] if style is None else _kept_declarations(style, decls)
            v.node.set(
                "style", "; ".join([*own, *(f"{k}: {d} !important" for k, d in decls.items())])
            )
        if not changed:
            out.append(svg)
            continue
        # ElementTree writes the SVG namespace with a prefix (ns0:svg); the renderer
        # matches elements by namespace, not prefix, so the drawing is the same.
        with _without(document.parents, left_out):
            out.append(ET.tostring(visited[0].node, encoding="utf-8"))
    return out


def _prunable(document: _Document) -> set[ET.Element]:
    """Elements whose subtree an isolated SVG may leave out when it draws nothing.

    Left out, a subtree that draws nothing changes the rendered mask only
    through what refers to it or what its presence changes for others, so an
    element qualifies only when its whole subtree is shapes, groups and
    ``<use>`` elements the walk visited (no ``<defs>``, ``<clipPath>``, text or
    unknown elements, whose content the renderer may draw or look up), none
    but a ``<use>`` has an ``id`` (cairosvg looks paths up by id, for
    ``clip-path`` too), it is not the root nor a child of ``<switch>`` (which
    renders its first child), and no selector of the stylesheet depends on
    siblings or descendants (``:nth-child``, ``+``, ``:has()`` ...,
    :func:`_reads_structure`).
    """
    if document.structural or not document.visited:
        return set()
    visited = {v.node: v for v in document.visited}
    ok: set[ET.Element] = set()
    for v in reversed(document.visited):  # children before their parents
        node = v.node
        if _local(document.parents.get(node, node)) == "switch":
            continue
        if _is_use(v):  # drawn by none of the groups; cairosvg registers no id of it
            ok.add(node)
            continue
        if v.hidden_kind or node.get("id") is not None or not all(child in ok for child in node):
            continue
        ok.add(node)
    ok.discard(document.visited[0].node)  # the root stays
    return ok & visited.keys()


def _is_use(v: _Visited) -> bool:
    return v.hidden_kind and _local(v.node) == "use"


def _disarm_uses(document: _Document, kept: Container[ET.Element]) -> bool:
    """Point every ``<use>`` the group SVGs keep at nothing; whether there was one.

    cairosvg draws a ``<use>``'s target whatever the ``<use>``'s ``display``,
    so ``display: none`` alone would put the target into every group's mask;
    a reference to an id the file does not have draws nothing, and the
    element stays where selectors may look for it.
    """
    uses = [v.node for v in document.visited if _is_use(v) and v.node in kept]
    if not uses:
        return False
    ids = {e.get("id") for e in document.visited[0].node.iter()}
    nothing = next(
        f"alpha-audit-nothing-{k}"
        for k in range(len(ids) + 1)
        if f"alpha-audit-nothing-{k}" not in ids
    )
    for node in uses:
        for name in ("href", "{http://www.w3.org/1999/xlink}href"):
            if node.get(name) is not None:
                node.set(name, f"#{nothing}")
    return True


def _left_out(
    visited: Sequence[_Visited], movable: set[ET.Element], keep: Callable[[Paint], bool]
) -> set[ET.Element]:
    """The outermost movable elements that draw none of ``keep``'s paints."""
    if not movable:
        return set()
    drawing: set[ET.Element] = set()  # elements drawing a kept paint, or above one
    for v in reversed(visited):  # children before their parents
        if any(p.opacity > 0.0 and keep(p) for p in v.paints) or any(
            child in drawing for child in v.node
        ):
            drawing.add(v.node)
    out: set[ET.Element] = set()
    skipped: set[ET.Element] = set()  # inside an element already left out
    for v in visited:  # parents first: only the outermost one of a subtree is removed
        key = v.node
        if key in skipped:
            skipped.update(v.node)
        elif key in movable and key not in drawing:
            out.add(key)
            skipped.update(v.node)
    return out


@contextlib.contextmanager
def _without(parents: dict[ET.Element, ET.Element], left_out: set[ET.Element]) -> Iterator[None]:
    """The tree with the ``left_out`` elements detached, put back in place afterwards."""
    touched: dict[ET.Element, tuple[ET.Element, list[ET.Element]]] = {}
    for key in left_out:
        parent = parents[key]
        touched.setdefault(parent, (parent, list(parent)))
    try:
        for parent, children in touched.values():
            parent[:] = [c for c in children if c not in left_out]
        yield
    finally:
        for parent, children in touched.values():
            parent[:] = children


@dataclass
class _Visited:
    node: ET.Element
    paints: tuple[Paint, ...]
    hidden_kind: bool  # an element the audit does not judge (text, image, use ...)
    rendered: dict[str, str | None]  # the renderer's view of what a mask overrides


@dataclass
class _Document:
    """A walked SVG: its rendered elements in document order and what pruning may rely on."""

    visited: list[_Visited]
    parents: dict[ET.Element, ET.Element]  # element -> parent element
    structural: bool  # a selector depends on siblings or descendants


@dataclass(frozen=True)
class _Extent:
    """How big a parsed tree is: what bounds the work of matching one selector."""

    elements: int
    depth: int  # of the deepest element, the root's being 0
    widest: int  # most children of one element


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
            # An opaque hex colour draws full coverage as it is, and so does
            # currentColor where no color is declared (cairosvg draws it black);
            # translucency, the host's fill and anything else are made #000000.
            if paint.opacity != 1.0 or not _opaque(value, seen["color"]):
                decls[kind] = _MASK_INK
            if opacity is not None:
                decls[f"{kind}-opacity"] = "1"
        elif value != "none":
            decls[kind] = "none"
    return decls


def _opaque(value: str | None, color: str | None) -> bool:
    """Whether cairosvg draws the paint ``value`` as one opaque colour as it is."""
    if value is None:
        return False
    return bool(_PLAIN_HEX.fullmatch(value)) or (value == "currentColor" and color is None)


def _kept_declarations(style: str, ours: Container[str]) -> list[str]:
    """An inline ``style``'s valid declarations, minus the properties we override."""
    return [
        f"{d.name}: {tinycss2.serialize(d.value).strip()}{' !important' if d.important else ''}"
        for d in tinycss2.parse_declaration_list(style, skip_comments=True, skip_whitespace=True)
        if d.type == "declaration" and d.lower_name not in ours
    ]


def _parse(
    svg: bytes, path: str | Path | None
) -> tuple[ET.Element, dict[ET.Element, int], _Extent]:
    """The XML tree, each element's start line (keyed by ``id``) and its extent.

    The element count and depth are refused as the parser reaches them, before
    the rest of the file is read.
    """
    lines: list[int] = []
    parser_box: list[defusedxml.ElementTree.DefusedXMLParser] = []
    open_children: list[int] = []  # per open element, its children so far
    extent = {"depth": 0, "widest": 0}

    class _LineBuilder(ET.TreeBuilder):
        def start(self, tag: Any, attrs: dict[Any, Any], /) -> ET.Element:
            if len(lines) >= MAX_ELEMENTS:
                raise SvgError(
                    f"has more than {MAX_ELEMENTS} elements; refused (resource limit)", path=path
                )
            if len(open_children) > MAX_DEPTH:
                raise SvgError(
                    f"nests elements deeper than {MAX_DEPTH}; refused (resource limit)",
                    path=path,
                    line=parser_box[0].parser.CurrentLineNumber,
                )
            lines.append(parser_box[0].parser.CurrentLineNumber)
            extent["depth"] = max(extent["depth"], len(open_children))
            if open_children:
                open_children[-1] += 1
                extent["widest"] = max(extent["widest"], open_children[-1])
            open_children.append(0)
            return super().start(tag, attrs)

        def end(self, tag: Any, /) -> ET.Element:
            open_children.pop()
            return super().end(tag)

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
    extent_ = _Extent(len(lines), extent["depth"], extent["widest"])
    return root, {e: n for e, n in zip(root.iter(), lines, strict=False)}, extent_


def _stylesheet(
    root: ET.Element, extent: _Extent, path: str | Path | None
) -> tuple[tuple[cssselect2.Matcher, cssselect2.Matcher] | None, bool]:
    """Normal and ``!important`` matchers of every ``<style type="text/css">``, like cairosvg
    (None when there is no rule to match), and whether a selector depends on siblings or
    descendants (:func:`_reads_structure`).

    Before a selector is compiled its matching work is counted (:func:`_match_cost`
    on every element, plus its declarations applied to each); past
    :data:`MAX_MATCH_WORK` in all, or :data:`MAX_SELECTORS` selectors, the file
    is refused before any element is matched.
    """
    normal, important = cssselect2.Matcher(), cssselect2.Matcher()
    selectors = work = 0
    structural = False
    for style in root.iter(f"{{{SVG_NS}}}style"):
        if style.get("type", "text/css") != "text/css" or not style.text:
            continue
        for rule in tinycss2.parse_stylesheet(style.text, skip_comments=True, skip_whitespace=True):
            if rule.type != "qualified-rule":  # @media, @import ...: ignored, as cairosvg does
                continue
            plain, strong = _declarations(rule.content)
            try:
                parsed = list(cssselect2.parser.parse(rule.prelude))
            except cssselect2.SelectorError:
                continue  # an invalid selector drops its rule (CSS Syntax 3)
            except RecursionError as exc:
                raise SvgError(
                    "nests CSS selectors too deeply; refused (resource limit)", path=path
                ) from exc
            for one in parsed:
                selectors += 1
                if selectors > MAX_SELECTORS:
                    raise SvgError(
                        f"has more than {MAX_SELECTORS} CSS selectors; refused (resource limit)",
                        path=path,
                    )
                try:
                    cost = _match_cost(one.parsed_tree, extent)
                    reads_structure = _reads_structure(one.parsed_tree)
                    selector = cssselect2.compiler.CompiledSelector(one)
                except cssselect2.SelectorError:
                    continue
                except RecursionError as exc:
                    raise SvgError(
                        "nests CSS selectors too deeply; refused (resource limit)", path=path
                    ) from exc
                if one.pseudo_element is not None or selector.never_matches:
                    continue
                work += extent.elements * (cost + len(plain) + len(strong))
                if work > MAX_MATCH_WORK:
                    raise SvgError(
                        f"has CSS selectors whose matching on {extent.elements} elements "
                        f"(nesting depth {extent.depth}) needs more than {MAX_MATCH_WORK} "
                        "element tests; refused before matching (resource limit)",
                        path=path,
                    )
                structural = structural or reads_structure
                if plain:
                    normal.add_selector(selector, plain)
                if strong:
                    important.add_selector(selector, strong)
    return ((normal, important) if work else None), structural


# Pseudo-classes whose match depends on an element's siblings or children.
_POSITIONAL = frozenset(
    {"first-child", "last-child", "only-child", "first-of-type", "last-of-type", "only-of-type"}
)


# Selectors holding a list of selectors: :not(), :is()/:where(), and the like.
_SELECTOR_LISTS = (
    cssselect2.parser.NegationSelector,
    cssselect2.parser.MatchesAnySelector,
    cssselect2.parser.SpecificityAdjustmentSelector,
)


def _match_cost(node: object, extent: _Extent) -> int:
    """An upper bound on the element tests cssselect2 makes matching ``node`` on one element.

    Follows cssselect2's compiled tests (``cssselect2/compiler.py``): a
    descendant combinator tries every ancestor for the left part, ``~`` every
    earlier sibling, ``:has()`` every descendant or later sibling, an
    ``:nth-child(... of S)`` every sibling; nested parts multiply.  Capped just
    above :data:`MAX_MATCH_WORK`, which refuses anything larger anyway.
    """
    p = cssselect2.parser
    cap = MAX_MATCH_WORK + 1
    if isinstance(node, p.CombinedSelector):
        fan = {" ": extent.depth, "~": extent.widest}.get(node.combinator, 1)
        left = _match_cost(node.left, extent)
        return min(cap, _match_cost(node.right, extent) + max(1, fan) * left)
    if isinstance(node, p.CompoundSelector):
        return min(cap, sum(_match_cost(s, extent) for s in node.simple_selectors) or 1)
    if isinstance(node, _SELECTOR_LISTS):
        return min(cap, 1 + sum(_match_cost(s.parsed_tree, extent) for s in node.selector_list))
    if isinstance(node, p.RelationalSelector):
        fans = {" ": extent.elements}
        return min(
            cap,
            1
            + sum(
                max(1, fans.get(r.combinator, extent.widest))
                * _match_cost(r.selector.parsed_tree, extent)
                for r in node.selector_list
            ),
        )
    if isinstance(node, p.PseudoClassSelector):
        return max(1, extent.widest) if node.name in _POSITIONAL else 1
    if isinstance(node, p.FunctionalPseudoClassSelector):
        if node.name == "lang":
            return max(1, extent.depth)
        of = _nth_of(node)
        inner = sum(_match_cost(s.parsed_tree, extent) for s in of) if of else 1
        return min(cap, max(1, extent.widest) * (inner + 1))
    return 1  # type, class, id, attribute, namespace: one test


def _nth_of(node: Any) -> list[Any]:
    """The selectors after ``of`` in ``:nth-child(An+B of S)``, parsed as cssselect2 does."""
    arguments = list(node.arguments)
    for k, token in enumerate(arguments):
        if token.type == "ident" and token.value == "of":
            return list(cssselect2.parser.parse(arguments[k + 1 :]))
    return []


def _reads_structure(node: object) -> bool:
    """Whether a selector's match may change when another element's subtree is removed.

    Sibling combinators, positional pseudo-classes, ``:empty``, ``:nth-*()`` and
    ``:has()`` look beyond an element and its ancestors; type, class, id and
    attribute tests and the descendant and child combinators do not.
    """
    p = cssselect2.parser
    if isinstance(node, p.CombinedSelector):
        return (
            node.combinator in ("+", "~")
            or _reads_structure(node.left)
            or _reads_structure(node.right)
        )
    if isinstance(node, p.CompoundSelector):
        return any(_reads_structure(s) for s in node.simple_selectors)
    if isinstance(node, _SELECTOR_LISTS):
        return any(_reads_structure(s.parsed_tree) for s in node.selector_list)
    if isinstance(node, p.RelationalSelector):
        return True
    if isinstance(node, p.PseudoClassSelector):
        return str(node.name) in _POSITIONAL or node.name == "empty"
    if isinstance(node, p.FunctionalPseudoClassSelector):
        return bool(node.name != "lang")
    return False


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


@functools.lru_cache(maxsize=4096)
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


@functools.lru_cache(maxsize=4096)
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


@functools.lru_cache(maxsize=4096)
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


@functools.lru_cache(maxsize=4096)
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
    matchers: tuple[cssselect2.Matcher, cssselect2.Matcher] | None,
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
    if matchers is not None:
        layers += [rule[-1] for rule in matchers[0].match(wrapper)]
    layers.append(inline_normal)
    if matchers is not None:
        layers += [rule[-1] for rule in matchers[1].match(wrapper)]
    layers.append(inline_important)
    raw = {name: parent_raw[name] if name in _INHERITED_MASK else None for name in parent_raw}
    for declarations in layers:
        for name, value in declarations:
            if name in raw:
                text = value.strip()
                # cairosvg resolves currentColor before inherit: a color "inherit" stays.
                raw[name] = parent_raw[name] if text == "inherit" and name != "color" else text
            if not _valid(name, value):
                continue
            if value.strip().lower() == "inherit":
                computed[name] = parent.get(name, _INITIAL.get(name))
            elif name == "color" and tinycss2.color4.parse_color(value) == "currentcolor":
                computed[name] = parent["color"]  # color: currentColor means inherit
            else:
                computed[name] = value.strip()
    return computed, raw


def _read(svg: bytes, path: str | Path | None, unaudited: list[Unaudited]) -> _Document:
    """Parse, check the bounds, and walk ``svg``; unaudited elements are noted."""
    root, lines, extent = _parse(svg, path)
    if _local(root) != "svg" or not _in_svg_namespace(root):
        raise SvgError("has no <svg> root element; not an SVG file", path=path)
    matchers, structural = _stylesheet(root, extent, path)
    visited = list(_walk(root, lines, matchers, path, unaudited))
    parents = {child: parent for parent in root.iter() for child in parent}
    return _Document(visited, parents, structural)


def _walk(
    root: ET.Element,
    lines: dict[ET.Element, int],
    matchers: tuple[cssselect2.Matcher, cssselect2.Matcher] | None,
    path: str | Path | None,
    unaudited: list[Unaudited],
) -> Iterator[_Visited]:
    """Every rendered SVG element with its paints, in document order; unaudited ones noted."""
    ids = {e.get("id"): e for e in root.iter() if e.get("id")}
    wrapper_root = cssselect2.ElementWrapper.from_xml_root(root)
    initial: dict[str, str | None] = {**_INITIAL, "opacity": "1"}
    nothing: dict[str, str | None] = dict.fromkeys(_MASK_PROPERTIES)
    # (wrapper, parent computed values, the renderer's view of them, product of
    # ancestors' opacity, filtered above); the depth was bounded by the parse
    stack: list[
        tuple[
            cssselect2.ElementWrapper,
            dict[str, str | None],
            dict[str, str | None],
            float,
            bool,
        ]
    ] = [(wrapper_root, initial, nothing, 1.0, False)]
    while stack:
        wrapper, parent, parent_raw, group_opacity, filtered = stack.pop()
        node = wrapper.etree_element
        tag = _local(node)
        if not _in_svg_namespace(node) or tag in _NOT_RENDERED:
            continue
        computed, raw = _cascade(wrapper, parent, parent_raw, matchers)
        if (computed["display"] or "").lower() == "none":
            continue
        line = lines.get(node)
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
            stack.append((child, computed, raw, opacity, filtered))


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
