"""Hostile token sources, CSS sheets and configs from a pull request: bounded, contained, named.

Every case is a few kilobytes written here.  Bounds are *counted* (steps,
values, modes), never timed, so each case ends in the same error on a loaded
machine: exit 2, one line naming the file and the bound.
"""

from __future__ import annotations

import json
import os
import re
from pathlib import Path

import pytest
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.errors import InputError
from alpha_audit.load.config import find_config, load_config
from alpha_audit.load.tokens import load_token_modes, token_color
from alpha_audit.load.tokens.model import MAX_MODES
from alpha_audit.load.tokens.themes import TokenConfig, token_themes
from alpha_audit.safe_text import first_unsafe

SVG = '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24"><path d="M4 4h16v16H4z"/></svg>'


def _write(folder: Path, name: str, data: object) -> Path:
    path = folder / name
    path.write_text(data if isinstance(data, str) else json.dumps(data))
    return path


# --- bounds: every expansion counted ---------------------------------------------------------
def _ref_doubling(levels: int) -> dict:
    defs: dict = {"d0": {"colorSpace": "srgb", "components": [0, 0, 0]}}
    for i in range(1, levels):
        defs[f"d{i}"] = [{"$ref": f"#/defs/d{i - 1}"}, {"$ref": f"#/defs/d{i - 1}"}]
    return {"defs": defs, "x": {"$type": "color", "$value": {"$ref": f"#/defs/d{levels - 1}"}}}


def _extends_fanout(groups: int, tokens: int) -> dict:
    doc: dict = {"g0": {"$type": "color", **{f"t{i}": {"$value": "#fff"} for i in range(tokens)}}}
    for i in range(1, groups):
        doc[f"g{i}"] = {"$extends": f"{{g{i - 1}}}"}
    return doc


def _resolver_modes(n: int) -> dict:
    contexts = {f"c{i}": [{"bg": {"$type": "color", "$value": "#fff"}}] for i in range(n)}
    return {
        "resolutionOrder": [
            {"type": "modifier", "name": "m", "contexts": contexts, "default": "c0"}
        ]
    }


def _studio_modes(n: int) -> dict:
    return {
        "core": {"bg": {"value": "#fff", "type": "color"}},
        "$themes": [{"name": f"t{i}", "selectedTokenSets": {"core": "enabled"}} for i in range(n)],
    }


def _css_modes(n: int) -> str:
    return ":root { --bg: #fff }\n" + "".join(
        f".m{i} {{ --bg: #{i % 9}{i % 9}{i % 9} }}\n" for i in range(n)
    )


def _css_bomb(levels: int) -> str:
    props = ["--v0: #fff;"] + [
        f"--v{i}: var(--v{i - 1}) var(--v{i - 1});" for i in range(1, levels)
    ]
    return ":root { --bg: #fff; " + " ".join(props) + " }"


BOUNDS = [
    # (file name, content, expected words in the one-line error)
    ("ref.tokens.json", _ref_doubling(40), "more than 10,000 JSON values"),
    ("extends.tokens.json", _extends_fanout(400, 400), "more than 100000 tokens"),
    ("resolver.json", _resolver_modes(MAX_MODES + 1), f"{MAX_MODES + 1} modes; at most 4096"),
    ("studio.json", _studio_modes(MAX_MODES + 1), f"{MAX_MODES + 1} modes; at most 4096"),
    ("modes.css", _css_modes(MAX_MODES + 1), "modes; at most 4096"),
    ("bomb.css", _css_bomb(40), "CSS tokens"),
]


@pytest.mark.parametrize(("name", "content", "words"), BOUNDS, ids=[b[0] for b in BOUNDS])
def test_expansions_stop_at_a_counted_bound_naming_the_file(
    tmp_path: Path, name: str, content: object, words: str
) -> None:
    path = _write(tmp_path, name, content)
    with pytest.raises(InputError) as info:
        modes = load_token_modes(path, root=tmp_path)
        for tokens in modes.modes.values():  # a bomb nobody selects is still resolved: bounded
            for token in tokens.values():
                token_color(token, gamut="clip", allow_alpha=True)
    text = str(info.value)
    assert name in text and words in text and "\n" not in text


