"""JUnit XML: one test case per icon x canvas, failures carry the gate's reason.

A finding folded over canvases fails the case of each of its canvases (its
figures are the worst canvas's).

Suites are audits (``theme / icon set``; a page run's audits of one state and
story, one per backdrop, share their suite); a case is named after the icon,
its class after the icon set and canvas, which is how CI test viewers (GitLab,
Jenkins, Azure, dorny/test-reporter) group them.  A page state that could not
be audited is an ``error`` case of its suite.  Exempted or baselined
findings make a case ``skipped`` with the reason; an icon that could not be
rendered is an ``error`` when the ``unrenderable`` rule is on, else skipped.
Control characters that XML 1.0 forbids are removed from every string.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections import defaultdict

from alpha_audit.findings import Finding
from alpha_audit.render.common import RenderOptions, display_path, xml_safe
from alpha_audit.results import CheckReport
from alpha_audit.rules import Level, Rule
from alpha_audit.safe_text import safe_text

__all__ = ["render_report", "xml_safe"]


def _element(parent: ET.Element, tag: str, text: str | None = None, **attrs: object) -> ET.Element:
    el = ET.SubElement(parent, tag, {k: xml_safe(v) for k, v in attrs.items()})
    if text is not None:
        el.text = xml_safe(text)
    return el


def _details(f: Finding) -> str:
    # A figure may be a name a page supplied (a DOM path): one line each, escaped.
    numbers = ", ".join(
        f"{k}={v:.6g}" if isinstance(v, float) else f"{k}={safe_text(v)}"
        for k, v in f.figures.to_dict().items()
    )
    return f"{f.rule.value}: {f.message}\n{numbers}" if numbers else f"{f.rule.value}: {f.message}"


def render_report(report: CheckReport, options: RenderOptions) -> str:
    """The report as a JUnit XML document (``<testsuites>``)."""
    by_cell: dict[tuple[str, str, str | None, str], list[Finding]] = defaultdict(list)
    for f in report.gate.findings:
        for name in f.canvases or (f.canvas,):  # a root cause fails each of its canvases
            for icon_name in f.icons:
                by_cell[(f.theme, f.iconset, name, icon_name)].append(f)
    unrenderable_fails = report.gate.policy.level(Rule.UNRENDERABLE) is Level.FAIL

    root = ET.Element("testsuites", {"name": "alpha-audit"})
    totals = {"tests": 0, "failures": 0, "errors": 0, "skipped": 0}
    suites: dict[tuple[str, str], tuple[ET.Element, dict[str, int]]] = {}

    def suite_of(theme: str, iconset: str) -> tuple[ET.Element, dict[str, int]]:
        if (theme, iconset) not in suites:
            element = _element(root, "testsuite", name=f"{theme} / {iconset}")
            suites[theme, iconset] = (element, dict.fromkeys(totals, 0))
        return suites[theme, iconset]

    def case(theme: str, iconset: str, **attrs: object) -> tuple[ET.Element, dict[str, int]]:
        """A test case of the suite of ``theme / iconset``, counted."""
        suite, counts = suite_of(theme, iconset)
        counts["tests"] += 1
        return _element(suite, "testcase", None, **attrs, time="0"), counts

    for result in report.audits:
        theme, iconset = result.theme.name, result.iconset.name
        suite_of(theme, iconset)  # every audit has its suite, cases or not
        for canvas in result.theme.canvases:
            for icon in result.iconset.icons:
                element, counts = case(
                    theme,
                    iconset,
                    name=icon.name,
                    classname=f"{iconset}.{canvas.name}",
                    file=display_path(icon.file, options.base),
                )
                found = by_cell.get((theme, iconset, canvas.name, icon.name), [])
                failing = [f for f in found if f.fails]
                if failing:
                    counts["failures"] += 1
                    _element(
                        element,
                        "failure",
                        "\n".join(_details(f) for f in failing),
                        message="; ".join(f"{f.rule.value}: {f.message}" for f in failing),
                        type=",".join(sorted({f.rule.value for f in failing})),
                    )
                elif found:
                    counts["skipped"] += 1
                    f = found[0]
                    why = f"exempt: {f.exemption.reason}" if f.exemption else "in the baseline"
                    _element(element, "skipped", message=f"{f.rule.value} {why}")
        for problem in result.problems:
            element, counts = case(
                theme,
                iconset,
                name=problem.icon,
                classname=f"{iconset}.render",
                file=display_path(problem.file, options.base),
            )
            if unrenderable_fails:
                counts["errors"] += 1
                _element(element, "error", problem.message, message=problem.message, type="render")
            else:
                counts["skipped"] += 1
                _element(element, "skipped", message=f"could not be rendered: {problem.message}")
    for q in report.pages.problems if report.pages is not None else ():
        element, counts = case(q.state, q.source, name=f"[{q.engine}]", classname=q.source)
        counts["errors"] += 1
        _element(element, "error", q.message, message=q.message, type="page")
    for suite, counts in suites.values():
        for k, v in counts.items():
            suite.set(k, str(v))
            totals[k] += v
    for k, v in totals.items():
        root.set(k, str(v))
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, "unicode") + "\n"
