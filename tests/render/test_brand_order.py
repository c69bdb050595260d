"""A brand-like set (thousands of logos, each in its own colour): the root cause leads.

At alpha 1.6 every dark brand colour clips to #000000 on white: one collision
of hundreds of colours, the headline problem, must come first in the comment,
the table and the annotations, ahead of thousands of small losses.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

import numpy as np

from alpha_audit.gate import evaluate, rule_summary
from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.policy import Policy
from alpha_audit.render import CheckFormat, RenderOptions
from alpha_audit.results import CheckReport
from alpha_audit.rows import audit
from alpha_audit.rules import Rule

LOGOS = 3000


@cache
def brand_report() -> CheckReport:
    rng = np.random.default_rng(2024)
    codes = rng.integers(0, 256, size=(LOGOS, 3))
    icons = tuple(
        Icon(f"logo-{k}", Path(f"logos/logo-{k}.svg"), "#{:02x}{:02x}{:02x}".format(*c), 1.6)
        for k, c in enumerate(codes.tolist())
    )
    theme = Theme("site", (Canvas("white", "#ffffff"), Canvas("night", "#0d1117")))
    result = audit(theme, IconSet("brands", icons, path=Path("logos/brands.yaml")))
    policy = Policy(rules=frozenset({Rule.LOSS, Rule.NEWLY_FAILING, Rule.NEW_COLLISION}))
    return CheckReport(audits=(result,), gate=evaluate([result], policy))


def _largest_collision() -> int:
    """The most distinct colours any collision holds, counted from the rows themselves."""
    result = brand_report().audits[0]
    return max(len(c.sources) for c in result.collisions if c.new)


def test_the_gate_orders_the_largest_collision_first() -> None:
    failures = brand_report().gate.failures
    assert len(failures) > 300  # thousands of logos, hundreds of root causes
    first = failures[0]
    assert first.rule is Rule.NEW_COLLISION
    assert first.figures.colours == _largest_collision() > 100
    sizes = [f.figures.colours for f in failures if f.rule is Rule.NEW_COLLISION]
    assert sizes == sorted(sizes, reverse=True)
    # Losses come after the collisions, the largest loss first.
    losses = [float(f.figures.gain) for f in failures if f.rule is Rule.LOSS]
    assert losses == sorted(losses)
    assert rule_summary(brand_report().gate)[0].rule is Rule.NEW_COLLISION


def test_the_comment_and_the_annotations_lead_with_it() -> None:
    report = brand_report()
    largest = _largest_collision()
    text = CheckFormat.MARKDOWN.renderer()(report, RenderOptions())
    lines = text.splitlines()
    rule_rows = [line for line in lines if line.startswith("| `")]
    assert rule_rows[0].startswith("| `new-collision` |")
    failing = lines.index("| colour | set at | canvases | rule | numbers | icons | fix |")
    first_row = lines[failing + 2]
    assert " new-collision " in first_row and f"{largest} colours all give #" in first_row
    github = CheckFormat.GITHUB.renderer()(report, RenderOptions()).splitlines()
    errors = [line for line in github if line.startswith("::error ")]
    assert "title=alpha-audit new-collision::" in errors[0]
    # Losses on logos already invisible are reported in the JSON and SARIF, not annotated.
    assert not any("reported, not gated" in line for line in github)
    table = CheckFormat.TABLE.renderer()(report, RenderOptions(width=120))
    worst = table.split("Worst first:")[1].splitlines()[1]
    assert worst.lstrip().startswith("new-collision:")
