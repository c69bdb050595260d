"""Paint extraction on hand-written SVGs: the cascade, inheritance and opacity as rendered."""

from __future__ import annotations

import re

import pytest

from alpha_audit.errors import SvgError
from alpha_audit.load.paints import MAX_DEPTH, MAX_ELEMENTS, extract_paints, isolate_paints
from alpha_audit.paints import CURRENT_COLOR

NS = 'xmlns="http://www.w3.org/2000/svg"'


def paints(body: str, root_attrs: str = "") -> list[tuple[str, str, float, str]]:
    svg = f'<svg {NS} viewBox="0 0 24 24" {root_attrs}>{body}</svg>'.encode()
    return [(p.color, p.kind, round(p.opacity, 12), p.element) for p in extract_paints(svg).paints]


def test_an_unset_fill_is_the_hosts_the_manifest_colour_and_no_stroke() -> None:
    # SVG's initial fill is black, but an icon that never sets one is painted by its
    # host (inline SVG inherits CSS fill), which the manifest's colour stands for.
    assert paints('<rect width="4" height="4"/>') == [(CURRENT_COLOR, "fill", 1.0, "<rect>")]


def test_a_fill_the_svg_sets_to_black_stays_black() -> None:
    assert paints('<rect width="4" height="4" fill="black"/>') == [
        ("#000000", "fill", 1.0, "<rect>")
    ]


def test_lucide_style_root_inherits_currentcolor_stroke_and_no_fill() -> None:
    got = paints(
        '<path d="M1 1h4"/><circle id="c" cx="12" cy="12" r="3"/>',
        'fill="none" stroke="currentColor" stroke-width="2"',
    )
    assert got == [
        (CURRENT_COLOR, "stroke", 1.0, "<path>"),
        (CURRENT_COLOR, "stroke", 1.0, '<circle id="c">'),
    ]


def test_nested_group_opacity_multiplies_down() -> None:
    got = paints(
        '<g opacity="0.5"><g opacity="50%"><circle r="2" fill="#ff0000" fill-opacity=".8"/>'
        '</g><rect width="1" height="1" fill="currentColor"/></g>'
    )
    assert got == [("#ff0000", "fill", 0.2, "<circle>"), (CURRENT_COLOR, "fill", 0.5, "<rect>")]


def test_thirty_percent_disc() -> None:
    assert paints('<circle r="8" opacity="0.3"/>') == [(CURRENT_COLOR, "fill", 0.3, "<circle>")]


def test_fill_and_stroke_opacity_inherit_but_opacity_does_not() -> None:
    got = paints(
        '<g fill-opacity="0.5" stroke-opacity="0.25" stroke="#00f">'
        '<rect width="1" height="1" fill="#0f0"/></g>'
    )
    assert got == [("#00ff00", "fill", 0.5, "<rect>"), ("#0000ff", "stroke", 0.25, "<rect>")]


def test_currentcolor_follows_color_set_in_the_svg() -> None:
    got = paints(
        '<g color="#123456"><path d="M0 0h1" fill="currentColor"/></g>'
        '<path d="M0 0h2" fill="currentColor"/>'
    )
    assert got == [("#123456", "fill", 1.0, "<path>"), (CURRENT_COLOR, "fill", 1.0, "<path>")]


def test_fill_none_strokes_and_lines_have_no_fill() -> None:
    got = paints(
        '<path d="M0 0h1" fill="none" stroke="#ff0000"/><line x2="4" stroke="currentColor"/>'
        '<polyline points="0,0 1,1" stroke="none"/>'
    )
    assert got == [
        ("#ff0000", "stroke", 1.0, "<path>"),
        (CURRENT_COLOR, "stroke", 1.0, "<line>"),
        (CURRENT_COLOR, "fill", 1.0, "<polyline>"),
    ]


def test_style_attribute_beats_presentation_attribute() -> None:
    got = paints('<rect width="1" height="1" fill="#ff0000" style="fill: #00ff00; opacity: .5"/>')
    assert got == [("#00ff00", "fill", 0.5, "<rect>")]


