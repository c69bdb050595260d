"""SARIF ``fixes``: applying each one to the file clears the finding it is attached to.

The edits are applied by a small applier written here (by line and column,
independently of the loaders' span code), the edited project is checked again
from its files, and the finding the fix was attached to must be gone.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path
from typing import Any

import pytest

from alpha_audit.load.config import ProjectConfig
from alpha_audit.pipeline import check_project
from alpha_audit.policy import Policy
from alpha_audit.render import CheckFormat, RenderOptions
from alpha_audit.rules import Rule

SVG = (
    '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24">'
    '<rect x="2" y="2" width="20" height="20" fill="currentColor"/></svg>'
)
THEME = """name: t
threshold: 3.0
canvases:
  - {name: white, color: "#ffffff", mode: light}
  - {name: yellow, color: "#ffff00", mode: light}
"""
# navy loses contrast on yellow above alpha 1 (wave's override 1.3: the
# largest safe alpha goes there); leafy is below 3:1 on yellow at the
# set-wide 1.4 (the smallest reaching alpha goes to the set-wide value); sun's
# own colour is below 3:1 everywhere (the nearest colour replaces it).
MANIFEST = """name: s
icons: [bolt.svg, wave.svg, leaf.svg, sun.svg]
palette:
  orange: "#ee7733"
  navy:   '#0000d0'   # single-quoted
  leafy: oklch(0.75 0.12 150)
color: cycle
alpha: 1.4   # set-wide
sizes: [16]
overrides:
  wave: {alpha: 1.3}
  sun:
    color: "#ffee00"
"""
POLICY = Policy(rules=frozenset({Rule.LOSS, Rule.BELOW_THRESHOLD, Rule.NEWLY_FAILING}))


def _project(root: Path, manifest: str = MANIFEST) -> Path:
    root.mkdir(parents=True, exist_ok=True)
    (root / ".git").mkdir(exist_ok=True)  # the project root
    for name in ("bolt", "wave", "leaf", "sun"):
        (root / f"{name}.svg").write_text(SVG)
    (root / "theme.yaml").write_text(THEME)
    (root / "set.yaml").write_bytes(manifest.encode())
    return root


def _failures(root: Path) -> set[tuple[str, str | None, tuple[str, ...]]]:
    report = check_project(
        ProjectConfig(themes=(root / "theme.yaml",), iconsets=(root / "set.yaml",), policy=POLICY)
    )
    return {(f.rule.value, f.canvas, f.icons) for f in report.gate.failures}


def _sarif(root: Path) -> dict[str, Any]:
    report = check_project(
        ProjectConfig(themes=(root / "theme.yaml",), iconsets=(root / "set.yaml",), policy=POLICY)
    )
    doc: dict[str, Any] = json.loads(CheckFormat.SARIF.renderer()(report, RenderOptions(base=root)))
    return doc


def _offset(text: str, line: int, column: int) -> int:
    """Character offset of a 1-based (line, column), lines ended by LF (or CRLF)."""
    lines = text.split("\n")
    return sum(len(s) + 1 for s in lines[: line - 1]) + column - 1


def _apply(text: str, replacement: dict[str, Any]) -> tuple[str, int, int]:
    """``text`` with one SARIF replacement applied; also the deleted region's offsets."""
    region = replacement["deletedRegion"]
    start = _offset(text, region["startLine"], region["startColumn"])
    end = _offset(text, region["endLine"], region["endColumn"])
    return text[:start] + replacement["insertedContent"]["text"] + text[end:], start, end


def _rule_name(doc: dict[str, Any], rule_id: str) -> str:
    rules = doc["runs"][0]["tool"]["driver"]["rules"]
    return str(next(r for r in rules if r["id"] == rule_id)["properties"]["alphaAuditRule"])


def _fixed(doc: dict[str, Any]) -> list[tuple[dict[str, Any], dict[str, Any]]]:
    return [(r, fx) for r in doc["runs"][0]["results"] for fx in r.get("fixes", [])]


@pytest.fixture(scope="module")
def failing(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, dict[str, Any]]:
    root = _project(tmp_path_factory.mktemp("failing"))
    return root, _sarif(root)


