"""The CI gate: which findings of an audit fail the build, and why.

:func:`evaluate` turns audit results and a :class:`~alpha_audit.policy.Policy`
into :class:`Finding` objects, each naming its rule, theme, icon set, canvas,
icon(s) and numbers.  A finding fails the gate unless an exemption (with its
reason) or a baseline entry covers it.  Pure computation: nothing is printed.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from alpha_audit.audit import AuditResult
from alpha_audit.errors import AlphaAuditError, InputError, UsageError
from alpha_audit.load.files import read_text_capped
from alpha_audit.load.paints import CURRENT_COLOR
from alpha_audit.model import GamutAdjustment, Icon
from alpha_audit.paint_audit import PaintAudit, paint_findings
from alpha_audit.policy import PAINT_RULES, Exemption, Policy, Rule, contrast_breaks

if TYPE_CHECKING:
    from alpha_audit.fixes import ColorFix

__all__ = [
    "BASELINE_SCHEMA",
    "CheckReport",
    "Finding",
    "FindingKey",
    "GateResult",
    "baseline_document",
    "evaluate",
    "findings_for",
    "parse_baseline",
    "read_baseline",
    "unjudged_problems",
]

# (theme, icon set, rule, canvas, icons): what a baseline matches on.  Never a
# line number or a value, so editing a manifest does not invalidate a baseline.
FindingKey = tuple[str, str, str, str | None, tuple[str, ...]]


@dataclass(frozen=True)
class Finding:
    """One thing a gate rule objects to.

    ``numbers`` holds the figures a reviewer needs (contrast before and after,
    threshold, CIEDE2000, 8-bit output ...), ``files`` the icons' SVG files
    and ``lines`` the manifest lines that set each icon's colour or alpha;
    ``sources`` the (file, line) of each design token that sets a colour of
    the finding (icon colour first, then the canvas), where the fix goes.
    """

    rule: Rule
    theme: str
    iconset: str
    canvas: str | None
    icons: tuple[str, ...]
    message: str
    numbers: Mapping[str, float | str] = field(default_factory=dict)
    files: tuple[Path, ...] = ()
    manifest: Path | None = None
    lines: tuple[int, ...] = ()
    exemption: Exemption | None = None
    sources: tuple[tuple[Path, int], ...] = ()
    baselined: bool = False

    @property
    def key(self) -> FindingKey:
        """Identity for baselines: theme, icon set, rule, canvas and icons."""
        return (self.theme, self.iconset, self.rule.value, self.canvas, self.icons)

    @property
    def fails(self) -> bool:
        """Whether this finding fails the gate (not exempt, not in the baseline)."""
        return self.exemption is None and not self.baselined


@dataclass(frozen=True)
class GateResult:
    """Every finding of the enabled rules, in stable order, plus stale baseline entries.

    The verdict is decided here once: ``findings`` splits into :attr:`failures`,
    :attr:`exempted` and :attr:`baselined`; ``warnings`` are icons that could
    not be rendered while ``unrenderable`` is not a rule (reported, never
    failing, never baselined).  Renderers show these; they do not re-decide them.
    """

    policy: Policy
    findings: tuple[Finding, ...]
    stale: tuple[FindingKey, ...] = ()
    problems: int = 0  # icons that could not be rendered (reported, fail only with a rule)
    warnings: tuple[Finding, ...] = ()
    audited: int | None = None  # icon x canvas combinations audited; None: not counted

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
    def unrenderable_fails(self) -> bool:
        """Whether an icon that could not be rendered fails the gate (else it is a warning)."""
        return Rule.UNRENDERABLE in self.policy.rules

    @property
    def passed(self) -> bool:
        """True when no finding fails the gate and something was audited."""
        return not self.failures and not self.vacuous

    def counts(self) -> dict[str, int]:
        """Failures per rule name, rules in policy order (stable)."""
        out: dict[str, int] = {}
        if self.vacuous:  # every report then says why the gate failed without findings
            out[VACUOUS] = self.problems
        for f in self.failures:
            out[f.rule.value] = out.get(f.rule.value, 0) + 1
        return dict(sorted(out.items()))


@dataclass(frozen=True)
class CheckReport:
    """What ``check`` produces: one audit per theme x icon set, and the gate over all."""

    audits: tuple[AuditResult, ...]
    gate: GateResult
    # A fix per failing (colour, canvas), from alpha_audit.fixes.with_fixes
    # (which builds on this module); None when not computed.
    fixes: tuple[ColorFix, ...] | None = None
    gamut: tuple[GamutAdjustment, ...] = ()  # colours outside sRGB the gamut policy moved


def _icon_refs(
    by_name: Mapping[str, Icon], names: Sequence[str]
) -> tuple[tuple[Path, ...], tuple[int, ...]]:
    files: list[Path] = []
    lines: list[int] = []
    for name in names:
        icon = by_name.get(name)
        if icon is None:
            continue
        files.append(Path(icon.file))
        lines.extend(n for n in (icon.color_line, icon.alpha_line) if n is not None)
    return tuple(files), tuple(sorted(set(lines)))


def _token_sources(
    result: AuditResult, by_name: Mapping[str, Icon], names: Sequence[str], canvas: str | None
) -> tuple[tuple[Path, int], ...]:
    """(file, line) of the design tokens setting the icons' colours, then the canvas's."""
    out: list[tuple[Path, int]] = []
    for name in names:
        icon = by_name.get(name)
        if icon is not None and icon.token_file is not None and icon.token_line is not None:
            out.append((Path(icon.token_file), icon.token_line))
    for c in result.theme.canvases:
        if c.name == canvas and c.file is not None and c.line is not None:
            out.append((Path(c.file), c.line))
    return tuple(dict.fromkeys(out))  # unique, first-seen order


def _cell_findings(
    result: AuditResult | PaintAudit, policy: Policy
) -> Iterable[tuple[Rule, int, int, str]]:
    """(rule, row index, canvas index, message) for the per icon (or paint) x canvas rules."""
    t = result.threshold
    templates = {
        Rule.LOSS: "contrast drops {ref:.3f} -> {now:.3f} ({gain:+.4f}) at alpha {a:g}",
        Rule.NEWLY_FAILING: (
            f"passes {t:g}:1 at alpha 1 ({{ref:.3f}}) but not at alpha {{a:g}} ({{now:.3f}})"
        ),
        Rule.BELOW_THRESHOLD: f"contrast {{now:.3f}} is below {t:g}:1 at alpha {{a:g}}",
    }
    for rule in policy.contrast_rules:
        template = templates[rule]
        mask = contrast_breaks(
            rule, policy, result.contrast_ref, result.contrast, t, result.tolerance
        )
        # Canvas order, then icon order: the same order as AuditResult.rows().
        for j, i in zip(*np.nonzero(mask.T), strict=True):
            i, j = int(i), int(j)
            yield (
                rule,
                i,
                j,
                template.format(
                    ref=float(result.contrast_ref[i, j]),
                    now=float(result.contrast[i, j]),
                    gain=float(result.gain[i, j]),
                    a=float(result.alpha[i]),
                ),
            )


def findings_for(result: AuditResult, policy: Policy) -> list[Finding]:
    """Every finding of ``policy``'s rules in one audit, exemptions applied.

    Order is stable: per-cell rules (loss, newly-failing, below-threshold) in
    canvas then icon order, then collisions, separations and render problems.
    """
    theme, iconset = result.theme.name, result.iconset.name
    manifest = result.iconset.path
    out: list[Finding] = []
    by_name = {i.name: i for i in result.iconset.icons}  # once: a brand set has thousands

    def add(
        rule: Rule,
        canvas: str | None,
        icons: tuple[str, ...],
        message: str,
        numbers: dict[str, float | str],
    ) -> None:
        files, lines = _icon_refs(by_name, icons)
        out.append(
            Finding(
                rule=rule,
                theme=theme,
                iconset=iconset,
                canvas=canvas,
                icons=icons,
                message=message,
                numbers=numbers,
                files=files,
                manifest=manifest,
                lines=lines,
                exemption=policy.exempt(rule, canvas, icons),
                sources=_token_sources(result, by_name, icons, canvas),
            )
        )

    canvases, icons = result.theme.canvases, result.iconset.icons
    # With the icons' own paints read, the per-cell rules judge every paint as drawn.
    cells = result.paints if result.paints is not None else result
    for rule, i, j, message in _cell_findings(cells, policy):
        numbers: dict[str, float | str] = {
            "alpha": float(cells.alpha[i]),
            "contrast_ref": float(cells.contrast_ref[i, j]),
            "contrast": float(cells.contrast[i, j]),
            "gain": float(cells.gain[i, j]),
            "threshold": float(cells.threshold),
            "background": canvases[j].color,
        }
        if result.paints is None:
            numbers["source"] = icons[i].color
            add(rule, canvases[j].name, (icons[i].name,), message, numbers)
            continue
        entry = result.paints.entries[i]
        numbers.update(source=entry.source, paint=entry.paint, opacity=entry.opacity)
        if entry.paint != CURRENT_COLOR or entry.opacity != 1.0:
            message += f" (paint {entry.paint} at opacity {entry.opacity:g})"
        add(rule, canvases[j].name, (entry.icon.name,), message, numbers)

    collision_rule = policy.collision_rule
    for c in result.collisions:
        if collision_rule is None or (collision_rule is Rule.NEW_COLLISION and not c.new):
            continue
        give = "both give" if len(c.sources) == 2 else "all give"
        message = f"distinct colours {', '.join(c.sources)} {give} {c.output}" + (
            "" if c.new else " (already at alpha 1)"
        )
        numbers = {"output": c.output, "sources": ", ".join(c.sources), "new": str(c.new).lower()}
        add(collision_rule, c.canvas, tuple(sorted(c.icons)), message, numbers)

    if Rule.SEPARATION in policy.rules:
        for s in result.separations:
            if s.delta_e < policy.min_delta_e:
                message = (
                    f"closest colours are CIEDE2000 {s.delta_e:.2f} apart "
                    f"(at alpha 1: {s.delta_e_ref:.2f}); minimum {policy.min_delta_e:g}"
                )
                numbers = {
                    "delta_e": s.delta_e,
                    "delta_e_ref": s.delta_e_ref,
                    "min_delta_e": policy.min_delta_e,
                    "sources": ", ".join(s.sources),
                }
                add(Rule.SEPARATION, s.canvas, tuple(sorted(s.icons)), message, numbers)

    if result.paints is not None and policy.rules & PAINT_RULES:
        for pf in paint_findings(result.paints, policy):
            numbers = dict(pf.numbers)
            if pf.paint is not None:
                numbers["paint"] = pf.paint
            if pf.element is not None:
                numbers["element"] = pf.element + (f" (line {pf.line})" if pf.line else "")
            add(pf.rule, pf.canvas, pf.icons, pf.message, numbers)

    if Rule.UNRENDERABLE in policy.rules:
        out.extend(_problem_findings(result, policy))
    return out


def _problem_findings(result: AuditResult, policy: Policy) -> list[Finding]:
    """One ``unrenderable`` finding per icon that could not be rendered."""
    # Broken icons are not in result.iconset any more; name their file directly.
    return [
        Finding(
            rule=Rule.UNRENDERABLE,
            theme=result.theme.name,
            iconset=result.iconset.name,
            canvas=None,
            icons=(p.icon,),
            message=p.message,
            files=(Path(p.file),),
            manifest=result.iconset.path,
            exemption=policy.exempt(Rule.UNRENDERABLE, None, (p.icon,)),
        )
        for p in result.problems
    ]


def unjudged_problems(report: CheckReport) -> list[Finding]:
    """Icons that could not be rendered, as findings, when the gate does not judge them.

    With ``unrenderable`` off they fail nothing, but CI formats still list them
    (as information) so a broken file is not silent.  Empty when the rule is on:
    then they are among the gate's own findings.
    """
    if Rule.UNRENDERABLE in report.gate.policy.rules:
        return []
    return [
        Finding(
            Rule.UNRENDERABLE,
            audit.theme.name,
            audit.iconset.name,
            None,
            (p.icon,),
            p.message,
            files=(Path(p.file),),
        )
        for audit in report.audits
        for p in audit.problems
    ]


def evaluate(
    audits: Sequence[AuditResult],
    policy: Policy,
    *,
    baseline: Iterable[FindingKey] | None = None,
) -> GateResult:
    """Apply ``policy`` to every audit; findings in ``baseline`` do not fail.

    Baseline entries that match no finding any more are returned as ``stale``
    so the baseline can be tightened.

    >>> from alpha_audit.audit import audit
    >>> from alpha_audit.model import Canvas, Icon, IconSet, Theme
    >>> theme = Theme("t", (Canvas("yellow", "#ffff00"),))
    >>> icons = IconSet("s", (Icon("dot", "dot.svg", "#0000d0", 1.4),))
    >>> gate = evaluate([audit(theme, icons)], Policy())
    >>> [(f.rule.value, f.canvas, f.icons) for f in gate.failures]
    [('loss', 'yellow', ('dot',))]
    """
    findings: list[Finding] = []
    warnings: list[Finding] = []
    unrenderable: set[tuple[str, tuple[str, ...]]] = set()
    gated = Rule.UNRENDERABLE in policy.rules
    for result in audits:
        found = findings_for(result, policy)
        if not gated:  # reported, never failing: the gate's warnings
            found += [replace(f, exemption=None) for f in _problem_findings(result, policy)]
        for f in found:
            if f.rule is Rule.UNRENDERABLE:  # one per icon, not one per theme
                if (f.iconset, f.icons) in unrenderable:
                    continue
                unrenderable.add((f.iconset, f.icons))
            (findings if gated or f.rule is not Rule.UNRENDERABLE else warnings).append(f)
    stale: tuple[FindingKey, ...] = ()
    if baseline is not None:
        known = set(baseline)
        seen = {f.key for f in findings}
        findings = [replace(f, baselined=True) if f.key in known else f for f in findings]
        stale = tuple(sorted(known - seen, key=_sort_key))
    problems = sum(len(r.problems) for r in audits)
    audited = sum(int(r.contrast.size) for r in audits)
    return GateResult(
        policy=policy,
        findings=tuple(findings),
        stale=stale,
        problems=problems,
        warnings=tuple(warnings),
        audited=audited,
    )


def _sort_key(key: FindingKey) -> tuple[str, str, str, str, tuple[str, ...]]:
    theme, iconset, rule, canvas, icons = key
    return (theme, iconset, rule, canvas or "", icons)


BASELINE_SCHEMA = "alpha-audit.baseline/1"
# The counts() entry of a gate that audited nothing (like pytest's "no tests ran").
VACUOUS = "unrenderable, nothing audited"
MAX_BASELINE_BYTES = 16 << 20  # 16 MiB: a few hundred bytes per entry


def baseline_document(gate: GateResult) -> dict[str, object]:
    """Today's findings as a baseline: every finding not covered by an exemption.

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


