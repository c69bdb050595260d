"""Previews draw and label what the rows say: each paint in its colour, the rows' numbers."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest
from PIL import Image
from typer.testing import CliRunner

from alpha_audit import load_iconset, load_theme
from alpha_audit.cli import app
from alpha_audit.load.paint_masks import paint_masks
from alpha_audit.preview.figures import preview_rows
from multipaint import write_multipaint


def _check_json(theme, manifest, pipeline, alpha):
    args = ["check", str(theme), str(manifest), "--format", "json", "--pipeline", pipeline]
    result = CliRunner().invoke(app, [*args, "-a", str(alpha)])
    return json.loads(result.stdout)


@pytest.mark.parametrize(("pipeline", "alpha"), [("linear", 1.2), ("css", 0.8)])
def test_labels_are_the_json_rows_size_contrast(tmp_path, pipeline, alpha):
    theme_path, manifest = write_multipaint(tmp_path)
    theme, iconset = load_theme(theme_path), load_iconset(manifest)
    masks = paint_masks([(i.name, i.file) for i in iconset.icons], [24, 48], cache=False)
    drawn = preview_rows(theme, iconset, masks, [24, 48], pipeline)
    report = _check_json(theme_path, manifest, pipeline, alpha)
    canvases = [c.name for c in theme.canvases]
    for size in (24, 48):
        labels = drawn.size_contrast(alpha, size, iconset.icons)
        for i, icon in enumerate(iconset.icons):
            for j, canvas in enumerate(canvases):
                rows = [
                    r for r in report["rows"] if r["icon"] == icon.name and r["canvas"] == canvas
                ]
                want = min(r["sizes"][str(size)]["contrast"] for r in rows)
                assert labels[i, j] == pytest.approx(want, abs=1e-9), (icon.name, canvas, size)
    # The figures: a disc at opacity 0.3 on white is 1.40 (linear), not its colour's 21;
    # css blends encoded values and shows #b2b2b2, 2.12.
    disc = [i.name for i in iconset.icons].index("disc")
    want = 1.40 if pipeline == "linear" else 2.12
    assert drawn.size_contrast(1.0, 48, iconset.icons)[disc, 0] == pytest.approx(want, abs=0.005)


def test_a_red_stroke_is_drawn_red_and_marked_fixed(tmp_path):
    theme_path, manifest = write_multipaint(tmp_path)
    out = tmp_path / "out"
    result = CliRunner().invoke(
        app, ["preview", str(theme_path), str(manifest), "-o", str(out), "-a", "1", "-s", "48"]
    )
    assert result.exit_code == 0, result.output
    pixels = np.asarray(Image.open(out / "t-grid-white-48px.png"))
    colours = {tuple(int(v) for v in p) for p in pixels.reshape(-1, 3)}
    assert (255, 0, 0) in colours  # the red stroke, fully covered
    assert (9, 105, 218) in colours  # the two-colour icon's currentColor square, manifest blue


def test_css_previews_agree_with_check_css(tmp_path):
    # preview --pipeline css draws the css rows: the disc at 0.3 is b' + 0.3 (0 - b') in codes.
    theme_path, manifest = write_multipaint(tmp_path)
    out = tmp_path / "out"
    args = ["preview", str(theme_path), str(manifest), "-o", str(out), "-a", "1", "-s", "48"]
    result = CliRunner().invoke(app, [*args, "--pipeline", "css"])
    assert result.exit_code == 0, result.output
    pixels = np.asarray(Image.open(out / "t-grid-white-48px.png")).reshape(-1, 3)
    report = _check_json(theme_path, manifest, "css", 1.0)
    (disc,) = [r for r in report["rows"] if r["icon"] == "disc" and r["canvas"] == "white"]
    solid = tuple(int(disc["output"][k : k + 2], 16) for k in (1, 3, 5))
    assert solid == (178, 178, 178)  # round(255 - 0.3 * 255) = 178.5 -> 178, half to even
    linear = CliRunner().invoke(app, [*args[:4], str(tmp_path / "lin"), *args[5:]])
    assert linear.exit_code == 0
    lin = np.asarray(Image.open(tmp_path / "lin" / "t-grid-white-48px.png")).reshape(-1, 3)

    def count(pixels, code):
        return int(np.all(pixels == code, axis=1).sum())

    # The disc's inside (about 1,100 px at 48 px): css #b2b2b2, linear #dadada.
    assert count(pixels, solid) > 1000 and count(lin, solid) < 100
    assert count(lin, (218, 218, 218)) > 1000 and count(pixels, (218, 218, 218)) < 100


def test_unreadable_icons_are_skipped_on_stderr_and_left_out(tmp_path):
    theme_path, manifest = write_multipaint(tmp_path)
    (tmp_path / "red.svg").write_text("<svg")
    out = tmp_path / "out"
    result = CliRunner().invoke(
        app,
        [
            "preview",
            str(theme_path),
            str(manifest),
            "-o",
            str(out),
            "--html",
            str(tmp_path / "p.html"),
        ],
    )
    assert result.exit_code == 0, result.output
    assert re.search(r"skipped red: .*red\.svg", result.output)
    page = (tmp_path / "p.html").read_text()
    data = json.loads(re.search(r'id="alpha-audit-data">(.*?)</script>', page, re.S).group(1))
    assert [i["name"] for i in data["icons"]] == ["disc", "two", "mixed"]
