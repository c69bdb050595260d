"""Fuzzing the token readers: mutated DTCG, Resolver, Tokens Studio, Style Dictionary, Figma
and CSS sources end in exit 0 or 2 (one line), never in an internal error.

Each example mutates one valid source (bytes deleted, inserted or replaced, lines
duplicated, hostile fragments spliced in) and runs ``export -f json`` on a project
whose config selects its tokens, in-process.  Derandomized: the same examples on
every run, so the suite's verdict does not depend on luck.
``ALPHA_AUDIT_FUZZ_EXAMPLES`` raises the count for a longer local run.
"""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from alpha_audit.cli import app

EXAMPLES = int(os.environ.get("ALPHA_AUDIT_FUZZ_EXAMPLES", 40))

_BG = {"$type": "color", "$value": "#ffffff"}
SOURCES: dict[str, str] = {
    "dtcg.tokens.json": json.dumps(
        {
            "color": {
                "$type": "color",
                "bg": {"$value": {"colorSpace": "srgb", "components": [1, 1, 1]}},
                "base": {"blue": {"$value": "oklch(0.55 0.15 250)"}},
                "icon": {
                    "fg": {"$value": "{color.base.blue}"},
                    "ref": {"$value": {"$ref": "#/color/base/blue/$value"}},
                },
                "alt": {"$extends": "{color.icon}"},
            },
            "size": {"$type": "dimension", "s": {"$value": {"value": 4, "unit": "px"}}},
        },
        indent=1,
    ),
    "system.resolver.json": json.dumps(
        {
            "resolutionOrder": [
                {"type": "set", "sources": [{"color": {"bg": _BG}}]},
                {
                    "type": "modifier",
                    "name": "theme",
                    "default": "light",
                    "contexts": {
                        "light": [
                            {"color": {"icon": {"fg": {"$type": "color", "$value": "#0062ba"}}}}
                        ],
                        "dark": [{"color": {"icon": {"fg": {"$type": "color", "$value": "#9cf"}}}}],
                    },
                },
            ]
        },
        indent=1,
    ),
    "studio.json": json.dumps(
        {
            "core": {"color": {"bg": {"value": "#fff", "type": "color"}}},
            "light": {"color": {"icon": {"fg": {"value": "{color.bg}", "type": "color"}}}},
            "$themes": [
                {"name": "Light", "selectedTokenSets": {"core": "source", "light": "enabled"}}
            ],
            "$metadata": {"tokenSetOrder": ["core", "light"]},
        },
        indent=1,
    ),
    "sd.json": json.dumps(
        {
            "color": {
                "bg": {"value": "#ffffff", "type": "color"},
                "icon": {"fg": {"value": "{color.bg.value}", "type": "color"}},
            }
        },
        indent=1,
    ),
    "figma.json": json.dumps(
        {
            "meta": {
                "variableCollections": {
                    "C:1": {
                        "name": "T",
                        "modes": [{"modeId": "1:0", "name": "L"}],
                        "defaultModeId": "1:0",
                    }
                },
                "variables": {
                    "V:1": {
                        "name": "color/bg",
                        "variableCollectionId": "C:1",
                        "resolvedType": "COLOR",
                        "valuesByMode": {"1:0": {"r": 1, "g": 1, "b": 1, "a": 1}},
                    },
                    "V:2": {
                        "name": "color/icon/fg",
                        "variableCollectionId": "C:1",
                        "resolvedType": "COLOR",
                        "valuesByMode": {"1:0": {"type": "VARIABLE_ALIAS", "id": "V:1"}},
                    },
                },
            }
        },
        indent=1,
    ),
    "sheet.css": (
        "@layer base, theme;\n"
        "@layer theme { :root { --color-bg: #fff; --color-icon-fg: var(--blue); } }\n"
        ":root { --blue: oklch(55% 0.15 250); --space: 4px; --gap: var(--space); }\n"
        '[data-theme="dark"] { --color-bg: light-dark(#fff, #111); }\n'
        "@media (prefers-color-scheme: dark) { :root { --color-icon-fg: #9cf; } }\n"
        "@supports (color: color(display-p3 1 1 1)) {\n"
        "  :root { --blue: color(display-p3 0 .4 .8); }\n}\n"
        ".card .x { --color-bg: color-mix(in oklab, var(--blue) 8%, transparent); }\n"
    ),
}
INSERTS = [
    *(b"\x00", b"\x1b[2J", b"\xe2\x80\xae", b"\xed\xa0\x80", b"{", b"}", b"[", b'"', b",", b":"),
    *(b'{"$ref": "#/"}', b'"$extends": "{color}",', b'"{color.icon.fg}"', b'"$type": 5,'),
    *(b"var(--blue)", b"light-dark(", b"@layer x {", b"@media (prefers-color-scheme: dark) {"),
    *(b"color-mix(in oklab, ", b"oklch(from var(--blue) l c h / 50%)", b"\\2e ", b"--a: var(--a);"),
    *(b'"VARIABLE_ALIAS"', b'"selectedTokenSets": {"x": "enabled"}', b"1e999", b"NaN"),
    # Round 3 of hostile input: expansions the readers count.
    *(b'"hex": [[1], {"$ref": "#/color"}],', b'{"$ref": "#/' + b"a/" * 80 + b'"}'),
    *(b'"$extends": "{color.alt}",', b"--b: var(--a) var(--a); --a: var(--b);"),
    *(b'"$metadata": {"tokenSetOrder": [[], "light", "core", "light"]},',),
]