def test_modes_count_toward_the_canvas_cap(tmp_path: Path) -> None:
    css = ":root { --bg-a: #fff; --bg-b: #eee }\n"
    css += "".join(f".m{i} {{ --bg-a: #{i:06x} }}\n" for i in range(2100))
    modes = load_token_modes(_write(tmp_path, "t.css", css), root=tmp_path)
    config = TokenConfig(file=modes.source, canvases=("bg.*",))
    with pytest.raises(InputError, match=r"t\.css: more than 4096 canvases over \d+ modes"):
        token_themes(modes, config)


def test_a_resolver_with_many_modes_of_many_tokens_is_refused_before_resolving(
    tmp_path: Path,
) -> None:
    tokens = {f"t{i}": {"$type": "color", "$value": "#fff"} for i in range(2000)}
    contexts = {f"c{i}": [{"bg": {"$type": "color", "$value": "#fff"}}] for i in range(600)}
    doc = {
        "resolutionOrder": [
            {"type": "set", "sources": [tokens]},
            {"type": "modifier", "name": "m", "contexts": contexts, "default": "c0"},
        ]
    }
    with pytest.raises(InputError, match=r"600 modes x 2001 tokens = 1,200,600 to resolve"):
        load_token_modes(_write(tmp_path, "r.json", doc), root=tmp_path)


# --- containment -----------------------------------------------------------------------------
def test_a_pyproject_linking_outside_the_root_is_never_opened(tmp_path: Path) -> None:
    outside = tmp_path / "outside.toml"
    outside.write_text('[tool.alpha-audit]\nthemes = ["/etc/passwd"]\n')
    root = tmp_path / "repo"
    (root / ".git").mkdir(parents=True)
    (root / "pyproject.toml").symlink_to(outside)
    outside.chmod(0o000)  # opening it would fail differently (root reads anyway: see below)
    try:
        with pytest.raises(InputError, match="outside the project root"):
            find_config(root)
    finally:
        outside.chmod(0o644)


def test_a_token_source_linking_outside_is_refused(tmp_path: Path) -> None:
    secret = _write(tmp_path, "secret.tokens.json", {"bg": {"$type": "color", "$value": "#fff"}})
    root = tmp_path / "repo"
    root.mkdir()
    (root / "link.tokens.json").symlink_to(secret)
    resolver = {
        "resolutionOrder": [{"type": "set", "sources": [{"$ref": "link.tokens.json"}]}],
    }
    with pytest.raises(InputError, match="outside the project root"):
        load_token_modes(_write(root, "r.resolver.json", resolver), root=root)
    cfg = _write(root, "alpha-audit.yaml", "tokens:\n  file: link.tokens.json\n  canvases: bg\n")
    with pytest.raises(InputError, match="outside"):
        load_config(cfg)


# --- one name policy -------------------------------------------------------------------------
HOSTILE_NAMES = ["a\x1b]52;c;SGVsbG8=\x07", "x\n::add-mask::y", "ev\u202eil", "\ud800", "c1\x9b"]