def test_css_classes_ids_and_specificity_in_style_element() -> None:
    body = (
        "<style>.a { fill: #111111 } rect.a { fill: #222222 } #x { stroke: #333333 }"
        " g .b { fill: currentColor; fill-opacity: 0.5 } path { fill: #444444 }</style>"
        '<rect class="a" width="1" height="1" fill="#ff0000"/>'
        '<circle class="a" id="x" r="1"/>'
        '<g><path class="b" d="M0 0h1"/></g><path d="M0 0h1"/>'
    )
    assert paints(body) == [
        ("#222222", "fill", 1.0, '<rect class="a">'),  # rect.a beats .a; both beat the attribute
        ("#111111", "fill", 1.0, '<circle id="x">'),
        ("#333333", "stroke", 1.0, '<circle id="x">'),
        (CURRENT_COLOR, "fill", 0.5, '<path class="b">'),  # (0,1,1) beats path (0,0,1)
        ("#444444", "fill", 1.0, "<path>"),
    ]


def test_important_rule_beats_style_attribute() -> None:
    body = (
        "<style>rect { fill: #010101 !important }</style>"
        '<rect style="fill:#ff0000" width="1" height="1"/>'
    )
    assert paints(body) == [("#010101", "fill", 1.0, "<rect>")]


def test_inherit_rgba_named_colours_and_invalid_values() -> None:
    got = paints(
        '<g fill="rgba(255, 0, 0, 0.5)"><rect fill="inherit" width="1" height="1"/></g>'
        '<rect fill="rebeccapurple" width="1" height="1"/>'
        '<g fill="#00ff00"><rect fill="not-a-colour" width="1" height="1"/></g>'
    )
    assert got == [
        ("#ff0000", "fill", 0.5, "<rect>"),
        ("#663399", "fill", 1.0, "<rect>"),
        ("#00ff00", "fill", 1.0, "<rect>"),  # an invalid value is ignored: inherited green
    ]


def test_hidden_and_invisible_paints_are_left_out() -> None:
    got = paints(
        '<g display="none"><rect width="1" height="1"/></g>'
        '<rect visibility="hidden" width="1" height="1"/>'
        '<rect fill="transparent" width="1" height="1"/>'
        '<rect opacity="0" width="1" height="1"/>'
        '<path d="M0 0h1" fill="none" stroke="#000" stroke-width="0"/>'
        '<defs><rect id="d" width="1" height="1"/></defs>'
        '<clipPath id="cp"><rect width="1" height="1"/></clipPath>'
    )
    assert got == []


def test_gradients_patterns_text_images_use_are_not_audited() -> None:
    svg = (
        f'<svg {NS} xmlns:xlink="http://www.w3.org/1999/xlink">'
        '<defs><linearGradient id="g"><stop offset="0" stop-color="red"/></linearGradient>'
        '<pattern id="p" width="1" height="1"/></defs>\n'
        '<rect id="r" fill="url(#g)" stroke="url(#p) red" width="1" height="1"/>\n'
        '<text x="1">Hi</text>\n<image href="x.png" width="1" height="1"/>\n'
        '<use xlink:href="#r"/>\n<rect fill="#0000ff" width="1" height="1"/></svg>'
    ).encode()
    result = extract_paints(svg)
    assert [(p.color, p.kind) for p in result.paints] == [("#0000ff", "fill")]
    assert [(u.element, u.line) for u in result.unaudited] == [
        ('<rect id="r">', 2),
        ('<rect id="r">', 2),
        ("<text>", 3),
        ("<image>", 4),
        ("<use>", 5),
    ]
    reasons = " | ".join(u.reason for u in result.unaudited)
    assert '<linearGradient id="g">' in reasons
    assert '<pattern id="p">' in reasons
    assert result.paints[0].line == 6


