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
            mode.colors["ui.icon.alert"].linear,
            _independent("display-p3", [0.9, 0.1, 0.1], gamut),
            atol=1e-12,
        )
        np.testing.assert_allclose(
            mode.colors["ui.icon.calm"].linear,
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


def test_a_mode_without_canvases_is_an_error(tmp_path) -> None:
    cfg = _project(tmp_path, "clip")
    cfg.write_text(cfg.read_text().replace("ui.bg.*", "nothing.*"))
    with pytest.raises(InputError, match="no opaque token matching canvases nothing"):
        load_token_themes(load_config(cfg).tokens)


def test_bad_coefficient_extension(tmp_path) -> None:
    cfg = _project(tmp_path, "clip")
    light = json.loads((tmp_path / "light.json").read_text())
    light["ui"]["icon"]["alert"]["$extensions"]["com.alpha-audit"]["alpha"] = "1.2"
    (tmp_path / "light.json").write_text(json.dumps(light, indent=1))
    with pytest.raises(InputError, match=r"light\.json:\d+: ui\.icon\.alert: .*finite number"):
        load_token_themes(load_config(cfg).tokens)