def _named_sources(name: str) -> list[tuple[str, object]]:
    bg = {"$type": "color", "$value": "#fff"}
    return [
        ("dtcg.tokens.json", {"bg": bg, name: bg}),
        ("sd.json", {"bg": {"value": "#fff", "type": "color"}, name: {"value": "#000"}}),
        (
            "resolver.json",
            {
                "resolutionOrder": [
                    {"type": "modifier", "name": "m", "contexts": {name: [{"bg": bg}]}}
                ]
            },
        ),
        (
            "studio.json",
            {
                "core": {"bg": {"value": "#fff", "type": "color"}},
                "$themes": [{"name": name, "selectedTokenSets": {"core": "enabled"}}],
            },
        ),
        (
            "sets.json",
            {
                name: {"bg": {"value": "#fff", "type": "color"}},
                "$themes": [{"name": "t", "selectedTokenSets": {name: "enabled"}}],
            },
        ),
        (
            "modifier.resolver.json",
            {
                "resolutionOrder": [
                    {"type": "modifier", "name": name, "contexts": {"c": [{"bg": bg}]}}
                ]
            },
        ),
        (
            "set.resolver.json",
            {
                "sets": {name: {"sources": [{"bg": bg}]}},
                "resolutionOrder": [{"$ref": f"#/sets/{name}"}],
            },
        ),
        ("figma.json", _figma_collection(name)),
        ("sheet.css", f":root {{ --bg: #fff; --{_css_escape(name)}: #000 }}"),
        ("modes.css", f":root {{ --bg: #fff }}\n.{_css_escape(name)} {{ --bg: #000 }}"),
    ]


def _figma_collection(name: str) -> dict[str, object]:
    """A Figma variables export whose one collection is called ``name``."""
    white = {"r": 1, "g": 1, "b": 1, "a": 1}
    return {
        "meta": {
            "variableCollections": {
                "C:1": {"id": "C:1", "name": name, "modes": [{"modeId": "1:0", "name": "Light"}]}
            },
            "variables": {
                "V:1": {
                    "id": "V:1",
                    "name": "bg",
                    "resolvedType": "COLOR",
                    "variableCollectionId": "C:1",
                    "valuesByMode": {"1:0": white},
                }
            },
        }
    }


def _css_escape(name: str) -> str:
    return "".join(ch if ch.isalnum() else f"\\{ord(ch):x} " for ch in name)


@pytest.mark.parametrize("name", HOSTILE_NAMES, ids=lambda n: n.encode("unicode_escape").decode())
def test_names_with_controls_bidi_or_surrogates_are_refused_at_load(
    tmp_path: Path, name: str
) -> None:
    for file, content in _named_sources(name):
        if "\ud800" in name and file.endswith(".css"):
            continue  # a CSS escape of a surrogate is U+FFFD (CSS Syntax 3, 4.3.7)
        text = content if isinstance(content, str) else json.dumps(content)
        path = tmp_path / file
        path.write_text(text, encoding="utf-8", errors="surrogatepass")
        with pytest.raises(InputError, match="names may not hold control") as info:
            load_token_modes(path, root=tmp_path)
        message = str(info.value)
        assert first_unsafe(message) is None, (file, message)
        # The file, a line and the refused character by code point (load/names.py).
        assert re.match(rf".*{re.escape(file)}:\d+: ", message), (file, message)
        assert f"U+{ord(first_unsafe(name) or '?'):04X}" in message, (file, message)


@pytest.mark.parametrize(
    "name",
    [
        "👩\u200d💻",  # ZWJ sequence
        "\U0001f3f4\U000e0067\U000e0062\U000e0077\U000e006c\U000e0073\U000e007f",  # Wales
        "\u0646\u0627\u0645\u200c\u0647\u0627",  # Persian with ZWNJ
    ],
)
def test_emoji_and_joiners_are_legal_in_every_source(tmp_path: Path, name: str) -> None:
    for file, content in _named_sources(name):
        text = content if isinstance(content, str) else json.dumps(content)
        path = tmp_path / file
        path.write_text(text, encoding="utf-8")
        assert load_token_modes(path, root=tmp_path).modes, file


def test_emoji_zwj_sequences_stay_legal(tmp_path: Path) -> None:
    name = "👩\u200d💻"
    modes = load_token_modes(
        _write(tmp_path, "t.tokens.json", {"bg": {"$type": "color", "$value": "#fff", name: {}}}),
        root=tmp_path,
    )
    assert "bg" in modes.modes["default"]
    doc = {"bg": {"$type": "color", "$value": "#fff"}, name: {"$type": "color", "$value": "#000"}}
    assert name in load_token_modes(_write(tmp_path, "u.tokens.json", doc)).modes["default"]
    from alpha_audit.load.theme import theme_from_doc
    from alpha_audit.load.yamldoc import parse_yaml

    text = f"name: {name}\ncanvases: [{{color: '#fff'}}]\n"
    theme = theme_from_doc(parse_yaml(text, tmp_path / "t.yaml"))
    assert theme.name == name