def test_every_kind_of_fix_is_offered_at_its_target(failing: tuple[Path, dict[str, Any]]) -> None:
    root, doc = failing
    text = (root / "set.yaml").read_text()
    got = {}
    for result, fx in _fixed(doc):
        (change,) = fx["artifactChanges"]
        assert change["artifactLocation"] == {"uri": "set.yaml", "uriBaseId": "%SRCROOT%"}
        (rep,) = change["replacements"]
        region = rep["deletedRegion"]
        line = text.split("\n")[region["startLine"] - 1]
        got[(result["properties"]["icons"][0], fx["description"]["text"].split(",")[0])] = (
            line,
            rep["insertedContent"]["text"],
        )
    # The override's alpha for wave, the set-wide alpha for leaf.  Judged as it
    # ships: navy on yellow shows code (0, 0, 208) up to a = 1.005 as at a = 1, and
    # (0, 0, 209) from 1.0055 on (a lower contrast), so 1.005 is the largest safe alpha.
    assert got[("wave", "set alpha to 1.005")] == ("  wave: {alpha: 1.3}", "1.005")
    leaf_alpha = next(v for (icon, d), v in got.items() if icon == "leaf" and "alpha" in d)
    assert leaf_alpha[0] == "alpha: 1.4   # set-wide" and float(leaf_alpha[1]) > 1.4
    # Colours: quotes as written (single stays single; a plain value gains double
    # quotes, since a bare # starts a YAML comment); sun's own colour on its override.
    navy = next(v for (icon, d), v in got.items() if icon == "wave" and d.startswith("use"))
    assert navy[0].startswith("  navy:") and navy[1].startswith("'#") and navy[1].endswith("'")
    leafy = next(v for (icon, d), v in got.items() if icon == "leaf" and d.startswith("use"))
    assert leafy[0].startswith("  leafy:") and leafy[1].startswith('"#')
    sun = next(v for (icon, d), v in got.items() if icon == "sun" and d.startswith("use"))
    assert sun[0] == '    color: "#ffee00"' and sun[1].startswith('"#')


def test_applying_each_fix_clears_its_finding_and_touches_only_its_region(
    failing: tuple[Path, dict[str, Any]], tmp_path: Path
) -> None:
    root, doc = failing
    original = (root / "set.yaml").read_text()
    before = _failures(root)
    pairs = _fixed(doc)
    assert len(pairs) >= 5  # the three kinds, at override, set-wide, palette and icon targets
    for k, (result, fx) in enumerate(pairs):
        finding = (
            _rule_name(doc, result["ruleId"]),
            result["properties"]["canvas"],
            tuple(result["properties"]["icons"]),
        )
        assert finding in before
        (rep,) = fx["artifactChanges"][0]["replacements"]
        edited, start, end = _apply(original, rep)
        # Only the deleted region changed, and it held what the snippet says.
        assert original[start:end] == rep["deletedRegion"]["snippet"]["text"]
        inserted = rep["insertedContent"]["text"]
        assert edited[:start] == original[:start]
        assert edited[start + len(inserted) :] == original[end:]
        copy = tmp_path / f"p{k}"
        shutil.copytree(root, copy)
        (copy / "set.yaml").write_text(edited)
        after = _failures(copy)
        assert finding not in after, (fx["description"]["text"], finding)


def test_crlf_manifests_get_regions_in_lf_or_crlf_lines(tmp_path: Path) -> None:
    root = _project(tmp_path / "crlf", MANIFEST.replace("\n", "\r\n"))
    doc = _sarif(root)
    original = (root / "set.yaml").read_bytes().decode()
    pairs = _fixed(doc)
    assert pairs
    for _, fx in pairs:
        (rep,) = fx["artifactChanges"][0]["replacements"]
        _, start, end = _apply(original, rep)
        assert original[start:end] == rep["deletedRegion"]["snippet"]["text"]
        assert "\r" not in original[start:end]


