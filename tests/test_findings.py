"""Paint rows, pipelines, drift, size contrast and the paint rules on the issue's own cases."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from alpha_audit.color import (
    composite_paint,
    contrast_ratio,
    delta_e_2000,
    hex_to_linear,
    linear_to_hex,
)
from alpha_audit.color.coverage import CoverageStats
from alpha_audit.errors import InputError, UsageError
from alpha_audit.findings import findings_for
from alpha_audit.load.paint_masks import measure_paints
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.paints import (
    CURRENT_COLOR,
    IconPaints,
    Paint,
    PaintCoverage,
    PaintGroup,
    PaintSet,
    SvgPaints,
)
from alpha_audit.policy import Policy
from alpha_audit.rows import audit, check_pipeline, resolve_pipeline
from alpha_audit.rules import Rule


def find(result, rules, **limits):  # type: ignore[no-untyped-def]
    """Findings of the named rules with the policy's limits."""
    policy = Policy(rules=frozenset(Rule(r) for r in rules), warnings=frozenset(), **limits)
    return findings_for(result, policy)


LIGHT = Theme("primer", (Canvas("light-default", "#ffffff"), Canvas("light-muted", "#f6f8fa")))
SOLID = CoverageStats(q50=1.0, full_share=1.0, ink=10.0, pixels=10)
THIN = CoverageStats(q50=0.4, full_share=0.2, ink=10.0, pixels=30)


def painted(
    icons: list[Icon],
    groups: dict[str, list[tuple[str, float]]] | None = None,
    coverage: CoverageStats = SOLID,
    sizes: tuple[int, ...] = (24,),
    palette: dict[str, str] | None = None,
) -> tuple[IconSet, PaintSet]:
    """An icon set and hand-made paint coverage (no rendering): one stroke per group."""
    out = {}
    for icon in icons:
        spec = (groups or {}).get(icon.name, [(CURRENT_COLOR, 1.0)])
        cov = tuple(
            PaintCoverage(
                PaintGroup(c, o, (Paint(c, "stroke", o, "<path>", 3),)),
                dict.fromkeys(sizes, coverage),
            )
            for c, o in spec
        )
        paints = SvgPaints(tuple(p for c in cov for p in c.group.paints))
        out[icon.name] = IconPaints(icon.name, Path(icon.file), paints, cov)
    iconset = IconSet("set", tuple(icons), palette=palette or {}, sizes=sizes)
    return iconset, PaintSet(out, ())


def test_primer_severe_and_danger_confuse_at_1_15() -> None:
    icons = [
        Icon("alert", "a.svg", "#bc4c00", 1.15, color_name="severe"),
        Icon("stop", "s.svg", "#d1242f", 1.15, color_name="danger"),
    ]
    iconset, paints = painted(icons)
    result = audit(LIGHT, iconset, paints)
    found = find(result, {"confusion"})
    # One root cause (the pair of roles) over both canvases, with the worst one's figures.
    (first,) = found
    assert first.canvases == ("light-default", "light-muted")
    # The closer of the two as they ship (8-bit outputs, CIEDE2000 by colour-science from
    # the spec's matrices): 5.2468 on light-default, 5.2589 on light-muted.
    assert first.canvas == "light-default"
    assert first.figures.roles == ("danger", "severe")
    assert first.figures.delta_e_ref == pytest.approx(16.0897, abs=1e-4)
    assert first.figures.delta_e == pytest.approx(5.2468, abs=1e-4)
    assert set(first.icons) == {"alert", "stop"}
    # at alpha 1 they are told apart: no finding
    iconset1, paints1 = painted([Icon(i.name, i.file, i.color, 1.0, i.color_name) for i in icons])
    assert find(audit(LIGHT, iconset1, paints1), {"confusion"}) == []


def test_slate_500_drifts_29_5_at_1_2_on_white() -> None:
    iconset, paints = painted([Icon("muted", "m.svg", "#64748b", 1.2)])
    result = audit(Theme("w", (Canvas("white", "#ffffff"),)), iconset, paints)
    (row,) = result.rows()
    assert row.output == "#00195d"
    assert row.drift == pytest.approx(29.5, abs=0.05)
    # Drift of what ships: CIEDE2000 between the 8-bit colours at alpha 1 and at 1.2.
    assert row.drift == pytest.approx(
        float(delta_e_2000(hex_to_linear("#64748b"), hex_to_linear("#00195d"))), abs=1e-12
    )
    assert row.hue_shift is not None and abs(row.hue_shift) < 30
    drift = find(result, {"drift"}, max_drift=20)
    assert [(f.rule, f.canvas, f.figures.output) for f in drift] == [("drift", "white", "#00195d")]
    assert find(result, {"drift"}, max_drift=30) == []
    assert find(result, {"lock"}) == []
    locked_set = replace(iconset, locked=frozenset({"muted"}))
    locked = find(audit(result.theme, locked_set, paints), {"lock"})
    assert [f.rule for f in locked] == [Rule.LOCK]


