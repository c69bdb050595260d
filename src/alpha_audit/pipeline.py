"""Files in, audit out: load themes and icon sets, read and rasterise paints, audit, gate."""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING

from alpha_audit.color import GamutPolicy, Pipeline
from alpha_audit.color.metrics import preload_colour
from alpha_audit.errors import SvgError, UsageError
from alpha_audit.findings import FindingKey
from alpha_audit.fixes import with_fixes
from alpha_audit.gate import evaluate
from alpha_audit.load.iconset import load_iconset
from alpha_audit.load.paint_masks import PaintSet, measure_paints
from alpha_audit.load.svg import IconProblem, RenderLimits
from alpha_audit.load.theme import load_theme
from alpha_audit.load.tokens.themes import TokenConfig
from alpha_audit.model import GamutAdjustment, IconSet, Theme
from alpha_audit.policy import Policy
from alpha_audit.results import CheckReport
from alpha_audit.rows import (
    AuditResult,
    audit,
    check_combinations,
    check_pipeline,
    resolve_pipeline,
)

if TYPE_CHECKING:
    from alpha_audit.load.sandbox import RenderPool

__all__ = ["check_files", "check_project", "render_paints", "render_pool"]


def render_paints(
    iconset: IconSet,
    *,
    strict_svg: bool,
    on_icon: Callable[[], None] | None,
    pool: RenderPool | None = None,
) -> PaintSet:
    """Every icon's paints, each measured at every size; empty icons become problems.

    ``pool``: render workers the caller started early (:func:`render_pool`).
    """
    preload_colour()  # the audit needs it next; the import runs while the workers render
    paints = measure_paints(
        [(i.name, i.file) for i in iconset.icons], iconset.sizes, progress=on_icon, pool=pool
    )
    empty = []
    for name, measured in paints.icons.items():
        inked = [
            size
            for size in iconset.sizes
            if any(c.sizes[size].pixels > 0 for c in measured.coverage)
        ]
        if len(inked) < len(iconset.sizes) and not measured.paints.unaudited:
            missing = next(s for s in iconset.sizes if s not in inked)
            empty.append(
                IconProblem(name, measured.file, f"renders nothing at {missing}px (empty icon)")
            )
    if empty:
        gone = {p.icon for p in empty}
        order = {i.name: n for n, i in enumerate(iconset.icons)}
        problems = sorted([*paints.problems, *empty], key=lambda p: order.get(p.icon, 0))
        paints = PaintSet({k: v for k, v in paints.icons.items() if k not in gone}, tuple(problems))
    if strict_svg and paints.problems:
        first = paints.problems[0]
        raise SvgError(first.message, path=first.file)
    return paints


@contextlib.contextmanager
def render_pool() -> Iterator[RenderPool]:
    """Render workers started now, so they are ready once the inputs are read.

    Each takes a few tenths of a second to start; a check starts them before
    loading anything (an input error just stops them) and renders with them.
    """
    from alpha_audit.load.sandbox import RenderPool

    limits = RenderLimits()
    with RenderPool(limits, workers=limits.workers) as pool:
        yield pool.prestart()


def _audit(
    theme: Theme,
    iconset: IconSet,
    paints: PaintSet,
    *,
    alpha: float | None,
    threshold: float | None,
    pipeline: Pipeline,
) -> AuditResult:
    return audit(theme, iconset, paints, alpha=alpha, threshold=threshold, pipeline=pipeline)


def _check_sizes(themes: Sequence[Theme], iconsets: Sequence[IconSet]) -> None:
    """Refuse a check over the bounds before any icon is rendered (each icon draws a paint)."""
    icons = sum(len(s.icons) for s in iconsets)
    canvases = sum(len(t.canvases) for t in themes)
    path = themes[0].path if len(themes) == 1 else None
    check_combinations(icons, canvases, 1, path)