@st.composite
def mutated(draw: st.DrawFn) -> tuple[str, bytes]:
    name = draw(st.sampled_from(sorted(SOURCES)))
    data = bytearray(SOURCES[name].encode())
    for _ in range(draw(st.integers(1, 4))):
        at = draw(st.integers(0, len(data)))
        kind = draw(st.sampled_from(["delete", "insert", "replace", "dup-line"]))
        if kind == "delete":
            del data[at : at + draw(st.integers(1, 12))]
        elif kind == "insert":
            piece = draw(st.one_of(st.sampled_from(INSERTS), st.binary(min_size=1, max_size=4)))
            data[at:at] = piece
        elif kind == "replace" and at < len(data):
            data[at] = draw(st.integers(0, 255))
        else:
            lines = bytes(data).split(b"\n")
            k = draw(st.integers(0, len(lines) - 1))
            lines.insert(k, lines[k])
            data = bytearray(b"\n".join(lines))
    return name, bytes(data)


@settings(
    max_examples=EXAMPLES,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.too_slow],
)
@given(mutated())
def test_token_sources_on_mutated_inputs_exit_cleanly(case: tuple[str, bytes]) -> None:
    name, data = case
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp).resolve()
        (root / ".git").mkdir()
        (root / name).write_bytes(data)
        (root / "alpha-audit.yaml").write_text(
            f"alpha: 1.1\ngamut: clip\ntokens:\n  file: {name}\n  canvases: 'color.bg'\n"
            "  colors: 'color.icon.*'\n"
        )
        cwd = os.getcwd()
        os.chdir(root)
        try:
            result = CliRunner().invoke(app, ["export", "-f", "json"])
        finally:
            os.chdir(cwd)
    output = result.output
    assert result.exit_code in (0, 2), (name, result.exit_code, output, result.exception)
    assert "Traceback" not in output and "internal error" not in output
    if result.exit_code == 2:
        errors = [line for line in output.splitlines() if line.startswith("alpha-audit: error")]
        assert len(errors) == 1 and "\x1b" not in errors[0], output


def test_every_unmutated_source_exports() -> None:
    for name in SOURCES:
        with tempfile.TemporaryDirectory() as tmp:
            root = Path(tmp).resolve()
            (root / ".git").mkdir()
            (root / name).write_text(SOURCES[name])
            (root / "alpha-audit.yaml").write_text(
                f"alpha: 1.1\ngamut: clip\ntokens:\n  file: {name}\n  canvases: 'color.bg'\n"
                "  colors: 'color.icon.*'\n"
            )
            cwd = os.getcwd()
            os.chdir(root)
            try:
                result = CliRunner().invoke(app, ["export", "-f", "json"])
            finally:
                os.chdir(cwd)
        assert result.exit_code == 0, (name, result.output)


# ---------------------------------------------------------------- wrong types, every place
#
# A structured fuzzer over real-shaped documents of the four JSON token readers (Figma
# Variables, Tokens Studio, the DTCG Resolver, DTCG itself): the value at every position
# of every document (the documents a resolver or $themes.json names included) is
# replaced, in turn, by a value of each JSON type (and a finite number too large for any
# colour).  Counted, not sampled: every case loads its themes and colours, or is refused
# by an error naming the file and a line or key; no other exception, and no number that
# is not finite in what loads.

