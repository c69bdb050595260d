"""Hostile token sources, CSS sheets and configs from a pull request: bounded, contained, named.

Every case is a few kilobytes written here.  Bounds are *counted* (steps,
values, modes), never timed, so each case ends in the same error on a loaded
machine: exit 2, one line naming the file and the bound.
"""

from __future__ import annotations

import json
import os
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
        ("sheet.css", f":root {{ --bg: #fff; --{_css_escape(name)}: #000 }}"),
        ("modes.css", f":root {{ --bg: #fff }} .{_css_escape(name)} {{ --bg: #000 }}"),
    ]


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
        assert first_unsafe(message) is None and file in message, (file, message)


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
