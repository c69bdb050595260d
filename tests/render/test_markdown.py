"""The pull-request comment: verdict, a <details> per audit, groups by colour x canvas, fixes."""

from __future__ import annotations

import re
from dataclasses import replace
from functools import cache
from pathlib import Path

from markdown_it import MarkdownIt

from alpha_audit.fixes import with_fixes
from alpha_audit.gate import evaluate
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.policy import Exemption, Policy
from alpha_audit.render.common import RenderOptions, escape_markdown
from alpha_audit.render.markdown import COMMENT_LIMIT, MARKER, render_markdown, render_report
from alpha_audit.results import CheckReport
from alpha_audit.rows import audit
from alpha_audit.rules import Rule

OPTIONS = RenderOptions(base=Path("/repo"))
# Blue at alpha 1.6 loses contrast on mid grey (clipping in linear sRGB); red
# too; orange at 1.3 newly reaches 3:1 on white.
LOSING = {"blue": "#0000cc", "red": "#aa0000"}


def _theme(name: str = "grey") -> Theme:
    return Theme(name, (Canvas("mid", "#777777"), Canvas("mid-warm", "#7a7770")))


def _iconset(per_colour: int = 10, alpha_line: int | None = None) -> IconSet:
    """Each role a palette entry setting its colour and alpha on its own line (3, 4), or
    with ``alpha_line`` one set-wide ``alpha:`` for every icon."""
    icons = tuple(
        Icon(
            f"{role}-{k}",
            Path(f"{role}-{k}.svg"),
            colour,
            1.6,
            color_name=role,
            color_line=3 + r,
            alpha_line=3 + r if alpha_line is None else alpha_line,
        )
        for r, (role, colour) in enumerate(LOSING.items())
        for k in range(per_colour)
    )
    return IconSet("set", icons, palette=dict(LOSING), path=Path("/repo/set.yaml"))


@cache
def report() -> CheckReport:
    audits = tuple(audit(_theme(name), _iconset()) for name in ("grey", "warm grey"))
    policy = Policy(rules=frozenset({Rule.LOSS}))
    return with_fixes(CheckReport(audits=audits, gate=evaluate(list(audits), policy)))


def _rows(text: str, header: str) -> list[list[str]]:
    """Cells of every row of every Markdown table whose header starts with ``header``."""
    out, inside = [], False
    for line in text.splitlines():
        if line.startswith(header):
            inside = True
            continue
        if inside and line.startswith("|---"):
            continue
        if inside and line.startswith("| "):
            out.append([c.strip() for c in re.split(r"(?<!\\)\|", line)[1:-1]])
        else:
            inside = False
    return out


def test_comment_opens_with_the_marker_and_a_verdict() -> None:
    text = render_report(report(), OPTIONS)
    first, headline = text.splitlines()[:2]
    assert first == MARKER
    failures = len(report().gate.failures)  # one root cause per icon, however many canvases
    assert failures == 40  # 2 audits x 20 icons
    assert headline == (
        f"## ❌ alpha-audit: gate failed: {failures} root cause(s) ({failures} loss) "
        "in 2 of 2 audit(s)"
    )
    # Then a line per rule: root causes, icons, and the worst one with its line.
    (rule_row,) = _rows(text, "| rule | failing root causes |")
    assert rule_row[:4] == ["`loss`", "40", "20", "0"]
    assert rule_row[6].startswith("blue-0 on mid")


FAILING = "| colour | set at | canvases | rule |"


def test_one_details_section_per_audit_grouped_by_colour() -> None:
    text = render_report(report(), OPTIONS)
    html = MarkdownIt("commonmark").enable("table").render(text)
    assert html.count("<details") == 2 and html.count("</details>") == 2
    rows = _rows(text, FAILING)
    # 2 audits x 2 palette lines, not 40 icons x 2 canvases: each row folds the root
    # causes its line sets, over both canvases.
    assert len(rows) == 4
    assert [r[0] for r in rows[:2]] == ["blue #0000cc", "red #aa0000"]  # the larger loss first
    assert [r[1] for r in rows[:2]] == ["set.yaml:3", "set.yaml:4"]
    assert all(r[2].endswith("(worst) +1") for r in rows)
    assert rows[0][5] == "10 icons: blue-0, blue-1, blue-2 +7 more"


def test_a_set_wide_alpha_failing_every_icon_is_one_row_per_audit() -> None:
    """Fold by the line that causes it: one row for the set-wide alpha: line and the rule."""
    audits = tuple(audit(_theme(n), _iconset(alpha_line=2)) for n in ("grey", "warm grey"))
    gate = evaluate(list(audits), Policy(rules=frozenset({Rule.LOSS})))
    rep = with_fixes(CheckReport(audits=audits, gate=gate))
    rows = _rows(render_report(rep, OPTIONS), FAILING)
    assert len(gate.failures) == 40 and len(rows) == 2  # one per audit section
    for row in rows:
        assert row[0] == "blue #0000cc, red #aa0000" and row[1] == "set.yaml:2"
        assert row[5].startswith("20 icons: ") and "blue: alpha 1" in row[6] and "red: " in row[6]


