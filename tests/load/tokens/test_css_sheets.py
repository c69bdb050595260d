"""CSS token sheets as real systems ship them: layers, dark modes, non-colour properties."""

from __future__ import annotations

from pathlib import Path

import pytest
from coloraide import Color

from alpha_audit.errors import InputError
from alpha_audit.load.tokens import load_token_modes, token_color
from alpha_audit.load.tokens.themes import TokenConfig, token_themes


def _load(tmp_path: Path, text: str):
    path = tmp_path / "tokens.css"
    path.write_text(text)
    return load_token_modes(path, root=tmp_path)


def _themes(tmp_path: Path, text: str, canvases=("bg",), colors=("fg",)):
    modes = _load(tmp_path, text)
    return token_themes(
        modes, TokenConfig(file=modes.source, canvases=tuple(canvases), colors=tuple(colors))
    )


def _hex(text: str) -> str:
    return Color(text).convert("srgb").to_string(hex=True)


def _colors(themes) -> dict[str, dict[str, str]]:
    out = {}
    for mode in themes.modes:
        found = {c.name: _hex(c.color) for c in mode.theme.canvases}
        found.update({p: _hex(c.css) for p, c in mode.colors.items()})
        out[mode.name] = found
    return out


def test_a_var_to_a_length_does_not_refuse_the_sheet(tmp_path: Path) -> None:
    themes = _themes(
        tmp_path, ":root { --bg: #ffffff; --fg: #0062ba; --space: 4px; --gap: var(--space); }"
    )
    assert _colors(themes) == {"default": {"bg": "#ffffff", "fg": "#0062ba"}}


def test_a_selected_token_that_is_no_colour_names_its_chain(tmp_path: Path) -> None:
    text = ":root { --bg: #fff; --space: 4px; --fg: var(--gap); --gap: var(--space); }"
    with pytest.raises(InputError, match=r"tokens\.css:1: fg: is '4px' \(via fg -> gap -> space\)"):
        _themes(tmp_path, text)


def test_layers_are_read_in_layer_order(tmp_path: Path) -> None:
    text = (
        "@layer base, theme;\n"
        "@layer theme { :root { --bg: #fff; --fg: #0062ba } }\n"
        "@layer base { :root { --bg: #000; --fg: #111 } }\n"
    )
    # "theme" is declared after "base", so it wins although it comes first in the file.
    assert _colors(_themes(tmp_path, text)) == {"default": {"bg": "#ffffff", "fg": "#0062ba"}}
    unlayered = "@layer theme { :root { --bg: #fff; --fg: #0062ba } }\n:root { --fg: #222 }\n"
    assert _colors(_themes(tmp_path, unlayered))["default"]["fg"] == "#222222"


def test_utility_classes_that_set_no_custom_property_are_no_modes(tmp_path: Path) -> None:
    text = ":root { --bg: #fff; --fg: #0062ba }\n.type-title { font-family: serif }\n"
    text += "".join(f".u{i} {{ margin: {i}px }}\n" for i in range(13))
    assert [m.name for m in _themes(tmp_path, text).modes] == ["default"]


@pytest.mark.parametrize(
    "dark",
    [
        '[data-color-scheme="dark"] { --bg: #111; --fg: #9cf }',
        "[data-mode=dark] { --bg: #111; --fg: #9cf }",
        ":root.dark { --bg: #111; --fg: #9cf }",
        "@media (prefers-color-scheme: dark) { :root { --bg: #111; --fg: #9cf } }",
        "@media only screen and (prefers-color-scheme: dark) { :root:not([data-theme]) "
        "{ --bg: #111; --fg: #9cf } }",
    ],
)
def test_dark_modes_written_the_common_ways(tmp_path: Path, dark: str) -> None:
    themes = _themes(tmp_path, ":root { --bg: #fff; --fg: #0062ba }\n" + dark)
    assert _colors(themes) == {
        "default": {"bg": "#ffffff", "fg": "#0062ba"},
        "dark": {"bg": "#111111", "fg": "#99ccff"},
    }
    assert any(note.startswith("mode dark from tokens.css: line 2") for note in themes.notes)


def test_light_dark_values_give_both_modes(tmp_path: Path) -> None:
    text = ":root { color-scheme: light dark; --bg: light-dark(#fff, #111); --fg: #0062ba }"
    assert _colors(_themes(tmp_path, text)) == {
        "default": {"bg": "#ffffff", "fg": "#0062ba"},
        "dark": {"bg": "#111111", "fg": "#0062ba"},
    }


