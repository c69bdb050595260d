"""The audit engine against an independent scalar implementation of the paper's equations."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from alpha_audit import audit, load_iconset, load_theme
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.render.common import dumps
from alpha_audit.render.json import check_to_dict


# --- independent reference: plain Python floats, written from the paper ----------------
def ref_decode(c8: int) -> float:
    v = c8 / 255
    return v / 12.92 if v <= 0.04045 else ((v + 0.055) / 1.055) ** 2.4


def ref_encode(v: float) -> float:
    return 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055


def ref_hex_to_linear(text: str) -> list[float]:
    return [ref_decode(int(text[i : i + 2], 16)) for i in (1, 3, 5)]


def ref_luminance(c: list[float]) -> float:
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]


def ref_contrast(a: list[float], b: list[float]) -> float:
    ya, yb = ref_luminance(a), ref_luminance(b)
    return (max(ya, yb) + 0.05) / (min(ya, yb) + 0.05)


def ref_composite(s: list[float], b: list[float], alpha: float) -> list[float]:
    return [min(1.0, max(0.0, bk + alpha * (sk - bk))) for sk, bk in zip(s, b, strict=True)]


def ref_hex(c: list[float]) -> str:
    return "#" + "".join(f"{round(ref_encode(v) * 255):02x}" for v in c)  # round() is half-even


hexes = st.integers(0, 0xFFFFFF).map(lambda v: f"#{v:06x}")


def make(sources: list[str], alphas: list[float], canvases: list[str]) -> tuple[Theme, IconSet]:
    theme = Theme("t", tuple(Canvas(f"c{j}", c) for j, c in enumerate(canvases)))
    icons = tuple(
        Icon(f"i{i}", Path(f"i{i}.svg"), s, a)
        for i, (s, a) in enumerate(zip(sources, alphas, strict=True))
    )
    return theme, IconSet("s", icons)


@settings(max_examples=60, deadline=None)
@given(
    st.lists(hexes, min_size=1, max_size=6),
    st.lists(hexes, min_size=1, max_size=4),
    st.floats(-2, 3, allow_nan=False),
)
def test_every_json_number_agrees_with_reference(
    sources: list[str], canvases: list[str], alpha: float
) -> None:
    theme, icons = make(sources, [alpha] * len(sources), canvases)
    doc = json.loads(dumps(check_to_dict(audit(theme, icons))))
    for row in doc["rows"]:
        s = ref_hex_to_linear(row["source"])
        b = ref_hex_to_linear(row["background"])
        out = ref_composite(s, b, row["alpha"])
        assert row["output"] == ref_hex(out)
        # The float maths, and what ships: the 8-bit output on the (8-bit) canvas.
        assert row["contrast_ref_float"] == pytest.approx(ref_contrast(s, b), abs=1e-9)
        assert row["contrast_float"] == pytest.approx(ref_contrast(out, b), abs=1e-9)
        shipped = ref_hex_to_linear(ref_hex(out))
        ref, cr = ref_contrast(ref_hex_to_linear(ref_hex(s)), b), ref_contrast(shipped, b)
        assert row["contrast_ref"] == pytest.approx(ref, abs=1e-9)
        assert row["contrast"] == pytest.approx(cr, abs=1e-9)
        assert row["gain"] == pytest.approx(cr - ref, abs=1e-9)
        assert row["loss"] == (cr - ref < -1e-10)
        assert row["passes"] == (cr >= 3.0)
        assert row["newly_passes"] == (cr >= 3.0 and ref < 3.0)


def test_issue_row_vibrant_orange_on_white() -> None:
    theme, icons = make(["#ee7733"], [1.1], ["#ffffff"])
    row = json.loads(dumps(check_to_dict(audit(theme, icons))))["rows"][0]
    assert row["output"] == "#ec5a00"
    assert row["contrast_ref"] == row["contrast_ref_float"] == 2.868083650384096
    assert row["contrast_float"] == 3.4733853122940994  # the float maths
    shipped = ref_contrast(ref_hex_to_linear("#ec5a00"), ref_hex_to_linear("#ffffff"))
    assert row["contrast"] == pytest.approx(shipped, abs=1e-12)  # what a screen shows
    assert row["gain"] == pytest.approx(shipped - 2.868083650384096, abs=1e-12)
    assert (row["passes_ref"], row["passes"], row["newly_passes"], row["loss"]) == (
        False,
        True,
        True,
        False,
    )


def test_identity_at_alpha_one() -> None:
    theme, icons = make(["#ee7733", "#0077bb", "#33bbee"], [1.0] * 3, ["#ffffff", "#0d1117"])
    result = audit(theme, icons)
    np.testing.assert_allclose(result.gain, 0, atol=1e-12)
    assert result.summary.unchanged_pct == 100.0
    assert not result.collisions


def test_alpha_override_replaces_every_coefficient() -> None:
    theme, icons = make(["#ee7733", "#0077bb"], [1.0, 1.5], ["#ffffff"])
    assert audit(theme, icons, alpha=1.2).alpha.tolist() == [1.2, 1.2]


def test_worst_case_is_a_loss() -> None:
    # The paper's worst combination, as an icon: sRGB (0, 0, 0.8125) = #0000cf on yellow.
    theme, icons = make(["#0000cf"], [1.4], ["#ffff00"])
    result = audit(theme, icons)
    assert result.loss.all()
    assert (result.contrast_ref_float - result.contrast_float).max() == pytest.approx(
        10.2773 - 8.6379, abs=2e-4
    )  # the paper's float figures; what ships differs by the 8-bit rounding
    assert result.summary.max_loss == pytest.approx(10.2773 - 8.6379, abs=0.02)


def test_collision_between_distinct_sources_is_found() -> None:
    # Vibrant orange and magenta both clip to pure-ish red on white at 1.4 (paper Fig. 5).
    theme, icons = make(["#ee7733", "#ee3377", "#0077bb"], [1.4] * 3, ["#ffffff"])
    result = audit(theme, icons)
    assert len(result.collisions) == 1
    collision = result.collisions[0]
    assert set(collision.sources) == {"#ee7733", "#ee3377"}
    assert collision.new
    assert result.summary.min_delta_e == 0.0


def test_same_colour_twice_is_not_a_collision() -> None:
    theme, icons = make(["#ee7733", "#ee7733"], [1.4, 1.4], ["#ffffff"])
    assert audit(theme, icons).collisions == ()


def test_collision_present_at_alpha_one_is_not_new() -> None:
    # Two rgb() sources that differ below 8-bit resolution already share a code at 1.
    theme, icons = make(["rgb(128 128 128)", "rgb(128.2 128 128)"], [1.0, 1.0], ["#ffffff"])
    result = audit(theme, icons)
    assert len(result.collisions) == 1
    assert not result.collisions[0].new


def test_separation_reports_closest_distinct_pair() -> None:
    theme, icons = make(["#ee7733", "#ee3377", "#0077bb"], [1.0] * 3, ["#ffffff"])
    sep = audit(theme, icons).separations[0]
    assert set(sep.sources) == {"#ee7733", "#ee3377"}
    assert sep.delta_e == pytest.approx(sep.delta_e_ref)
    assert sep.decreases == 0 and sep.pairs == 3


def test_bundled_example_on_every_bundled_theme(repo: Path) -> None:
    icons = load_iconset(repo / "examples/vibrant/iconset.yaml")
    for path in sorted((repo / "themes").glob("*.yaml")):
        result = audit(load_theme(path), icons)
        assert result.contrast.shape == (len(icons.icons), len(result.theme.canvases))
        # Pure black and white never lose contrast for a >= 1 (paper, Section 4).
        for j, canvas in enumerate(result.theme.canvases):
            if canvas.color in ("#000000", "#ffffff"):
                assert not result.loss[:, j].any()


def test_rows_are_in_stable_canvas_then_icon_order() -> None:
    theme, icons = make(["#ee7733", "#0077bb"], [1.1, 1.1], ["#ffffff", "#000000"])
    rows = [(r.canvas, r.icon) for r in audit(theme, icons).rows()]
    assert rows == [("c0", "i0"), ("c0", "i1"), ("c1", "i0"), ("c1", "i1")]


def test_json_has_no_nan_and_full_precision() -> None:
    theme, icons = make(["#ee7733"], [1.1], ["#ffffff"])
    text = dumps(check_to_dict(audit(theme, icons)))
    assert "NaN" not in text and "3.4733853122940994" in text  # contrast_float, in full
    doc = json.loads(text)
    assert math.isclose(doc["summary"]["mean_gain"], doc["rows"][0]["gain"], rel_tol=1e-15)


def test_the_sets_minimum_at_alpha_1_is_its_own_closest_pair() -> None:
    """The table's left min ΔE, not the pair closest at alpha: brute force over the sources.

    CIELAB as the project pins it (CSS Color 4 matrix, D65); the distances and the
    minimum by colour-science over every pair, against the pruned search.
    """
    import itertools
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        import colour
    from alpha_audit.color import hex_to_linear, linear_to_lab
    from alpha_audit.model import Canvas, Icon, IconSet, Theme
    from alpha_audit.render.json import check_to_dict

    hexes = ["#ee7733", "#0077bb", "#33bbee", "#ee3377", "#cc3311", "#009988", "#bbbbbb"]
    icons = tuple(Icon(f"i{k}", Path(f"i{k}.svg"), h, 1.6) for k, h in enumerate(hexes))
    theme = Theme("t", (Canvas("white", "#ffffff"), Canvas("ink", "#101010")))
    result = audit(theme, IconSet("s", icons))
    lab = {h: linear_to_lab(hex_to_linear(h)) for h in hexes}
    brute = min(
        float(colour.delta_E(lab[a], lab[b], method="CIE 2000"))
        for a, b in itertools.combinations(hexes, 2)
    )
    closest_at_alpha_at_1 = {s.delta_e_ref for s in result.separations}
    assert any(abs(v - brute) > 1.0 for v in closest_at_alpha_at_1)  # the two really differ here
    for s in result.separations:
        assert abs(s.set_delta_e_ref - brute) < 1e-9
    doc = check_to_dict(result)
    assert all(abs(s["set_min_delta_e_ref"] - brute) < 1e-9 for s in doc["separation"])


def test_json_rows_are_the_row_objects_field_for_field(tmp_path: Path) -> None:
    """The JSON writer reads the result's columns; rows() makes objects of the same columns.
    Both must give every row's every field in the same order (multi-paint icons, two sizes,
    fixed paints with an achromatic hue)."""
    from alpha_audit.pipeline import render_paints
    from multipaint import write_multipaint

    theme_path, manifest = write_multipaint(tmp_path, alpha=1.3)
    iconset = load_iconset(manifest)
    result = audit(load_theme(theme_path), iconset, render_paints(iconset))
    doc = json.loads(dumps(check_to_dict(result)))
    rows = list(result.rows())
    assert len(doc["rows"]) == len(rows) == len(result.columns()) > 8
    assert any(r.hue_shift is None for r in rows) and any(r.fixed for r in rows)
    for written, row in zip(doc["rows"], rows, strict=True):
        expected = {
            name: getattr(row, name)
            for name in written
            if name not in {"kinds", "sizes", "newly_passes", "newly_fails"}
        }
        assert {k: written[k] for k in expected} == expected
        assert written["kinds"] == list(row.kinds)
        assert (written["newly_passes"], written["newly_fails"]) == (
            row.newly_passes,
            row.newly_fails,
        )
        assert written["sizes"] == {
            str(s): {
                k: (v if math.isfinite(v) else None)
                for k, v in (("q50", f.q50), ("full_share", f.full_share), ("contrast", f.contrast))
            }
            for s, f in row.sizes.items()
        }
