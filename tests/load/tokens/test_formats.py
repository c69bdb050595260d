"""Tokens Studio, Figma Variables and Tailwind v4 @theme inputs."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from alpha_audit.errors import InputError
from alpha_audit.load.tokens import load_token_modes, token_color

REPO = Path(__file__).resolve().parents[3]


def _figma(tmp_path: Path, values: dict) -> Path:
    doc = {
        "status": 200,
        "error": False,
        "meta": {
            "variableCollections": {
                "VariableCollectionId:1:0": {
                    "id": "VariableCollectionId:1:0",
                    "name": "Primitives",
                    "modes": [{"modeId": "1:0", "name": "Value"}],
                    "defaultModeId": "1:0",
                },
                "VariableCollectionId:2:0": {
                    "id": "VariableCollectionId:2:0",
                    "name": "Theme",
                    "modes": [
                        {"modeId": "2:0", "name": "Light"},
                        {"modeId": "2:1", "name": "Dark"},
                    ],
                    "defaultModeId": "2:0",
                },
            },
            "variables": values,
        },
    }
    path = tmp_path / "figma.json"
    path.write_text(json.dumps(doc, indent=2))
    return path


def _var(vid: str, name: str, coll: str, values: dict) -> dict:
    return {
        vid: {
            "id": vid,
            "name": name,
            "variableCollectionId": coll,
            "resolvedType": "COLOR",
            "valuesByMode": values,
        }
    }


PRIM = "VariableCollectionId:1:0"
THEME = "VariableCollectionId:2:0"


def test_figma_aliases_resolve_across_collections(tmp_path: Path) -> None:
    values = {
        **_var("V:1", "gray/0", PRIM, {"1:0": {"r": 1, "g": 1, "b": 1, "a": 1}}),
        **_var("V:2", "gray/900", PRIM, {"1:0": {"r": 0.05, "g": 0.07, "b": 0.09, "a": 1}}),
        **_var(
            "V:3",
            "color/bg/canvas",
            THEME,
            {
                "2:0": {"type": "VARIABLE_ALIAS", "id": "V:1"},
                "2:1": {"type": "VARIABLE_ALIAS", "id": "V:2"},
            },
        ),
    }
    modes = load_token_modes(_figma(tmp_path, values))
    assert modes.kind == "figma" and list(modes.modes) == ["Light", "Dark"]
    assert modes.default == "Light"
    light, dark = modes.modes["Light"]["color.bg.canvas"], modes.modes["Dark"]["color.bg.canvas"]
    assert token_color(light).encoded == (1.0, 1.0, 1.0)
    assert token_color(dark).encoded == (0.05, 0.07, 0.09)
    assert dark.chain == ("gray.900",)
    assert dark.line is not None and dark.alias_line is not None and dark.line != dark.alias_line


def test_figma_alias_cycle_names_the_chain(tmp_path: Path) -> None:
    values = {
        **_var(
            "V:1",
            "a",
            THEME,
            {"2:0": {"type": "VARIABLE_ALIAS", "id": "V:2"}, "2:1": {"r": 0, "g": 0, "b": 0}},
        ),
        **_var(
            "V:2",
            "b",
            THEME,
            {"2:0": {"type": "VARIABLE_ALIAS", "id": "V:1"}, "2:1": {"r": 0, "g": 0, "b": 0}},
        ),
    }
    with pytest.raises(InputError, match=r"alias cycle: a -> b -> a"):
        load_token_modes(_figma(tmp_path, values))


@pytest.mark.parametrize(("hops", "refused"), [(63, False), (64, True)])
def test_figma_alias_chain_is_capped_like_every_format(
    tmp_path: Path, hops: int, refused: bool
) -> None:
    # The DTCG, $ref, $extends and var() chains share one cap and one message
    # (MAX_ALIAS_CHAIN = 64 followed references; tests/load/tokens/test_dtcg.py).
    red = {"r": 1, "g": 0, "b": 0}
    values = {**_var(f"V:{hops}", f"t/{hops}", THEME, {"2:0": red, "2:1": red})}
    for i in range(hops):
        alias = {"type": "VARIABLE_ALIAS", "id": f"V:{i + 1}"}
        values |= _var(f"V:{i}", f"t/{i}", THEME, {"2:0": alias, "2:1": alias})
    if refused:
        with pytest.raises(
            InputError, match=r": t\.0: alias chain longer than 64: t\.0 -> t\.1 -> "
        ):
            load_token_modes(_figma(tmp_path, values))
    else:
        token = load_token_modes(_figma(tmp_path, values)).modes["Dark"]["t.0"]
        assert token_color(token).encoded == (1.0, 0.0, 0.0)


def test_figma_translucent_colour_is_an_error_where_alpha_is_not_an_opacity(tmp_path: Path) -> None:
    values = _var(
        "V:1",
        "c",
        THEME,
        {"2:0": {"r": 1, "g": 0, "b": 0, "a": 0.5}, "2:1": {"r": 1, "g": 0, "b": 0}},
    )
    token = load_token_modes(_figma(tmp_path, values)).modes["Light"]["c"]
    with pytest.raises(InputError, match="own alpha"):
        token_color(token)


def test_tailwind_theme_with_none_hue_and_dark_override() -> None:
    modes = load_token_modes(REPO / "examples/tokens/tailwind/theme.css")
    assert modes.kind == "css" and list(modes.modes) == ["default", "dark"]
    tokens = modes.modes["default"]
    grey = token_color(tokens["color.neutral.400"])
    assert grey.encoded[0] == pytest.approx(grey.encoded[1]) == pytest.approx(grey.encoded[2])
    assert tokens["color.icon.danger"].chain == ("color.red.500",)
    with pytest.raises(InputError, match="outside sRGB"):
        token_color(tokens["color.sky.500"])  # Tailwind's sky-500 lies outside sRGB
    assert token_color(tokens["color.sky.500"], gamut="map").adjusted
    assert not token_color(tokens["color.red.500"]).adjusted
    assert token_color(modes.modes["dark"]["color.bg.canvas"]).encoded[0] < 0.1
    assert tokens["color.red.500"].line == 10
    assert tokens["color.icon.info"].line == 11  # the line that sets the colour
    assert tokens["color.icon.info"].alias_line == 14


def test_tailwind_var_to_unknown_property(tmp_path: Path) -> None:
    css = tmp_path / "t.css"
    css.write_text("@theme {\n  --color-a: var(--color-nope);\n}\n")
    css.write_text("@theme {\n  --color-a: var(--color-nope);\n  --color-b: red;\n}\n")
    token = load_token_modes(css).modes["default"]["color.a"]  # loads: nothing selects it yet
    with pytest.raises(InputError, match=r"t\.css:2: color\.a: var\(--color-nope\) names"):
        token_color(token)


def test_tokens_studio_single_file_themes(tmp_path: Path) -> None:
    doc = {
        "core": {
            "white": {"value": "#ffffff", "type": "color"},
            "black": {"value": "#000000", "type": "color"},
        },
        "light": {"bg": {"value": "{white}", "type": "color"}},
        "dark": {"bg": {"$value": "{black}", "$type": "color"}},
        "$themes": [
            {
                "id": "1",
                "name": "Light",
                "selectedTokenSets": {"core": "source", "light": "enabled"},
            },
            {
                "id": "2",
                "name": "Dark",
                "selectedTokenSets": {"core": "source", "dark": "enabled", "light": "disabled"},
            },
        ],
        "$metadata": {"tokenSetOrder": ["core", "light", "dark"]},
    }
    path = tmp_path / "tokens.json"
    path.write_text(json.dumps(doc))
    modes = load_token_modes(path)
    assert modes.kind == "tokens-studio" and list(modes.modes) == ["Light", "Dark"]
    assert modes.modes["Light"]["bg"].value == "#ffffff"
    assert modes.modes["Dark"]["bg"].value == "#000000"


def test_tokens_studio_folder_with_themes_json(tmp_path: Path) -> None:
    (tmp_path / "core.json").write_text(json.dumps({"ink": {"value": "#111111", "type": "color"}}))
    (tmp_path / "brand.json").write_text(json.dumps({"ink": {"value": "#222222", "type": "color"}}))
    (tmp_path / "$metadata.json").write_text(json.dumps({"tokenSetOrder": ["core", "brand"]}))
    themes = [{"name": "Brand", "selectedTokenSets": {"brand": "enabled", "core": "enabled"}}]
    (tmp_path / "$themes.json").write_text(json.dumps(themes))
    modes = load_token_modes(tmp_path / "$themes.json")
    # tokenSetOrder puts brand last, so it wins whatever order the theme lists them in
    assert modes.modes["Brand"]["ink"].value == "#222222"


def test_tokens_studio_set_outside_root(tmp_path: Path) -> None:
    inner = tmp_path / "in"
    inner.mkdir()
    (inner / "$themes.json").write_text(
        json.dumps([{"name": "x", "selectedTokenSets": {"../evil": "enabled"}}])
    )
    with pytest.raises(InputError, match="outside"):
        load_token_modes(inner / "$themes.json")


def test_figma_library_alias_loads_and_fails_only_where_selected(tmp_path: Path) -> None:
    values = {
        **_var(
            "V:1",
            "color/bg",
            THEME,
            {"2:0": {"r": 1, "g": 1, "b": 1}, "2:1": {"r": 0, "g": 0, "b": 0}},
        ),
        **_var(
            "V:2",
            "space/pad",
            THEME,
            {
                "2:0": {"type": "VARIABLE_ALIAS", "id": "VariableID:abc/1:2"},
                "2:1": {"type": "VARIABLE_ALIAS", "id": "VariableID:abc/1:2"},
            },
        ),
    }
    modes = load_token_modes(_figma(tmp_path, values))
    assert token_color(modes.modes["Dark"]["color.bg"]).encoded == (0.0, 0.0, 0.0)
    with pytest.raises(InputError, match=r"does not hold \(a library variable"):
        token_color(modes.modes["Light"]["space.pad"])


def test_figma_without_the_rest_envelope(tmp_path: Path) -> None:
    values = _var(
        "V:1", "color/bg", THEME, {"2:0": {"r": 1, "g": 1, "b": 1}, "2:1": {"r": 0, "g": 0, "b": 0}}
    )
    path = _figma(tmp_path, values)
    path.write_text(json.dumps(json.loads(path.read_text())["meta"]))
    modes = load_token_modes(path)
    assert modes.kind == "figma" and list(modes.modes) == ["Light", "Dark"]


def test_tokens_studio_without_themes_refuses_a_silent_merge(tmp_path: Path) -> None:
    doc = {
        "light": {"bg": {"value": "#ffffff", "type": "color"}},
        "dark": {"bg": {"value": "#111111", "type": "color"}},
        "$themes": [],
        "$metadata": {"tokenSetOrder": ["light", "dark"]},
    }
    path = tmp_path / "tokens.json"
    path.write_text(json.dumps(doc))
    with pytest.raises(InputError, match=r"'light' and 'dark' both set bg"):
        load_token_modes(path)
    doc["dark"] = {"fg": {"value": "#111111", "type": "color"}}  # no overlap: one mode
    path.write_text(json.dumps(doc))
    assert list(load_token_modes(path).modes["default"]) == ["bg", "fg"]


def test_tokens_studio_enabled_sets_win_over_source_sets(tmp_path: Path) -> None:
    doc = {
        "brand": {"ink": {"value": "#222222", "type": "color"}},
        "core": {"ink": {"value": "#111111", "type": "color"}},
        "$themes": [{"name": "t", "selectedTokenSets": {"brand": "enabled", "core": "source"}}],
        "$metadata": {"tokenSetOrder": ["brand", "core"]},
    }
    path = tmp_path / "tokens.json"
    path.write_text(json.dumps(doc))
    assert load_token_modes(path).modes["t"]["ink"].value == "#222222"


def test_tokens_studio_metadata_outside_the_root_is_not_opened(tmp_path: Path) -> None:
    inner = tmp_path / "in"
    inner.mkdir()
    secret = tmp_path / "secret.json"
    secret.write_text('{"tokenSetOrder": []}')
    (inner / "$metadata.json").symlink_to(secret)
    (inner / "$themes.json").write_text("[]")
    with pytest.raises(InputError, match="outside the project root"):
        load_token_modes(inner / "$themes.json", root=inner)


@pytest.mark.parametrize(
    ("data", "shape"),
    [
        (
            {"a-color": {"sets": {"light": {"value": "#fff"}, "dark": {"value": "#000"}}}},
            "per-token sets",
        ),
        ([{"name": "a/b", "value": 0, "mode": "dark", "type": "FLOAT"}], "Primer"),
        ([1, 2], "JSON list"),
        (  # @atlaskit/tokens 20.7.0, figma/atlassian-dark.json (its first entry)
            {
                "name": "Dark",
                "tokens": {
                    "Dark/color.background.accent.lime.subtlest": {
                        "value": "#28311B",
                        "attributes": {"group": "paint", "state": "active"},
                    }
                },
            },
            "Atlassian's Figma sync JSON",
        ),
    ],
)
def test_formats_that_are_not_read_are_named(tmp_path: Path, data, shape: str) -> None:
    path = tmp_path / "x.json"
    path.write_text(json.dumps(data))
    with pytest.raises(InputError, match=f"looks like .*{shape}.*which alpha-audit does not read"):
        load_token_modes(path)


def test_figma_variables_meeting_in_one_token_path_are_both_named(tmp_path: Path) -> None:
    white = {"2:0": {"r": 1, "g": 1, "b": 1}, "2:1": {"r": 0, "g": 0, "b": 0}}
    values = {
        **_var("V:1", "color/bg", THEME, white),
        **_var("V:2", "color / bg", THEME, white),  # Figma trims each part: one path
    }
    with pytest.raises(
        InputError, match=r"'color/bg' and 'color / bg' both name the token color\.bg"
    ):
        load_token_modes(_figma(tmp_path, values))
