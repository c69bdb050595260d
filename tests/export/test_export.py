"""export: every colour equals the audit's output; DTCG/Tailwind exports read back the same."""

from __future__ import annotations

import json
import shutil
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.color import srgb_decode, to_8bit
from alpha_audit.errors import InputError, UsageError
from alpha_audit.export import ExportFormat, export_table, render_export, write_export
from alpha_audit.export.css import render_css
from alpha_audit.load.config import load_config
from alpha_audit.load.tokens import load_token_modes, parse_json, token_color, tokens_from_docs
from alpha_audit.load.tokens.model import TokenModes
from alpha_audit.load.tokens.themes import TokenConfig, load_token_themes, token_themes
from alpha_audit.model import Icon, IconSet
from alpha_audit.rows import audit

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples/tokens"


def _example_themes():
    return load_token_themes(load_config(EXAMPLE / "alpha-audit.yaml").tokens)


def test_example_modes_canvases_colours_and_gamut_report() -> None:
    themes = _example_themes()
    assert [m.name for m in themes.modes] == ["light", "dark"]
    light, dark = themes.modes
    assert [c.name for c in light.theme.canvases] == ["color.bg.canvas", "color.bg.subtle"]
    assert [c.mode for c in dark.theme.canvases] == ["dark", "dark"]
    assert light.theme.canvases[1].color == "#f6f8fa"  # via a $ref pointer
    assert light.colors["color.icon.info"].alpha == 1.15  # from $extensions
    (adj,) = themes.adjusted  # the display-p3 rose of the dark theme
    assert (adj.mode, adj.token, adj.policy) == ("dark", "color.icon.danger", "map")
    assert adj.file == EXAMPLE / "base.tokens.json" and adj.line == 16
    assert 0 < adj.delta_e < 5


def test_export_equals_the_audit_output_for_every_colour_and_canvas() -> None:
    themes = _example_themes()
    table = export_table(themes)
    for mode, emode in zip(themes.modes, table.modes, strict=True):
        icons = IconSet(
            "tokens",
            tuple(Icon(p, Path(f"{p}.svg"), c.css, c.alpha) for p, c in mode.colors.items()),
        )
        rows = {(r.icon, r.canvas): r.output for r in audit(mode.theme, icons).rows()}
        assert len(rows) == len(emode.colors) * len(emode.canvases)
        for color in emode.colors:
            for canvas, hex_ in zip(emode.canvases, color.outputs, strict=True):
                assert rows[(color.token, canvas.token)] == hex_


def test_svg_filter_reproduces_the_outputs() -> None:
    """feFuncX type=linear: clamp(slope*C + intercept) in linearRGB equals the output code."""
    import xml.etree.ElementTree as ET

    table = export_table(_example_themes())
    svg = ET.fromstring(render_export(table, "svg")["filters.svg"])
    ns = {"s": "http://www.w3.org/2000/svg"}
    filters = {f.get("id"): f for f in svg.iterfind(".//s:filter", ns)}
    for mode in table.modes:
        for color in mode.colors:
            for canvas, hex_ in zip(mode.canvases, color.outputs, strict=True):
                fid = f"alpha-{mode.name}-{canvas.short}-a{color.alpha:g}".replace(".", "_")
                funcs = filters[fid].findall(".//s:feComponentTransfer/*", ns)
                slope = np.array([float(f.get("slope")) for f in funcs])
                intercept = np.array([float(f.get("intercept")) for f in funcs])
                cs = srgb_decode(
                    np.array([int(color.source[i : i + 2], 16) for i in (1, 3, 5)]) / 255
                )
                # The filter runs on the source colour as the browser holds it (8-bit sRGB)
                codes = to_8bit(np.clip(slope * cs + intercept, 0, 1))
                expected = np.array([int(hex_[i : i + 2], 16) for i in (1, 3, 5)])
                assert np.abs(codes.astype(int) - expected).max() <= 1


def test_css_blocks_and_light_dark() -> None:
    table = export_table(_example_themes())
    css = render_css(table)
    assert '[data-theme="light"] {' in css and '[data-theme="dark"] {' in css
    light = table.modes[0].colors[0].outputs[0]
    dark = table.modes[1].colors[0].outputs[0]
    assert f"--color-icon-info-on-canvas: light-dark({light}, {dark});" in css
    assert "color-scheme: light dark;" in css
    assert render_css(table, selector=".theme-<mode>").count(".theme-light {") == 1