def test_fixed_colour_is_audited_as_itself_with_a_finding() -> None:
    iconset, paints = painted(
        [Icon("stop", "s.svg", "#0969da", 1.0)],
        groups={"stop": [(CURRENT_COLOR, 1.0), ("#ff0000", 1.0)]},
    )
    result = audit(Theme("w", (Canvas("white", "#ffffff"),)), iconset, paints)
    rows = list(result.rows())
    assert [(r.paint, r.source, r.fixed) for r in rows] == [
        (CURRENT_COLOR, "#0969da", False),
        ("#ff0000", "#ff0000", True),
    ]
    assert rows[1].contrast == pytest.approx(
        float(contrast_ratio(hex_to_linear("#ff0000"), np.ones(3)))
    )
    (finding,) = find(result, {"fixed-colour"})
    assert finding.figures.paint == "#ff0000" and "(line 3)" in finding.figures.element
    assert "will not follow" in finding.message


def test_thirty_percent_disc_uses_the_coverage_form() -> None:
    iconset, paints = painted(
        [Icon("disc", "d.svg", "#000000", 1.2)], groups={"disc": [("#000000", 0.3)]}
    )
    canvas = hex_to_linear("#ffffff")
    result = audit(Theme("w", (Canvas("white", "#ffffff"),)), iconset, paints)
    (row,) = result.rows()
    by_hand = 0.3 * np.clip(canvas + 1.2 * (np.zeros(3) - canvas), 0, 1) + 0.7 * canvas
    assert row.contrast_float == pytest.approx(float(contrast_ratio(by_hand, canvas)), rel=1e-12)
    shown = hex_to_linear(row.output)  # what ships: the 8-bit colour
    assert row.contrast == pytest.approx(float(contrast_ratio(shown, canvas)), rel=1e-12)
    assert row.contrast < 3.0 < float(contrast_ratio(np.zeros(3), canvas))
    assert row.drift == pytest.approx(0.0, abs=1e-9)  # black cannot get darker: alpha moves nothing


def test_css_pipeline_at_0_6_is_the_gamma_blend_and_refuses_1_2(tmp_path: Path) -> None:
    iconset, paints = painted([Icon("a", "a.svg", "#ee7733", 0.6)])
    white = Theme("w", (Canvas("white", "#ffffff"),))
    css = next(audit(white, iconset, paints, pipeline="css").rows())
    linear = next(audit(white, iconset, paints).rows())
    assert (css.output, css.pipeline) == ("#f5ad85", "css")
    assert (linear.output, linear.pipeline) == ("#f5bdad", "linear")
    with pytest.raises(UsageError, match=r"`alpha` 1.2 cannot be drawn by pipeline css"):
        audit(white, iconset, paints, alpha=1.2, pipeline="css")
    with pytest.raises(InputError, match=r"'a' has alpha 1.2, which pipeline css.*export per-the"):
        check_pipeline(iconset.with_alpha(1.2), "css")
    check_pipeline(iconset.with_alpha(1.2), "linear")  # fine in linear light


def test_resolve_pipeline_precedence_and_unknown_names() -> None:
    assert resolve_pipeline(None, None, None) == "linear"
    assert resolve_pipeline("CSS", "linear") == "css"
    with pytest.raises(UsageError, match="use one of: linear, css"):
        resolve_pipeline("webgl")


def test_thin_strokes_and_size_contrast() -> None:
    iconset, paints = painted([Icon("x", "x.svg", "#57606a", 1.0)], coverage=THIN, sizes=(16, 48))
    white = Theme("w", (Canvas("white", "#ffffff"),))
    result = audit(white, iconset, paints)
    (row,) = result.rows()
    canvas = hex_to_linear("#ffffff")
    at_q50 = composite_paint(hex_to_linear("#57606a"), canvas, 1.0, 0.4)
    expected = float(contrast_ratio(hex_to_linear(linear_to_hex(at_q50)), canvas))  # as shipped
    assert row.sizes[16].contrast == pytest.approx(expected, rel=1e-12)
    assert row.sizes[16].contrast < row.contrast
    (finding,) = find(result, {"thin-strokes"})
    assert finding.figures.size == 16
    assert find(result, {"thin-strokes"}, min_size_contrast=1.5) == []


def test_cvd_confusion_finds_red_green_only_under_protanopia() -> None:
    """Primer's danger and success at 1.2 on white: 67.6 -> 60.9 apart, 12.8 -> 4.9 for protans."""
    icons = [
        Icon("err", "e.svg", "#d1242f", 1.2, color_name="danger"),
        Icon("ok", "o.svg", "#1a7f37", 1.2, color_name="success"),
    ]
    iconset, paints = painted(icons)
    result = audit(Theme("w", (Canvas("white", "#ffffff"),)), iconset, paints)
    assert find(result, {"confusion"}) == []
    found = find(result, {"cvd-confusion"})
    assert [f.figures.deficiency for f in found] == ["protanopia"]
    assert found[0].figures.delta_e_ref == pytest.approx(12.8, abs=0.05)
    assert found[0].figures.delta_e == pytest.approx(4.97, abs=0.05)  # as shipped, 8-bit
    # at alpha 1 nothing changes, so neither CVD rule objects
    same = painted([Icon(i.name, i.file, i.color, 1.0, i.color_name) for i in icons])
    assert find(audit(result.theme, *same), {"cvd-confusion", "cvd-collision"}) == []


