"""The CI gate: which findings of the audits fail the build, and the baseline they are judged by.

:func:`evaluate` collects every audit's findings (:mod:`alpha_audit.findings`)
and decides the verdict once: a finding of a failing rule fails the gate unless
an exemption (with its reason) or the baseline covers it; findings of
reported rules are warnings.  The baseline is a :class:`Baseline`: the keys of
a baseline file (:mod:`alpha_audit.baseline`) or of the base revision's
own findings (``check --base``), matched the same way.  Findings come out
worst first (:func:`~alpha_audit.findings.ranked`).  Pure computation:
nothing is printed.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, replace
from typing import Literal

from alpha_audit.findings import Finding, FindingKey, findings_for, ranked, severity
from alpha_audit.policy import Policy
from alpha_audit.rows import AuditResult
from alpha_audit.rules import Level, Rule

__all__ = [
    "BASELINE_SCHEMA",
    "LEGACY_BASELINE_SCHEMA",
    "VACUOUS",
    "Baseline",
    "CanvasKey",
    "GateResult",
    "RuleSummary",
    "baseline_document",
    "collect",
    "evaluate",
    "judge",
    "rule_summary",
]

BASELINE_SCHEMA = "alpha-audit.baseline/2"
# Per-canvas entries (one finding per paint x canvas, before findings folded over
# canvases): still read, each folded finding matched canvas by canvas.
LEGACY_BASELINE_SCHEMA = "alpha-audit.baseline/1"
# The counts() entry of a gate that audited nothing (like pytest's "no tests ran").
VACUOUS = "unrenderable, nothing audited"

# (theme, icon set, rule, canvas, icons): an entry of a baseline/1 file.
CanvasKey = tuple[str, str, str, str | None, tuple[str, ...]]


@dataclass(frozen=True)
class Baseline:
    """What the gate does not fail on again: finding keys, from a file or the base revision.

    ``keys`` match :attr:`~alpha_audit.findings.Finding.key`.  ``cells`` are
    the entries of a ``baseline/1`` file (one per canvas): a finding is
    covered when each of its canvases is.  ``kind`` says where it came from
    (``file`` or ``base``) and ``name`` names it (the file, or the ref).
    """

    keys: frozenset[FindingKey] = frozenset()
    cells: frozenset[CanvasKey] = frozenset()
    kind: Literal["file", "base"] = "file"
    name: str = ""

    @classmethod
    def of(cls, baseline: Baseline | Iterable[FindingKey | CanvasKey]) -> Baseline:
        """``baseline`` itself, or a file baseline of the keys given (per-canvas ones too)."""
        if isinstance(baseline, Baseline):
            return baseline
        keys: set[FindingKey] = set()
        cells: set[CanvasKey] = set()
        for key in baseline:
            if len(key) == 5:
                cells.add(key)  # a baseline/1 entry
            else:
                keys.add(key)
        return cls(keys=frozenset(keys), cells=frozenset(cells))

    @property
    def legacy(self) -> bool:
        """Whether it holds per-canvas (``baseline/1``) entries."""
        return bool(self.cells)

    def covers(self, finding: Finding) -> bool:
        """Whether ``finding`` is in the baseline (every canvas of it, for per-canvas entries)."""
        if finding.key in self.keys:
            return True
        if not self.cells:
            return False
        theme, iconset, rule, icons = finding.key
        return all(
            (theme, iconset, rule, canvas, icons) in self.cells
            for canvas in finding.canvases or (None,)
        )

    def stale(self, findings: Sequence[Finding]) -> tuple[FindingKey, ...]:
        """Entries that match none of ``findings``, sorted (per-canvas ones by their key)."""
        seen = {f.key for f in findings}
        cells = {(*f.key[:3], c, f.icons) for f in findings for c in f.canvases or (None,)}
        gone = set(self.keys - seen)
        gone |= {(t, s, r, i) for t, s, r, c, i in self.cells - cells if (t, s, r, i) not in seen}
        return tuple(sorted(gone))


@dataclass(frozen=True)
class GateResult:
    """Every finding of the failing rules, in stable order, plus warnings and stale entries.

    The verdict is decided here once: ``findings`` splits into :attr:`failures`,
    :attr:`exempted` and :attr:`baselined`; ``warnings`` are findings of the
    reported rules (icons that could not be rendered, hard-coded paints ...),
    never failing and never baselined.  Renderers show these; they do not
    re-decide them.
    """

    policy: Policy
    findings: tuple[Finding, ...]
    stale: tuple[FindingKey, ...] = ()
    problems: int = 0  # icons that could not be rendered
    warnings: tuple[Finding, ...] = ()
    audited: int | None = None  # paint x canvas rows audited; None: not counted
    baseline: Baseline | None = None  # what the findings were judged against

    @property
    def on_base(self) -> bool:
        """Whether the baseline is the base revision's findings (``check --base``)."""
        return self.baseline is not None and self.baseline.kind == "base"

    @property
    def vacuous(self) -> bool:
        """True when nothing was audited (every icon unrenderable): the gate cannot pass."""
        return self.audited == 0

    @property
    def failures(self) -> tuple[Finding, ...]:
        """Findings that fail the gate."""
        return tuple(f for f in self.findings if f.fails)

    @property
    def exempted(self) -> tuple[Finding, ...]:
        """Findings an exemption covers (with its reason)."""
        return tuple(f for f in self.findings if f.exemption is not None)

    @property
    def baselined(self) -> tuple[Finding, ...]:
        """Findings the baseline covers and no exemption does."""
        return tuple(f for f in self.findings if f.baselined and f.exemption is None)

    @property
    def passed(self) -> bool:
        """True when no finding fails the gate and something was audited."""
        return not self.failures and not self.vacuous

    def counts(self) -> dict[str, int]:
        """Failing root causes per rule name, sorted by name (stable)."""
        out: dict[str, int] = {}
        if self.vacuous:  # every report then says why the gate failed without findings
            out[VACUOUS] = self.problems
        for f in self.failures:
            out[f.rule.value] = out.get(f.rule.value, 0) + 1
        return dict(sorted(out.items()))

    def counts_text(self, escape: Callable[[str], str] = str) -> str:
        """``counts()`` as a report says it: ``2 below-threshold, 1 loss``."""
        return ", ".join(f"{n} {escape(rule)}" for rule, n in self.counts().items())


