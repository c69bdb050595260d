"""Tokens Studio theme groups: one theme of each group combined, as Tokens Studio applies them.

The combinations and their token sets are checked against ``permutateThemes`` of
``@tokens-studio/sd-transforms`` (the package Style Dictionary users build these
files with), run by Node on the same ``$themes``; the colours against a plain walk
written here that merges those sets in that order and follows ``{a.b}`` aliases.
"""

from __future__ import annotations

import importlib.util
import json
import os
import shutil
import subprocess
from pathlib import Path
from typing import Any

import pytest
from coloraide import Color

from alpha_audit.errors import InputError
from alpha_audit.load.config import load_config
from alpha_audit.load.tokens import load_token_modes, token_color
from alpha_audit.load.tokens.themes import load_token_themes

REPO = Path(__file__).resolve().parents[3]


def _source(name: str, group: str, sets: dict[str, str]) -> dict[str, Any]:
    return {"id": name, "name": name, "group": group, "selectedTokenSets": sets}


# A core palette (source), two brands and two colour modes, as a brand x mode system ships.
STUDIO = {
    "core": {
        "blue": {"value": "#0062ba", "type": "color"},
        "teal": {"value": "#007d79", "type": "color"},
        "white": {"value": "#ffffff", "type": "color"},
        "ink": {"value": "#161616", "type": "color"},
        "radius": {"value": "4px", "type": "borderRadius"},
    },
    "brand/a": {"brand": {"accent": {"value": "{blue}", "type": "color"}}},
    "brand/b": {"brand": {"accent": {"value": "{teal}", "type": "color"}}},
    "mode/light": {
        "bg": {"value": "{white}", "type": "color"},
        "icon": {"value": "{brand.accent}", "type": "color"},
    },
    "mode/dark": {
        "bg": {"value": "{ink}", "type": "color"},
        "icon": {"value": "{brand.accent}", "type": "color"},
        "blue": {"value": "#78a9ff", "type": "color"},
    },
    "$themes": [
        _source("a", "brand", {"core": "source", "brand/a": "enabled"}),
        _source("b", "brand", {"core": "source", "brand/b": "enabled"}),
        _source("light", "mode", {"core": "source", "mode/light": "enabled"}),
        _source("dark", "mode", {"core": "source", "mode/dark": "enabled"}),
    ],
    "$metadata": {"tokenSetOrder": ["core", "brand/a", "brand/b", "mode/light", "mode/dark"]},
}


def _write(tmp_path: Path) -> Path:
    path = tmp_path / "tokens.json"
    path.write_text(json.dumps(STUDIO, indent=1), encoding="utf-8")
    return path


def _independent(sets: list[str]) -> dict[str, tuple[float, ...]]:
    flat: dict[str, Any] = {}

    def walk(node: Any, path: list[str]) -> None:
        if isinstance(node, dict) and "value" in node:
            flat[".".join(path)] = node
        elif isinstance(node, dict):
            for k, v in node.items():
                walk(v, [*path, k])

    for name in sets:  # later sets win
        walk(STUDIO[name], [])

    def value(path: str) -> str:
        v = flat[path]["value"]
        return value(v[1:-1]) if v.startswith("{") else v

    return {
        p: tuple(Color(value(p)).convert("srgb").coords())
        for p, t in flat.items()
        if t["type"] == "color"
    }


def test_groups_combine_one_theme_of_each(tmp_path: Path) -> None:
    modes = load_token_modes(_write(tmp_path))
    assert list(modes.modes) == ["a-light", "a-dark", "b-light", "b-dark"]
    dark_b = modes.modes["b-dark"]
    assert dark_b["icon"].value == "#007d79" and dark_b["bg"].value == "#161616"
    # The mode's own set overrides the core palette it sources.
    assert modes.modes["a-dark"]["icon"].value == "#78a9ff"
    assert modes.modes["a-light"]["icon"].value == "#0062ba"


def test_groups_can_be_chosen_or_turned_off(tmp_path: Path) -> None:
    path = _write(tmp_path)
    assert list(load_token_modes(path, groups=("mode",)).modes) == ["light", "dark"]
    assert list(load_token_modes(path, groups=()).modes) == ["a", "b", "light", "dark"]
    with pytest.raises(InputError, match="names 'size', which no theme has; groups: brand, mode"):
        load_token_modes(path, groups=("mode", "size"))


def test_the_config_combines_groups_and_skips_themes_without_canvases(tmp_path: Path) -> None:
    _write(tmp_path)
    cfg = tmp_path / "alpha-audit.yaml"
    cfg.write_text(
        "tokens:\n  file: tokens.json\n  canvases: bg\n  colors: icon\n", encoding="utf-8"
    )
    themes = load_token_themes(load_config(cfg).tokens)
    assert [m.name for m in themes.modes] == ["a-light", "a-dark", "b-light", "b-dark"]
    # Each theme alone: the brand themes set no canvas, so they are skipped with a note
    # (and a mode theme alone has no brand: its icon colour names no token).
    cfg.write_text(
        "tokens:\n  file: tokens.json\n  canvases: bg\n  modes: {groups: false}\n",
        encoding="utf-8",
    )
    themes = load_token_themes(load_config(cfg).tokens)
    assert [m.name for m in themes.modes] == ["light", "dark"]
    assert themes.skipped == ("a", "b")
    assert "modes a, b: no token matching canvases bg" in themes.notes


def _missing(reason: str) -> None:
    if os.environ.get("CI"):
        pytest.fail(reason, pytrace=False)
    pytest.skip(reason)


def test_combinations_are_those_of_sd_transforms(tmp_path: Path) -> None:
    if shutil.which("npm") is None or shutil.which("node") is None:
        _missing("npm and Node fetch and run @tokens-studio/sd-transforms")
    spec = importlib.util.spec_from_file_location("tf", REPO / "tools/token_fixtures.py")
    assert spec is not None and spec.loader is not None
    tool = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tool)
    package = tool.fetch("@tokens-studio/sd-transforms", "2.0.3")
    script = (
        f"import({json.dumps((package / 'dist/permutateThemes.js').as_uri())})"
        ".then((m) => process.stdout.write(JSON.stringify("
        f"m.permutateThemes({json.dumps(STUDIO['$themes'])}))))"
    )
    out = subprocess.run(
        ["node", "--input-type=module", "-e", script],
        check=True,
        capture_output=True,
        text=True,
        timeout=60,
    ).stdout
    theirs: dict[str, list[str]] = json.loads(out)
    modes = load_token_modes(_write(tmp_path))
    assert list(modes.modes) == list(theirs)
    compared = 0
    for name, sets in theirs.items():
        expected = _independent(sets)
        ours = {
            p: tuple(token_color(t, gamut="clip").encoded)
            for p, t in modes.modes[name].items()
            if t.type == "color"
        }
        assert ours.keys() == expected.keys()
        for path, value in expected.items():
            assert ours[path] == pytest.approx(value, abs=1e-12), (name, path)
            compared += 1
    assert compared == 4 * 7