def check_files(
    theme_path: str | Path,
    iconset_path: str | Path,
    *,
    alpha: float | None = None,
    threshold: float | None = None,
    strict_svg: bool = False,
    pipeline: str | None = None,
    on_start: Callable[[int], None] | None = None,
    on_icon: Callable[[], None] | None = None,
    gamut: GamutPolicy | None = None,
) -> AuditResult:
    """Load both files, read and rasterise every icon's paints at every size, and audit.

    Icons that cannot be rendered are left out and listed in
    ``result.problems``; with ``strict_svg`` the first one raises
    :class:`~alpha_audit.errors.SvgError`.  ``pipeline`` overrides the icon
    set's and the theme's (docs/model.md); an alpha the pipeline cannot draw
    is an :class:`~alpha_audit.errors.InputError` raised before any render.
    ``on_start(n)`` and ``on_icon()`` report progress; ``gamut`` is the
    project's policy for colours outside sRGB (else each file's ``gamut:``).
    """
    with render_pool() as pool:
        theme = load_theme(theme_path, gamut=gamut)
        iconset = load_iconset(iconset_path, gamut=gamut)
        chosen = resolve_pipeline(pipeline, iconset.pipeline, theme.pipeline)
        check_pipeline(iconset, chosen, alpha)
        if on_start is not None:
            on_start(len(iconset.icons))
        paints = render_paints(iconset, strict_svg=strict_svg, on_icon=on_icon, pool=pool)
    return _audit(theme, iconset, paints, alpha=alpha, threshold=threshold, pipeline=chosen)


def check_project(
    themes: Sequence[str | Path],
    iconsets: Sequence[str | Path],
    *,
    policy: Policy,
    alpha: float | None = None,
    threshold: float | None = None,
    baseline: Iterable[FindingKey] | None = None,
    strict_svg: bool = False,
    pipeline: str | None = None,
    on_start: Callable[[int], None] | None = None,
    on_icon: Callable[[], None] | None = None,
    tokens: TokenConfig | None = None,
    gamut: GamutPolicy | None = None,
    pool: RenderPool | None = None,
) -> CheckReport:
    """Audit every icon set on every theme and apply the gate ``policy``.

    ``policy`` is required: the gate applies what the caller chose (the
    CLI passes the config's policy, ``Policy()`` is the documented default),
    never a default picked here.

    Every file is loaded (and every input error raised) before any icon is
    rendered; each icon set is rendered once whatever the number of themes.
    Audits come in icon-set order, then theme order.  With ``tokens`` (the
    config's ``tokens:`` table) each icon set is also audited on every token
    mode, its icons' colours named by token path.  ``pipeline`` (from
    ``--pipeline`` or the config) overrides each icon set's, then each
    theme's; ``linear`` when none says.  ``gamut`` (``--gamut``, else the
    config's) decides colours outside sRGB in every file, tokens included;
    the colours it moved are in ``report.gamut``.  ``pool``: render workers
    the caller started early (:func:`render_pool`), else started here.
    """
    with contextlib.ExitStack() as stack:
        if pool is None:
            pool = stack.enter_context(render_pool())
        if tokens is not None and gamut is not None:
            tokens = replace(tokens, gamut=gamut)
        if tokens is not None:
            return _check_with_tokens(
                themes,
                iconsets,
                tokens,
                pool,
                policy=policy,
                alpha=alpha,
                threshold=threshold,
                baseline=baseline,
                strict_svg=strict_svg,
                pipeline=pipeline,
                on_start=on_start,
                on_icon=on_icon,
                gamut=gamut,
            )
        if not themes or not iconsets:
            raise UsageError(
                "nothing to audit: give THEME ICONSET, or name themes and iconsets in "
                "alpha-audit.yaml or [tool.alpha-audit] in pyproject.toml"
            )
        loaded_themes = [load_theme(t, gamut=gamut) for t in _unique(themes)]
        loaded_sets = [load_iconset(s, gamut=gamut) for s in _unique(iconsets)]
        policy.check_exemptions(
            (c.name for t in loaded_themes for c in t.canvases),
            (i.name for s in loaded_sets for i in s.icons),
        )
        _check_sizes(loaded_themes, loaded_sets)  # before any icon is rendered
        chosen = {
            (t.name, s.name): resolve_pipeline(pipeline, s.pipeline, t.pipeline)
            for s in loaded_sets
            for t in loaded_themes
        }
        for s in loaded_sets:
            for t in loaded_themes:
                check_pipeline(s, chosen[(t.name, s.name)], alpha)
        if on_start is not None:
            on_start(sum(len(s.icons) for s in loaded_sets))
        audits = []
        for iconset in loaded_sets:
            paints = render_paints(iconset, strict_svg=strict_svg, on_icon=on_icon, pool=pool)
            for theme in loaded_themes:
                kind = chosen[(theme.name, iconset.name)]
                audits.append(
                    _audit(theme, iconset, paints, alpha=alpha, threshold=threshold, pipeline=kind)
                )
        gate = evaluate(audits, policy, baseline=baseline)
        moved = _gamut_notes([*loaded_themes, *loaded_sets])
        # Every renderer shows the fix for each failing colour: computed once, here.
        return with_fixes(CheckReport(audits=tuple(audits), gate=gate, gamut=moved))


