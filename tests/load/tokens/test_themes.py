"""Token themes against an independent resolution (the issue's held-out bar, in small)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from coloraide import Color

from alpha_audit.color import srgb_decode
from alpha_audit.errors import InputError
from alpha_audit.load.config import load_config
from alpha_audit.load.tokens.themes import load_token_themes

BASE = {
    "prim": {
        "$type": "color",
        "snow": {"$value": {"colorSpace": "oklch", "components": [0.985, 0.002, 247]}},
        "coal": {"$value": {"colorSpace": "srgb", "components": [0.05, 0.06, 0.08]}},
        "p3red": {"$value": {"colorSpace": "display-p3", "components": [0.9, 0.1, 0.1]}},
        "teal": {"$value": "oklch(0.6 0.1 190)"},
    }
}
LIGHT = {
    "ui": {
        "$type": "color",
        "bg": {"main": {"$value": "{prim.snow}"}},
        "icon": {
            "alert": {
                "$value": {"$ref": "#/prim/p3red/$value"},
                "$extensions": {"com.alpha-audit": {"alpha": 1.2}},
            },
            "calm": {"$value": "{ui.icon.alias}"},
            "alias": {"$value": "{prim.teal}"},
        },
    }
}
DARK = {"ui": {"bg": {"main": {"$type": "color", "$value": "{prim.coal}"}}}}


def _project(tmp_path: Path, gamut: str) -> Path:
    (tmp_path / "base.json").write_text(json.dumps(BASE))
    (tmp_path / "light.json").write_text(json.dumps(LIGHT))
    (tmp_path / "dark.json").write_text(json.dumps(DARK))
    resolver = {
        "version": "2025.10",
        "sets": {"base": {"sources": [{"$ref": "base.json"}, {"$ref": "light.json"}]}},
        "modifiers": {
            "mode": {"contexts": {"day": [], "night": [{"$ref": "dark.json"}]}, "default": "day"}
        },
        "resolutionOrder": [{"$ref": "#/sets/base"}, {"$ref": "#/modifiers/mode"}],
    }
    (tmp_path / "r.json").write_text(json.dumps(resolver))
    cfg = tmp_path / "alpha-audit.yaml"
    cfg.write_text(
        "tokens:\n  file: r.json\n  canvases: ui.bg.*\n  colors: ui.icon.*\n"
        f"  modes: {{day: light, night: dark}}\n  gamut: {gamut}\n"
    )
    return cfg


def _independent(space: str, coords: list[float], gamut: str) -> np.ndarray:
    c = Color(space, coords)
    if gamut == "map" and not c.in_gamut("srgb"):
        c = c.fit("srgb", method="minde-chroma", pspace="oklch", jnd=0.02)
    return srgb_decode(np.clip(c.convert("srgb")[:3], 0, 1))


@pytest.mark.parametrize("gamut", ["clip", "map"])
def test_backgrounds_and_sources_equal_an_independent_resolution(tmp_path, gamut) -> None:
    themes = load_token_themes(load_config(_project(tmp_path, gamut)).tokens)
    day, night = themes.modes
    assert (day.name, night.name) == ("day", "night")
    assert day.theme.canvases[0].mode == "light" and night.theme.canvases[0].mode == "dark"
    np.testing.assert_allclose(
        day.theme.backgrounds[0], _independent("oklch", [0.985, 0.002, 247], gamut), atol=1e-12
    )
    np.testing.assert_allclose(
        night.theme.backgrounds[0], _independent("srgb", [0.05, 0.06, 0.08], gamut), atol=1e-12
    )
    for mode in (day, night):  # the night context overrides only the canvas
        np.testing.assert_allclose(
            srgb_decode(mode.colors["ui.icon.alert"].parsed.array),
            _independent("display-p3", [0.9, 0.1, 0.1], gamut),
            atol=1e-12,
        )
        np.testing.assert_allclose(
            srgb_decode(mode.colors["ui.icon.calm"].parsed.array),
            _independent("oklch", [0.6, 0.1, 190], gamut),
            atol=1e-12,
        )
        assert mode.colors["ui.icon.alert"].alpha == 1.2
        assert mode.colors["ui.icon.calm"].alpha is None
    adjusted = {(a.mode, a.token) for a in themes.adjusted}
    assert adjusted == {("day", "ui.icon.alert"), ("night", "ui.icon.alert")}
    assert all(a.policy == gamut and a.delta_e > 0 for a in themes.adjusted)


def test_gamut_error_names_file_line_and_token(tmp_path) -> None:
    with pytest.raises(InputError, match=r"base\.json:1: ui\.icon\.alert: .*outside sRGB"):
        load_token_themes(load_config(_project(tmp_path, "error")).tokens)


def test_no_mode_with_canvases_is_an_error(tmp_path) -> None:
    cfg = _project(tmp_path, "clip")
    cfg.write_text(cfg.read_text().replace("ui.bg.*", "nothing.*"))
    with pytest.raises(InputError, match=r"no mode has an opaque token matching canvases nothing"):
        load_token_themes(load_config(cfg).tokens)


def _css_project(tmp_path: Path, sheet: str, tokens: str) -> Path:
    (tmp_path / "t.css").write_text(sheet, encoding="utf-8")
    cfg = tmp_path / "alpha-audit.yaml"
    cfg.write_text(f"tokens:\n  file: t.css\n{tokens}", encoding="utf-8")
    return cfg


CARBON = (
    ":root{--font:serif} .theme-white{--bg:#ffffff;--fg:#0062ba}"
    " .theme-g100{--bg:#161616;--fg:#78a9ff} .utility{--fg:#0062ba}"
)


def test_modes_setting_no_selected_canvas_are_skipped_with_one_note(tmp_path) -> None:
    # Carbon: the theme classes set the colours; .utility sets an icon colour only.
    cfg = _css_project(tmp_path, CARBON, "  canvases: bg\n  colors: fg\n")
    themes = load_token_themes(load_config(cfg).tokens)
    assert [m.name for m in themes.modes] == ["theme-white", "theme-g100"]
    assert themes.skipped == ("utility",)
    assert "mode utility: no token matching canvases bg" in themes.notes


def test_modes_lists_the_modes_to_audit_and_maps_them(tmp_path) -> None:
    cfg = _css_project(
        tmp_path,
        CARBON,
        "  canvases: bg\n  colors: fg\n  modes: {audit: ['*g100'], dark: ['theme-g*']}\n",
    )
    themes = load_token_themes(load_config(cfg).tokens)
    assert [m.name for m in themes.modes] == ["theme-g100"]
    assert themes.modes[0].theme.canvases[0].mode == "dark"
    assert "theme-white" in themes.skipped
    cfg = _css_project(tmp_path, CARBON, "  canvases: bg\n  modes: ['theme-g10']\n")
    with pytest.raises(InputError, match=r"'theme-g10' matches no mode of t\.css; modes: "):
        load_token_themes(load_config(cfg).tokens)


def test_a_glob_maps_modes_to_light_and_dark(tmp_path) -> None:
    cfg = _css_project(tmp_path, CARBON, "  canvases: bg\n  modes: {'*white': dark}\n")
    themes = load_token_themes(load_config(cfg).tokens)
    # Declared, not inferred: the glob says dark although the canvas is white.
    assert themes.modes[0].theme.canvases[0].mode == "dark"
    assert themes.modes[1].theme.canvases[0].mode == "dark"  # inferred from #161616


def test_modes_setting_errors_name_the_key(tmp_path) -> None:
    for setting, match in (
        ("{audit: 3}", r"modes\.audit.*a list of mode names or globs"),
        ("{mood: [x]}", r"unknown key 'mood'"),
        ("{x: grey}", r"mode: light\|dark"),
        ("3", r"a list of the modes to audit"),
    ):
        cfg = _css_project(tmp_path, CARBON, f"  canvases: bg\n  modes: {setting}\n")
        with pytest.raises(InputError, match=match):
            load_config(cfg)


def test_tokens_table_is_read_like_the_rest_of_the_config(tmp_path) -> None:
    # The same field readers as the config's top level: a near miss is named,
    # a key spelt both ways is refused, a bad gamut lists the policies.
    for setting, match in (
        ("  canvases: bg\n  colours: fg\n", r":4: tokens\.colours: .*did you mean 'colors'\?"),
        (
            "  canvases: bg\n  alpha_extension: a.b\n  alpha-extension: c.d\n",
            r"tokens\.alpha-extension: 'alpha-extension' repeats 'alpha_extension'",
        ),
        ("  canvases: bg\n  gamut: squash\n", r"not a gamut policy; use one of: clip, map, error"),
        ("  canvases: bg\n  modes: {light: [a], dakr: [b]}\n", r"did you mean 'dark'\?"),
    ):
        cfg = _css_project(tmp_path, CARBON, setting)
        with pytest.raises(InputError, match=match):
            load_config(cfg)
    cfg = _css_project(tmp_path, CARBON, "  canvases: bg\n  alpha_extension: a.b\n")
    assert load_config(cfg).tokens.alpha_extension == "a.b"


def test_duplicate_css_modes_are_aliases_in_one_note(tmp_path) -> None:
    sheet = ":root{--bg:#fff;--fg:#123} .a{--fg:#123;--x:#000} .b{--fg:#123;--y:#111}"
    cfg = _css_project(tmp_path, sheet, "  canvases: bg\n  colors: fg\n")
    themes = load_token_themes(load_config(cfg).tokens)
    assert [m.name for m in themes.modes] == ["default"]
    assert themes.aliases == {"a": "default", "b": "default"}
    assert "modes a, b: the same selected colours as mode default" in themes.notes
    assert set(themes.conditions) == {"default", "a", "b"}


def test_a_translucent_css_surface_is_drawn_as_a_browser_draws_it(tmp_path) -> None:
    # Primer: bgColor.neutral.muted over bgColor.default, in the default linear pipeline.
    from alpha_audit.color import composite_css, hex_to_linear, linear_to_hex

    sheet = ":root{--bgColor-default:#212830;--bgColor-neutral-muted:rgb(101 108 118 / 0.2)}"
    cfg = _css_project(tmp_path, sheet, "  canvases: bgColor.*\n")
    theme = load_token_themes(load_config(cfg).tokens).modes[0].theme
    muted = theme.canvases[1]
    assert (muted.blend, muted.opacity, muted.over) == ("css", 0.2, "bgColor.default")
    for pipeline in ("linear", "css"):
        assert theme.flattened(pipeline).canvases[1].color == "#2f363e"
    # Every browser: 0.2 * 101 + 0.8 * 33 = 46.6 -> 47 = 0x2f (and 54, 62).
    assert (
        linear_to_hex(composite_css(hex_to_linear("#656c76"), hex_to_linear("#212830"), 0.2))
        == "#2f363e"
    )


def test_a_translucent_json_surface_follows_the_pipeline(tmp_path) -> None:
    tokens = {
        "bg": {
            "$type": "color",
            "page": {"$value": "#212830"},
            "muted": {"$value": "rgb(101 108 118 / 0.2)"},
        }
    }
    (tmp_path / "t.tokens.json").write_text(json.dumps(tokens), encoding="utf-8")
    cfg = tmp_path / "alpha-audit.yaml"
    cfg.write_text("tokens:\n  file: t.tokens.json\n  canvases: bg.*\n", encoding="utf-8")
    theme = load_token_themes(load_config(cfg).tokens).modes[0].theme
    assert theme.canvases[1].blend is None
    assert theme.flattened("linear").canvases[1].color == "#373d45"
    assert theme.flattened("css").canvases[1].color == "#2f363e"


def test_untyped_tokens_are_typed_by_the_config(tmp_path) -> None:
    # Style Dictionary output: the type is in attributes (or nowhere), not in "type".
    tokens = {
        "color": {
            "bg": {"value": "#ffffff", "attributes": {"category": "color", "type": "bg"}},
            "icon": {"value": "{color.base.value}"},
            "base": {"value": "#0062ba"},
        }
    }
    (tmp_path / "sd.json").write_text(json.dumps(tokens), encoding="utf-8")
    cfg = tmp_path / "alpha-audit.yaml"
    cfg.write_text(
        "tokens:\n  file: sd.json\n  canvases: color.bg\n  colors: color.icon\n",
        encoding="utf-8",
    )
    with pytest.raises(InputError, match=r"color\.bg: token has no \$type.*tokens: \{types: "):
        load_token_themes(load_config(cfg).tokens)
    cfg.write_text(cfg.read_text() + "  types: {'color.*': color}\n", encoding="utf-8")
    mode = load_token_themes(load_config(cfg).tokens).modes[0]
    assert mode.theme.canvases[0].color == "#ffffff"
    assert list(mode.colors["color.icon"].parsed.encoded) == pytest.approx(
        [0, 0x62 / 255, 0xBA / 255]
    )


def test_bad_coefficient_extension(tmp_path) -> None:
    cfg = _project(tmp_path, "clip")
    light = json.loads((tmp_path / "light.json").read_text())
    light["ui"]["icon"]["alert"]["$extensions"]["com.alpha-audit"]["alpha"] = "1.2"
    (tmp_path / "light.json").write_text(json.dumps(light, indent=1))
    with pytest.raises(InputError, match=r"light\.json:\d+: ui\.icon\.alert: .*finite number"):
        load_token_themes(load_config(cfg).tokens)