def test_hostile_names_are_escaped(tmp_path: Path) -> None:
    doc = {
        "c": {
            "$type": "color",
            "bg;--x:0": {"$value": "#ffffff"},
            "i<svg>": {"$value": "#ff0000", "$extensions": {"com.alpha-audit": {"alpha": 1.1}}},
        }
    }
    modes = TokenModes(tmp_path, "dtcg", {'da"rk': tokens_from_docs([parse_json(json.dumps(doc))])})
    config = TokenConfig(file=tmp_path, canvases=("c.bg*",), colors=("c.i*",))
    table = export_table(token_themes(modes, config))
    css = render_export(table, "css")["colors.css"]
    assert ";--x:0" not in css and '"da"rk"' not in css
    svg = render_export(table, "svg")["filters.svg"]
    assert "<svg>" not in svg.split("\n", 1)[1]


def test_write_export_refuses_existing_files_and_writes_nothing(tmp_path: Path) -> None:
    files = render_export(export_table(_example_themes()), "dtcg")
    (tmp_path / "dark.tokens.json").write_text("mine")
    with pytest.raises(UsageError, match="already exists"):
        write_export(files, tmp_path)
    assert not (tmp_path / "light.tokens.json").exists()
    assert (tmp_path / "dark.tokens.json").read_text() == "mine"
    write_export(files, tmp_path, overwrite=True)
    assert (tmp_path / "dark.tokens.json").read_text() != "mine"


def test_every_format_renders() -> None:
    table = export_table(_example_themes())
    for fmt in ExportFormat:
        files = render_export(table, fmt)
        assert files and all(text.endswith("\n") for text in files.values())


def _read_back(files: dict[str, str], tmp_path: Path, fmt: str) -> dict[str, dict[str, str]]:
    """{mode: {token path: hex}} read back from exported files."""
    out = {}
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    for name in files:
        modes = load_token_modes(tmp_path / name)
        for mode, tokens in modes.modes.items():
            key = name.split(".")[0] if fmt == "dtcg" else mode
            out[key] = {
                p: "#"
                + "".join(f"{int(v):02x}" for v in np.rint(np.array(token_color(t).encoded) * 255))
                for p, t in tokens.items()
            }
    return out


colour = st.tuples(*(st.integers(0, 255) for _ in range(3))).map(lambda c: "#" + bytes(c).hex())


@settings(max_examples=25, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    canvases=st.lists(colour, min_size=1, max_size=3),
    icons=st.lists(st.tuples(colour, st.floats(-2, 3, allow_nan=False)), min_size=1, max_size=4),
    dark_shift=st.integers(0, 255),
)
def test_round_trip_exported_tokens_give_back_the_same_colours(
    tmp_path_factory, canvases, icons, dark_shift
) -> None:
    tmp = tmp_path_factory.mktemp("rt")
    modes = {}
    for mode in ("light", "dark"):
        doc = {"color": {"$type": "color", "bg": {}, "icon": {}}}
        for i, c in enumerate(canvases):
            if mode == "dark":
                c = "#" + bytes((int(c[k : k + 2], 16) + dark_shift) % 256 for k in (1, 3, 5)).hex()
            doc["color"]["bg"][f"c{i}"] = {"$value": c}
        for i, (c, a) in enumerate(icons):
            doc["color"]["icon"][f"i{i}"] = {
                "$value": c,
                "$extensions": {"com.alpha-audit": {"alpha": a}},
            }
        modes[mode] = tokens_from_docs([parse_json(json.dumps(doc))])
    themes = token_themes(
        TokenModes(tmp, "dtcg", modes),
        TokenConfig(file=tmp, canvases=("color.bg.*",), colors=("color.icon.*",)),
    )
    table = export_table(themes)
    expected = {
        m.name: {
            (c.token if len(m.canvases) == 1 else f"{c.token}.on.{cv.short}"): out
            for c in m.colors
            for cv, out in zip(m.canvases, c.outputs, strict=True)
        }
        for m in table.modes
    }
    dtcg = _read_back(render_export(table, "dtcg"), tmp, "dtcg")
    assert dtcg == expected
    resolver = _read_back(render_export(table, "resolver"), tmp, "resolver")
    assert resolver == expected
    tw_dir = tmp / "tw"
    tw_dir.mkdir()
    tailwind = _read_back(render_export(table, "tailwind"), tw_dir, "tailwind")
    assert tailwind["default"] == {k: v for k, v in expected["light"].items()}
    assert tailwind["dark"] == expected["dark"]
    shutil.rmtree(tmp)