def _gamut_notes(
    inputs: Sequence[Theme | IconSet], *extra: Sequence[GamutAdjustment]
) -> tuple[GamutAdjustment, ...]:
    """Every colour the gamut policy moved, each once, in input order."""
    notes = [a for item in inputs for a in item.adjusted]
    notes += [a for group in extra for a in group]
    return tuple(dict.fromkeys(notes))


def _check_with_tokens(
    themes: Sequence[str | Path],
    iconsets: Sequence[str | Path],
    tokens: TokenConfig,
    pool: RenderPool,
    *,
    policy: Policy,
    alpha: float | None,
    threshold: float | None,
    baseline: Iterable[FindingKey] | None,
    strict_svg: bool,
    pipeline: str | None,
    on_start: Callable[[int], None] | None,
    on_icon: Callable[[], None] | None,
    gamut: GamutPolicy | None,
) -> CheckReport:
    """check_project with token themes: every icon set on every token mode (and YAML theme)."""
    from alpha_audit.load.tokens.project import token_audit_pairs
    from alpha_audit.load.tokens.themes import load_token_themes

    if not iconsets:
        raise UsageError("nothing to audit: the config has tokens: but names no iconset")
    token_themes = load_token_themes(tokens)
    loaded_themes = [load_theme(t, gamut=gamut) for t in _unique(themes)]
    per_set = [token_audit_pairs(token_themes, s, gamut=gamut) for s in _unique(iconsets)]
    # YAML themes get the first mode's icon colours.
    per_set = [pairs + [(t, pairs[0][1]) for t in loaded_themes] for pairs in per_set]
    for pairs in per_set:  # before any icon is rendered
        _check_sizes([t for t, _ in pairs], [pairs[0][1]])
        for theme, iconset in pairs:
            check_pipeline(
                iconset, resolve_pipeline(pipeline, iconset.pipeline, theme.pipeline), alpha
            )
    if on_start is not None:
        on_start(sum(len(pairs[0][1].icons) for pairs in per_set))
    audits = []
    for pairs in per_set:
        # The modes differ in colours only: the icons render once.
        paints = render_paints(pairs[0][1], strict_svg=strict_svg, on_icon=on_icon, pool=pool)
        for theme, iconset in pairs:
            kind = resolve_pipeline(pipeline, iconset.pipeline, theme.pipeline)
            audits.append(
                _audit(theme, iconset, paints, alpha=alpha, threshold=threshold, pipeline=kind)
            )
    gate = evaluate(audits, policy, baseline=baseline)
    sets = [pairs[0][1] for pairs in per_set]
    moved = _gamut_notes([*loaded_themes, *sets], token_themes.adjusted)
    return with_fixes(CheckReport(audits=tuple(audits), gate=gate, gamut=moved))


def _unique(paths: Sequence[str | Path]) -> list[Path]:
    """Paths in order, each file once."""
    seen: dict[Path, Path] = {}
    for p in paths:
        seen.setdefault(Path(p).resolve(), Path(p))
    return list(seen.values())
