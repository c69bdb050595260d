"""Recorded spans are exact: the file text at each span is the recorded text and reads back
as the value it was recorded for (manifests, JSON token files, CSS custom properties)."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from alpha_audit.load.iconset import iconset_from_doc
from alpha_audit.load.tokens.jsondoc import parse_json
from alpha_audit.load.tokens.stylesheet import modes_from_stylesheet
from alpha_audit.load.yamldoc import parse_yaml
from alpha_audit.model import Span

ICONS = ("a", "b", "c")
SVG = '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 4 4"><rect width="4" height="4"/></svg>'


def _at(text: str, span: Span) -> str:
    """The text between a span's (line, column) ends, found by splitting lines here."""
    lines = text.split("\n")

    def offset(line: int, column: int) -> int:
        return sum(len(s) + 1 for s in lines[: line - 1]) + column - 1

    return text[offset(span.start_line, span.start_column) : offset(span.end_line, span.end_column)]


@pytest.fixture(scope="module")
def folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("spans")
    for name in ICONS:
        (root / f"{name}.svg").write_text(SVG)
    return root


# ------------------------------------------------------------------ manifests

HEXES = st.sampled_from(["#ee7733", "#0077BB", "#3be", "#cc3311ff"])
PLAIN = st.sampled_from(["red", "oklch(0.7 0.1 40)", "rgb(10 20 30)", "hsl(120 50% 40%)"])


@st.composite
def colour_text(draw: st.DrawFn) -> tuple[str, str]:
    """(YAML text of a colour, the colour string it means)."""
    style = draw(st.sampled_from(["single", "double", "plain"]))
    if style == "plain":
        value = draw(PLAIN)
        return value, value
    value = draw(st.one_of(HEXES, PLAIN))
    return (f"'{value}'" if style == "single" else f'"{value}"'), value


ALPHAS = st.sampled_from(["1.2", "1", "0.85", "1.25e0", "2.", "+1.5"])
GAP = st.sampled_from([" ", "  ", "   "])
COMMENT = st.sampled_from(["", "  # note", " #x"])


@st.composite
def manifests(draw: st.DrawFn) -> tuple[str, dict[str, str], dict[str, str]]:
    """(manifest text, palette name -> colour, icon -> alpha text that applies)."""
    names = draw(st.lists(st.sampled_from(["ink", "sky", "warn", "mint"]), min_size=1, unique=True))
    entries = {n: draw(colour_text()) for n in names}
    flow_palette = draw(st.booleans())
    lines = ["name: s"]
    own: dict[str, str] = {}  # alphas written on the icons: entries
    if draw(st.booleans()):
        lines.append("icons: [a.svg, b.svg, c.svg]")
    else:
        lines.append("icons:")
        for icon in ICONS:
            if draw(st.booleans()):
                own[icon] = draw(ALPHAS)
                lines.append(f"  - {{file: {icon}.svg, alpha:{draw(GAP)}{own[icon]}}}")
            else:
                lines.append(f"  - file: '{icon}.svg'{draw(COMMENT)}")
    if flow_palette:
        body = ", ".join(f"{n}:{draw(GAP)}{t}" for n, (t, _) in entries.items())
        lines.append(f"palette: {{{body}}}{draw(COMMENT)}")
    else:
        lines.append("palette:")
        lines += [f"  {n}:{draw(GAP)}{t}{draw(COMMENT)}" for n, (t, _) in entries.items()]
    lines.append("color: cycle")
    set_alpha = draw(ALPHAS)
    lines.append(f"alpha:{draw(GAP)}{set_alpha}{draw(COMMENT)}")
    alphas = {icon: own.get(icon, set_alpha) for icon in ICONS}
    overridden = draw(st.lists(st.sampled_from(ICONS), unique=True))
    if overridden:
        lines.append("overrides:")
        for icon in overridden:
            alpha = draw(ALPHAS)
            alphas[icon] = alpha
            if draw(st.booleans()):
                lines.append(f"  {icon}: {{alpha:{draw(GAP)}{alpha}}}{draw(COMMENT)}")
            else:
                lines += [f"  {icon}:", f"    alpha:{draw(GAP)}{alpha}{draw(COMMENT)}"]
    newline = draw(st.sampled_from(["\n", "\r\n"]))
    return newline.join(lines) + newline, {n: v for n, (_, v) in entries.items()}, alphas


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(manifests())
def test_manifest_spans_are_exact(
    folder: Path, manifest: tuple[str, dict[str, str], dict[str, str]]
) -> None:
    text, palette, alphas = manifest
    doc = parse_yaml(text, folder / "set.yaml")
    iconset = iconset_from_doc(doc, root=folder)
    for span in doc.spans.values():  # every recorded span, not only the icons'
        assert _at(text, span) == span.text
        assert "\n" not in span.text
    for icon in iconset.icons:
        # Every value here is written in the file, so every icon has both spans.
        assert icon.color_span is not None and icon.alpha_span is not None
        assert _at(text, icon.color_span) == icon.color_span.text
        assert yaml.safe_load(icon.color_span.text) == palette[icon.color_name or ""]
        assert _at(text, icon.alpha_span) == icon.alpha_span.text == alphas[icon.name]
        assert float(icon.alpha_span.text) == icon.alpha