def test_the_cli_error_line_escapes_file_names_and_keys(tmp_path: Path) -> None:
    folder = tmp_path / "repo"
    (folder / ".git").mkdir(parents=True)
    evil = folder / "t\x1b]52;c;x\x07\n::stop-commands::y.yaml"
    evil.write_text('name: t\ncanvases: [{name: "a\\e]52;c;Zm9v\\a", color: "#fff"}]\n')
    (folder / "s.yaml").write_text('icons: svg/*.svg\ncolor: "#000"\n')
    old = Path.cwd()
    os.chdir(folder)
    try:
        result = CliRunner().invoke(app, ["check", evil.name, "s.yaml"])
    finally:
        os.chdir(old)
    assert result.exit_code == 2
    line = result.output.strip()
    assert "\n" not in line and "\x1b" not in line and "\x07" not in line, repr(line)
    assert "\\x1b" in line


# --- identity --------------------------------------------------------------------------------
def test_a_css_escape_cannot_make_a_second_property_pose_as_a_token(tmp_path: Path) -> None:
    css = ":root { --bg: #fff; --color-icon-fg: #767676; --color-icon\\2e fg: #000 }"
    with pytest.raises(InputError, match=r"--color-icon-fg and --color-icon\.fg .* both name"):
        load_token_modes(_write(tmp_path, "t.css", css))


# --- wrong words: malformed values are input errors naming the file --------------------------
MALFORMED = [
    {"c": {"$type": "color", "$value": {"colorSpace": "srgb", "components": [[1], 0, 0]}}},
    {"c": {"$type": "color", "$value": {"colorSpace": ["srgb"], "components": [1, 0, 0]}}},
    {"c": {"$type": "color", "$value": {"colorSpace": "srgb", "components": "fff"}}},
    {
        "c": {
            "$type": "color",
            "$value": {"colorSpace": "srgb", "components": [1, 0, 0], "alpha": []},
        }
    },
    {"c": {"$type": "color", "$value": ["#fff"]}},
    {"c": {"$type": "color", "$value": 12}},
    {"c": {"$type": "color", "$value": None}},
    {"c": {"$type": "color", "$value": "color-mix(in oklab, red 200%, blue)"}},
    {"c": {"$type": "color", "$value": "oklch(from red calc(l + 0.1) c h)"}},
    {"c": {"$type": "color", "$value": "color-mix(" * 200}},
    {"c": {"$type": ["color"], "$value": "#fff"}},
    # finite channels whose conversion overflows or meets a domain error (were exit 3)
    {"c": {"$type": "color", "$value": "lab(50 1e308 1e308)"}},
    {"c": {"$type": "color", "$value": "oklch(0.5 0.1 1e400)"}},
    {"c": {"$type": "color", "$value": {"colorSpace": "lab", "components": [50, 1e308, 1e308]}}},
    {"c": {"$type": "color", "$value": "color-mix(in lab, lab(50 1e308 1e308), red)"}},
    {"c": {"$type": "color", "$value": {"colorSpace": "srgb", "components": [1, 0, 0], "hex": 5}}},
    {"c": {"$type": "color", "$value": "#fff", "$extensions": {"com.alpha-audit": {"alpha": "x"}}}},
]


