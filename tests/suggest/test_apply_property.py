"""The manifest editor, as a property: the re-read manifest says exactly the requested alphas,
and every line the edit had no reason to touch is byte for byte what it was."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from alpha_audit.load.iconset import load_iconset
from alpha_audit.suggest.apply import edit_alphas, explicit_alpha_icons, format_alpha, set_alpha

NAMES = ("alert", "b", "check-mark", "d", "e")
ICON_STYLES = ("bare", "flow", "flow-alpha", "block-alpha")
OVERRIDE_STYLES = ("flow-colour", "flow-alpha", "block-colour", "block-alpha")
# Lines the editor may add: a top-level alpha, an overrides section, a new entry, a block alpha.
ADDED = re.compile(r" *(alpha: -?[\d.]+|overrides:|[\w-]+: +\{alpha: -?[\d.]+\})")

alphas = st.floats(-5, 5, allow_nan=False).map(lambda a: format_alpha(a, 3))
gaps = st.integers(1, 6).map(lambda n: " " * n)
COMMENT = "# why"
comments = st.one_of(st.just(""), gaps.map(lambda g: g + COMMENT))


@st.composite
def manifests(draw: st.DrawFn) -> tuple[list[str], list[str | None], list[str]]:
    """(lines, the icon or ``top`` each line holds an alpha or override for, icon names)."""
    lines: list[tuple[str, str | None]] = []
    if draw(st.booleans()):
        lines.append(("# Demo icons -- keep this comment", None))
    lines += [("name: Demo", None), ("icons:", None)]
    names = draw(st.lists(st.sampled_from(NAMES), min_size=1, max_size=5, unique=True))
    for name in names:
        style, value, note = draw(st.sampled_from(ICON_STYLES)), draw(alphas), draw(comments)
        if style == "bare":
            lines.append((f"  - {name}.svg{note}", None))
        elif style == "flow":
            lines.append((f"  - {{file: {name}.svg}}{note}", None))
        elif style == "flow-alpha":
            lines.append((f"  - {{file: {name}.svg, alpha: {value}}}{note}", name))
        else:
            lines += [(f"  - file: {name}.svg", None), (f"    alpha: {value}{note}", name)]
    lines.append(("color: '#ee7733'", None))
    if draw(st.booleans()):
        lines.append((f"alpha:{draw(gaps)}{draw(alphas)}{draw(comments)}", "top"))
    overridden = draw(st.lists(st.sampled_from(names), unique=True))
    if overridden:
        lines.append(("overrides:", None))
        column = max(len(n) for n in overridden) + 4  # values aligned in one column
        for name in overridden:
            head = f"  {name}:"
            pad = " " * (column - len(head))
            style, value, note = (
                draw(st.sampled_from(OVERRIDE_STYLES)),
                draw(alphas),
                draw(comments),
            )
            if style == "flow-colour":
                lines.append((f'{head}{pad}{{color: "#0077bb"}}{note}', name))
            elif style == "flow-alpha":
                lines.append((f"{head}{pad}{{alpha: {value}}}{note}", name))
            elif style == "block-colour":
                lines += [(head, None), ('    color: "#0077bb"' + note, None)]
            else:
                lines += [(head, None), (f"    alpha: {value}{note}", name)]
    return [t for t, _ in lines], [tag for _, tag in lines], names


@pytest.fixture(scope="module")
def project(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("project")
    (root / ".git").mkdir()
    for name in NAMES:
        (root / f"{name}.svg").write_text("<svg xmlns='http://www.w3.org/2000/svg'/>")
    return root


def _alphas(project: Path, text: str) -> dict[str, float]:
    path = project / "iconset.yaml"
    path.write_text(text, encoding="utf-8")
    return {icon.name: icon.alpha for icon in load_iconset(path).icons}


def _normalised(line: str) -> str:
    """``line`` with its alpha values and the spaces before its comment made uniform."""
    return re.sub(r" +#", " #", re.sub(r"(alpha: +)-?[\d.]+", r"\1V", line))


def _may_become(before: str, after: str) -> bool:
    """Whether ``after`` is ``before`` with an alpha value set (replaced, or added to a mapping)."""
    was, now = before.find(COMMENT), after.find(COMMENT)
    if (was < 0) != (now < 0):
        return False  # a comment is never added or dropped
    b, a = _normalised(before), _normalised(after)
    if a == b:  # a value replaced: its comment moves only if the value no longer fits
        return was < 0 or was == now or after[now - 2] != " "
    # An alpha added to a flow mapping: the line grows, the gap before its comment stays.
    gap_kept = was < 0 or after[now - 2 :] == before[was - 2 :]
    return a == b.replace("}", ", alpha: V}", 1) and gap_kept


@settings(max_examples=150, deadline=None)
@given(manifest=manifests(), data=st.data())
def test_editing_sets_exactly_the_requested_alphas_and_nothing_else(
    project: Path, manifest: tuple[list[str], list[str | None], list[str]], data: st.DataObject
) -> None:
    lines, tags, names = manifest
    eol = data.draw(st.sampled_from(["\n", "\r\n"]))
    text = eol.join(lines) + eol
    top = data.draw(st.none() | alphas)
    icons = data.draw(st.dictionaries(st.sampled_from(names), alphas))

    before = _alphas(project, text)
    edited = edit_alphas(text, top=top, icons=icons)
    after = _alphas(project, edited)

    # Re-read: the requested alphas exactly, the top level for icons without their own.
    explicit = explicit_alpha_icons(text)
    for name in names:
        if name in icons:
            expected = float(icons[name])
        elif top is not None and name not in explicit:
            expected = float(top)
        else:
            expected = before[name]
        assert after[name] == expected, (name, edited)

    # Every original line is still there, in order: unchanged, or (if it held an alpha
    # the edit asked for) with only that alpha set; any other line is one the edit added.
    wanted = set(icons) | ({"top"} if top is not None else set())
    new = edited.split(eol)
    assert new[-1] == "" and all("\r" not in line for line in new)  # line endings kept
    j = 0
    for line, tag in zip(lines, tags, strict=True):
        while j < len(new) and new[j] != line and ADDED.fullmatch(new[j]):
            if tag in wanted and _may_become(line, new[j]):
                break
            j += 1
        assert j < len(new), (line, edited)
        assert new[j] == line or (tag in wanted and _may_become(line, new[j])), (line, new[j])
        j += 1
    assert all(ADDED.fullmatch(line) for line in new[j:-1]), edited


@settings(max_examples=60, deadline=None)
@given(manifest=manifests(), value=alphas)
def test_the_set_wide_edit_gives_every_icon_the_value(
    project: Path, manifest: tuple[list[str], list[str | None], list[str]], value: str
) -> None:
    lines, _, names = manifest
    text = "\n".join(lines) + "\n"
    assert _alphas(project, set_alpha(text, value)) == dict.fromkeys(names, float(value))