def test_config_tokens_errors(tmp_path: Path) -> None:
    cfg = tmp_path / "alpha-audit.yaml"
    cfg.write_text("tokens:\n  file: t.json\n  canvases: 'a.*'\n  gamut: squash\n")
    with pytest.raises(InputError, match=r"alpha-audit\.yaml:4.*gamut.*clip, map, error"):
        load_config(cfg)
    cfg.write_text("tokens:\n  file: ../t.json\n  canvases: 'a.*'\n")
    with pytest.raises(InputError, match="outside"):
        load_config(cfg)


def test_cli_export(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    project = tmp_path / "p"
    shutil.copytree(EXAMPLE, project)
    monkeypatch.chdir(project)
    runner = CliRunner()
    result = runner.invoke(app, ["export", "-f", "json"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert data["schema"] == "alpha-audit.export/1" and data["gamut"] == "map"
    out = project / "out"
    out.mkdir()
    assert runner.invoke(app, ["export", "-f", "dtcg", "-o", str(out)]).exit_code == 0
    again = runner.invoke(app, ["export", "-f", "dtcg", "-o", str(out)])
    assert again.exit_code == 2 and "already exists" in again.output
    assert runner.invoke(app, ["export", "-f", "dtcg", "-o", str(out), "--force"]).exit_code == 0
    err = runner.invoke(app, ["export", "--gamut", "error"])
    assert err.exit_code == 2 and "base.tokens.json:16: color.icon.danger" in err.output
    assert runner.invoke(app, ["export", "-f", "nope"]).exit_code == 2


def test_cli_check_on_tokens_and_export_agree(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The bar: export colours equal check's output for every icon colour and canvas."""
    import yaml

    project = tmp_path / "p"
    shutil.copytree(EXAMPLE, project)
    monkeypatch.chdir(project)
    runner = CliRunner()
    checked = runner.invoke(app, ["check", "-f", "json"])
    assert checked.exit_code in (0, 1), checked.output
    exported = json.loads(runner.invoke(app, ["export", "-f", "json"]).stdout)
    manifest = yaml.safe_load((project / "iconset.yaml").read_text())
    color_of = {icon: o["color"] for icon, o in manifest["overrides"].items()}
    audits = json.loads(checked.stdout)["audits"]
    assert len(audits) == len(exported["modes"]) == 2
    compared = 0
    for audit_doc, mode in zip(audits, exported["modes"], strict=True):
        outputs = {c["token"]: c["outputs"] for c in mode["colors"]}
        for row in audit_doc["rows"]:
            assert row["output"] == outputs[color_of[row["icon"]]][row["canvas"]]
            compared += 1
    assert compared == 16


def test_replace_keeps_exact_colours_and_takes_new_ones() -> None:
    from dataclasses import replace

    icon = Icon("i", Path("i.svg"), "oklch(0.55 0.16 255)", 1.0)
    assert replace(icon, alpha=1.2).linear == icon.linear
    assert replace(icon, color="#ff0000").linear == (1.0, 0.0, 0.0)


def test_cli_export_without_a_project_config_says_none_was_found(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # In a folder with no config, "the project config has no tokens: table" sent a
    # new user looking for a config that does not exist.
    (tmp_path / ".git").mkdir()  # the project root: discovery stops here
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(app, ["export"])
    assert result.exit_code == 2
    (line,) = result.output.strip().splitlines()
    assert "no project config found" in line and "alpha-audit.yaml" in line
    assert "tokens:" in line


def test_css_header_names_the_token_file_as_written() -> None:
    # A CSS comment does not interpret escapes: "system\2e resolver\2e json" is
    # what a reader saw. The name stays readable; only "*/" could end the comment.
    table = export_table(_example_themes())
    first = render_css(table).splitlines()[0]
    assert first.startswith("/* alpha-audit export from system.resolver.json ")
    hostile = render_css(replace(table, source="a*/b{}.json")).splitlines()[0]
    assert hostile.count("*/") == 1 and hostile.endswith("*/")


def _css_project(tmp_path: Path, colors: str, css: str) -> Path:
    (tmp_path / ".git").mkdir()
    (tmp_path / "t.css").write_text(css)
    (tmp_path / "alpha-audit.yaml").write_text(
        f"alpha: 1.1\ntokens:\n  file: t.css\n  canvases: bg\n  colors: {colors!r}\n"
    )
    return tmp_path


def test_export_refuses_a_colours_glob_that_matches_nothing(tmp_path: Path) -> None:
    from alpha_audit.export import table_from_config

    project = _css_project(tmp_path, "icon.*", ":root { --bg: #fff; --fg: #0062ba }")
    with pytest.raises(InputError, match=r"colors: 'icon\.\*' matches no colour token of t\.css"):
        table_from_config(load_config(project / "alpha-audit.yaml"))


def test_export_refuses_two_token_paths_that_become_one_property(tmp_path: Path) -> None:
    from alpha_audit.export import table_from_config

    css = '{"bg": {"$type": "color", "$value": "#fff"}, "a": {"$type": "color", '
    css += '"b-c": {"$value": "#123456"}}, "a-b": {"$type": "color", "c": {"$value": "#654321"}}}'
    (tmp_path / ".git").mkdir()
    (tmp_path / "t.tokens.json").write_text(css)
    (tmp_path / "alpha-audit.yaml").write_text(
        "alpha: 1.1\ntokens:\n  file: t.tokens.json\n  canvases: bg\n  colors: 'a*'\n"
    )
    table = table_from_config(load_config(tmp_path / "alpha-audit.yaml"))
    assert len(render_export(table, "dtcg")) == 1  # DTCG keeps the two paths apart
    for fmt in ("css", "tailwind"):
        with pytest.raises(
            InputError, match=r"token (color\.)?a\.b-c and token (color\.)?a-b\.c both become"
        ):
            render_export(table, fmt)


def _css_table(tmp_path: Path, css: str, colors: str, canvases: str = "bg"):  # type: ignore[no-untyped-def]
    from alpha_audit.export import table_from_config

    project = _css_project(tmp_path, colors, css)
    config = project / "alpha-audit.yaml"
    config.write_text(config.read_text().replace("canvases: bg", f"canvases: {canvases!r}"))
    return table_from_config(load_config(config))


def test_export_refuses_two_modes_that_become_one_file_or_filter_id(tmp_path: Path) -> None:
    css = ':root { --bg: #fff; --fg: #0062ba } [data-theme="a b"] { --bg: #000 } '
    css += '[data-theme="a_b"] { --bg: #111 }'
    table = _css_table(tmp_path, css, "fg")
    assert len(table.modes) == 3
    with pytest.raises(InputError, match=r"mode a b and mode a_b both become the DTCG file a_b"):
        render_export(table, "dtcg")
    with pytest.raises(InputError, match=r"mode a b on bg .* and mode a_b on bg .* filter id"):
        render_export(table, "svg")
    assert render_export(table, "resolver")  # contexts keep the names themselves


def test_dtcg_export_refuses_a_token_that_would_have_to_be_a_group(tmp_path: Path) -> None:
    # The token fg.on.bg (from --fg-on-bg) drawn on bg is fg.on.bg.on.bg, and fg drawn
    # on bg is fg.on.bg: in DTCG one token would have to hold the other.
    css = ":root { --bg: #fff; --bg2: #eee; --fg: #0062ba; --fg-on-bg: #123456 }"
    table = _css_table(tmp_path, css, "fg*", "bg*")
    with pytest.raises(InputError, match=r"DTCG tokens fg\.on\.bg and fg\.on\.bg\.on\.bg"):
        render_export(table, "dtcg")
    assert "--fg-on-bg-on-bg: " in render_export(table, "css")["colors.css"]


def test_export_refuses_two_outputs_that_meet_in_one_token_path(tmp_path: Path) -> None:
    # a on the canvas b.on.c and a.on.b on the canvas c are both a.on.b.on.c
    css = ":root { --x-b-on-c: #fff; --x-c: #eee; --a: #0062ba; --a-on-b: #123456 }"
    table = _css_table(tmp_path, css, "a*", "x.*")
    for fmt in ("css", "dtcg", "tailwind"):
        with pytest.raises(InputError, match=r"a on x\.b\.on\.c and a\.on\.b on x\.c both"):
            render_export(table, fmt)
