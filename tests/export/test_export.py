"""export: every colour equals the audit's output; DTCG/Tailwind exports read back the same."""

from __future__ import annotations

import json
import shutil
from dataclasses import replace
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.color import srgb_decode, to_8bit
from alpha_audit.errors import InputError, UsageError
from alpha_audit.export import ExportFormat, export_project, render_export, write_export
from alpha_audit.export.css import render_css
from alpha_audit.load.config import Overrides, load_config, resolve_config
from alpha_audit.load.tokens import load_token_modes, token_color
from alpha_audit.load.tokens.themes import load_token_themes
from alpha_audit.model import Icon
from alpha_audit.pipeline import check_project
from helpers import spec_hex

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples/tokens"


def _example_themes():
    return load_token_themes(load_config(EXAMPLE / "alpha-audit.yaml").tokens)


def _example_table():  # type: ignore[no-untyped-def]
    return export_project(load_config(EXAMPLE / "alpha-audit.yaml"))


def _check_outputs(project) -> dict[tuple[str, str, str], str]:  # type: ignore[no-untyped-def]
    """``{(theme, icon, canvas): output}`` of check's rows of each icon's manifest colour
    (the ``currentColor`` paint at opacity 1), SVGs read and rendered as check does."""
    out = {}
    for result in check_project(project).audits:
        for row in result.rows():
            if row.paint == "currentColor" and row.opacity == 1.0:
                out[(result.theme.name, row.icon, row.canvas)] = row.output
    return out


def assert_export_is_checks(project) -> int:  # type: ignore[no-untyped-def]
    """Every exported output is check's row output for that icon colour, canvas and theme,
    and every such row of check's is exported; returns how many were compared."""
    table = export_project(project)
    checked = _check_outputs(project)
    seen = set()
    for mode in table.modes:
        for color in mode.colors:
            for canvas, hex_ in zip(mode.canvases, color.outputs, strict=True):
                for icon in color.icons:
                    key = (mode.name, icon, canvas.token)
                    assert checked[key] == hex_, (key, color.token)
                    seen.add(key)
    assert seen == set(checked)
    return len(seen)


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


@pytest.mark.parametrize("pipeline", ["linear", "css"])
@pytest.mark.parametrize("theme", ["paper16.yaml", "github-primer.yaml", "material3.yaml"])
def test_export_of_the_bundled_yaml_example_is_checks_outputs(theme: str, pipeline: str) -> None:
    """The bar (issue 28): YAML themes and a manifest, both pipelines, every output is check's.

    Under css the manifest's alpha 1.1 cannot be drawn, so the project's alpha is 0.9
    (a set-wide ``alpha:``, as a config writes it); under linear the manifest's own
    alphas (1.1, and 1.18 for one icon) apply.
    """
    overrides = Overrides(
        themes=(REPO / "themes" / theme,),
        iconsets=(REPO / "examples/vibrant/iconset.yaml",),
        pipeline=pipeline,
        alpha=0.9 if pipeline == "css" else None,
    )
    project = resolve_config(overrides, REPO)
    compared = assert_export_is_checks(project)
    table = export_project(project)
    assert {m.pipeline for m in table.modes} == {pipeline}
    assert compared == 12 * sum(len(m.canvases) for m in table.modes)
    # And what the specs give, written out here (not alpha-audit's code).
    for mode in table.modes:
        for color in mode.colors:
            for canvas, hex_ in zip(mode.canvases, color.outputs, strict=True):
                assert hex_ == _spec_output(color.source, canvas.hex, color.alpha, pipeline)


