"""Files in, audit out: load themes and icon sets, rasterise, audit, apply the gate."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from pathlib import Path

from alpha_audit.audit import AuditResult, audit, check_combinations
from alpha_audit.errors import SvgError, UsageError
from alpha_audit.fixes import with_fixes
from alpha_audit.gate import CheckReport, FindingKey, evaluate
from alpha_audit.load.iconset import load_iconset
from alpha_audit.load.svg import MaskSet, rasterize_icons
from alpha_audit.load.theme import load_theme
from alpha_audit.load.tokens.themes import TokenConfig
from alpha_audit.model import IconSet
from alpha_audit.policy import Policy

__all__ = ["check_files", "check_project"]


def _render(
    iconset: IconSet,
    *,
    strict_svg: bool,
    on_icon: Callable[[], None] | None,
) -> MaskSet:
    masks = rasterize_icons(
        [(i.name, i.file) for i in iconset.icons], iconset.sizes, progress=on_icon
    )
    if strict_svg and masks.problems:
        first = masks.problems[0]
        raise SvgError(first.message, path=first.file)
    return masks


def check_files(
    theme_path: str | Path,
    iconset_path: str | Path,
    *,
    alpha: float | None = None,
    threshold: float | None = None,
    strict_svg: bool = False,
    on_start: Callable[[int], None] | None = None,
    on_icon: Callable[[], None] | None = None,
) -> AuditResult:
    """Load both files, rasterise every icon at every size and audit.

    Icons that cannot be rendered are left out and listed in
    ``result.problems``; with ``strict_svg`` the first one raises
    :class:`~alpha_audit.errors.SvgError`.  ``on_start(n)`` and ``on_icon()``
    report progress.
    """
    theme = load_theme(theme_path)
    iconset = load_iconset(iconset_path)
    if on_start is not None:
        on_start(len(iconset.icons))
    masks = _render(iconset, strict_svg=strict_svg, on_icon=on_icon)
    return audit(theme, iconset, alpha=alpha, threshold=threshold, problems=masks.problems)


def check_project(
    themes: Sequence[str | Path],
    iconsets: Sequence[str | Path],
    *,
    policy: Policy | None = None,
    alpha: float | None = None,
    threshold: float | None = None,
    baseline: Iterable[FindingKey] | None = None,
    strict_svg: bool = False,
    on_start: Callable[[int], None] | None = None,
    on_icon: Callable[[], None] | None = None,
    tokens: TokenConfig | None = None,
) -> CheckReport:
    """Audit every icon set on every theme and apply the gate ``policy``.

    Every file is loaded (and every input error raised) before any icon is
    rendered; each icon set is rendered once whatever the number of themes.
    Audits come in icon-set order, then theme order.  With ``tokens`` (the
    config's ``tokens:`` table) each icon set is also audited on every token
    mode, its icons' colours named by token path.
    """
    if tokens is not None:
        return _check_with_tokens(
            themes,
            iconsets,
            tokens,
            policy=policy,
            alpha=alpha,
            threshold=threshold,
            baseline=baseline,
            strict_svg=strict_svg,
            on_start=on_start,
            on_icon=on_icon,
        )
    if not themes or not iconsets:
        raise UsageError(
            "nothing to audit: give THEME ICONSET, or name themes and iconsets in "
            "alpha-audit.yaml or [tool.alpha-audit] in pyproject.toml"
        )
    loaded_themes = [load_theme(t) for t in _unique(themes)]
    loaded_sets = [load_iconset(s) for s in _unique(iconsets)]
    (policy or Policy()).check_exemptions(
        (c.name for t in loaded_themes for c in t.canvases),
        (i.name for s in loaded_sets for i in s.icons),
    )
    check_combinations(loaded_themes, loaded_sets)  # before any icon is rendered
    if on_start is not None:
        on_start(sum(len(s.icons) for s in loaded_sets))
    audits = []
    for iconset in loaded_sets:
        problems = _render(iconset, strict_svg=strict_svg, on_icon=on_icon).problems
        for theme in loaded_themes:
            audits.append(
                audit(theme, iconset, alpha=alpha, threshold=threshold, problems=problems)
            )
    gate = evaluate(audits, policy or Policy(), baseline=baseline)
    # Every renderer shows the fix for each failing colour: computed once, here.
    return with_fixes(CheckReport(audits=tuple(audits), gate=gate))


def _check_with_tokens(
    themes: Sequence[str | Path],
    iconsets: Sequence[str | Path],
    tokens: TokenConfig,
    *,
    policy: Policy | None,
    alpha: float | None,
    threshold: float | None,
    baseline: Iterable[FindingKey] | None,
    strict_svg: bool,
    on_start: Callable[[int], None] | None,
    on_icon: Callable[[], None] | None,
) -> CheckReport:
    """check_project with token themes: every icon set on every token mode (and YAML theme)."""
    from alpha_audit.load.tokens.project import token_audit_pairs
    from alpha_audit.load.tokens.themes import load_token_themes

    if not iconsets:
        raise UsageError("nothing to audit: the config has tokens: but names no iconset")
    token_themes = load_token_themes(tokens)
    loaded_themes = [load_theme(t) for t in _unique(themes)]
    per_set = [token_audit_pairs(token_themes, s) for s in _unique(iconsets)]
    if on_start is not None:
        on_start(sum(len(pairs[0][1].icons) for pairs in per_set))
    audits = []
    for pairs in per_set:
        # The modes differ in colours only: the icons render once.
        first = pairs[0][1]
        problems = _render(first, strict_svg=strict_svg, on_icon=on_icon).problems
        for theme, iconset in pairs:
            audits.append(
                audit(theme, iconset, alpha=alpha, threshold=threshold, problems=problems)
            )
        for theme in loaded_themes:  # YAML themes get the first mode's icon colours
            audits.append(audit(theme, first, alpha=alpha, threshold=threshold, problems=problems))
    gate = evaluate(audits, policy or Policy(), baseline=baseline)
    return CheckReport(audits=tuple(audits), gate=gate)


def _unique(paths: Sequence[str | Path]) -> list[Path]:
    """Paths in order, each file once."""
    seen: dict[Path, Path] = {}
    for p in paths:
        seen.setdefault(Path(p).resolve(), Path(p))
    return list(seen.values())