WRONG_VALUES = (
    None,
    True,
    0,
    -1,
    1.5,
    1e308,
    "",
    "x",
    "{color.bg}",
    [],
    [1],
    ["x"],
    {},
    {"a": 1},
    {"$value": 1},
)
_DTCG_BG = {"$type": "color", "$value": "#ffffff"}
STRUCTURED: dict[str, dict[str, object]] = {
    "dtcg": {
        "tokens.json": {
            "color": {
                "$type": "color",
                "bg": {
                    "$value": {
                        "colorSpace": "srgb",
                        "components": [1, 1, 1],
                        "alpha": 1,
                        "hex": "#ffffff",
                    }
                },
                "base": {
                    "blue": {
                        "$value": "oklch(0.55 0.15 250)",
                        "$extensions": {"com.alpha-audit": {"alpha": 1.2}},
                    }
                },
                "icon": {
                    "$description": "icons",
                    "fg": {"$value": "{color.base.blue}"},
                    "ref": {"$value": {"$ref": "#/color/base/blue/$value"}},
                },
                "alt": {"$extends": "{color.icon}"},
            },
            "size": {"$type": "dimension", "s": {"$value": {"value": 4, "unit": "px"}}},
        },
    },
    "resolver": {
        "system.resolver.json": {
            "version": "2025.10",
            "sets": {
                "base": {"sources": [{"$ref": "base.tokens.json"}, {"color": {"bg": _DTCG_BG}}]}
            },
            "modifiers": {
                "theme": {
                    "default": "light",
                    "contexts": {
                        "light": [{"$ref": "light.tokens.json#/color"}],
                        "dark": [{"icon": {"fg": {"$type": "color", "$value": "#9cf"}}}],
                    },
                }
            },
            "resolutionOrder": [
                {"$ref": "#/sets/base"},
                {"$ref": "#/modifiers/theme"},
                {"type": "set", "name": "inline", "sources": [{"color": {"x": _DTCG_BG}}]},
            ],
        },
        "base.tokens.json": {"color": {"y": _DTCG_BG}},
        "light.tokens.json": {"color": {"icon": {"fg": {"$type": "color", "$value": "#0062ba"}}}},
    },
    "tokens-studio": {
        "studio.json": {
            "core": {
                "color": {
                    "bg": {"value": "#fff", "type": "color"},
                    "blue": {"value": "#0062ba", "type": "color"},
                }
            },
            "light": {"color": {"icon": {"fg": {"value": "{color.blue}", "type": "color"}}}},
            "dark": {"color": {"icon": {"fg": {"value": "#9cf", "type": "color"}}}},
            "$themes": [
                {
                    "id": "1",
                    "name": "Light",
                    "group": "mode",
                    "selectedTokenSets": {"core": "source", "light": "enabled"},
                },
                {
                    "id": "2",
                    "name": "Dark",
                    "selectedTokenSets": {"core": "source", "dark": "enabled"},
                },
            ],
            "$metadata": {"tokenSetOrder": ["core", "light", "dark"]},
        },
        "$themes.json": [
            {
                "id": "1",
                "name": "Light",
                "selectedTokenSets": {"core": "source", "light": "enabled"},
            }
        ],
        "core.json": {"color": {"bg": {"value": "#fff", "type": "color"}}},
        "light.json": {"color": {"icon": {"fg": {"value": "{color.bg}", "type": "color"}}}},
        "$metadata.json": {"tokenSetOrder": ["core", "light"]},
    },
    "figma": {
        "figma.json": {
            "status": 200,
            "error": False,
            "meta": {
                "variableCollections": {
                    "C:1": {
                        "id": "C:1",
                        "name": "Theme",
                        "modes": [
                            {"modeId": "1:0", "name": "Light"},
                            {"modeId": "1:1", "name": "Dark"},
                        ],
                        "defaultModeId": "1:0",
                    }
                },
                "variables": {
                    "V:1": {
                        "id": "V:1",
                        "name": "color/bg",
                        "variableCollectionId": "C:1",
                        "resolvedType": "COLOR",
                        "valuesByMode": {
                            "1:0": {"r": 1, "g": 1, "b": 1, "a": 1},
                            "1:1": {"r": 0, "g": 0, "b": 0, "a": 1},
                        },
                    },
                    "V:2": {
                        "id": "V:2",
                        "name": "color/icon/fg",
                        "description": "icons",
                        "scopes": ["ALL_SCOPES"],
                        "variableCollectionId": "C:1",
                        "resolvedType": "COLOR",
                        "valuesByMode": {
                            "1:0": {"type": "VARIABLE_ALIAS", "id": "V:1"},
                            "1:1": {"r": 0.5, "g": 0.6, "b": 1, "a": 1},
                        },
                    },
                },
            },
        },
    },
}
# The file the config names, per reader, and every file it reads ($themes.json is
# Tokens Studio's folder layout, read on its own).
READS = {
    "dtcg": {"tokens.json": ("tokens.json",)},
    "resolver": {
        "system.resolver.json": ("system.resolver.json", "base.tokens.json", "light.tokens.json")
    },
    "tokens-studio": {
        "studio.json": ("studio.json",),
        "$themes.json": ("$themes.json", "core.json", "light.json", "$metadata.json"),
    },
    "figma": {"figma.json": ("figma.json",)},
}


