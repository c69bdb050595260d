"""``pair`` on colours outside sRGB: a Tailwind v4 colour works as documented."""

from __future__ import annotations

import json

import numpy as np
import pytest
from coloraide import Color
from typer.testing import CliRunner

from alpha_audit.cli import app
from alpha_audit.color import contrast_ratio, srgb_decode
from alpha_audit.pair import pair_report

BLUE_500 = "oklch(0.623 0.214 259.815)"  # Tailwind v4's --color-blue-500: outside sRGB


def test_the_documented_command_works_and_says_what_moved() -> None:
    result = CliRunner().invoke(app, ["pair", BLUE_500, "--on", "white", "-a", "1.1"])
    assert result.exit_code == 0, result.output
    assert "outside sRGB" in result.output and "gamut clip" in result.output


@pytest.mark.parametrize("policy", ["clip", "map"])
def test_rows_use_the_fitted_colour_as_coloraide_gives_it(policy: str) -> None:
    report = pair_report(BLUE_500, ["white"], [1.0], gamut=policy)
    fitted = Color(BLUE_500).convert("srgb")
    fitted = fitted.clip() if policy == "clip" else fitted.fit(method="minde-chroma", jnd=0.02)
    expected = srgb_decode(fitted.coords())
    (row,) = report.rows
    white = srgb_decode([1, 1, 1])
    assert row.contrast_float == pytest.approx(float(contrast_ratio(expected, white)))
    # Judged as it ships: the fitted colour's 8-bit code, as coloraide writes it.
    shipped = srgb_decode(np.array(Color(fitted.to_string(hex=True)).coords()))
    assert row.contrast == pytest.approx(float(contrast_ratio(shipped, white)), rel=1e-9)
    (moved,) = report.gamut
    assert moved.policy == policy and moved.output == fitted.to_string(hex=True)
    assert 0 < moved.delta_e < 2


def test_gamut_error_refuses_and_json_lists_moved_colours() -> None:
    runner = CliRunner()
    refused = runner.invoke(app, ["pair", BLUE_500, "--on", "white", "--gamut", "error"])
    assert refused.exit_code == 2 and "outside sRGB" in refused.output
    bad = runner.invoke(app, ["pair", BLUE_500, "--on", "white", "--gamut", "squash"])
    assert bad.exit_code == 2 and "clip, map, error" in bad.output
    out = runner.invoke(app, ["pair", BLUE_500, "--on", "white", "-f", "json", "--gamut", "map"])
    doc = json.loads(out.stdout)
    assert doc["gamut"][0]["policy"] == "map" and len(doc["rows"]) == 3
    inside = runner.invoke(app, ["pair", "#ee7733", "--on", "white", "-f", "json"])
    assert json.loads(inside.stdout)["gamut"] == []
