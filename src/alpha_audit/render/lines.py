"""Findings folded by the line that causes them: the one folding every CI report uses.

A finding is one root cause (a rule's objection to one paint, one pair of roles,
one group of colours), and its first :attr:`~alpha_audit.findings.Finding.locations`
entry is the line that sets its failing value.  Many root causes often share that
line: a set-wide ``alpha:`` that fails every icon, a palette entry several icons
use, a design token.  A pull request changes the line, so a reviewer should see it
once: :func:`by_line` folds findings of one rule and one standing (failing,
exempted with one reason, baselined, reported) by that line, keeping the order
given (worst first), so each :class:`LineGroup` is one GitHub annotation, one GitLab
Code Quality issue, one SARIF result and one pull-request comment row, with the
icon and canvas counts and the worst case.  A finding with no location, or whose
first location names where an icon is drawn rather than a value (an SVG, a story
or page file), is a group of its own.  The findings themselves (their keys, the
JSON report, baselines) are unchanged: this is how they are shown.

Pure functions of the findings given; the lead's ``render`` command feeds its
findings through the same renderers.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from alpha_audit.render.common import digest, display_path, shorten_names, where_text

if TYPE_CHECKING:
    from alpha_audit.findings import Finding
    from alpha_audit.model import Location
    from alpha_audit.results import CheckReport
    from alpha_audit.rules import Rule

__all__ = [
    "LineGroup",
    "audits_text",
    "by_line",
    "group_fix",
    "group_message",
    "group_where",
]


@dataclass(frozen=True)
class LineGroup:
    """Root causes of one rule whose failing value one line sets (:func:`by_line`).

    ``findings`` are in the order given (worst first); ``location`` is the
    line they share (``None``: a finding with no location, alone).
    """

    rule: Rule
    location: Location | None
    findings: tuple[Finding, ...]

    @property
    def worst(self) -> Finding:
        """The first (worst) root cause: the figures a report shows for the group."""
        return self.findings[0]

    @property
    def folded(self) -> bool:
        """Whether several root causes share the line."""
        return len(self.findings) > 1

    @property
    def icons(self) -> tuple[str, ...]:
        """Every icon of the group, each once, in the findings' order."""
        return tuple(dict.fromkeys(i for f in self.findings for i in f.icons))

    @property
    def canvases(self) -> tuple[str, ...]:
        """Every canvas where a root cause of the group occurs, each once."""
        return tuple(dict.fromkeys(c for f in self.findings for c in f.canvases))

    @property
    def audits(self) -> tuple[tuple[str, str], ...]:
        """The (theme, icon set) pairs the root causes come from, each once."""
        return tuple(dict.fromkeys((f.theme, f.iconset) for f in self.findings))

    def fingerprint(self, base: Path | None) -> str:
        """A stable identity for code-scanning and Code Quality dashboards; never a line.

        One root cause keeps its own identity (theme, icon set, rule, icons: what a
        baseline matches); a folded group is its rule, the file and kind of value of
        its line (``alpha``, ``colour``, ``token`` ...), its audits and its icons, so it
        stays one alert while the same icons fail on that line, wherever it moves.
        """
        if not self.folded or self.location is None:
            theme, iconset, rule, icons = self.worst.key
            return digest("\x1f".join([theme, iconset, rule, *icons]))
        where = display_path(self.location.file, base) or ""
        audits = ["\x1d".join(a) for a in sorted(self.audits)]
        parts = [self.rule.value, where, self.location.what, *audits, "\x1e", *sorted(self.icons)]
        return digest("\x1f".join(parts))


# Locations that name where an icon is drawn, not a value that makes it fail (an SVG,
# a story or page file at its first line): findings there are root causes of their
# own, never folded together.
_NOT_VALUES = frozenset({"svg", "story", "page"})


def _standing(f: Finding) -> tuple[object, ...]:
    """What a report does with a finding: a group never mixes failing and dismissed ones."""
    return (f.level, f.exemption, f.baselined)


def by_line(findings: Iterable[Finding]) -> list[LineGroup]:
    """``findings`` folded by (rule, standing, the line that sets the failing value).

    Groups come in the order of their first finding, so worst first when the
    findings are (the gate ranks them).

    >>> from alpha_audit.findings import Finding
    >>> from alpha_audit.model import Location
    >>> from alpha_audit.rules import Rule
    >>> line = Location(Path("set.yaml"), 4, "alpha")
    >>> found = [Finding(Rule.LOSS, "t", "s", "white", (i,), "m", locations=(line,)) for i in "ab"]
    >>> [(g.rule.value, g.location.line, g.icons) for g in by_line(found)]
    [('loss', 4, ('a', 'b'))]
    """
    groups: dict[tuple[object, ...], list[Finding]] = {}
    for n, f in enumerate(findings):
        if f.locations and f.locations[0].what not in _NOT_VALUES:
            at = f.locations[0]
            column = at.span.start_column if at.span is not None else None  # minified CSS
            key: tuple[object, ...] = (f.rule, _standing(f), at.file, at.line, column)
        else:
            key = (f.rule, n)  # nothing to share: alone
        groups.setdefault(key, []).append(f)
    return [
        LineGroup(
            found[0].rule, found[0].locations[0] if found[0].locations else None, tuple(found)
        )
        for found in groups.values()
    ]


def group_where(group: LineGroup, names: int = 3) -> str:
    """Who a group is about: one root cause's icons and canvases, or the counts of many.

    ``alert on paper (worst) and 2 more canvases`` for one root cause;
    ``69 icons (alert, bell, check +66 more) on 16 canvases; worst: alert on paper`` for many.
    """
    worst = group.worst
    if not group.folded:
        return where_text(worst, names)
    icons, canvases = group.icons, group.canvases
    head = f"{len(icons)} icon{'s' * (len(icons) != 1)} ({shorten_names(list(icons), names)})"
    if canvases:
        head += f" on {len(canvases)} canvas{'es' * (len(canvases) != 1)}"
    if worst.canvas is None:
        return head
    who = "" if set(worst.icons) == set(icons) else f"{shorten_names(list(worst.icons), names)} "
    return f"{head}; worst: {who}on {worst.canvas}"


def audits_text(group: LineGroup) -> str:
    """``theme / icon set`` of a group, or how many of each it spans."""
    audits = group.audits
    if len(audits) == 1:
        return f"{audits[0][0]} / {audits[0][1]}"
    themes = sorted({t for t, _ in audits})
    sets = sorted({s for _, s in audits})
    left = themes[0] if len(themes) == 1 else f"{len(themes)} themes"
    right = sets[0] if len(sets) == 1 else f"{len(sets)} icon sets"
    return f"{left} / {right}"


def group_fix(group: LineGroup, report: CheckReport, limit: int = 3) -> str:
    """The fixes of a group's root causes in words, each distinct one once (a few, then a count)."""
    from alpha_audit.render.common import finding_fix

    texts = list(dict.fromkeys(finding_fix(f, report) for f in group.findings))
    shown = "; ".join(texts[:limit])
    return shown if len(texts) <= limit else f"{shown}; +{len(texts) - limit} more"


def group_message(group: LineGroup) -> str:
    """One line for a group: who, where from, and the worst root cause's message."""
    return f"{group_where(group)} ({audits_text(group)}): {group.worst.message}"
