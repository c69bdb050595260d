"""``check`` outputs: ``-o`` belongs to the ``-f`` before it, every target is checked first."""

from __future__ import annotations

import json
import os
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.cli.check import pair_outputs
from alpha_audit.errors import UsageError
from alpha_audit.render import CheckFormat

REPO = Path(__file__).resolve().parents[2]
INPUTS = [str(REPO / "themes" / "github-primer.yaml"), str(REPO / "examples/vibrant/iconset.yaml")]
FMT, OUT = "format", "output"


def run(args: list[str], cwd: Path):
    old = Path.cwd()
    os.chdir(cwd)
    try:
        return CliRunner().invoke(app, args, catch_exceptions=False)
    finally:
        os.chdir(old)


def test_each_output_goes_to_the_format_before_it(tmp_path: Path) -> None:
    args = ["check", *INPUTS, "--exit-zero", "-f", "table", "-f", "junit", "-o", "j.xml"]
    args += ["-f", "sarif", "-o", "a.sarif", "-f", "json", "-o", "r.json"]
    result = run(args, tmp_path)
    assert result.exit_code == 0, result.output
    assert ET.parse(tmp_path / "j.xml").getroot().tag == "testsuites"
    assert json.loads((tmp_path / "a.sarif").read_text())["version"] == "2.1.0"
    assert json.loads((tmp_path / "r.json").read_text())["schema"] == "alpha-audit.check/4"
    assert "alpha-audit check" in result.stdout  # the table, on stdout


def test_a_later_bad_target_stops_the_run_before_anything_is_written(tmp_path: Path) -> None:
    (tmp_path / "taken.json").write_text("mine")
    args = ["check", *INPUTS, "-f", "sarif", "-o", "a.sarif", "-f", "json", "-o", "taken.json"]
    result = run(args, tmp_path)
    assert result.exit_code == 2
    assert "taken.json" in result.output and "already exists" in result.output
    assert not (tmp_path / "a.sarif").exists()
    assert (tmp_path / "taken.json").read_text() == "mine"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["taken.json"]  # no temporary file


def test_the_baseline_target_is_checked_with_the_reports(tmp_path: Path) -> None:
    (tmp_path / "base.json").write_text("{}")
    args = ["check", *INPUTS, "-f", "json", "-o", "r.json", "--write-baseline", "base.json"]
    result = run(args, tmp_path)
    assert result.exit_code == 2 and "base.json" in result.output
    assert not (tmp_path / "r.json").exists()


@pytest.mark.parametrize(
    ("formats", "outputs", "order", "expected"),
    [
        ([], [], [], [(CheckFormat.TABLE, None)]),
        (["json"], ["r.json"], [OUT, FMT], [(CheckFormat.JSON, Path("r.json"))]),  # one -o, one -f
        ([], ["r.txt"], [OUT], [(CheckFormat.TABLE, Path("r.txt"))]),
        (
            ["table", "junit"],
            ["junit.xml"],
            [FMT, FMT, OUT],
            [(CheckFormat.TABLE, None), (CheckFormat.JUNIT, Path("junit.xml"))],
        ),
        (
            ["junit", "table"],
            ["j.xml"],
            [FMT, OUT, FMT],
            [(CheckFormat.JUNIT, Path("j.xml")), (CheckFormat.TABLE, None)],
        ),
        (["table", "json"], ["-", "r.json"], [FMT, OUT, FMT, OUT], None),  # fine: "-" is stdout
    ],
)
def test_pairing(formats, outputs, order, expected) -> None:
    got = pair_outputs([CheckFormat(f) for f in formats], [Path(o) for o in outputs], order)
    if expected is not None:
        assert got == expected
    else:
        assert got == [(CheckFormat.TABLE, None), (CheckFormat.JSON, Path("r.json"))]


@pytest.mark.parametrize(
    ("formats", "outputs", "order", "words"),
    [
        (
            ["junit"],
            ["a.sarif"],
            [FMT, OUT],
            ["a.sarif", "junit", ".xml", "another format"],
        ),  # extension of sarif
        (["github", "table"], ["-"], [FMT, OUT, FMT], ["github and table"]),
        (["json", "table"], [], [FMT, FMT], ["json and table", "stdout"]),
        (["json", "sarif"], ["a.json", "b.sarif"], [OUT, FMT, FMT, OUT], ["a.json", "before any"]),
        (
            ["json", "sarif"],
            ["a.json", "b.json"],
            [FMT, OUT, OUT, FMT],
            ["b.json", "after --format"],
        ),
    ],
)
def test_pairing_refuses(formats, outputs, order, words) -> None:
    with pytest.raises(UsageError) as err:
        pair_outputs([CheckFormat(f) for f in formats], [Path(o) for o in outputs], order)
    for word in words:
        assert word in str(err.value)


def test_reports_name_files_relative_to_the_folder_they_ran_in(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A JSON or table uploaded from CI names no folder of the machine (problems included)."""
    (tmp_path / ".git").mkdir()
    (tmp_path / "svg").mkdir()
    ns = 'xmlns="http://www.w3.org/2000/svg"'
    (tmp_path / "svg" / "ok.svg").write_text(f'<svg {ns} viewBox="0 0 8 8"><rect width="8"/></svg>')
    (tmp_path / "svg" / "broken.svg").write_text("<svg")
    (tmp_path / "set.yaml").write_text("name: s\nicons: svg/*.svg\ncolor: '#0077bb'\nsizes: [16]\n")
    monkeypatch.chdir(tmp_path)
    from typer.testing import CliRunner

    from alpha_audit.cli import app

    for fmt in ("json", "table"):
        result = CliRunner().invoke(app, ["check", "paper16", "set.yaml", "-f", fmt])
        assert result.exit_code in (0, 1), result.output
        assert "broken" in result.output
        assert str(tmp_path) not in result.output and str(tmp_path.resolve()) not in result.output
    doc = json.loads(CliRunner().invoke(app, ["check", "paper16", "set.yaml", "-f", "json"]).stdout)
    assert doc["problems"][0]["file"] == "svg/broken.svg"
    assert doc["iconset"]["path"] == "set.yaml"


def test_ci_formats_name_files_from_the_repository_root_when_run_in_a_subfolder(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """GitHub annotations and SARIF's %SRCROOT% want paths from the checkout, not the cwd."""
    import shutil

    from typer.testing import CliRunner

    from alpha_audit.cli import app

    root = Path(__file__).resolve().parents[2]
    (tmp_path / ".git").mkdir()
    shutil.copytree(root / "examples" / "vibrant", tmp_path / "design" / "vibrant")
    (tmp_path / "ci").mkdir()
    monkeypatch.chdir(tmp_path / "ci")
    manifest = "../design/vibrant/iconset.yaml"
    github = CliRunner().invoke(app, ["check", "paper16", manifest, "-a", "1.3", "-f", "github"])
    files = re.findall(r"file=([^,]+),", github.stdout)
    assert files and all(f.startswith("design/vibrant/") for f in files), github.stdout
    assert "../" not in github.stdout
    sarif = CliRunner().invoke(app, ["check", "paper16", manifest, "-a", "1.3", "-f", "sarif"])
    uris = re.findall(r'"uri": "([^"]+)"', sarif.stdout)
    assert uris and all(u.startswith("design/vibrant/") for u in uris), uris[:5]