def _spec_output(source: str, canvas: str, alpha: float, pipeline: str) -> str:
    """The displayed 8-bit colour by the paper (linear) or CSS Compositing 1 (css)."""
    if pipeline == "linear":  # clip(Cb + a (Cs - Cb)) in linear light, then encoded
        cs, cb = spec_hex(source), spec_hex(canvas)
        shown = np.clip(cb + alpha * (cs - cb), 0.0, 1.0)
        encoded = np.where(shown <= 0.0031308, 12.92 * shown, 1.055 * shown ** (1 / 2.4) - 0.055)
        return "#" + "".join(f"{int(v):02x}" for v in np.rint(encoded * 255.0))
    # source-over on the encoded codes, in exact arithmetic, rounded half to even
    a = Fraction(alpha).limit_denominator(10**6)
    s, b = ([int(c[k : k + 2], 16) for k in (1, 3, 5)] for c in (source, canvas))
    return "#" + "".join(f"{round(cb + a * (cs - cb)):02x}" for cs, cb in zip(s, b, strict=True))


def test_export_of_the_token_example_is_checks_outputs() -> None:
    """The manifest's alpha where a token carries none, as check applies it."""
    assert assert_export_is_checks(load_config(EXAMPLE / "alpha-audit.yaml")) == 16


def test_the_pipeline_in_force_changes_the_export() -> None:
    """pipeline: css (a config key, not only the flag) is the pipeline every output follows."""
    base = Overrides(
        themes=(REPO / "themes/github-primer.yaml",),
        iconsets=(REPO / "examples/vibrant/iconset.yaml",),
        alpha=0.9,
    )
    linear = export_project(resolve_config(base, REPO))
    css = export_project(resolve_config(replace(base, pipeline="css"), REPO))
    pairs = [
        (a, b)
        for m, n in zip(linear.modes, css.modes, strict=True)
        for c, d in zip(m.colors, n.colors, strict=True)
        for a, b in zip(c.outputs, d.outputs, strict=True)
    ]
    assert len(pairs) == 7 * 8 and sum(a != b for a, b in pairs) > 40


def test_yaml_names_are_palette_roles_and_icons_with_their_own_alpha() -> None:
    """vibrant: seven palette colours at the set's 1.1, and alert (orange at 1.18) apart."""
    project = resolve_config(
        Overrides(themes=("paper16",), iconsets=(REPO / "examples/vibrant/iconset.yaml",)), REPO
    )
    (mode,) = export_project(project).modes
    names = {c.token: (c.alpha, c.icons) for c in mode.colors}
    assert list(names) == ["alert", "blue", "cyan", "magenta", "red", "teal", "grey", "orange"]
    assert names["orange"] == (1.1, ("info",))
    assert names["alert"] == (1.18, ("alert",))
    assert names["orange"][0] == 1.1 and "alert" not in names["orange"][1]


def test_svg_filter_reproduces_the_outputs() -> None:
    """feFuncX type=linear: clamp(slope*C + intercept) in linearRGB equals the output code."""
    import xml.etree.ElementTree as ET

    table = _example_table()
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
    table = _example_table()
    css = render_css(table)
    assert '[data-theme="light"] {' in css and '[data-theme="dark"] {' in css
    light, dark = (
        next(c for c in m.colors if c.token == "color.icon.info").outputs[0] for m in table.modes
    )
    assert f"--color-icon-info-on-canvas: light-dark({light}, {dark});" in css
    assert "color-scheme: light dark;" in css
    assert render_css(table, selector=".theme-<mode>").count(".theme-light {") == 1


def _token_project(
    tmp: Path, docs: dict[str, dict], canvases: str, colors: str, extra: str = ""
) -> Path:
    """A project whose tokens are one DTCG file per mode behind a Resolver document."""
    (tmp / ".git").mkdir(exist_ok=True)
    contexts = {}
    for k, (mode, doc) in enumerate(docs.items()):
        (tmp / f"m{k}.tokens.json").write_text(json.dumps(doc))
        contexts[mode] = [{"$ref": f"m{k}.tokens.json"}]
    resolver = {
        "version": "2025.10",
        "modifiers": {"theme": {"contexts": contexts, "default": next(iter(docs))}},
        "resolutionOrder": [{"$ref": "#/modifiers/theme"}],
    }
    (tmp / "t.resolver.json").write_text(json.dumps(resolver))
    config = tmp / "alpha-audit.yaml"
    config.write_text(
        f"tokens:\n  file: t.resolver.json\n  canvases: {canvases!r}\n  colors: {colors!r}\n"
        + extra
    )
    return config