def test_fixed_and_groups() -> None:
    result = extract_paints(
        f'<svg {NS} fill="none" stroke="currentColor"><path d="M0 0h1"/><path d="M0 0h2"/>'
        '<circle r="1" fill="#ff0000" stroke="none"/>'
        '<path d="M0 0h3" stroke="#ff0000"/></svg>'.encode()
    )
    groups = result.groups()
    assert [(g.color, g.opacity, len(g.paints), g.fixed) for g in groups] == [
        (CURRENT_COLOR, 1.0, 2, False),
        ("#ff0000", 1.0, 2, True),
    ]
    assert [p.kind for p in groups[1].paints] == ["fill", "stroke"]


@pytest.mark.parametrize(
    ("svg", "message"),
    [
        (b"<svg", "not well-formed XML"),
        (
            b'<?xml version="1.0"?><!DOCTYPE svg [<!ENTITY a "aaaa">]><svg>&a;</svg>',
            "entities",
        ),
        (f"<html {NS}/>".encode(), "no <svg> root"),
        (
            f"<svg {NS}>".encode()
            + b"<g>" * (MAX_DEPTH + 2)
            + b"</g>" * (MAX_DEPTH + 2)
            + b"</svg>",
            "deeper than",
        ),
        (f"<svg {NS}>".encode() + b"<g/>" * (MAX_ELEMENTS + 1) + b"</svg>", "more than"),
        (
            f"<svg {NS}><style>".encode()
            + b"".join(b"*.c%d{fill:red}" % i for i in range(200))
            + b"</style>"
            + b"<rect/>" * 15000
            + b"</svg>",
            "CSS selectors",
        ),
    ],
)
def test_bad_input_and_limits(svg: bytes, message: str) -> None:
    with pytest.raises(SvgError, match=message):
        extract_paints(svg, path="icon.svg")


def test_isolate_keeps_only_the_chosen_paints_opaque() -> None:
    svg = (
        f'<svg {NS} viewBox="0 0 4 4"><style>.s {{ stroke: #00f; stroke-width: 2 }}</style>'
        '<g opacity=".5"><rect class="s" fill="#f00" width="2" height="2"/></g>'
        "<text>a</text></svg>"
    ).encode()
    out = isolate_paints(svg, lambda p: p.kind == "stroke")
    again = extract_paints(out)
    # the style rule survives; the stroke is black at opacity 1, the fill is gone, text hidden
    assert [(p.color, p.kind, p.opacity) for p in again.paints] == [("#000000", "stroke", 1.0)]
    assert b"stroke-width: 2" in out
    assert re.search(rb"<ns0:text style=\"[^\"]*display: none !important", out)


def test_isolated_masks_partition_what_the_renderer_draws() -> None:
    """Rendered by cairosvg: each paint's mask is its own shape, opaque, whatever its opacity."""
    import numpy as np

    from alpha_audit.load.svg import rasterize

    svg = (
        f'<svg {NS} viewBox="0 0 8 8"><style>.l {{ fill: #ff0000 }}</style>'
        '<g opacity="0.3"><rect class="l" width="4" height="8"/></g>'
        '<rect x="4" width="4" height="8" fill="currentColor" fill-opacity="0.5"/></svg>'
    ).encode()
    groups = extract_paints(svg).groups()
    assert [(g.color, g.opacity) for g in groups] == [("#ff0000", 0.3), (CURRENT_COLOR, 0.5)]
    left = rasterize(isolate_paints(svg, lambda p: p.color == "#ff0000"), 8)
    right = rasterize(isolate_paints(svg, lambda p: p.color == CURRENT_COLOR), 8)
    np.testing.assert_array_equal(left[:, :4], 1.0)
    np.testing.assert_array_equal(left[:, 4:], 0.0)
    np.testing.assert_array_equal(right[:, 4:], 1.0)
    np.testing.assert_array_equal(right[:, :4], 0.0)
    # the original draws them translucent: 0.3 and 0.5 in the alpha channel
    whole = rasterize(svg, 8)
    np.testing.assert_allclose(whole[:, :4], 0.3, atol=1 / 255)
    np.testing.assert_allclose(whole[:, 4:], 0.5, atol=1 / 255)


