"""A finding's figures: the record its rule's family names, read from the rows it came from."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from alpha_audit import figures as fg
from alpha_audit import load_iconset, load_theme
from alpha_audit.findings import findings_for
from alpha_audit.policy import Policy
from alpha_audit.rows import AuditResult, audit
from alpha_audit.rules import CHECK_RULES, RULES, Family, Rule

# The test's own statement of which record each family's findings carry.
RECORD = {
    Family.CONTRAST: fg.ContrastFigures,
    Family.COLLISION: fg.CollisionFigures,
    Family.SEPARATION: fg.SeparationFigures,
    Family.CONFUSION: fg.ConfusionFigures,
    Family.CVD_COLLISION: fg.CvdCollisionFigures,
    Family.DRIFT: fg.DriftFigures,
    Family.THIN_STROKES: fg.ThinStrokeFigures,
    Family.RENDER_DRIFT: fg.RenderDriftFigures,
}
SVG_RECORDS = {
    Rule.UNRENDERABLE: fg.NoFigures,
    Rule.FIXED_COLOUR: fg.FixedPaintFigures,
    Rule.NOT_AUDITED: fg.ElementFigures,
}
REPO = Path(__file__).resolve().parents[1]
ALL = Policy(rules=frozenset(CHECK_RULES), warnings=frozenset(), min_delta_e=25.0, max_drift=3.0)


@pytest.fixture(scope="module", params=[0.55, 1.6])
def result(request: pytest.FixtureRequest) -> AuditResult:
    icons = load_iconset(REPO / "examples/vibrant/iconset.yaml").with_alpha(request.param)
    return audit(load_theme(REPO / "themes/github-primer.yaml"), icons)


def test_every_finding_carries_the_record_its_family_names(result: AuditResult) -> None:
    found = findings_for(result, ALL)
    assert len({RULES[f.rule].family for f in found}) >= 3  # several families at once
    for f in found:
        family = RULES[f.rule].family
        want = SVG_RECORDS[f.rule] if family is Family.SVG else RECORD[family]
        assert type(f.figures) is want, f.rule


def test_a_paint_finding_reads_the_row_it_names(result: AuditResult) -> None:
    canvases = [c.name for c in result.theme.canvases]
    for f in findings_for(result, ALL):
        fig = f.figures
        if isinstance(fig, fg.ContrastFigures):
            (p,) = f.rows
            j = canvases.index(f.canvas or "")
            assert result.entries[p].icon.name == f.icons[0]
            assert (fig.contrast, fig.contrast_ref) == (
                result.contrast[p, j],
                result.contrast_ref[p, j],
            )
            assert fig.alpha == result.alpha[p] and fig.source == result.entries[p].source
        elif isinstance(fig, fg.DriftFigures):
            (p,) = f.rows
            assert fig.drift == result.drift[p, canvases.index(f.canvas or "")]


def test_confusion_names_its_two_roles_as_a_pair_and_their_rows(result: AuditResult) -> None:
    policy = Policy(rules=frozenset({Rule.CONFUSION}), warnings=frozenset(), min_delta_e=40.0)
    found = findings_for(result, policy)
    for f in found:
        assert isinstance(f.figures, fg.ConfusionFigures)
        one, two = f.figures.roles
        assert one < two and {result.entries[p].role for p in f.rows} == {one, two}
        assert f.figures.to_dict()["roles"] == f"{one},{two}"  # the JSON's form, unchanged


def test_the_written_figures_are_json_and_only_numbers_and_names(result: AuditResult) -> None:
    for f in findings_for(result, ALL):
        written = f.figures.to_dict()
        assert json.loads(json.dumps(written)) == written
        assert all(isinstance(v, float | int | str) for v in written.values())


def test_the_rule_record_says_what_fixes_a_rule() -> None:
    for rule, spec in RULES.items():
        if spec.reach_clears:  # only contrast below the threshold is lifted by reaching it
            assert spec.family is Family.CONTRAST and rule is not Rule.LOSS
        if spec.family in (Family.SVG, Family.RENDER_DRIFT):
            assert spec.fixed_by is None  # no alpha or colour of ours changes what a page draws
        if spec.family is Family.CONTRAST:
            assert spec.closed_form and spec.fixed_by == "colour"