def test_hostile_names_are_escaped(tmp_path: Path) -> None:
    doc = {
        "c": {
            "$type": "color",
            "bg;--x:0": {"$value": "#ffffff"},
            "i<svg>": {"$value": "#ff0000", "$extensions": {"com.alpha-audit": {"alpha": 1.1}}},
        }
    }
    config = _token_project(tmp_path, {'da"rk': doc}, "c.bg*", "c.i*")
    table = export_project(load_config(config))
    css = render_export(table, "css")["colors.css"]
    assert ";--x:0" not in css and '"da"rk"' not in css
    svg = render_export(table, "svg")["filters.svg"]
    assert "<svg>" not in svg.split("\n", 1)[1]


def test_write_export_refuses_existing_files_and_writes_nothing(tmp_path: Path) -> None:
    files = render_export(_example_table(), "dtcg")
    (tmp_path / "dark.tokens.json").write_text("mine")
    with pytest.raises(UsageError, match="already exists"):
        write_export(files, tmp_path)
    assert not (tmp_path / "light.tokens.json").exists()
    assert (tmp_path / "dark.tokens.json").read_text() == "mine"
    write_export(files, tmp_path, overwrite=True)
    assert (tmp_path / "dark.tokens.json").read_text() != "mine"


def test_every_format_renders() -> None:
    table = _example_table()
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
                p.removesuffix(".$root"): "#"
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
    docs = {}
    for mode in ("light", "dark"):
        doc: dict = {"color": {"$type": "color", "bg": {}, "icon": {}}}
        for i, c in enumerate(canvases):
            if mode == "dark":
                c = "#" + bytes((int(c[k : k + 2], 16) + dark_shift) % 256 for k in (1, 3, 5)).hex()
            doc["color"]["bg"][f"c{i}"] = {"$value": c}
        for i, (c, a) in enumerate(icons):
            doc["color"]["icon"][f"i{i}"] = {
                "$value": c,
                "$extensions": {"com.alpha-audit": {"alpha": a}},
            }
        docs[mode] = doc
    table = export_project(load_config(_token_project(tmp, docs, "color.bg.*", "color.icon.*")))
    expected = {
        name: {
            (c.token if len(m.canvases) == 1 else f"{c.token}.on.{cv.short}"): out
            for c in m.colors
            for cv, out in zip(m.canvases, c.outputs, strict=True)
        }
        for m in table.modes
        for name in m.names
    }
    out = tmp / "out"
    out.mkdir()
    dtcg = _read_back(render_export(table, "dtcg"), out, "dtcg")
    assert dtcg == expected
    resolver = _read_back(render_export(table, "resolver"), out, "resolver")
    assert resolver == expected
    tw_dir = tmp / "tw"
    tw_dir.mkdir()
    tailwind = _read_back(render_export(table, "tailwind"), tw_dir, "tailwind")
    first = table.modes[0].name
    assert tailwind["default"] == expected[first]
    for name in expected:
        if name != first:
            assert tailwind[name] == expected[name]
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
    assert "THEME ICONSET" in line


def test_css_header_names_the_token_file_as_written() -> None:
    # A CSS comment does not interpret escapes: "system\2e resolver\2e json" is
    # what a reader saw. The name stays readable; only "*/" could end the comment.
    table = _example_table()
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
    project = _css_project(tmp_path, "icon.*", ":root { --bg: #fff; --fg: #0062ba }")
    with pytest.raises(InputError, match=r"colors: 'icon\.\*' matches no colour token of t\.css"):
        export_project(load_config(project / "alpha-audit.yaml"))