@dataclass(frozen=True)
class RuleSummary:
    """What one rule found over every audit: the lines a report leads with.

    Counts are root causes (findings), ``icons`` the distinct icons of the
    failing ones; ``worst`` the worst failing finding (the gate orders them),
    else the worst reported one.
    """

    rule: Rule
    failing: int
    icons: int
    reported: int
    exempted: int
    baselined: int
    worst: Finding | None


def rule_summary(gate: GateResult) -> list[RuleSummary]:
    """One :class:`RuleSummary` per rule with any finding, worst rule first.

    Rules are ordered by their worst failing finding's severity
    (:func:`~alpha_audit.findings.severity`), rules with no failure last.
    """
    out = []
    failing = gate.failures
    for rule in Rule:
        mine = [f for f in failing if f.rule is rule]
        noted = [f for f in gate.warnings if f.rule is rule]
        exempt = sum(1 for f in gate.exempted if f.rule is rule)
        base = sum(1 for f in gate.baselined if f.rule is rule)
        if not (mine or noted or exempt or base):
            continue
        icons = {i for f in mine for i in f.icons}
        worst = mine[0] if mine else (noted[0] if noted else None)
        out.append(RuleSummary(rule, len(mine), len(icons), len(noted), exempt, base, worst))
    return sorted(out, key=lambda s: (s.failing == 0, severity(s.worst) if s.worst else (9, 0.0)))


def evaluate(
    audits: Sequence[AuditResult],
    policy: Policy,
    *,
    baseline: Baseline | Iterable[FindingKey | CanvasKey] | None = None,
) -> GateResult:
    """Apply ``policy`` to every audit; findings the ``baseline`` covers do not fail.

    Baseline entries that match no finding any more are returned as ``stale``
    so the baseline can be tightened.  A rule that judges icons, not canvases
    (``unrenderable``, ``fixed-colour``, ``not-audited``) reports each icon once,
    however many themes it was audited on.  Findings and warnings are ordered
    worst root cause first.

    >>> from alpha_audit.rows import audit
    >>> from alpha_audit.model import Canvas, Icon, IconSet, Theme
    >>> canvases = (Canvas("yellow", "#ffff00"), Canvas("lemon", "#ffff40"))
    >>> icons = IconSet("s", (Icon("dot", "dot.svg", "#0000d0", 1.4),))
    >>> gate = evaluate([audit(Theme("t", canvases), icons)], Policy())
    >>> [(f.rule.value, f.canvas, f.canvases, f.icons) for f in gate.failures]
    [('loss', 'yellow', ('yellow', 'lemon'), ('dot',))]
    """
    return judge(audits, policy, collect(audits, policy), baseline)


def collect(
    audits: Iterable[AuditResult], policy: Policy, *, seen: Iterable[Finding] = ()
) -> list[Finding]:
    """Every audit's findings, icon-judging ones once over all themes (:func:`evaluate`).

    ``seen``: findings collected already (from earlier audits, one at a time).
    """
    out: list[Finding] = []
    once = {(f.rule.value, f.iconset, f.message, f.icons) for f in seen if not f.canvases}
    for result in audits:
        for f in findings_for(result, policy):
            if not f.canvases:  # judged per icon: once for all themes
                key = (f.rule.value, f.iconset, f.message, f.icons)
                if key in once:
                    continue
                once.add(key)
            out.append(f)
    return out


def judge(
    audits: Sequence[AuditResult],
    policy: Policy,
    found: Sequence[Finding],
    baseline: Baseline | Iterable[FindingKey | CanvasKey] | None = None,
) -> GateResult:
    """The verdict on findings already collected (:func:`collect`) from ``audits``."""
    findings = [f for f in found if f.level is Level.FAIL]
    warnings = [f for f in found if f.level is not Level.FAIL]
    stale: tuple[FindingKey, ...] = ()
    judged = None if baseline is None else Baseline.of(baseline)
    if judged is not None:
        findings = [replace(f, baselined=True) if judged.covers(f) else f for f in findings]
        stale = judged.stale(findings)
    return GateResult(
        policy=policy,
        findings=tuple(ranked(findings)),
        stale=stale,
        problems=sum(len(r.problems) for r in audits),
        warnings=tuple(ranked(warnings)),
        audited=sum(int(r.contrast.size) for r in audits),
        baseline=judged,
    )


def baseline_document(gate: GateResult) -> dict[str, object]:
    """Today's findings as a baseline: every failing-rule finding no exemption covers.

    Entries carry no numbers, canvases or line numbers, only what they are
    matched on (:attr:`~alpha_audit.findings.Finding.key`), sorted so that the
    file diffs cleanly.
    """
    keys = sorted({f.key for f in gate.findings if f.exemption is None})
    return {
        "schema": BASELINE_SCHEMA,
        "entries": [{"theme": t, "iconset": s, "rule": r, "icons": list(i)} for t, s, r, i in keys],
    }