def test_isolated_mask_keeps_mask_content_inherited_from_the_root() -> None:
    """<mask> content inherits the root's fill; isolating must not turn it to none."""
    import numpy as np

    from alpha_audit.load.svg import rasterize

    svg = (
        f'<svg {NS} viewBox="0 0 8 8" fill="#ffffff">'
        '<mask id="m"><rect width="4" height="8"/></mask>'
        '<rect width="8" height="8" fill="currentColor" mask="url(#m)"/></svg>'
    ).encode()
    mask = rasterize(isolate_paints(svg, lambda p: True), 8)
    np.testing.assert_array_equal(mask[:, :4], 1.0)
    np.testing.assert_array_equal(mask[:, 4:], 0.0)


def test_isolating_many_paints_on_many_elements_is_bounded() -> None:
    from alpha_audit.load.paints import MAX_ISOLATE_WORK, paints_and_isolates

    # 11 colours x 1,000 rects: 11,000 elements, each rendered once per colour's mask.
    n = MAX_ISOLATE_WORK // 100
    rects = "".join(f'<rect width="1" height="1" fill="#0000{k:02x}"/>' * n for k in range(11))
    svg = f"<svg {NS}>{rects}</svg>".encode()
    assert len(extract_paints(svg).groups()) == 11 and 11 * 11 * n > MAX_ISOLATE_WORK
    with pytest.raises(SvgError, match="element renders; refused"):
        paints_and_isolates(svg)


def _force_everything(v: object, keep: object) -> dict[str, str]:
    """The reference mask recipe: every property forced on every element, none skipped."""
    from alpha_audit.load import paints as module

    decls = {"opacity": "1", "filter": "none", **dict.fromkeys(module._MARKERS, "none")}
    if v.hidden_kind:  # type: ignore[attr-defined]  # a _Visited, untyped in this test
        decls["display"] = "none"
    if module._local(v.node) in module._SHAPES:  # type: ignore[attr-defined]  # as above
        for kind in ("fill", "stroke"):
            paint = next((p for p in v.paints if p.kind == kind), None)  # type: ignore[attr-defined]  # as above
            drawn = paint is not None and paint.opacity > 0.0 and keep(paint)  # type: ignore[operator]  # a predicate
            decls[kind] = "#000000" if drawn else "none"
            decls[f"{kind}-opacity"] = "1"
    return decls


TRICKY = [
    # a stylesheet that would undo a skipped declaration, on a fixed opaque colour
    '<style>.a { stroke: #0f0; opacity: .5 }</style><rect class="a" width="3" height="3" '
    'fill="#ff0000" stroke-width="2"/><circle cx="6" cy="6" r="2" stroke="currentColor"/>',
    # translucent hex and rgba paints, a group opacity, an invalid opacity
    '<g opacity="0.4"><rect width="4" height="4" fill="#ff000080"/></g>'
    '<rect x="4" width="4" height="4" fill="rgba(0,0,255,0.3)" opacity="x"/>',
    # markers inherited from a group, a filter, text and <use>
    '<defs><marker id="m" markerWidth="2" markerHeight="2"><rect width="2" height="2"/>'
    '</marker><filter id="f"><feGaussianBlur stdDeviation="1"/></filter></defs>'
    '<g marker-end="url(#m)"><path d="M1 1L7 7" stroke="#123456"/></g>'
    '<rect filter="url(#f)" width="2" height="2" fill="#00ff00"/><text y="8">a</text>'
    '<use href="#m"/>',
    # gradients, visibility, inline styles with !important, stroke-opacity inherited
    '<linearGradient id="g"><stop stop-color="#f00"/></linearGradient>'
    '<g stroke-opacity=".5" style="fill: #abc !important"><rect width="3" height="3" '
    'fill="url(#g)" stroke="#fff"/><rect x="3" width="3" height="3" visibility="hidden"/>'
    '<circle cx="6" cy="2" r="1" style="stroke: red; fill: #00f"/></g>',
    # mask and clipPath content inheriting from the root, a host-painted shape
    '<mask id="k"><rect width="4" height="8" fill="#fff"/></mask><clipPath id="c">'
    '<circle cx="4" cy="4" r="3"/></clipPath><rect width="8" height="8" mask="url(#k)" '
    'fill="#ff8800"/><rect width="8" height="8" clip-path="url(#c)"/>',
    # currentColor: drawn as it is only where no color is declared; a translucent color
    # (attribute or rule), color: inherit (cairosvg then inherits the paint) and a
    # lowercase currentcolor (cairosvg does not resolve it) are overridden
    '<path d="M1 1L7 7" stroke="currentColor" stroke-width="2" fill="none"/>',
    '<g color="rgba(0,0,0,0.5)"><path d="M1 1L7 7" stroke="currentColor" stroke-width="2"/></g>',
    '<path d="M1 1L7 7" stroke="currentColor" color="inherit" stroke-width="2"/>'
    '<g stroke="#f00"><path d="M1 7L7 1" stroke="currentColor" color="inherit"/></g>',
    "<style>path { color: rgba(0,0,255,.3) }</style>"
    '<path d="M1 7L7 1" stroke="currentColor" stroke-width="2"/>',
    '<path d="M1 1L7 1" stroke="currentcolor" stroke-width="2"/>',
]