def test_no_fix_without_a_written_target(tmp_path: Path) -> None:
    # No alpha: key anywhere (the default 1 is written nowhere) and colours
    # written as hex on the icons: an alpha fix would have to insert a key.
    manifest = """name: s
icons:
  - {file: leaf.svg, color: "#ffee00"}
sizes: [16]
"""
    root = _project(tmp_path / "bare", manifest)
    doc = _sarif(root)
    kinds = [fx["description"]["text"] for _, fx in _fixed(doc)]
    assert kinds and all(k.startswith("use #") for k in kinds)  # only the colour is written
    failing = [r for r in doc["runs"][0]["results"] if "suppressions" not in r]
    assert failing and all("Fix: " in r["message"]["text"] for r in failing)


def test_alpha_from_the_command_line_gets_no_alpha_fix(tmp_path: Path) -> None:
    root = _project(tmp_path / "cli")
    report = check_project(
        ProjectConfig(
            themes=(root / "theme.yaml",), iconsets=(root / "set.yaml",), policy=POLICY, alpha=1.4
        )
    )
    doc = json.loads(CheckFormat.SARIF.renderer()(report, RenderOptions(base=root)))
    texts = [fx["description"]["text"] for _, fx in _fixed(doc)]
    assert texts and not any(t.startswith("set alpha") for t in texts)


def test_colour_findings_point_at_the_palette_entry(failing: tuple[Path, dict[str, Any]]) -> None:
    root, doc = failing
    lines = (root / "set.yaml").read_text().split("\n")
    for result in doc["runs"][0]["results"]:
        if result["properties"]["icons"] == ["leaf"]:
            first = result["locations"][0]["physicalLocation"]
            region = first["region"]
            line = lines[region["startLine"] - 1]
            assert line.startswith("  leafy:")
            assert line[region["startColumn"] - 1 : region["endColumn"] - 1] == (
                "oklch(0.75 0.12 150)"
            )


# SARIF 2.1.0 schema (OASIS, sarif-schema-2.1.0.json), the definitions a fix
# uses: required properties, and every property allowed (additionalProperties
# is false in each).  Checked structurally, as the other SARIF tests do.
_ALLOWED = {
    "fix": ({"artifactChanges"}, {"description", "artifactChanges", "properties"}),
    "artifactChange": (
        {"artifactLocation", "replacements"},
        {"artifactLocation", "replacements", "properties"},
    ),
    "replacement": ({"deletedRegion"}, {"deletedRegion", "insertedContent", "properties"}),
    "artifactContent": (set(), {"text", "binary", "rendered", "properties"}),
    "message": (set(), {"text", "markdown", "id", "arguments", "properties"}),
}
_REGION = {
    "startLine",
    "startColumn",
    "endLine",
    "endColumn",
    "charOffset",
    "charLength",
    "byteOffset",
    "byteLength",
    "snippet",
    "message",
    "sourceLanguage",
    "properties",
}


def _shape(kind: str, value: dict[str, Any]) -> None:
    required, allowed = _ALLOWED[kind]
    assert required <= set(value) <= allowed, (kind, sorted(value))


def test_fixes_have_the_schema_shape(failing: tuple[Path, dict[str, Any]]) -> None:
    _, doc = failing
    run = doc["runs"][0]
    assert run["columnKind"] in ("utf16CodeUnits", "unicodeCodePoints")  # 3.14.27
    pairs = _fixed(doc)
    assert pairs
    for _, fx in pairs:
        _shape("fix", fx)
        _shape("message", fx["description"])
        assert fx["artifactChanges"]  # minItems 1
        for change in fx["artifactChanges"]:
            _shape("artifactChange", change)
            assert set(change["artifactLocation"]) == {"uri", "uriBaseId"}
            assert not change["artifactLocation"]["uri"].startswith("/")
            assert change["replacements"]  # minItems 1
            for rep in change["replacements"]:
                _shape("replacement", rep)
                _shape("artifactContent", rep["insertedContent"])
                region = rep["deletedRegion"]
                assert set(region) <= _REGION
                for key in ("startLine", "startColumn", "endLine", "endColumn"):
                    assert isinstance(region[key], int) and region[key] >= 1  # minimum 1
                assert (region["endLine"], region["endColumn"]) > (
                    region["startLine"],
                    region["startColumn"],
                )


# ------------------------------------------------------------------ token files

TOKEN_MANIFEST = """name: s
icons: [sun.svg]
color: color.icon.warn
sizes: [16]
"""


