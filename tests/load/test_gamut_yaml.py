"""The gamut policy for YAML themes and manifests (issue 12, deliverable 2)."""

from __future__ import annotations

import json
from pathlib import Path

import colour
import numpy as np
import pytest
from coloraide import Color

from alpha_audit.color import srgb_decode
from alpha_audit.errors import InputError
from alpha_audit.load.config import ProjectConfig, load_config
from alpha_audit.load.iconset import load_iconset
from alpha_audit.load.theme import load_theme
from alpha_audit.pipeline import check_project
from alpha_audit.policy import Policy
from alpha_audit.render import CheckFormat, RenderOptions

P3 = "color(display-p3 0.1 0.9 0.2)"
SVG = (
    '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 24 24">'
    '<rect width="24" height="24"/></svg>'
)


def _theme(tmp_path: Path, own: str | None = None) -> Path:
    path = tmp_path / "theme.yaml"
    head = f"gamut: {own}\n" if own else ""
    path.write_text(
        f"name: wide\n{head}canvases:\n"
        '  - {name: paper, color: "#ffffff"}\n'
        '  - {name: calm, color: "oklch(0.7 0.1 200)"}\n'
        f'  - {{name: p3, color: "{P3}"}}\n'
    )
    return path


def _manifest(tmp_path: Path, own: str | None = None) -> Path:
    (tmp_path / ".git").mkdir(exist_ok=True)
    (tmp_path / "a.svg").write_text(SVG)
    path = tmp_path / "iconset.yaml"
    head = f"gamut: {own}\n" if own else ""
    path.write_text(
        f"name: set\n{head}palette:\n  brand: '{P3}'\n  ink: '#222222'\n"
        "icons: [a.svg]\ncolor: brand\n"
    )
    return path


def _independent(policy: str) -> np.ndarray:
    """Linear sRGB of the P3 colour fitted by coloraide directly (not through our code)."""
    c = Color(P3)
    if policy == "map":
        c = c.fit("srgb", method="minde-chroma", pspace="oklch", jnd=0.02)
    return srgb_decode(np.clip(c.convert("srgb")[:3], 0, 1))


def _delta_e(policy: str) -> float:
    """CIEDE2000 by colour-science from coloraide's linear values (independent path).

    colour-science derives its sRGB matrix from the primaries, our metrics and
    coloraide use CSS Color 4's; the two differ in the 4th decimal, hence the
    1e-3 tolerance where this is compared.
    """
    before = Color(P3).convert("srgb-linear")[:3]
    d65 = colour.CCS_ILLUMINANTS["CIE 1931 2 Degree Standard Observer"]["D65"]
    lab = [
        colour.XYZ_to_Lab(colour.RGB_to_XYZ(x, "sRGB"), d65) for x in (before, _independent(policy))
    ]
    return float(colour.delta_E(lab[0], lab[1], method="CIE 2000"))


def test_out_of_srgb_is_an_error_by_default_naming_file_line_and_key(tmp_path) -> None:
    with pytest.raises(InputError, match=r"theme\.yaml:5: canvases\[2\]\.color: .*outside sRGB"):
        load_theme(_theme(tmp_path))


def _line_of(path: Path, needle: str) -> int:
    return next(n for n, t in enumerate(path.read_text().splitlines(), 1) if needle in t)


@pytest.mark.parametrize("policy", ["clip", "map"])
def test_the_files_own_policy_fits_like_coloraide(tmp_path, policy) -> None:
    path = _theme(tmp_path, policy)
    theme = load_theme(path)
    np.testing.assert_allclose(theme.canvases[2].linear, _independent(policy), atol=1e-12)
    (note,) = theme.adjusted
    assert (note.file, note.line, note.token, note.mode) == (
        path,
        _line_of(path, P3),
        "canvases[2].color",
        "wide",
    )
    assert note.policy == policy and note.text == P3
    assert note.delta_e == pytest.approx(_delta_e(policy), abs=1e-3)
    encoded = colour.cctf_encoding(_independent(policy), function="sRGB")
    assert note.output == "#" + "".join(f"{int(v):02x}" for v in np.rint(encoded * 255))


