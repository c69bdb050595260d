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