def _token_project(root: Path, file: str, text: str) -> Path:
    root.mkdir(parents=True)
    (root / ".git").mkdir()
    (root / "sun.svg").write_text(SVG)
    (root / file).write_bytes(text.encode())
    (root / "set.yaml").write_text(TOKEN_MANIFEST)
    (root / "alpha-audit.yaml").write_text(
        f'tokens:\n  file: {file}\n  canvases: "color.bg.*"\n  colors: "color.icon.*"\n'
        "  modes: {default: light}\niconset: set.yaml\n"
    )
    return root


def _token_check(root: Path) -> Any:
    from alpha_audit.load.config import load_config

    project = load_config(root / "alpha-audit.yaml")
    return check_project(
        ProjectConfig(iconsets=project.iconsets, policy=POLICY, tokens=project.tokens)
    )


@pytest.mark.parametrize(
    ("file", "text"),
    [
        (
            "tokens.json",
            '{\r\n  "color": {\r\n    "$type": "color",\r\n'
            '    "bg": {"canvas": {"$value": "#ffffff"}},\r\n'
            '    "base": {"sun": {"$value": "#ffcc00"}},\r\n'
            '    "icon": {"warn": {"$value": "{color.base.sun}"}}\r\n  }\r\n}\r\n',
        ),
        (
            "theme.css",
            "@theme {\n  --color-bg-canvas: #ffffff;\n  --color-base-sun:   #ffcc00;\n"
            "  --color-icon-warn: var(--color-base-sun);\n}\n",
        ),
        # A byte-order mark is a code point of line 1: the region starts one column later.
        (
            "tokens.json",
            '\ufeff{"color": {"$type": "color", "bg": {"canvas": {"$value": "#ffffff"}}, '
            '"base": {"sun": {"$value": "#ffcc00"}}, "icon": {"warn": {"$value": '
            '"{color.base.sun}"}}}}\n',
        ),
        (
            "theme.css",
            "\ufeff@theme { --color-bg-canvas: #ffffff; --color-base-sun: #ffcc00; "
            "--color-icon-warn: var(--color-base-sun); }\n",
        ),
    ],
    ids=["json", "css", "json-bom", "css-bom"],
)
def test_a_token_colour_fix_edits_the_token_value(tmp_path: Path, file: str, text: str) -> None:
    root = _token_project(tmp_path / "tokens", file, text)
    report = _token_check(root)
    before = {(f.rule.value, f.canvas, f.icons) for f in report.gate.failures}
    assert before
    doc = json.loads(CheckFormat.SARIF.renderer()(report, RenderOptions(base=root)))
    pairs = [(r, fx) for r, fx in _fixed(doc) if fx["description"]["text"].startswith("use #")]
    assert pairs
    for k, (result, fx) in enumerate(pairs):
        (change,) = fx["artifactChanges"]
        assert change["artifactLocation"]["uri"] == file
        (rep,) = change["replacements"]
        edited, start, end = _apply(text, rep)
        assert (
            text[start:end]
            == rep["deletedRegion"]["snippet"]["text"]
            == "#ffcc00".join(['"', '"'] if file.endswith(".json") else ["", ""])
        )
        copy = tmp_path / f"edited{k}"
        shutil.copytree(root, copy)
        (copy / file).write_bytes(edited.encode())
        finding = (
            _rule_name(doc, result["ruleId"]),
            result["properties"]["canvas"],
            tuple(result["properties"]["icons"]),
        )
        assert finding in before
        after = {(f.rule.value, f.canvas, f.icons) for f in _token_check(copy).gate.failures}
        assert finding not in after


def test_a_token_project_keeps_the_manifest_alpha_as_a_fix_target(tmp_path: Path) -> None:
    text = '{"color": {"$type": "color", "bg": {"canvas": {"$value": "#ffff00"}},\n'
    text += ' "icon": {"warn": {"$value": "#0000d0"}}}}\n'  # navy on yellow: loses above 1
    root = _token_project(tmp_path / "alpha", "tokens.json", text)
    (root / "set.yaml").write_text(TOKEN_MANIFEST + "alpha: 1.3\n")
    report = _token_check(root)
    doc = json.loads(CheckFormat.SARIF.renderer()(report, RenderOptions(base=root)))
    alpha = [fx for _, fx in _fixed(doc) if fx["description"]["text"].startswith("set alpha")]
    assert alpha
    change = alpha[0]["artifactChanges"][0]
    assert change["artifactLocation"]["uri"] == "set.yaml"
    assert change["replacements"][0]["deletedRegion"]["snippet"]["text"] == "1.3"