def test_a_currentcolor_icon_with_no_color_is_its_own_mask_svg() -> None:
    """A Lucide-style icon draws opaque black as it is: its one group's SVG is the file
    itself, and its masks are those of the same drawing stroked #000000."""
    import numpy as np

    from alpha_audit.load.paints import paints_and_isolates
    from alpha_audit.load.svg import rasterize

    svg = (
        f'<svg {NS} viewBox="0 0 24 24" fill="none" stroke="currentColor" stroke-width="2">'
        '<path d="M3 12h18M12 3v18"/><circle cx="12" cy="12" r="5"/></svg>'
    ).encode()
    _, (only,) = paints_and_isolates(svg)
    assert only == svg
    black = svg.replace(b'stroke="currentColor"', b'stroke="#000000"')
    for size in (16, 24, 48):
        np.testing.assert_array_equal(rasterize(only, size), rasterize(black, size))


@pytest.mark.parametrize("body", TRICKY)
@pytest.mark.parametrize("root", ["", 'fill="none" stroke="currentColor"', 'opacity="0.5"'])
def test_isolates_draw_what_forcing_every_declaration_draws(
    body: str, root: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Skipping declarations that change nothing leaves every mask unchanged, pixel for pixel."""
    import numpy as np

    from alpha_audit.load import paints as module
    from alpha_audit.load.paints import paints_and_isolates
    from alpha_audit.load.svg import rasterize

    svg = f'<svg {NS} viewBox="0 0 8 8" {root}>{body}</svg>'.encode()
    found, lean = paints_and_isolates(svg)
    monkeypatch.setattr(module, "_overrides", _force_everything)
    _, forced = paints_and_isolates(svg)
    assert len(lean) == len(forced) == len(found.groups()) > 0
    for a, b in zip(lean, forced, strict=True):
        for size in (8, 17, 24):
            np.testing.assert_array_equal(rasterize(a, size), rasterize(b, size))
    assert sum(len(v) for v in lean) < sum(len(v) for v in forced)  # it did skip some


PRUNING = [
    # groups, a <switch>, ids, a clip path that is a <path> with an id, nested shapes
    '<g><rect width="3" height="3" fill="#f00"/><g><circle cx="6" cy="6" r="2" fill="#00f"/>'
    '</g></g><switch><rect width="8" height="1" fill="#0f0"/><rect fill="#f00"/></switch>'
    '<path id="c" d="M0 0h4v4z" fill="#00f"/><rect width="8" height="8" fill="#f00" '
    'clip-path="url(#c)"/><rect x="2" width="2" height="8" fill="#0f0"><circle r="9" '
    'fill="#f00"/></rect>',
    # <use> draws its target whatever its display; <a> and text stay
    '<defs><rect id="r" width="4" height="4"/></defs><use href="#r" fill="#0f0"/>'
    '<a><rect x="4" width="4" height="4" fill="#00f"/></a><text y="8" fill="#f00">a</text>'
    '<g id="keep"><rect y="4" width="4" height="4" fill="#00f"/></g>',
    # a stylesheet of classes and descendants (structure-free: pruning stays)
    "<style>.a { fill: #f00 } g .b { fill: #00f }</style>"
    '<g><rect class="a" width="4" height="4"/><rect class="b" x="4" width="4" height="4"/></g>',
    # a positional selector: what is left out would change what matches
    "<style>rect:first-child { fill: #f00 } rect + rect { stroke: #00f }</style>"
    '<g><rect width="4" height="4" fill="#0f0"/><rect x="4" width="4" height="4"/></g>',
]


@pytest.mark.parametrize("body", PRUNING + TRICKY)
def test_leaving_out_what_draws_nothing_changes_no_mask(
    body: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Each group's SVG without the elements that draw nothing renders pixel for pixel
    what the whole SVG with them unpainted renders."""
    import numpy as np

    from alpha_audit.load import paints as module
    from alpha_audit.load.paints import paints_and_isolates
    from alpha_audit.load.svg import rasterize

    svg = f'<svg {NS} viewBox="0 0 8 8">{body}</svg>'.encode()
    _, pruned = paints_and_isolates(svg)
    monkeypatch.setattr(module, "_prunable", lambda document: set())
    _, whole = paints_and_isolates(svg)
    assert len(pruned) == len(whole) > 0
    for a, b in zip(pruned, whole, strict=True):
        for size in (8, 13, 24):
            np.testing.assert_array_equal(rasterize(a, size), rasterize(b, size))


def test_a_group_svg_holds_only_its_own_shapes_unless_selectors_read_structure() -> None:
    from alpha_audit.load.paints import paints_and_isolates

    flag = "".join(
        f'<rect x="{i}" width="1" height="8" fill="{c}"/>'
        for i, c in enumerate(["#f00", "#0f0"] * 4)
    )
    _, (red, green) = paints_and_isolates(f'<svg {NS} viewBox="0 0 8 8">{flag}</svg>'.encode())
    assert red.count(b"<ns0:rect") == green.count(b"<ns0:rect") == 4
    positional = f"<style>rect:nth-child(3) {{ stroke-width: 2 }}</style>{flag}"
    _, variants = paints_and_isolates(f'<svg {NS} viewBox="0 0 8 8">{positional}</svg>'.encode())
    assert all(v.count(b"<ns0:rect") == 8 for v in variants)


@pytest.mark.parametrize(
    "style",
    ["", "<style>rect:first-child { stroke-width: 1 }</style>"],  # prunable or not
)
def test_a_use_target_is_in_no_groups_mask(style: str) -> None:
    """cairosvg draws a <use>'s target whatever the <use>'s display: the group SVGs must
    not carry one that points anywhere (its paints are not audited)."""
    import numpy as np

    from alpha_audit.load.paints import paints_and_isolates
    from alpha_audit.load.svg import rasterize

    xlink = 'xmlns:xlink="http://www.w3.org/1999/xlink"'
    svg = (
        f'<svg {NS} {xlink} viewBox="0 0 8 8">{style}<defs><rect id="r" width="4" height="4" '
        'fill="#00f"/></defs><rect x="4" y="4" width="4" height="4" fill="#f00"/>'
        '<use xlink:href="#r"/><g><use href="#r" x="4"/></g></svg>'
    ).encode()
    found, (red,) = paints_and_isolates(svg)
    assert [g.color for g in found.groups()] == ["#ff0000"]
    assert [u.element for u in found.unaudited] == ["<use>", "<use>"]
    mask = rasterize(red, 8)
    np.testing.assert_array_equal(mask[4:, 4:], 1.0)  # the red square ...
    assert mask[:4, :].sum() == 0 and mask[:, :4].sum() == 0  # ... and nothing else
    assert rasterize(svg, 8)[:4, :4].sum() > 0  # the whole drawing does show the target