def test_export_refuses_two_token_paths_that_become_one_property(tmp_path: Path) -> None:
    css = '{"bg": {"$type": "color", "$value": "#fff"}, "a": {"$type": "color", '
    css += '"b-c": {"$value": "#123456"}}, "a-b": {"$type": "color", "c": {"$value": "#654321"}}}'
    (tmp_path / ".git").mkdir()
    (tmp_path / "t.tokens.json").write_text(css)
    (tmp_path / "alpha-audit.yaml").write_text(
        "alpha: 1.1\ntokens:\n  file: t.tokens.json\n  canvases: bg\n  colors: 'a*'\n"
    )
    table = export_project(load_config(tmp_path / "alpha-audit.yaml"))
    assert len(render_export(table, "dtcg")) == 1  # DTCG keeps the two paths apart
    for fmt in ("css", "tailwind"):
        with pytest.raises(
            InputError, match=r"token (color\.)?a\.b-c and token (color\.)?a-b\.c both become"
        ):
            render_export(table, fmt)


def _css_table(tmp_path: Path, css: str, colors: str, canvases: str = "bg"):  # type: ignore[no-untyped-def]
    project = _css_project(tmp_path, colors, css)
    config = project / "alpha-audit.yaml"
    config.write_text(config.read_text().replace("canvases: bg", f"canvases: {canvases!r}"))
    return export_project(load_config(config))


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


def test_dtcg_export_writes_a_token_that_is_also_a_group_as_its_root(tmp_path: Path) -> None:
    # The token fg.on.bg (from --fg-on-bg) drawn on bg is fg.on.bg.on.bg, and fg drawn
    # on bg is fg.on.bg: DTCG 2025.10 writes the group's own token as $root.
    css = ":root { --bg: #fff; --bg2: #eee; --fg: #0062ba; --fg-on-bg: #123456 }"
    table = _css_table(tmp_path, css, "fg*", "bg*")
    (text,) = render_export(table, "dtcg").values()
    group = json.loads(text)["fg"]["on"]["bg"]
    assert set(group) == {"$root", "on"} and "$value" in group["$root"]
    read = _read_back(render_export(table, "dtcg"), tmp_path, "dtcg")["default"]
    assert {"fg.on.bg", "fg.on.bg.on.bg"} <= set(read)
    assert "--fg-on-bg-on-bg: " in render_export(table, "css")["colors.css"]


def test_export_refuses_two_outputs_that_meet_in_one_token_path(tmp_path: Path) -> None:
    # a on the canvas b.on.c and a.on.b on the canvas c are both a.on.b.on.c
    css = ":root { --x-b-on-c: #fff; --x-c: #eee; --a: #0062ba; --a-on-b: #123456 }"
    table = _css_table(tmp_path, css, "a*", "x.*")
    for fmt in ("css", "dtcg", "tailwind"):
        with pytest.raises(InputError, match=r"a on x\.b\.on\.c and a\.on\.b on x\.c both"):
            render_export(table, fmt)


def test_modes_check_audits_once_are_still_written(tmp_path: Path) -> None:
    """A CSS mode with another's colours is audited once; export writes it under its name."""
    css = ':root { --bg: #fff; --fg: #0062ba } [data-theme="dark"] { --bg: #111; --fg: #78a9ff }'
    css += ' [data-theme="dark-dimmed"] { --bg: #111; --fg: #78a9ff }'
    table = _css_table(tmp_path, css, "fg")
    assert [(m.name, m.aliases) for m in table.modes] == [
        ("default", ()),
        ("dark", ("dark-dimmed",)),
    ]
    files = render_export(table, "dtcg")
    assert sorted(files) == ["dark-dimmed.tokens.json", "dark.tokens.json", "default.tokens.json"]
    assert json.loads(files["dark-dimmed.tokens.json"])["fg"]["$value"]["hex"] == "#7db0ff"
    assert '[data-theme="dark"], [data-theme="dark-dimmed"] {' in render_css(table)
    contexts = json.loads(render_export(table, "resolver")["colors.resolver.json"])
    assert set(contexts["modifiers"]["theme"]["contexts"]) == {"default", "dark", "dark-dimmed"}
    assert json.loads(render_export(table, "json")["colors.json"])["modes"][1]["aliases"] == [
        "dark-dimmed"
    ]
    svg = render_export(table, "svg")["filters.svg"]
    assert 'id="alpha-dark-dimmed-bg"' in svg and 'id="alpha-dark-bg"' in svg