def test_each_failing_group_names_a_largest_safe_alpha_that_holds() -> None:
    text = render_report(report(), OPTIONS)
    for colour, hexcode in LOSING.items():
        fixes = {r[6] for r in _rows(text, FAILING) if r[0].startswith(colour)}
        (fix,) = fixes  # one answer per colour, on every canvas and audit
        # Safe on [1, a*]: "alpha 1 to a*", or "alpha 1" when a* is 1.
        found = re.match(rf"{colour}: alpha 1(?: to (\d+(?:\.\d+)?))?(?: |;|$)", fix)
        assert found, fix
        alpha = float(found.group(1) or 1)
        # Checked by compositing again: safe at the value, a loss just above it.
        for a, loses in ((alpha, False), (alpha + 0.002, True)):
            icons = tuple(
                replace(i, alpha=a) if i.color == hexcode else i for i in _iconset(1).icons
            )
            result = audit(_theme(), replace(_iconset(1), icons=icons))
            lost = [r for r in result.rows() if r.loss and r.source == hexcode]
            assert bool(lost) is loses, (colour, a)


def test_without_computed_fixes_the_fix_column_gives_the_rules_advice() -> None:
    from alpha_audit.rules import RULES

    bare = replace(report(), fixes=(), gate=evaluate(list(report().audits), report().gate.policy))
    rows = _rows(render_markdown(bare, OPTIONS), FAILING)
    assert rows and all(
        r[6] == escape_markdown(RULES[Rule.LOSS].fix.replace("`", "")) for r in rows
    )


def test_newly_passing_groups_are_listed_as_improved() -> None:
    theme = Theme("paper", (Canvas("white", "#ffffff"),))
    icons = tuple(
        Icon(f"o{k}", Path(f"o{k}.svg"), "#ee7733", 1.3, color_name="orange") for k in range(4)
    )
    result = audit(theme, IconSet("s", icons))
    gate = evaluate([result], Policy())
    text = render_report(CheckReport(audits=(result,), gate=gate), OPTIONS)
    assert text.splitlines()[1].startswith("## ✅ alpha-audit: gate passed")
    (row,) = _rows(text, "| colour | canvas | contrast |")
    assert row[:2] == ["orange #ee7733", "white"] and row[3].startswith("4 icons")
    assert "2.868 → " in row[2]  # WCAG contrast of #ee7733 on white at alpha 1


def test_exempted_groups_show_their_reason() -> None:
    audits = report().audits
    policy = Policy(
        rules=frozenset({Rule.LOSS}), exemptions=(Exemption("brand red", icon="red-0"),)
    )
    text = render_report(CheckReport(audits=audits, gate=evaluate(list(audits), policy)), OPTIONS)
    rows = _rows(text, "| colour | canvases | rule | icons | reason |")
    assert rows and all(r[4] == "brand red" and r[3].startswith("1 icon:") for r in rows)


def test_a_huge_failing_run_fits_githubs_comment_limit_and_says_what_was_left_out() -> None:
    long = "surface-container-" + "x" * 60
    theme = Theme("huge", tuple(Canvas(f"{long}-{k}", f"#77{k:02x}77") for k in range(0, 200, 20)))
    # 400 blues, one per icon (a brand set): 400 root causes per audit, one row each.
    colours = [f"#00{g:02x}{c:02x}" for g in range(10) for c in range(0x80, 0xD0, 2)]
    icons = tuple(
        Icon(f"icon-{'n' * 40}-{k}", Path(f"i{k}.svg"), colours[k], 1.6) for k in range(400)
    )
    audits = tuple(audit(replace(theme, name=n), IconSet("big", icons)) for n in ("a", "b", "c"))
    gate = evaluate(list(audits), Policy(rules=frozenset({Rule.LOSS})))
    text = render_markdown(CheckReport(audits=audits, gate=gate), OPTIONS)
    assert len(text) <= COMMENT_LIMIT
    html = MarkdownIt("commonmark").enable("table").render(text)
    assert html.count("<details") == 3  # every theme keeps its section
    shown = len(_rows(text, FAILING))
    left_out = int(re.search(r"\*\*(\d+) row\(s\) left out\*\*", text).group(1))
    groups = {(f.theme, f.canvas, f.canvases, f.figures.source) for f in gate.failures}
    assert shown > 0 and shown + left_out == len(groups)
    assert "65,536-character comment limit" in text


def test_the_fix_is_the_colours_largest_safe_alpha_as_suggest_gives_it() -> None:
    """The report's fix for a colour is suggest's per-colour answer, in the same words."""
    from alpha_audit.render.common import finding_fix, safe_span
    from alpha_audit.suggest import suggest

    rep = report()
    result = rep.audits[0]
    per_color = {c.color: c.safe.alpha for c in suggest(result, rep.gate.policy).per_color}
    for finding in rep.gate.failures:
        if finding.theme != result.theme.name:
            continue
        role = finding.icons[0].split("-")[0]
        assert finding_fix(finding, rep).startswith(f"{role}: {safe_span(per_color[role])}")


def test_past_the_fix_budget_the_comment_points_at_suggest(monkeypatch) -> None:
    """A brand set fails thousands of colours: past the budget the fix says run suggest."""
    import alpha_audit.fixes as fixes
    from alpha_audit.render.common import finding_fix

    monkeypatch.setattr(fixes, "MAX_FIXED_COLORS", 1)
    bare = report()
    rep = fixes.with_fixes(
        replace(bare, fixes=(), gate=evaluate(list(bare.audits), bare.gate.policy))
    )
    assert rep.fixes_left_out > 0
    texts = [finding_fix(f, rep) for f in rep.gate.failures if not f.fixes]
    assert texts and all("alpha-audit suggest" in t for t in texts)
