"""CSS modes as a browser resolves them: the minimal case of each defect of issue 29.

Each sheet's expected values are worked out here from the cascade rules (Selectors
4 matching, CSS Cascade 5 order, custom properties inheriting from ``<html>`` to
``<body>`` as computed values); test_modes_in_browser.py checks the same sheets,
and the real packages they come from, against Chromium.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from alpha_audit.load.tokens import load_token_modes
from alpha_audit.load.tokens.model import ModeConditions

# name -> (sheet, {mode: {token: value}}, modes in order)
MINIMAL: dict[str, tuple[str, dict[str, dict[str, str]], list[str]]] = {
    # PatternFly 6: a combined theme also matches each of its parts.
    "compound": (
        ":root{--bg:#ffffff;--fg:#1f1f1f} :root:where(.dark){--bg:#292929;--fg:#f2f2f2}"
        " :root:where(.dark.felt){--radius:4px}",
        {
            "default": {"bg": "#ffffff", "fg": "#1f1f1f"},
            "dark": {"bg": "#292929", "fg": "#f2f2f2"},
            "dark-felt": {"bg": "#292929", "fg": "#f2f2f2", "radius": "4px"},
        },
        ["default", "dark", "dark-felt"],
    ),
    # Mantine 9: a selector list is read item by item; :host(X) is the root with X.
    "host-list": (
        ':root{--bg:#fff} :root[data-scheme="dark"], :host([data-scheme="dark"]){--bg:#111}',
        {"default": {"bg": "#fff"}, "dark": {"bg": "#111"}},
        ["default", "dark"],
    ),
    # Carbon: the root sets no colour, so it is no mode; each theme class is one.
    "no-root-colour": (
        ":root{--font:serif} .theme-white{--bg:#ffffff;--fg:#0062ba}"
        " .theme-g100{--bg:#161616;--fg:#78a9ff}",
        {
            "theme-white": {"bg": "#ffffff", "fg": "#0062ba"},
            "theme-g100": {"bg": "#161616", "fg": "#78a9ff"},
        },
        ["theme-white", "theme-g100"],
    ),
    # Twilio Paste: a body theme wins over what <body> inherits from the root, and a
    # root property that uses var() keeps the value computed on the root.
    "body-theme": (
        ':root{--bg:#fff;--ink:#000;--fg:var(--ink)} body[data-theme="dark"]{--bg:#000;--ink:#fff}',
        {
            "default": {"bg": "#fff", "ink": "#000", "fg": "#000"},
            "dark": {"bg": "#000", "ink": "#fff", "fg": "#000"},
        },
        ["default", "dark"],
    ),
    # Mantine's component classes that set sizes only are no modes.
    "no-colour-rules": (
        ":root{--bg:#fff;--scale:1} .m_1{--size:2rem} .m_2{--pad:calc(1rem * var(--scale))}",
        {"default": {"bg": "#fff"}},
        ["default"],
    ),
    # Specificity across items, then :not() on the root.
    "cascade": (
        ":root:not(.dark){--bg:#fff} :root.dark{--bg:#111} .dark{--bg:#222;--fg:#eee}",
        {"default": {"bg": "#fff"}, "dark": {"bg": "#111", "fg": "#eee"}},
        ["default", "dark"],
    ),
    # A theme changing what a root colour computes (a hue) is a mode.
    "var-on-root": (
        ":root{--hue:0;--bg:hsl(var(--hue) 50% 50%)} .blue{--hue:240}",
        {
            "default": {"bg": "hsl(0 50% 50%)"},
            "blue": {"bg": "hsl(240 50% 50%)"},
        },
        ["default", "blue"],
    ),
}


@pytest.mark.parametrize("case", sorted(MINIMAL))
def test_minimal_sheet_modes_and_values(case: str, tmp_path: Path) -> None:
    text, expected, order = MINIMAL[case]
    sheet = tmp_path / f"{case}.css"
    sheet.write_text(text, encoding="utf-8")
    modes = load_token_modes(sheet)
    assert list(modes.modes) == order
    for mode, values in expected.items():
        got = {path: modes.modes[mode][path].value for path in values}
        assert got == values, mode


def test_the_host_form_is_the_same_state_as_the_root_form(tmp_path: Path) -> None:
    sheet = tmp_path / "m.css"
    sheet.write_text(MINIMAL["host-list"][0], encoding="utf-8")
    modes = load_token_modes(sheet)
    assert modes.conditions["dark"] == ModeConditions(root_attributes=(("data-scheme", "dark"),))
    assert modes.aliases == {}


def test_body_themes_are_conditions_on_body(tmp_path: Path) -> None:
    sheet = tmp_path / "b.css"
    sheet.write_text(MINIMAL["body-theme"][0], encoding="utf-8")
    state = load_token_modes(sheet).conditions["dark"]
    assert state == ModeConditions(body_attributes=(("data-theme", "dark"),))
    assert state.selector() == 'body[data-theme="dark"]'


def test_states_computing_the_same_values_are_aliases(tmp_path: Path) -> None:
    sheet = tmp_path / "r.css"
    sheet.write_text(
        ":root, .light {--bg:#fff} .dark, .dark-theme {--bg:#111}\n"
        "@media (prefers-color-scheme: dark) { :root:not(.light) {--bg:#111} }",
        encoding="utf-8",
    )
    modes = load_token_modes(sheet)
    # .dark names the class; the page without classes in a dark OS is written out.
    assert list(modes.modes) == ["default", "prefers-dark", "dark"]
    assert modes.conditions["prefers-dark"] == ModeConditions(scheme="dark")
    assert modes.modes["prefers-dark"]["bg"].value == "#111"
    assert modes.aliases["light"] == "default"
    assert modes.aliases["dark-theme"] == "dark"
    # .dark in a dark OS computes what the dark OS alone does (the media rule wins).
    assert modes.aliases[".dark+prefers-dark"] == "prefers-dark"


def test_a_name_taken_by_another_state_is_written_out(tmp_path: Path) -> None:
    sheet = tmp_path / "p.css"
    sheet.write_text(
        '[data-mode="dark"][data-dark-theme="dark"] {--bg:#111}\n'
        '@media (prefers-color-scheme: dark) { [data-mode="auto"][data-dark-theme="dark"] '
        "{--bg:#121212} }",
        encoding="utf-8",
    )
    modes = load_token_modes(sheet)
    assert list(modes.modes) == ["dark", "auto-dark"]
    assert modes.conditions["auto-dark"].scheme == "dark"
    assert modes.modes["auto-dark"]["bg"].value == "#121212"
