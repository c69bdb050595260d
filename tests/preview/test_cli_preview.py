"""``alpha-audit preview`` through typer's runner: files, refusals, exit codes."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from typer.testing import CliRunner

from alpha_audit.cli import app

ROOT = Path(__file__).resolve().parents[2]
THEME = str(ROOT / "themes" / "paper16.yaml")
ICONSET = str(ROOT / "examples" / "vibrant" / "iconset.yaml")


def run(*args: str):
    return CliRunner().invoke(app, ["preview", THEME, ICONSET, *args])


def test_grid_sheets_and_page_are_written_and_listed(tmp_path):
    out, page = tmp_path / "sheets", tmp_path / "page.html"
    result = run("-o", str(out), "--html", str(page), "-s", "24")
    assert result.exit_code == 0, result.output
    names = sorted(p.name for p in out.iterdir())
    assert len(names) == 16
    assert "paper16-grid-white-24px.png" in names
    listed = re.findall(r"wrote (\S+)", result.output)
    assert sorted(Path(p).name for p in listed) == sorted([*names, "page.html"])
    assert page.read_text().startswith("<!doctype html>")


@pytest.mark.parametrize(
    ("layout", "extra", "expected"),
    [
        ("swatches", [], 16),
        ("compare", ["-a", "2"], 1),
        ("compare", ["--near-source", "-a", "2", "-s", "16", "-s", "48"], 2),
    ],
)
def test_layouts(tmp_path, layout, extra, expected):
    result = run("-o", str(tmp_path), "-l", layout, *extra)
    assert result.exit_code == 0, result.output
    assert len(list(tmp_path.glob("*.png"))) == expected


def test_existing_files_are_not_replaced_without_force(tmp_path):
    assert run("-o", str(tmp_path), "-l", "compare").exit_code == 0
    target = tmp_path / "paper16-compare-48px.png"
    before = target.read_bytes()
    result = run("-o", str(tmp_path), "-l", "compare", "-a", "1.4")
    assert result.exit_code == 2
    assert "already exists; pass --force" in result.output
    assert target.read_bytes() == before
    assert run("-o", str(tmp_path), "-l", "compare", "-a", "1.4", "--force").exit_code == 0
    assert target.read_bytes() != before


@pytest.mark.parametrize(
    ("args", "message"),
    [
        ([], "nothing to write"),
        (
            ["-o", "OUT", "-a", "nan"],
            "--alpha nan is out of range; expected a finite coefficient between -100 and 100",
        ),
        (["-o", "OUT", "-s", "0"], "--size 0 is out of range; expected whole pixels 1-1024"),
        (["-o", "OUT", "-l", "mosaic"], "mosaic"),
        (["--html", "missing/page.html"], "does not exist"),
    ],
)
def test_bad_options_exit_2(tmp_path, args, message):
    args = [a.replace("OUT", str(tmp_path)) for a in args]
    args = [str(tmp_path / a) if a.startswith("missing/") else a for a in args]
    result = run(*args)
    assert result.exit_code == 2
    assert message in result.output


def test_bad_theme_is_an_input_error(tmp_path):
    theme = tmp_path / "t.yaml"
    theme.write_text("name: x\ncanvases: []\n")
    result = CliRunner().invoke(app, ["preview", str(theme), ICONSET, "-o", str(tmp_path)])
    assert result.exit_code == 2
    assert str(theme) in result.output


def test_page_data_carries_the_theme_and_sizes(tmp_path):
    page = tmp_path / "p.html"
    assert run("--html", str(page), "-a", "1.3").exit_code == 0
    text = page.read_text()
    data = json.loads(re.search(r'id="alpha-audit-data">(.*?)</script>', text, re.S).group(1))
    assert data["alpha"] == 1.3
    assert data["sizes"] == [16, 24, 48]
    assert len(data["canvases"]) == 16


@pytest.mark.parametrize("many", ["canvases", "sizes"])
def test_more_sheets_than_the_cap_are_refused_before_any_icon_is_drawn(tmp_path, monkeypatch, many):
    from alpha_audit.preview import files
    from alpha_audit.preview.sheets import MAX_SHEETS

    def never(*args, **kwargs):
        raise AssertionError("icons were rendered before the sheet count was checked")

    monkeypatch.setattr(files, "paint_masks", never)
    theme, sizes = THEME, [f"-s{s}" for s in range(1, MAX_SHEETS // 16 + 2)]  # 16 canvases
    if many == "canvases":
        theme, sizes = str(tmp_path / "wide.yaml"), []
        rows = "".join(f'  - {{name: c{i}, color: "#{i:06x}"}}\n' for i in range(4096))
        Path(theme).write_text(f"name: wide\ncanvases:\n{rows}")
    out = tmp_path / "sheets"
    result = CliRunner().invoke(app, ["preview", theme, ICONSET, "-o", str(out), *sizes])
    assert result.exit_code == 2, result.output
    assert f"would write more than {MAX_SHEETS} PNG sheets" in result.output
    assert Path(theme).name in result.output and "--html" in result.output
    assert not any(out.glob("*.png"))


def test_webp_sheets_hold_the_same_pixels_as_png_and_are_smaller(tmp_path):
    """--format webp is lossless: every sheet decodes to the PNG's pixels, in fewer bytes."""
    from PIL import Image

    png, webp = tmp_path / "png", tmp_path / "webp"
    assert run("-o", str(png), "-s", "24").exit_code == 0
    result = run("-o", str(webp), "-s", "24", "--format", "webp")
    assert result.exit_code == 0, result.output
    assert sorted(p.stem for p in webp.glob("*.webp")) == sorted(p.stem for p in png.iterdir())
    assert not list(webp.glob("*.png"))
    for sheet in png.iterdir():
        twin = webp / f"{sheet.stem}.webp"
        with Image.open(sheet) as a, Image.open(twin) as b:
            assert b.format == "WEBP"
            assert a.size == b.size
            assert a.convert("RGBA").tobytes() == b.convert("RGBA").tobytes()
    assert sum(f.stat().st_size for f in webp.iterdir()) < sum(
        f.stat().st_size for f in png.iterdir()
    )
    listed = re.findall(r"wrote (\S+)", result.output)
    assert all(p.endswith(".webp") for p in listed) and len(listed) == 16


def test_existing_webp_sheet_is_not_replaced_without_force(tmp_path):
    assert run("-o", str(tmp_path), "-l", "compare", "-f", "webp").exit_code == 0
    target = tmp_path / "paper16-compare-48px.webp"
    before = target.read_bytes()
    result = run("-o", str(tmp_path), "-l", "compare", "-f", "webp", "-a", "1.4")
    assert result.exit_code == 2
    assert "already exists; pass --force" in result.output
    assert target.read_bytes() == before
