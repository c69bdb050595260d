"""DTCG 2025.10 trees: aliases, $ref, $extends, group $type, errors with file, line and path."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from alpha_audit.errors import InputError
from alpha_audit.load.tokens import load_token_modes, parse_json, token_color, tokens_from_docs
from alpha_audit.load.tokens.jsondoc import MAX_JSON_DEPTH


def _tokens(text: str, name: str = "t.tokens.json") -> dict:
    return tokens_from_docs([parse_json(text, name)])


DOC = """{
  "color": {
    "$type": "color",
    "base": {
      "blue": { "$value": "#0055ff" },
      "red": { "$value": { "colorSpace": "oklch", "components": [0.6, 0.2, 25] } }
    },
    "accent": { "$value": "{color.base.blue}" },
    "link": { "$value": "{color.accent}" },
    "pointer": { "$value": { "$ref": "#/color/base/red/$value" } },
    "whole": { "$ref": "#/color/base/blue" }
  }
}"""


def test_alias_chain_resolves_to_the_literal_and_remembers_the_chain() -> None:
    tokens = _tokens(DOC)
    link = tokens["color.link"]
    assert link.value == "#0055ff"
    assert link.chain == ("color.accent", "color.base.blue")
    assert link.line == 5  # the line that sets the colour
    assert link.alias_line == 9


def test_group_type_is_inherited() -> None:
    tokens = _tokens(DOC)
    assert {t.type for t in tokens.values() if t.path != "color.whole"} == {"color"}


def test_json_pointer_ref_into_a_value() -> None:
    tokens = _tokens(DOC)
    assert tokens["color.pointer"].value == {"colorSpace": "oklch", "components": [0.6, 0.2, 25]}
    assert tokens["color.pointer"].chain == ("color.base.red",)


def test_cycle_is_an_error_naming_the_chain() -> None:
    text = (
        '{"a": {"$type": "color", "$value": "{b}"}, "b": {"$value": "{c}"}, "c": {"$value": "{a}"}}'
    )
    with pytest.raises(InputError, match=r"alias cycle: a -> b -> c -> a") as info:
        _tokens(text)
    assert info.value.path == Path("t.tokens.json") and info.value.line == 1


def test_ref_cycle_is_an_error() -> None:
    text = json.dumps(
        {
            "a": {"$type": "color", "$value": {"$ref": "#/b/$value"}},
            "b": {"$type": "color", "$value": {"$ref": "#/a/$value"}},
        }
    )
    with pytest.raises(InputError, match="cycle"):
        _tokens(text)


def test_token_without_type_is_an_error_where_selected_with_file_line_and_path() -> None:
    text = (
        '{\n  "size": {\n    "small": { "$value": "4px" }\n  },\n'
        '  "c": {"$type": "color", "$value": "#fff"}\n}'
    )
    tokens = _tokens(text)  # an untyped radius nobody selects does not stop the load
    assert token_color(tokens["c"]).encoded == (1.0, 1.0, 1.0)
    with pytest.raises(InputError, match=r"no \$type") as info:
        token_color(tokens["size.small"])
    assert str(info.value).startswith("t.tokens.json:3: size.small: ")


def test_alias_takes_the_type_of_its_target() -> None:
    text = '{"a": {"$type": "color", "$value": "#fff"}, "b": {"$value": "{a}"}}'
    assert _tokens(text)["b"].type == "color"


def test_missing_alias_target_is_an_error_where_selected() -> None:
    tokens = _tokens('{"a": {"$type": "color", "$value": "{nope}"}, "b": {"$value": "{a}"}}')
    for name in ("a", "b"):  # an alias of a broken token is broken the same way
        with pytest.raises(InputError, match=r"alias \{nope\} names no token"):
            token_color(tokens[name])


def test_style_dictionary_value_references() -> None:
    doc = parse_json(
        '{"base": {"blue": {"value": "#0062ba", "type": "color"}}, '
        '"icon": {"value": "{base.blue.value}", "type": "color"}}',
        "sd.json",
    )
    tokens = tokens_from_docs([doc], legacy=True)
    assert tokens["icon"].value == "#0062ba" and tokens["icon"].chain == ("base.blue",)


def test_metadata_beside_groups_is_not_a_token() -> None:
    tokens = _tokens('{"version": "1.2", "author": "x", "c": {"$type": "color", "$value": "#fff"}}')
    assert list(tokens) == ["c"]


def test_extends_copies_tokens_local_ones_win() -> None:
    text = json.dumps(
        {
            "base": {"$type": "color", "bg": {"$value": "#ffffff"}, "fg": {"$value": "#000000"}},
            "brand": {"$extends": "{base}", "fg": {"$type": "color", "$value": "#123456"}},
        }
    )
    tokens = _tokens(text)
    assert tokens["brand.bg"].value == "#ffffff" and tokens["brand.bg"].type == "color"
    assert tokens["brand.fg"].value == "#123456"


def test_extends_cycle() -> None:
    text = json.dumps(
        {
            "a": {"$extends": "{b}", "x": {"$type": "color", "$value": "#fff"}},
            "b": {"$extends": "{a}", "y": {"$type": "color", "$value": "#000"}},
        }
    )
    with pytest.raises(
        InputError, match=r"\$extends cycle: a -> b -> a|\$extends cycle: b -> a -> b"
    ):
        _tokens(text)


def test_root_token_and_extensions_and_deprecated() -> None:
    text = json.dumps(
        {
            "accent": {
                "$type": "color",
                "$root": {"$value": "#ff0000", "$extensions": {"com.alpha-audit": {"alpha": 1.2}}},
                "light": {"$value": "#ff8888", "$deprecated": "use accent"},
            }
        }
    )
    tokens = _tokens(text)
    assert tokens["accent.$root"].extensions == {"com.alpha-audit": {"alpha": 1.2}}
    assert tokens["accent.light"].deprecated == "use accent"


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ('{"a": {"$type": "color", "$value": "#fff"}, "a": {}}', "duplicate key 'a'"),
        ('{"a": NaN}', "NaN"),
        ('{"a": 1,}', "quoted key"),
        ('{"a": 1} x', "extra data"),
        ("[" * (MAX_JSON_DEPTH + 2), "nested deeper"),
        ('{"a.b": {"$type": "color", "$value": "#fff"}}', "may not be empty or contain"),
    ],
)
def test_bad_json_names_the_line(text: str, message: str) -> None:
    with pytest.raises(InputError, match=message) as info:
        _tokens(text)
    assert info.value.line is not None


def test_alias_chain_length_is_bounded() -> None:
    n = 100
    doc = {"t0": {"$type": "color", "$value": "#fff"}}
    doc.update({f"t{i}": {"$value": f"{{t{i - 1}}}"} for i in range(1, n)})
    with pytest.raises(InputError, match="alias chain longer than"):
        _tokens(json.dumps(doc))


def test_style_dictionary_legacy(tmp_path: Path) -> None:
    path = tmp_path / "sd.json"
    path.write_text(
        json.dumps(
            {
                "color": {
                    "bg": {"value": "#ffffff", "type": "color"},
                    "fg": {"value": "{color.bg}", "type": "color"},
                }
            }
        )
    )
    modes = load_token_modes(path)
    assert modes.kind == "style-dictionary"
    assert modes.modes["default"]["color.fg"].value == "#ffffff"


RESOLVER = {
    "version": "2025.10",
    "sets": {"base": {"sources": [{"$ref": "base.tokens.json"}]}},
    "modifiers": {
        "theme": {
            "contexts": {
                "light": [{"$ref": "light.tokens.json"}],
                "dark": [{"$ref": "dark.tokens.json"}],
            },
            "default": "light",
        }
    },
    "resolutionOrder": [
        {"$ref": "#/sets/base"},
        {"$ref": "#/modifiers/theme"},
        {
            "type": "set",
            "name": "late",
            "sources": [{"color": {"late": {"$type": "color", "$value": "#010203"}}}],
        },
    ],
}


def _resolver(tmp_path: Path) -> Path:
    (tmp_path / "base.tokens.json").write_text(
        json.dumps(
            {
                "color": {
                    "$type": "color",
                    "white": {"$value": "#ffffff"},
                    "black": {"$value": "#000000"},
                    "bg": {"$value": "{color.white}"},
                    "late": {"$value": "#999999"},
                }
            }
        )
    )
    (tmp_path / "light.tokens.json").write_text("{}")
    (tmp_path / "dark.tokens.json").write_text(
        json.dumps({"color": {"bg": {"$type": "color", "$value": "{color.black}"}}})
    )
    path = tmp_path / "system.resolver.json"
    path.write_text(json.dumps(RESOLVER, indent=2))
    return path


def test_resolver_contexts_and_order_last_wins(tmp_path: Path) -> None:
    modes = load_token_modes(_resolver(tmp_path))
    assert modes.kind == "resolver" and list(modes.modes) == ["light", "dark"]
    assert modes.default == "light"
    assert modes.modes["light"]["color.bg"].value == "#ffffff"
    assert modes.modes["dark"]["color.bg"].value == "#000000"
    # the inline set comes last in resolutionOrder, so it wins over base
    assert modes.modes["dark"]["color.late"].value == "#010203"


def test_resolver_source_outside_root_is_refused(tmp_path: Path) -> None:
    inner = tmp_path / "inner"
    inner.mkdir()
    doc = dict(RESOLVER, sets={"base": {"sources": [{"$ref": "../x.json"}]}})
    path = inner / "r.json"
    path.write_text(json.dumps(doc))
    with pytest.raises(InputError, match="outside"):
        load_token_modes(path)


def test_extends_sees_what_the_target_inherits_itself() -> None:
    text = json.dumps(
        {
            "x": {"$extends": "{y}"},
            "y": {"sub": {"$extends": "{z}"}, "own": {"$type": "color", "$value": "#111111"}},
            "z": {"deep": {"$type": "color", "$value": "#222222"}},
        }
    )
    tokens = _tokens(text)
    assert tokens["x.sub.deep"].value == "#222222"
    assert tokens["x.own"].value == "#111111"