def test_a_value_with_an_anchor_tag_or_several_lines_has_no_span(folder: Path) -> None:
    text = (
        "name: s\nicons: [a.svg]\npalette:\n  ink: &brand '#112233'\n  sky: !!str '#445566'\n"
        "  mint: >-\n    #778899\n  again: *brand\n  wide: '#aa\n    bbcc'\n"
        "color: ink\nalpha: 1.2\n"
    )
    doc = parse_yaml(text, folder / "set.yaml")
    assert ("palette", "ink") not in doc.spans  # replacing it would drop the anchor
    assert ("palette", "again") not in doc.spans  # the alias is the anchored value
    assert ("palette", "sky") not in doc.spans  # or the tag
    assert ("palette", "mint") not in doc.spans  # a block scalar
    assert ("palette", "wide") not in doc.spans  # a scalar over two lines
    assert doc.spans[("alpha",)].text == "1.2"


def test_an_unwritten_alpha_or_a_defaulted_colour_has_no_span(folder: Path) -> None:
    text = 'name: s\nicons: [a.svg, b.svg]\ncolor: "#123456"\noverrides:\n  b: {alpha: 1.5}\n'
    iconset = iconset_from_doc(parse_yaml(text, folder / "set.yaml"), root=folder)
    a, b = iconset.icons
    assert a.alpha_span is None  # the default 1 is written nowhere
    assert b.alpha_span is not None and b.alpha_span.text == "1.5"
    assert a.color_span == b.color_span and a.color_span is not None
    assert a.color_span.text == '"#123456"'
    assert iconset.with_alpha(1.1).icons[1].alpha_span is None  # --alpha: from no file


# ------------------------------------------------------------------ JSON tokens

_KEYS = st.one_of(
    st.text(alphabet="abcxyz-é", min_size=1, max_size=4), st.sampled_from(["$value", "value"])
)
_STRINGS = st.text(alphabet='#0aF"\\/é\u2028 \t', max_size=6)
_JSON: Any = st.recursive(
    st.one_of(_STRINGS, st.integers(-5, 5), st.booleans(), st.none()),
    lambda inner: st.one_of(st.lists(inner, max_size=3), st.dictionaries(_KEYS, inner, max_size=3)),
    max_leaves=12,
)


def _strings(data: Any, keys: tuple[Any, ...] = ()) -> dict[tuple[Any, ...], str]:
    """Every string that is the value of a ``$value`` or ``value`` member."""
    if isinstance(data, str):
        return {keys: data} if keys and keys[-1] in ("$value", "value") else {}
    items = (
        data.items()
        if isinstance(data, dict)
        else enumerate(data)
        if isinstance(data, list)
        else []
    )
    out: dict[tuple[Any, ...], str] = {}
    for k, v in items:
        out.update(_strings(v, (*keys, k)))
    return out