@pytest.mark.parametrize("doc", MALFORMED, ids=range(len(MALFORMED)))
def test_malformed_token_values_exit_2_naming_the_file(tmp_path: Path, doc: dict) -> None:
    root = tmp_path / "repo"
    (root / ".git").mkdir(parents=True)
    (root / "svg").mkdir()
    (root / "svg" / "a.svg").write_text(SVG)
    full = {"bg": {"$type": "color", "$value": "#ffffff"}, **doc}
    (root / "t.tokens.json").write_text(json.dumps(full))
    (root / "s.yaml").write_text("icons: svg/*.svg\ncolor: c\nalpha: 1.1\n")
    (root / "alpha-audit.yaml").write_text(
        "tokens:\n  file: t.tokens.json\n  canvases: bg\n  colors: c\niconset: s.yaml\n"
    )
    old = Path.cwd()
    os.chdir(root)
    try:
        runner = CliRunner()
        results = [runner.invoke(app, ["check"]), runner.invoke(app, ["export", "-f", "css"])]
    finally:
        os.chdir(old)
    for result in results:
        assert result.exit_code == 2, result.output
        assert "t.tokens.json" in result.output and "internal error" not in result.output


def test_css_nested_too_deeply_names_its_file(tmp_path: Path) -> None:
    path = _write(tmp_path, "deep.css", ":root { --bg: #fff; --x: " + "a(" * 5000 + " }")
    with pytest.raises(InputError, match=r"deep\.css: CSS nested too deeply"):
        load_token_modes(path)


# --- bounds, round 3: work counted, so the cost is linear in the file ------------------------
def _empty_groups_source(tmp_path: Path, kind: str, modes: int, groups: int) -> Path:
    """A source whose every mode walks ``groups`` empty groups again (no tokens in them)."""
    bg = {"$type": "color", "$value": "#fff"}
    empty = {f"g{i}": {} for i in range(groups)}
    if kind == "resolver":
        contexts = {f"m{i}": [{"bg": bg}] for i in range(modes)}
        doc: dict = {
            "defs": {"big": empty},
            "resolutionOrder": [
                {"type": "set", "sources": [{"$ref": "#/defs/big"}] * 10},
                {"type": "modifier", "name": "m", "contexts": contexts, "default": "m0"},
            ],
        }
    else:
        doc = {
            "core": {"bg": {"value": "#fff", "type": "color"}, **empty},
            "$themes": [
                {"name": f"t{i}", "selectedTokenSets": {"core": "enabled"}} for i in range(modes)
            ],
        }
    return _write(tmp_path, f"{kind}.json", doc)