def test_a_named_mode_under_a_dark_media_query(tmp_path: Path) -> None:
    text = (
        ":root { --bg: #fff; --fg: #0062ba }\n"
        "@media (prefers-color-scheme: light) { [data-color-scheme=auto] { --bg: #eee } }\n"
        "@media (prefers-color-scheme: dark) { [data-color-scheme=auto] { --bg: #222 } }\n"
    )
    colors = _colors(_themes(tmp_path, text))
    assert colors["auto"]["bg"] == "#eeeeee" and colors["auto-dark"]["bg"] == "#222222"


def test_specificity_and_source_order_decide_as_in_a_browser(tmp_path: Path) -> None:
    text = (
        ":where(html) { --bg: #000; --fg: #000 }\n"  # specificity 0: loses to html
        "html { --bg: #fff; --fg: #0062ba }\n"
        ".dark { --bg: #111 }\n"
        "html.dark { --fg: #9cf }\n"
    )
    assert _colors(_themes(tmp_path, text)) == {
        "default": {"bg": "#ffffff", "fg": "#0062ba"},
        "dark": {"bg": "#111111", "fg": "#99ccff"},
    }


def test_rules_for_parts_of_the_page_are_skipped_and_warned_about(tmp_path: Path) -> None:
    text = (
        ":root { --bg: #fff; --fg: #0062ba }\n"
        ".card .title { --fg: #f00 }\n"
        "@media (min-width: 768px) { :root { --fg: #0f0 } }\n"
    )
    themes = _themes(tmp_path, text)
    assert _colors(themes) == {"default": {"bg": "#ffffff", "fg": "#0062ba"}}
    (note,) = [n for n in themes.notes if n.startswith("fg:")]
    assert "line 2" in note and "not audited" in note


def test_one_selector_list_is_one_mode(tmp_path: Path) -> None:
    text = ":root, .light { --bg: #fff; --fg: #0062ba }\n.dark, .dark-theme { --bg: #111 }\n"
    assert [m.name for m in _themes(tmp_path, text).modes] == ["default", "dark"]


def test_css_escapes_are_unescaped_and_collisions_are_errors(tmp_path: Path) -> None:
    escaped = ":root { --bg: #fff; --color-icon\\2e fg: #f00; }"
    modes = _load(tmp_path, escaped)
    assert "color.icon.fg" in modes.modes["default"]
    both = ":root { --bg: #fff; --color-icon-fg: #0062ba; --color-icon\\2e fg: #f00; }"
    with pytest.raises(
        InputError, match=r"--color-icon-fg and --color-icon\.fg \(line 1\) both name"
    ):
        _load(tmp_path, both)


@pytest.mark.parametrize(
    ("value", "alpha"),
    [
        ("color-mix(in oklab, var(--blue) 8%, transparent)", 0.08),
        ("rgb(0 98 186 / 0.08)", 0.08),
        ("rgba(0, 98, 186, .08)", 0.08),
        ("oklch(from var(--blue) l c h / 0.08)", 0.08),
        ("oklch(from var(--blue) l c h / 8%)", 0.08),
    ],
)
def test_translucency_forms_are_parsed_and_kept(tmp_path: Path, value: str, alpha: float) -> None:
    text = f":root {{ --blue: #0062ba; --bg: #fff; --fg: #0062ba; --bg-hover: {value} }}"
    modes = _load(tmp_path, text)
    parsed = token_color(modes.modes["default"]["bg.hover"], allow_alpha=True)
    assert parsed.alpha == pytest.approx(alpha)
    assert _hex(parsed.css) == "#0062ba"  # the colour itself, before its own alpha
    themes = _themes(tmp_path, text, canvases=("bg", "bg.hover"))
    (mode,) = themes.modes
    # Audited as a layer over the mode's first opaque canvas (issue 20, item 4).
    bg, hover = mode.theme.canvases
    assert (bg.name, hover.name, hover.over) == ("bg", "bg.hover", "bg")
    assert hover.opacity == pytest.approx(alpha) and hover.color == "#0062ba"
    kept = mode.translucent["bg.hover"]
    assert kept.mode == "default" and kept.parsed.alpha == pytest.approx(alpha)
    assert any("bg.hover (0.08) audited as layers over bg" in n for n in themes.notes)


def test_a_translucent_icon_colour_is_an_error(tmp_path: Path) -> None:
    with pytest.raises(InputError, match=r"fg: .* is translucent \(alpha 0\.5\)"):
        _themes(tmp_path, ":root { --bg: #fff; --fg: rgb(0 0 0 / 0.5) }")


def test_var_fallbacks_and_unset_properties(tmp_path: Path) -> None:
    text = ":root { --bg: var(--nope, #fff); --fg: var(--a, var(--b, #0062ba)); --x: var(--z) }"
    modes = _load(tmp_path, text)
    assert _colors(_themes(tmp_path, text)) == {"default": {"bg": "#ffffff", "fg": "#0062ba"}}
    with pytest.raises(InputError, match=r"var\(--z\) names a custom property"):
        token_color(modes.modes["default"]["x"])