@settings(max_examples=80, deadline=None)
@given(
    st.dictionaries(_KEYS, _JSON, max_size=4),
    st.sampled_from([None, 0, 2, "\t"]),
    st.booleans(),
    st.booleans(),
)
def test_json_string_spans_are_exact(
    data: dict[str, Any], indent: Any, ascii: bool, crlf: bool
) -> None:
    text = json.dumps(data, indent=indent, ensure_ascii=ascii)
    if crlf:
        text = text.replace("\n", "\r\n")
    doc = parse_json(text, "t.json")
    expected = _strings(data)
    assert set(doc.offsets) == set(expected)  # every token value string, and nothing else
    for keys in doc.offsets:
        span = doc.span(keys)
        assert span is not None and _at(text, span) == span.text
        assert json.loads(span.text) == expected[keys]


def test_dtcg_token_spans_follow_aliases_to_the_literal(tmp_path: Path) -> None:
    from alpha_audit.load.tokens import load_token_modes

    text = (
        '{"palette": {"$type": "color",\n'
        '  "red": {"$value": "#cc3311"},\n'
        '  "obj": {"$value": {"colorSpace": "srgb", "components": [1, 0, 0]}}},\n'
        ' "icon": {"$type": "color", "danger": {"$value": "{palette.red}"},\n'
        '  "solid": {"$value": "{palette.obj}"}}}\n'
    )
    path = tmp_path / "t.tokens.json"
    path.write_text(text)
    tokens = load_token_modes(path).modes["default"]
    danger = tokens["icon.danger"].span
    assert danger is not None and danger.text == '"#cc3311"' and _at(text, danger) == danger.text
    assert danger.start_line == 2  # the literal, not the alias
    assert tokens["icon.solid"].span is None  # a colour object: no single value to replace


# ------------------------------------------------------------------ CSS


def test_css_value_spans_are_exact_or_absent(tmp_path: Path) -> None:
    text = (
        "@theme {\r\n  --color-a: #ff0000;\n\t--color-é-b:  oklch(63.7% 0.237 25.331) ;\n"
        "  --color-c: var(--color-a); --color-d: oklch(0.5 /*x*/ 0.1 20);\n}\n"
    )
    path = tmp_path / "theme.css"
    path.write_bytes(text.encode())
    tokens = modes_from_stylesheet(path).modes["default"]
    for name, value in (("color.a", "#ff0000"), ("color.é.b", "oklch(63.7% 0.237 25.331)")):
        span = tokens[name].span
        assert span is not None and span.text == value and _at(text, span) == value
    assert tokens["color.c"].span == tokens["color.a"].span  # the alias's literal
    assert tokens["color.d"].span is None  # a comment inside: the serialisation differs


def test_css_with_a_lone_cr_records_no_span(tmp_path: Path) -> None:
    path = tmp_path / "theme.css"
    path.write_bytes(b"@theme {\r  --color-a: #ff0000;\n}\n")
    assert modes_from_stylesheet(path).modes["default"]["color.a"].span is None


def test_tokens_studio_values_have_their_spans(tmp_path: Path) -> None:
    from alpha_audit.load.tokens import load_token_modes

    text = (
        '{"core": {"warm": {"value": "#ee7733", "type": "color"},\n'
        '          "alias": {"value": "{warm}", "type": "color"}},\n'
        ' "$themes": [], "$metadata": {"tokenSetOrder": ["core"]}}\n'
    )
    path = tmp_path / "tokens.json"
    path.write_text(text)
    modes = load_token_modes(path)
    assert modes.kind == "tokens-studio"
    tokens = next(iter(modes.modes.values()))
    span = tokens["warm"].span
    assert span is not None and span.text == '"#ee7733"' and _at(text, span) == span.text
    assert tokens["alias"].span == span