def test_dtcg_root_for_a_path_that_is_also_a_group(tmp_path: Path) -> None:
    """color.background and color.background.body (issue 29): $root, not a refusal."""
    css = ":root { --bg: #fff; --color-background: #123456; --color-background-body: #654321 }"
    table = _css_table(tmp_path, css, "color.background*")
    (text,) = render_export(table, "dtcg").values()
    group = json.loads(text)["color"]["background"]
    assert set(group) == {"$root", "body"}
    assert group["$root"]["$extensions"]["com.alpha-audit"]["source"] == "#123456"
    read = _read_back(render_export(table, "dtcg"), tmp_path, "dtcg")["default"]
    assert set(read) == {"color.background", "color.background.body"}


def test_css_pipeline_filters_blend_in_srgb() -> None:
    """Under pipeline css the filter works on encoded values (sRGB), as the browser blends."""
    import xml.etree.ElementTree as ET

    overrides = Overrides(
        themes=("paper16",), iconsets=(REPO / "examples/vibrant/iconset.yaml",), pipeline="css"
    )
    table = export_project(resolve_config(replace(overrides, alpha=0.6), REPO))
    svg = ET.fromstring(render_export(table, "svg")["filters.svg"])
    ns = {"s": "http://www.w3.org/2000/svg"}
    (mode,) = table.modes
    for f in svg.iterfind(".//s:filter", ns):
        assert f.get("color-interpolation-filters") == "sRGB"
    filters = {f.get("id"): f for f in svg.iterfind(".//s:filter", ns)}
    for color in mode.colors:
        for canvas, hex_ in zip(mode.canvases, color.outputs, strict=True):
            funcs = filters[f"alpha-{mode.name}-{canvas.short}"].findall(
                ".//s:feComponentTransfer/*", ns
            )
            slope = np.array([float(f.get("slope")) for f in funcs])
            intercept = np.array([float(f.get("intercept")) for f in funcs])
            source = np.array([int(color.source[i : i + 2], 16) for i in (1, 3, 5)]) / 255
            codes = np.rint(255 * np.clip(slope * source + intercept, 0, 1))
            expected = np.array([int(hex_[i : i + 2], 16) for i in (1, 3, 5)])
            assert np.abs(codes - expected).max() <= 1  # a tie may round either way


def test_errors_name_files_relative_to_the_project(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A YAML project's error names the file as the user would type it, never absolute."""
    (tmp_path / ".git").mkdir()
    (tmp_path / "icons").mkdir()
    (tmp_path / "icons" / "iconset.yaml").write_text('name: s\nicons: []\ncolor: "#12"\n')
    shutil.copy(REPO / "themes/paper16.yaml", tmp_path / "paper16.yaml")
    (tmp_path / "alpha-audit.yaml").write_text("theme: paper16.yaml\niconset: icons/iconset.yaml\n")
    (tmp_path / "sub").mkdir()
    runner = CliRunner()
    # Relative to the project root, wherever in it the command runs (as the reports are).
    for here, shown in ((tmp_path, "icons/iconset.yaml:3"), (tmp_path / "sub", "icons/")):
        monkeypatch.chdir(here)
        result = runner.invoke(app, ["export"])
        assert result.exit_code == 2
        assert f"error: {shown}" in result.output and str(tmp_path) not in result.output