def parse_baseline(text: str, path: Path) -> frozenset[FindingKey]:
    """Finding keys from a baseline file written by :func:`baseline_document`."""

    def bad(message: str) -> InputError:
        return InputError(f"not an alpha-audit baseline: {message}", path=path)

    try:
        doc = json.loads(text)
    except (ValueError, RecursionError) as exc:  # ValueError: also the int-digits limit
        raise bad(f"invalid JSON ({str(exc)[:100]})") from exc
    if not isinstance(doc, dict) or doc.get("schema") != BASELINE_SCHEMA:
        raise bad(f'expected {{"schema": "{BASELINE_SCHEMA}", "entries": [...]}}')
    entries = doc.get("entries")
    if not isinstance(entries, list):
        raise bad("entries must be a list")
    keys = set()
    for n, e in enumerate(entries):
        ok = (
            isinstance(e, dict)
            and all(isinstance(e.get(k), str) for k in ("theme", "iconset", "rule"))
            and "canvas" in e
            and (e["canvas"] is None or isinstance(e["canvas"], str))
            and isinstance(e.get("icons"), list)
            and all(isinstance(i, str) for i in e["icons"])
        )
        if not ok:
            raise bad(f"entries[{n}] needs theme, iconset, rule, canvas and icons")
        try:
            rule = Rule.parse(e["rule"]).value
        except (AlphaAuditError, ValueError) as exc:
            raise bad(f"entries[{n}].rule: {getattr(exc, 'message', exc)}") from exc
        keys.add((e["theme"], e["iconset"], rule, e["canvas"], tuple(e["icons"])))
    return frozenset(keys)


def read_baseline(path: str | Path) -> frozenset[FindingKey]:
    """Read a baseline file (at most :data:`MAX_BASELINE_BYTES`)."""
    p = Path(path)
    if not p.exists() and not p.is_symlink():
        raise UsageError("baseline file not found (record one with `baseline_document`)", path=p)
    text = read_text_capped(p, MAX_BASELINE_BYTES, InputError, "an alpha-audit baseline")
    return parse_baseline(text, p)
