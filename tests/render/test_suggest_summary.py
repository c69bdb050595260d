"""suggest on a big set: the table and comment show the worst answers; the JSON has every one."""

from __future__ import annotations

import json
from functools import cache
from pathlib import Path

import numpy as np

from alpha_audit.model import Canvas, Icon, IconSet, Theme
from alpha_audit.policy import Policy
from alpha_audit.render import RenderOptions, SuggestFormat
from alpha_audit.render.suggest import MAX_ROWS
from alpha_audit.results import SuggestResult
from alpha_audit.rows import audit
from alpha_audit.rules import Rule
from alpha_audit.suggest import suggest


@cache
def big() -> SuggestResult:
    """120 logos in 40 brand colours (3 each) on a yellow and a grey canvas."""
    rng = np.random.default_rng(5)
    colours = ["#{:02x}{:02x}{:02x}".format(*c) for c in rng.integers(0, 256, (40, 3)).tolist()]
    icons = tuple(
        Icon(f"logo-{k}", Path(f"l{k}.svg"), colours[k % 40], 1.0 + 0.01 * (k % 7))
        for k in range(120)
    )
    theme = Theme("t", (Canvas("sun", "#ffff00"), Canvas("mid", "#777777")))
    policy = Policy(rules=frozenset({Rule.LOSS, Rule.NEWLY_FAILING}))
    return suggest(audit(theme, IconSet("brands", icons)), policy, scopes=("colour", "icon"))


def _answers(text: str, names: str) -> list[str]:
    return [line for line in text.splitlines() if line.lstrip().startswith(names)]


def test_the_table_shows_the_smallest_answers_and_the_worst_icon_per_colour() -> None:
    result = big()
    assert len(result.per_color) == 40 and len(result.per_icon) == 120
    text = SuggestFormat.TABLE.renderer()(result, RenderOptions(width=160))
    icon_rows = _answers(text, "logo-")
    assert len(icon_rows) == MAX_ROWS  # one per colour, the worst colours only
    assert f"the worst of each colour shown ({MAX_ROWS} of 120 icons in 40 colours)" in text
    assert "15 more colours with larger answers: see --format json" in text
    # The colours shown are those with the smallest answers.
    smallest = sorted(
        (c.safe.alpha if c.safe.alpha is not None else -1.0) for c in result.per_color
    )[MAX_ROWS - 1]
    shown = [c for c in result.per_color if f"{c.color} {c.source}"[:9] in text]
    assert all((c.safe.alpha if c.safe.alpha is not None else -1.0) <= smallest for c in shown)
    # Each icon shown is the worst of its colour.
    by_colour: dict[str, list[float]] = {}
    for i in result.per_icon:
        by_colour.setdefault(i.color, []).append(-1.0 if i.safe.alpha is None else i.safe.alpha)
    for i in result.per_icon:
        if any(row.split()[0] == i.icon for row in icon_rows):
            assert (-1.0 if i.safe.alpha is None else i.safe.alpha) == min(by_colour[i.color])


def test_json_and_small_sets_keep_every_answer() -> None:
    doc = json.loads(SuggestFormat.JSON.renderer()(big(), RenderOptions()))
    assert len(doc["per_icon"]) == 120 and len(doc["per_color"]) == 40
    markdown = SuggestFormat.MARKDOWN.renderer()(big(), RenderOptions())
    assert len([line for line in markdown.splitlines() if line.startswith("| logo-")]) == MAX_ROWS