def test_no_colour_fix_for_a_token_value_that_also_sets_a_canvas(tmp_path: Path) -> None:
    text = (
        '{"color": {"$type": "color", "base": {"sun": {"$value": "#ffcc00"}},\n'
        ' "bg": {"canvas": {"$value": "{color.base.sun}"}, "paper": {"$value": "#ffffff"}},\n'
        ' "icon": {"warn": {"$value": "{color.base.sun}"}}}}\n'
    )
    root = _token_project(tmp_path / "shared", "tokens.json", text)
    report = _token_check(root)
    assert report.gate.failures
    doc = json.loads(CheckFormat.SARIF.renderer()(report, RenderOptions(base=root)))
    assert not [fx for _, fx in _fixed(doc) if fx["description"]["text"].startswith("use #")]


def test_no_colour_fix_for_a_token_value_that_is_another_modes_canvas(tmp_path: Path) -> None:
    # --color-base-sun is light's icon colour and, through an alias, dark's canvas: the
    # nearest-colour edit would move dark's canvas, so it is not offered.
    text = (
        ":root {\n  --color-base-sun: #ffcc00;\n  --color-bg-canvas: #ffffff;\n"
        "  --color-icon-warn: var(--color-base-sun);\n}\n"
        '[data-theme="dark"] {\n  --color-bg-canvas: {canvas};\n  --color-icon-warn: #000000;\n}\n'
    )
    offered = []
    for dark_canvas in ("#222222", "var(--color-base-sun)"):
        root = _token_project(
            tmp_path / str(len(offered)), "t.css", text.replace("{canvas}", dark_canvas)
        )
        (root / "alpha-audit.yaml").write_text(
            (root / "alpha-audit.yaml").read_text().replace("  modes: {default: light}\n", "")
            + "alpha: 1.0\n"
        )
        report = _token_check(root)
        assert report.gate.failures  # the yellow icon on white is below 3:1
        doc = json.loads(CheckFormat.SARIF.renderer()(report, RenderOptions(base=root)))
        sun = [
            fx
            for _, fx in _fixed(doc)
            for change in fx["artifactChanges"]
            for rep in change["replacements"]
            if rep["deletedRegion"]["snippet"]["text"] == "#ffcc00"
        ]
        offered.append(sun)
    assert offered[0] and not offered[1]


def test_a_locked_colour_gets_no_colour_fix(tmp_path: Path) -> None:
    root = _project(
        tmp_path / "locked", MANIFEST.replace("color: cycle\n", "color: cycle\nlock: [navy]\n")
    )
    wave = [
        fx["description"]["text"]
        for r, fx in _fixed(_sarif(root))
        if r["properties"]["icons"] == ["wave"]
    ]
    assert wave and not any(t.startswith("use #") for t in wave)  # the alpha fix stays


def test_a_fix_on_line_1_of_a_manifest_with_a_byte_order_mark_counts_it(tmp_path: Path) -> None:
    manifest = "alpha: 1.4   # set-wide\n" + MANIFEST.replace("alpha: 1.4   # set-wide\n", "")
    root = _project(tmp_path / "bom", "\ufeff" + manifest)
    text = (root / "set.yaml").read_text("utf-8")
    replaced = [
        (rep, _apply(text, rep))
        for _, fx in _fixed(_sarif(root))
        for rep in fx["artifactChanges"][0]["replacements"]
        if rep["deletedRegion"]["startLine"] == 1
    ]
    assert replaced  # the set-wide alpha's fix
    for rep, (_, start, end) in replaced:
        assert rep["deletedRegion"]["startColumn"] == len("\ufeffalpha: ") + 1
        assert text[start:end] == rep["deletedRegion"]["snippet"]["text"] == "1.4"
