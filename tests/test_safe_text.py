"""One sanitiser for printed text: every instruction character escaped, text kept."""

from __future__ import annotations

import re
import unicodedata

import pytest
from hypothesis import given
from hypothesis import strategies as st

from alpha_audit.errors import InputError
from alpha_audit.render.github import escape_data
from alpha_audit.safe_text import JOINERS, UNSAFE_CATEGORIES, first_unsafe, safe_text

HOSTILE = [
    "\x1b]52;c;SGVsbG8=\x07",  # OSC 52: write the reviewer's clipboard
    "\x1b]8;;https://evil/\x1b\\link\x1b]8;;\x1b\\",  # OSC 8 hyperlink
    "\x1b[2J\x1b[H",  # clear screen
    "\x9b2J",  # C1 CSI, one byte
    "name\n::add-mask::secret",  # forged workflow command
    "\r::stop-commands::x",
    "a\u202eexe.svg",  # RIGHT-TO-LEFT OVERRIDE (Trojan Source)
    "\u2066isolate\u2069",
    "\ud800",  # lone surrogate
    "line\u2028sep",
]


@pytest.mark.parametrize("text", HOSTILE)
def test_hostile_strings_become_printable_one_line_utf8(text: str) -> None:
    out = safe_text(text)
    assert first_unsafe(out) is None
    assert "\n" not in out and "\r" not in out and "\x1b" not in out
    out.encode("utf-8")  # no UnicodeEncodeError


@given(st.text())
def test_output_never_holds_an_unsafe_character_and_safe_text_is_kept(text: str) -> None:
    out = safe_text(text)
    assert all(ch in JOINERS or unicodedata.category(ch) not in UNSAFE_CATEGORIES for ch in out)
    if first_unsafe(text) is None:
        assert out == text


def test_ordinary_unicode_passes_unchanged() -> None:
    assert safe_text("Café ΔE00 ≥ 3 — 日本") == "Café ΔE00 ≥ 3 — 日本"


def test_error_str_is_sanitised_in_keys_and_paths() -> None:
    err = InputError("bad value", path="icons/\x1b]52;c;x\x07.yaml", key="ca\u202envas")
    text = str(err)
    assert first_unsafe(text) is None and "\\x1b" in text and "\\u202e" in text


def test_github_escape_keeps_newline_escaping_and_drops_escape_sequences() -> None:
    assert escape_data("a\nb") == "a%0Ab"
    out = escape_data("x\x1b[31m\u202e")
    assert "\x1b" not in out and "\u202e" not in out and "%0A" not in out


@pytest.mark.parametrize(
    ("name", "said"),
    [
        ("a\u202eb", "the bidi control U+202E (RIGHT-TO-LEFT OVERRIDE)"),
        ("\ud800", "the lone surrogate U+D800"),
        ("x\u2066y", "the bidi control U+2066 (LEFT-TO-RIGHT ISOLATE)"),
        ("bell\x07", "the control character U+0007"),
        ("c1\x9b", "the control character U+009B"),
        ("zw\u200bsp", "the invisible format character U+200B (ZERO WIDTH SPACE)"),
    ],
)
def test_names_and_reasons_with_unsafe_characters_are_refused(
    tmp_path, name: str, said: str
) -> None:
    from alpha_audit.load.config import config_from_doc
    from alpha_audit.load.theme import theme_from_doc
    from alpha_audit.load.yamldoc import parse_yaml

    escaped = name.encode("unicode_escape").decode("ascii")
    theme = parse_yaml(
        f'name: t\ncanvases: [{{name: "{escaped}", color: "#fff"}}]\n', tmp_path / "t.yaml"
    )
    with pytest.raises(InputError) as info:
        theme_from_doc(theme)
    message = str(info.value)
    assert message.startswith(f"{tmp_path / 't.yaml'}:2: canvases[0].name: '")
    assert f"has {said}; names may not hold control" in message
    assert first_unsafe(message) is None and escaped.lower() in message.lower()
    config = parse_yaml(
        f'exempt:\n  - {{icon: a, reason: "{escaped}"}}\n', tmp_path / "alpha-audit.yaml"
    )
    with pytest.raises(InputError, match=f"reason '.*' has {re.escape(said)}") as info:
        config_from_doc(config)
    assert first_unsafe(str(info.value)) is None


def test_emoji_joiners_are_text() -> None:
    assert safe_text("👩\u200d💻") == "👩\u200d💻" and first_unsafe("a\u200cb") is None


def test_emoji_tag_sequences_are_text_and_stray_tags_are_not() -> None:
    scotland = "\U0001f3f4\U000e0067\U000e0062\U000e0073\U000e0063\U000e0074\U000e007f"
    assert first_unsafe(f"flag {scotland}") is None and safe_text(scotland) == scotland
    hidden = "ok\U000e0069\U000e0067\U000e006e"  # tag letters smuggling "ign" invisibly
    assert first_unsafe(hidden) == "\U000e0069"
    assert safe_text(f"{scotland}{hidden}") == f"{scotland}ok\\U000e0069\\U000e0067\\U000e006e"
    # A flag followed by an upper-case tag is no subdivision flag (UTS #51, ED-14a).
    assert first_unsafe("\U0001f3f4\U000e0047\U000e0042\U000e007f") == "\U000e0047"


@pytest.mark.parametrize(
    ("ch", "said"),
    [
        ("\x1b", "the control character U+001B"),
        ("\u200f", "the bidi control U+200F (RIGHT-TO-LEFT MARK)"),
        ("\u061c", "the bidi control U+061C (ARABIC LETTER MARK)"),
        ("\ufeff", "the invisible format character U+FEFF (ZERO WIDTH NO-BREAK SPACE)"),
        ("\udfff", "the lone surrogate U+DFFF"),
        ("\u2029", "the paragraph separator U+2029"),
    ],
)
def test_refused_characters_are_described_by_kind_and_code_point(ch: str, said: str) -> None:
    from alpha_audit.safe_text import describe_char

    assert first_unsafe(f"a{ch}") == ch and describe_char(ch) == said