def _positions(node: object, at: tuple[object, ...] = ()) -> list[tuple[object, ...]]:
    found = [at]
    if isinstance(node, dict):
        for key, value in node.items():
            found += _positions(value, (*at, key))
    elif isinstance(node, list):
        for index, value in enumerate(node):
            found += _positions(value, (*at, index))
    return found


def _replaced(doc: object, at: tuple[object, ...], value: object) -> object:
    if not at:
        return value
    copy = json.loads(json.dumps(doc))
    node = copy
    for key in at[:-1]:
        node = node[key]  # type: ignore[index]
    node[at[-1]] = value  # type: ignore[index]
    return copy


def _numbers(value: object) -> list[float]:
    """Every float a loaded value holds (dataclasses, mappings, sequences, arrays)."""
    import dataclasses

    import numpy as np

    if isinstance(value, float):
        return [value]
    if isinstance(value, np.ndarray):
        return [float(v) for v in value.ravel()] if value.dtype.kind == "f" else []
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return [n for f in dataclasses.fields(value) for n in _numbers(getattr(value, f.name))]
    if isinstance(value, dict):
        return [n for v in value.values() for n in _numbers(v)]
    if isinstance(value, list | tuple):
        return [n for v in value for n in _numbers(v)]
    return []


@pytest.mark.parametrize("reader", list(STRUCTURED))
def test_wrong_json_types_at_every_position_are_input_errors_naming_file_and_place(
    reader: str, tmp_path: Path
) -> None:
    import math

    from alpha_audit.errors import AlphaAuditError
    from alpha_audit.load.tokens.themes import TokenConfig, load_token_themes

    files = STRUCTURED[reader]
    root = tmp_path.resolve()

    def load(entry: str) -> object:
        config = TokenConfig(
            file=root / entry,
            canvases=("color.bg",),
            colors=("color.icon.*",),
            root=root,
            gamut="clip",
        )
        return load_token_themes(config)

    def write_all() -> None:
        for name, doc in files.items():
            (root / name).write_text(json.dumps(doc, indent=1), encoding="utf-8")

    cases = refused = 0
    for entry, read in READS[reader].items():
        write_all()
        load(entry)  # the unmutated documents load
        for name in read:
            doc = files[name]
            for at in _positions(doc):
                for value in WRONG_VALUES:
                    (root / name).write_text(json.dumps(_replaced(doc, at, value)), "utf-8")
                    cases += 1
                    try:
                        loaded = load(entry)
                    except AlphaAuditError as exc:
                        refused += 1
                        where = (name, at, value, str(exc))
                        assert exc.path is not None, where
                        assert exc.path.resolve().is_relative_to(root), where
                        # A place in the file, or the whole file: its shape (the top
                        # replaced), or the config's selection that matched nothing there.
                        whole = not at or "matching canvases" in exc.message
                        assert exc.line is not None or exc.key or whole, where
                        continue
                    numbers = _numbers(loaded)
                    assert all(math.isfinite(n) for n in numbers), (name, at, value)
                (root / name).write_text(json.dumps(doc, indent=1), encoding="utf-8")
    assert cases > 300 and 0 < refused < cases, (cases, refused)