@pytest.mark.parametrize("kind", ["resolver", "studio"])
def test_modes_share_one_step_budget_so_rewalking_sets_is_refused(
    tmp_path: Path, kind: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Two modes x 1 token pass the modes x tokens cap; the groups walked per mode do not.
    from alpha_audit.load.tokens import model

    monkeypatch.setattr(model, "MAX_EXPANSION", 20_000)
    one_mode = _empty_groups_source(tmp_path, kind, modes=1, groups=900)
    assert load_token_modes(one_mode, root=tmp_path).modes  # 9,000 (or 900) keys: within
    path = _empty_groups_source(tmp_path, kind, modes=40, groups=900)
    with pytest.raises(InputError, match=r"takes more than 20,000 steps") as info:
        load_token_modes(path, root=tmp_path)
    assert path.name in str(info.value)


def test_a_large_value_aliased_many_times_is_measured_once(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from alpha_audit.load.tokens import dtcg

    defs: dict = {"d0": 0}
    for i in range(1, 13):  # 2^12 leaves: 8,191 JSON values, under MAX_VALUE_NODES
        defs[f"d{i}"] = [{"$ref": f"#/defs/d{i - 1}"}, {"$ref": f"#/defs/d{i - 1}"}]
    doc: dict = {"defs": defs, "big": {"$type": "other", "$value": {"$ref": "#/defs/d12"}}}
    doc |= {f"a{i}": {"$value": "{big}"} for i in range(2_000)}
    doc |= {f"p{i}": {"$value": {"$ref": "#/big/$value"}} for i in range(2_000)}
    calls = {"value": 0, "size": 0}
    value, size = dtcg.TokenTree._value, dtcg._size

    def counted_value(self, *args):  # type: ignore[no-untyped-def]
        calls["value"] += 1
        return value(self, *args)

    def counted_size(v):  # type: ignore[no-untyped-def]
        calls["size"] += 1
        return size(v)

    monkeypatch.setattr(dtcg.TokenTree, "_value", counted_value)
    monkeypatch.setattr(dtcg, "_size", counted_size)
    tokens = load_token_modes(_write(tmp_path, "t.tokens.json", doc)).modes["default"]
    assert tokens["a1999"].value is tokens["big"].value
    # Linear: each written value once, each alias and pointer once (before: 8,191 each).
    assert calls["value"] <= 2 * (12 * 3 + 4_002) and calls["size"] == 0, calls


def test_a_pointer_longer_than_the_file_nests_is_refused_before_it_is_split(
    tmp_path: Path,
) -> None:
    doc = {"bg": {"$type": "color", "$value": {"$ref": "#/" + "/".join(["a"] * 200_000)}}}
    with pytest.raises(InputError, match=r"has more parts than the file nests \(64 levels\)"):
        load_token_modes(_write(tmp_path, "t.tokens.json", doc))


def test_extends_chains_stop_at_the_alias_bound_in_any_order(tmp_path: Path) -> None:
    n = 3_000  # deeper than Python's recursion limit: was an error naming no file
    doc: dict = {f"g{n}": {"$type": "color", "t": {"$value": "#fff"}}}
    doc |= {f"g{i}": {"$extends": f"{{g{i + 1}}}"} for i in range(n)}
    with pytest.raises(InputError, match=r"\$extends chain longer than 64") as info:
        load_token_modes(_write(tmp_path, "t.tokens.json", doc))
    assert "t.tokens.json" in str(info.value)


def test_references_through_deeply_nested_values_name_the_file(tmp_path: Path) -> None:
    defs: dict = {}
    for i in range(64):
        value: object = {"$ref": f"#/defs/d{i + 1}"} if i < 63 else 1
        for _ in range(55):
            value = [value]
        defs[f"d{i}"] = value
    doc = {"defs": defs, "x": {"$type": "other", "$value": {"$ref": "#/defs/d0"}}}
    with pytest.raises(InputError, match=r"t\.tokens\.json: references nest too deeply"):
        load_token_modes(_write(tmp_path, "t.tokens.json", doc))


def test_a_colour_object_with_a_large_hex_is_refused_not_serialised(tmp_path: Path) -> None:
    defs: dict = {"d0": 0}
    for i in range(1, 13):
        defs[f"d{i}"] = [{"$ref": f"#/defs/d{i - 1}"}, {"$ref": f"#/defs/d{i - 1}"}]
    bg = {"colorSpace": "srgb", "components": [1, 1, 1], "hex": {"$ref": "#/defs/d12"}}
    doc = {"defs": defs, "bg": {"$type": "color", "$value": bg}}
    modes = load_token_modes(_write(tmp_path, "t.tokens.json", doc), root=tmp_path)
    with pytest.raises(InputError, match=r"hex must be a #rrggbb string .*got a list$"):
        token_themes(modes, TokenConfig(file=modes.source, canvases=("bg",)))


def test_css_modes_layers_and_selector_lists_are_indexed_not_rescanned(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import tinycss2

    from alpha_audit.load.tokens import stylesheet

    tests = [0]
    real = stylesheet.matches

    def counted(tree: object, element: object) -> object:
        tests[0] += 1
        return real(tree, element)  # type: ignore[arg-type]

    monkeypatch.setattr(stylesheet, "matches", counted)
    n = 3_000
    css = ":root { --bg: #fff }\n"
    css += "".join(f".m{i + 1}, .m{i} {{ --bg: #000 }}\n" for i in range(n))
    path = _write(tmp_path, "t.css", css)
    modes = load_token_modes(path)
    # :root and every class .m0 ... .m3000 (.m3000 computes what .m2999 does: an alias)
    assert len(modes.modes) + len(modes.aliases) == n + 2
    # Each state looks only at the parts its classes index: was every part per state.
    assert tests[0] <= 30 * n, tests
    sheet = stylesheet._Sheet(tmp_path / "l.css", None)
    layers = "@layer " + ", ".join(f"l{i}" for i in range(n)) + ";\n"
    rules = tinycss2.parse_stylesheet(layers, skip_comments=True, skip_whitespace=True)
    stylesheet._walk(sheet, rules, layers=(), scheme=None, p3=False, skip=None, depth=0)
    assert [sheet.layer_ranks[(f"l{i}",)] for i in range(n)] == list(range(n))


def test_css_declarations_applied_per_mode_count_toward_the_step_budget(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from alpha_audit.load.tokens import model

    monkeypatch.setattr(model, "MAX_EXPANSION", 20_000)
    css = ":root { --c: #000; " + "--bg: #fff; " * 2_000 + "}\n"
    css += "".join(f".m{i} {{ --c: #{i:06x} }}\n" for i in range(20))
    with pytest.raises(InputError, match=r"t\.css: cascading modes takes more than 20,000 steps"):
        load_token_modes(_write(tmp_path, "t.css", css))


@pytest.mark.parametrize("reverse", [False, True], ids=["forward", "reverse"])
def test_css_var_chains_stop_at_the_alias_bound(tmp_path: Path, reverse: bool) -> None:
    n = 2_000
    if reverse:
        props = [f"--v{i}: var(--v{i + 1});" for i in range(n)] + [f"--v{n}: #fff;"]
    else:
        props = ["--v0: #fff;"] + [f"--v{i}: var(--v{i - 1});" for i in range(1, n + 1)]
    css = ":root { --bg: #fff; " + " ".join(props) + " }"
    with pytest.raises(InputError, match=r"t\.css:1: v\d+: var\(\) chain longer than 64"):
        load_token_modes(_write(tmp_path, "t.css", css))


def test_css_aliases_of_a_long_value_serialise_it_once_per_mode(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import tinycss2

    big = " ".join(["x"] * 400)
    css = f":root {{ --bg: #fff; --big: {big}; "
    css += " ".join(f"--f{i}: var(--big);" for i in range(500)) + " }\n"
    css += "".join(f".m{i} {{ --bg: #{i:06x} }}\n" for i in range(5))
    long_ones = [0]
    serialize = tinycss2.serialize

    def counted(nodes):  # type: ignore[no-untyped-def]
        nodes = list(nodes)
        long_ones[0] += len(nodes) > 500
        return serialize(nodes)

    monkeypatch.setattr(tinycss2, "serialize", counted)
    modes = load_token_modes(_write(tmp_path, "t.css", css))
    assert len(modes.modes) == 6 and modes.modes["m4"]["f499"].problem is not None
    assert long_ones[0] <= 6 * 2, long_ones  # once per mode (and once for its span)


def test_figma_alias_hops_over_every_mode_count_toward_the_step_budget(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from alpha_audit.load.tokens import model

    def variable(i: int) -> dict:
        value = {"type": "VARIABLE_ALIAS", "id": f"V:{i - 1}"} if i else {"r": 1, "g": 1, "b": 1}
        return {
            "name": f"t{i}",
            "variableCollectionId": "C:1",
            "resolvedType": "COLOR",
            "valuesByMode": {str(m): value for m in range(20)},
        }

    modes = [{"modeId": str(i), "name": f"m{i}"} for i in range(20)]
    collection = {"name": "T", "defaultModeId": "0", "modes": modes}
    doc = {
        "meta": {
            "variableCollections": {"C:1": collection},
            "variables": {f"V:{i}": variable(i) for i in range(10)},  # chains of 1..10 hops
        }
    }
    path = _write(tmp_path, "figma.json", doc)
    assert len(load_token_modes(path).modes) == 20  # 20 modes x 55 hops = 1,100
    monkeypatch.setattr(model, "MAX_EXPANSION", 1_000)
    with pytest.raises(InputError, match=r"figma\.json.*resolving aliases takes more than 1,000"):
        load_token_modes(path)
