"""The CI gate: which findings of the audits fail the build, and the baseline they are judged by.

:func:`evaluate` collects every audit's findings (:mod:`alpha_audit.findings`)
and decides the verdict once: a finding of a failing rule fails the gate unless
an exemption (with its reason) or a baseline entry covers it; findings of
reported rules are warnings.  Pure computation: nothing is printed; the
baseline file is read by :mod:`alpha_audit.load.baseline`.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace

from alpha_audit.findings import Finding, FindingKey, findings_for
from alpha_audit.policy import Policy
from alpha_audit.rows import AuditResult
from alpha_audit.rules import Level

__all__ = [
    "BASELINE_SCHEMA",
    "VACUOUS",
    "GateResult",
    "baseline_document",
    "evaluate",
]

BASELINE_SCHEMA = "alpha-audit.baseline/1"
# The counts() entry of a gate that audited nothing (like pytest's "no tests ran").
VACUOUS = "unrenderable, nothing audited"


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
        """Failures per rule name, sorted by name (stable)."""
        out: dict[str, int] = {}
        if self.vacuous:  # every report then says why the gate failed without findings
            out[VACUOUS] = self.problems
        for f in self.failures:
            out[f.rule.value] = out.get(f.rule.value, 0) + 1
        return dict(sorted(out.items()))


def evaluate(
    audits: Sequence[AuditResult],
    policy: Policy,
    *,
    baseline: Iterable[FindingKey] | None = None,
) -> GateResult:
    """Apply ``policy`` to every audit; findings in ``baseline`` do not fail.

    Baseline entries that match no finding any more are returned as ``stale``
    so the baseline can be tightened.  A rule that judges icons, not canvases
    (``unrenderable``, ``fixed-colour``, ``not-audited``) reports each icon once,
    however many themes it was audited on.

    >>> from alpha_audit.rows import audit
    >>> from alpha_audit.model import Canvas, Icon, IconSet, Theme
    >>> theme = Theme("t", (Canvas("yellow", "#ffff00"),))
    >>> icons = IconSet("s", (Icon("dot", "dot.svg", "#0000d0", 1.4),))
    >>> gate = evaluate([audit(theme, icons)], Policy())
    >>> [(f.rule.value, f.canvas, f.icons) for f in gate.failures]
    [('loss', 'yellow', ('dot',))]
    """
    findings: list[Finding] = []
    warnings: list[Finding] = []
    once: set[tuple[str, str, str, tuple[str, ...]]] = set()
    for result in audits:
        for f in findings_for(result, policy):
            if f.canvas is None:  # judged per icon: once for all themes
                key = (f.rule.value, f.iconset, f.message, f.icons)
                if key in once:
                    continue
                once.add(key)
            (findings if f.level is Level.FAIL else warnings).append(f)
    stale: tuple[FindingKey, ...] = ()
    if baseline is not None:
        known = set(baseline)
        seen = {f.key for f in findings}
        findings = [replace(f, baselined=True) if f.key in known else f for f in findings]
        stale = tuple(sorted(known - seen, key=_sort_key))
    return GateResult(
        policy=policy,
        findings=tuple(findings),
        stale=stale,
        problems=sum(len(r.problems) for r in audits),
        warnings=tuple(warnings),
        audited=sum(int(r.contrast.size) for r in audits),
    )


def _sort_key(key: FindingKey) -> tuple[str, str, str, str, tuple[str, ...]]:
    theme, iconset, rule, canvas, icons = key
    return (theme, iconset, rule, canvas or "", icons)


def baseline_document(gate: GateResult) -> dict[str, object]:
    """Today's findings as a baseline: every failing-rule finding no exemption covers.

    Entries carry no numbers or line numbers, only what they are matched on,
    sorted so that the file diffs cleanly.
    """
    keys = sorted({f.key for f in gate.findings if f.exemption is None}, key=_sort_key)
    return {
        "schema": BASELINE_SCHEMA,
        "entries": [
            {"theme": t, "iconset": s, "rule": r, "canvas": c, "icons": list(i)}
            for t, s, r, c, i in keys
        ],
    }
