"""Issue 18: suggest answers from the gate's rows, joins confusing roles, writes palette alphas."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.load.iconset import load_iconset
from alpha_audit.suggest.apply import edit_alphas

VIBRANT = Path(__file__).parents[2] / "examples" / "vibrant" / "svg"


def _project(tmp_path: Path, manifest: str) -> Path:
    (tmp_path / ".git").mkdir()
    shutil.copytree(VIBRANT, tmp_path / "svg")
    (tmp_path / "iconset.yaml").write_text(manifest)
    return tmp_path


def _run(args: list[str], cwd: Path):  # type: ignore[no-untyped-def]
    import os

    old = Path.cwd()
    os.chdir(cwd)
    try:
        return CliRunner().invoke(app, args, catch_exceptions=False)
    finally:
        os.chdir(old)


ROLES = 'name: roles\nicons: svg/*.svg\npalette:\n  orange: "#ee7733"\n  red: {color: "#cc3311"}\n'


def test_apply_colour_joins_confusing_roles_and_check_then_passes(tmp_path: Path) -> None:
    root = _project(tmp_path, ROLES + '  blue: "#0077bb"\nalpha: 1.3\n')
    assert _run(["check", "paper16", "iconset.yaml"], root).exit_code == 1  # orange/red confused
    result = _run(["suggest", "paper16", "iconset.yaml", "--apply", "colour"], root)
    assert result.exit_code == 0, result.output
    assert "the gate passes with what was written" in result.output
    doc = yaml.safe_load((root / "iconset.yaml").read_text())
    # One line per colour: the palette entries carry their alpha, no per-icon overrides.
    assert "overrides" not in doc
    palette = doc["palette"]
    assert palette["orange"]["alpha"] == palette["red"]["alpha"] < 1.3  # the joint answer
    assert palette["orange"]["color"] == "#ee7733" and palette["red"]["color"] == "#cc3311"
    assert _run(["check", "paper16", "iconset.yaml"], root).exit_code == 0


def test_a_palette_alpha_sets_its_icons_unless_they_set_their_own(tmp_path: Path) -> None:
    root = _project(
        tmp_path,
        'name: p\nicons: svg/*.svg\npalette:\n  orange: {color: "#ee7733", alpha: 1.3}\n'
        '  blue: "#0077bb"\nalpha: 1.1\noverrides:\n  alert: {alpha: 1.0}\n',
    )
    icons = {i.name: i for i in load_iconset(root / "iconset.yaml").icons}
    assert icons["alert"].alpha == 1.0  # its own override wins
    oranges = [i for i in icons.values() if i.color_name == "orange" and i.name != "alert"]
    assert oranges and all(i.alpha == 1.3 for i in oranges)
    assert all(i.alpha_span is not None and i.alpha_span.start_line == 4 for i in oranges)
    blues = [i for i in icons.values() if i.color_name == "blue"]
    assert blues and all(i.alpha == 1.1 for i in blues)  # no alpha of its own: the set's


@pytest.mark.parametrize(
    ("palette", "expected"),
    [
        (
            'palette:\n  red: "#cc3311"  # brand\n',
            'palette:\n  red: {color: "#cc3311", alpha: 1.2}  # brand\n',
        ),
        (
            "palette:\n  red: {color: '#cc3311'}\n",
            "palette:\n  red: {color: '#cc3311', alpha: 1.2}\n",
        ),
        (
            "palette:\n  red: {color: '#cc3311', alpha: 1.1}\n",
            "palette:\n  red: {color: '#cc3311', alpha: 1.2}\n",
        ),
        (
            "palette:\n  red:\n    color: '#cc3311'\nname: x\n",
            "palette:\n  red:\n    color: '#cc3311'\n    alpha: 1.2\nname: x\n",
        ),
    ],
)
def test_editing_a_palette_alpha_keeps_the_layout(palette: str, expected: str) -> None:
    assert edit_alphas(palette, palette={"red": "1.2"}) == expected


def test_suggest_leaves_out_an_unreadable_svg_as_check_does(tmp_path: Path) -> None:
    root = _project(tmp_path, ROLES + "alpha: 1.1\n")
    (root / "svg" / "broken.svg").write_text("<svg><path d='M0 0 L")
    check = _run(["check", "paper16", "iconset.yaml", "-f", "json"], root)
    assert "broken" in check.output
    result = _run(["suggest", "paper16", "iconset.yaml", "-f", "json"], root)
    assert result.exit_code == 0, result.output
    doc = yaml.safe_load(result.stdout)
    assert doc["left_out"] == ["broken"]
    assert "broken" not in {i["icon"] for i in doc["per_icon"]}