def test_in_gamut_colours_keep_their_numbers_under_every_policy(tmp_path) -> None:
    path = _theme(tmp_path)
    path.write_text(path.read_text().replace(P3, "rgb(10 20 30)"))
    reference = load_theme(path)
    for policy in ("clip", "map"):
        fitted = load_theme(path, gamut=policy)
        assert fitted.adjusted == ()
        for a, b in zip(reference.canvases, fitted.canvases, strict=True):
            assert a.linear == b.linear and a.color == b.color


def test_the_projects_policy_wins_over_the_files(tmp_path) -> None:
    theme = load_theme(_theme(tmp_path, "error"), gamut="clip")
    np.testing.assert_allclose(theme.canvases[2].linear, _independent("clip"), atol=1e-12)
    with pytest.raises(InputError, match="outside sRGB"):
        load_theme(_theme(tmp_path, "map"), gamut="error")


def test_a_bad_policy_names_the_key_and_the_choices(tmp_path) -> None:
    with pytest.raises(InputError, match=r"theme\.yaml:2: gamut: 'squash'.*clip, map, error"):
        load_theme(_theme(tmp_path, "squash"))


def test_manifest_palette_colours_follow_the_manifests_policy(tmp_path) -> None:
    with pytest.raises(InputError, match=r"iconset\.yaml:\d+: palette\.brand: .*outside sRGB"):
        load_iconset(_manifest(tmp_path))
    iconset = load_iconset(_manifest(tmp_path, "clip"))
    np.testing.assert_allclose(iconset.icons[0].linear, _independent("clip"), atol=1e-12)
    (note,) = iconset.adjusted
    assert (note.token, note.mode, note.line) == ("palette.brand", "set", 4)


def test_check_reports_each_moved_colour_in_json_table_and_markdown(tmp_path) -> None:
    report = check_project(
        ProjectConfig(
            themes=(_theme(tmp_path),),
            iconsets=(_manifest(tmp_path),),
            policy=Policy(),
            gamut="map",
        )
    )
    assert {(n.token, n.mode) for n in report.gamut} == {
        ("canvases[2].color", "wide"),
        ("palette.brand", "set"),
    }
    options = RenderOptions(base=tmp_path)
    doc = json.loads(CheckFormat.JSON.renderer()(report, options))
    rows = {r["key"]: r for r in doc["gamut"]}
    assert set(rows) == {"canvases[2].color", "palette.brand"}
    row = rows["canvases[2].color"]
    assert (row["file"], row["line"], row["policy"], row["before"]) == ("theme.yaml", 5, "map", P3)
    assert row["delta_e"] == pytest.approx(_delta_e("map"), abs=1e-3)
    assert row["after"] == report.audits[0].theme.canvases[2].color
    table = CheckFormat.TABLE.renderer()(report, RenderOptions(base=tmp_path, width=200))
    lines = [line for line in table.splitlines() if P3 in line]
    assert len(lines) == 2 and any("theme.yaml:5 canvases[2].color" in x for x in lines)
    markdown = CheckFormat.MARKDOWN.renderer()(report, options)
    assert "Colours outside sRGB (2)" in markdown


def test_the_configs_gamut_reaches_themes_and_tokens(tmp_path) -> None:
    (tmp_path / "t.json").write_text(
        json.dumps(
            {"bg": {"$type": "color", "$value": P3}, "ic": {"$type": "color", "$value": "#000"}}
        )
    )
    cfg = tmp_path / "alpha-audit.yaml"
    cfg.write_text("gamut: clip\ntokens:\n  file: t.json\n  canvases: bg\n  colors: ic\n")
    project = load_config(cfg)
    assert project.gamut == "clip" and project.tokens.gamut == "clip"
    cfg.write_text(
        "gamut: clip\ntokens:\n  file: t.json\n  canvases: bg\n  colors: ic\n  gamut: map\n"
    )
    assert load_config(cfg).tokens.gamut == "map"  # the tokens: table's own key wins