def test_cvd_collision_is_new_at_alpha() -> None:
    """Two blacks-to-be: dark red and dark green both clip to #000000 on white at alpha 3."""
    icons = [
        Icon("a", "a.svg", "#550000", 3.0, color_name="r"),
        Icon("b", "b.svg", "#005500", 3.0, color_name="g"),
    ]
    result = audit(Theme("w", (Canvas("white", "#ffffff"),)), *painted(icons))
    (found,) = find(result, {"cvd-collision"})  # one pair of colours: one root cause
    assert found.figures.deficiencies == ("deuteranopia", "protanopia", "tritanopia")
    assert found.figures.output == "#000000" and set(found.icons) == {"a", "b"}


def test_end_to_end_with_rendered_masks(tmp_path: Path) -> None:
    ns = 'xmlns="http://www.w3.org/2000/svg"'
    (tmp_path / "stop.svg").write_text(
        f'<svg {ns} viewBox="0 0 24 24" fill="none" stroke-width="2">'
        '<path d="M4 4l16 16" stroke="#ff0000"/>'
        '<circle cx="12" cy="12" r="8" stroke="currentColor"/>'
        '<text x="1">!</text></svg>'
    )
    icon = Icon("stop", tmp_path / "stop.svg", "#0969da", 1.0)
    iconset = IconSet("set", (icon,), sizes=(16, 48))
    paints = measure_paints([("stop", icon.file)], iconset.sizes)
    result = audit(Theme("w", (Canvas("white", "#ffffff"),)), iconset, paints)
    rows = list(result.rows())
    assert [r.paint for r in rows] == ["#ff0000", CURRENT_COLOR]
    for r in rows:
        assert r.sizes[16].contrast <= r.sizes[48].contrast <= r.contrast + 1e-12
        assert 0 < r.sizes[16].q50 <= 1
    rules = [f.rule for f in find(result, {"fixed-colour", "not-audited"})]
    assert rules == ["fixed-colour", "not-audited"]


def test_what_cannot_be_audited_is_listed_by_default(tmp_path: Path) -> None:
    """No silent pass: a gradient and a <use> loop are warnings under the default policy."""
    ns = 'xmlns="http://www.w3.org/2000/svg"'
    square = '<rect x="4" y="4" width="8" height="8" fill="currentColor"/>'
    (tmp_path / "grad.svg").write_text(
        f'<svg {ns} viewBox="0 0 24 24"><defs><linearGradient id="g"><stop stop-color="#f00"/>'
        f'</linearGradient></defs><rect width="24" height="24" fill="url(#g)"/>{square}</svg>'
    )
    (tmp_path / "loop.svg").write_text(
        f'<svg {ns} viewBox="0 0 24 24"><g id="a"><use href="#b"/></g>'
        f'<g id="b"><use href="#a"/></g>{square}</svg>'
    )
    icons = tuple(Icon(n, tmp_path / f"{n}.svg", "#0969da", 1.0) for n in ("grad", "loop"))
    iconset = IconSet("set", icons)
    paints = measure_paints([(i.name, i.file) for i in icons], iconset.sizes)
    result = audit(Theme("w", (Canvas("white", "#ffffff"),)), iconset, paints)
    found = [f for f in findings_for(result, Policy()) if f.rule is Rule.NOT_AUDITED]
    assert sorted({f.icons for f in found}) == [("grad",), ("loop",)]  # each <use> of the loop
    assert all(f.level.value == "warn" and not f.fails for f in found)


def test_paint_audit_size_is_bounded(monkeypatch: pytest.MonkeyPatch) -> None:
    import alpha_audit.rows as pa

    iconset, paints = painted(
        [Icon(f"i{n}", f"{n}.svg", "#0969da", 1.0) for n in range(4)], sizes=(16, 24, 48)
    )
    monkeypatch.setattr(pa, "MAX_SIZE_CELLS", 4 * 2 * 3 - 1)
    two = Theme("t", (Canvas("a", "#ffffff"), Canvas("b", "#000000")))
    with pytest.raises(InputError, match="4 paints x 2 canvases x 3 sizes is more than"):
        audit(two, iconset, paints)
    monkeypatch.setattr(pa, "MAX_SIZE_CELLS", 4 * 2 * 3)
    assert len(list(audit(two, iconset, paints).rows())) == 8


def test_a_collision_of_many_colours_names_a_few_and_counts_the_rest() -> None:
    from alpha_audit.findings import _colours

    many = [f"#0000{k:02x}" for k in range(754)]
    text = _colours(many)
    assert text.startswith("754 distinct colours (#000000, ") and text.endswith("+746 more)")
    assert text.count("#") == 8
    assert _colours(many[:3]) == "distinct colours #000000, #000001, #000002"
