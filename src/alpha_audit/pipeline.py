"""Files in, report out: load, read and rasterise paints, audit the rows, gate, fix.

One way through for every command: a resolved
:class:`~alpha_audit.load.config.ProjectConfig` (:func:`~alpha_audit.load.config.resolve_config`)
-> themes and icon sets (YAML files, or one theme per design-token mode) -> each
icon set's paints, rendered once -> one :func:`~alpha_audit.rows.audit` per
theme x icon set -> the gate -> the fixes.  Nothing is printed.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING

from alpha_audit.color import Pipeline
from alpha_audit.color.metrics import preload_colour
from alpha_audit.errors import SvgError, UsageError
from alpha_audit.fixes import with_fixes
from alpha_audit.gate import evaluate
from alpha_audit.load.baseline import read_baseline
from alpha_audit.load.config import ProjectConfig
from alpha_audit.load.iconset import load_iconset
from alpha_audit.load.paint_masks import PaintSet, measure_paints
from alpha_audit.load.svg import IconProblem, RenderLimits
from alpha_audit.load.theme import load_theme
from alpha_audit.model import GamutAdjustment, IconSet, Theme
from alpha_audit.results import CheckReport, Progress
from alpha_audit.rows import (
    AuditResult,
    audit,
    check_combinations,
    check_pipeline,
    resolve_pipeline,
)

if TYPE_CHECKING:
    from alpha_audit.load.sandbox import RenderPool

__all__ = ["Work", "audits", "check_project", "plan", "render_paints", "render_pool"]


def render_paints(
    iconset: IconSet,
    *,
    strict_svg: bool = False,
    on_icon: Callable[[], None] | None = None,
    pool: RenderPool | None = None,
) -> PaintSet:
    """Every icon's paints, each measured at every size; empty icons become problems.

    ``pool``: render workers the caller started early (:func:`render_pool`).
    With ``strict_svg`` the first icon that cannot be rendered raises.
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

    Each takes a few tenths of a second to start; a command starts them before
    loading anything (an input error just stops them) and renders with them.
    """
    from alpha_audit.load.sandbox import RenderPool

    limits = RenderLimits()
    with RenderPool(limits, workers=limits.workers) as pool:
        yield pool.prestart()


@dataclass(frozen=True)
class Work:
    """One icon set and the themes it is audited on (each with that theme's icon colours).

    A YAML theme pairs with the set as written; a design-token mode with the
    set coloured by that mode's tokens.  ``pairs[0][1]`` is the set rendered.
    """

    pairs: tuple[tuple[Theme, IconSet], ...]
    pipelines: tuple[Pipeline, ...]


def plan(project: ProjectConfig) -> tuple[list[Work], tuple[GamutAdjustment, ...]]:
    """Every input loaded and checked before any icon is rendered.

    Returns the work per icon set (icon sets in order, then themes in order:
    token modes first, then YAML themes) and the colours the gamut policy moved.
    """
    from alpha_audit.load.tokens.project import token_audit_pairs
    from alpha_audit.load.tokens.themes import load_token_themes

    if not project.iconsets or not (project.themes or project.tokens):
        raise UsageError(
            "nothing to audit: give THEME ICONSET, or name themes and iconsets in "
            "alpha-audit.yaml or [tool.alpha-audit] in pyproject.toml"
        )
    gamut = project.gamut
    tokens = project.tokens
    if tokens is not None and gamut is not None:
        tokens = replace(tokens, gamut=gamut)
    token_themes = load_token_themes(tokens) if tokens is not None else None
    themes = [load_theme(t, gamut=gamut) for t in _unique(project.themes)]
    work = []
    for path in _unique(project.iconsets):
        if token_themes is not None:
            pairs = token_audit_pairs(token_themes, path, gamut=gamut)
            pairs += [(t, pairs[0][1]) for t in themes]  # YAML themes: the first mode's colours
        else:
            iconset = load_iconset(path, gamut=gamut)
            pairs = [(t, iconset) for t in themes]
        icons = len(pairs[0][1].icons)
        canvases = sum(len(t.canvases) for t, _ in pairs)
        check_combinations(icons, canvases, 1, pairs[0][1].path)  # each icon draws a paint
        chosen = []
        for theme, iconset in pairs:
            kind = resolve_pipeline(project.pipeline, iconset.pipeline, theme.pipeline)
            check_pipeline(iconset, kind, project.alpha)
            chosen.append(kind)
        work.append(Work(tuple(pairs), tuple(chosen)))
    project.policy.check_exemptions(
        (c.name for w in work for t, _ in w.pairs for c in t.canvases),
        (i.name for w in work for i in w.pairs[0][1].icons),
    )
    moved = [a for w in work for t, s in w.pairs for a in (*t.adjusted, *s.adjusted)]
    if token_themes is not None:
        moved += token_themes.adjusted
    return work, tuple(dict.fromkeys(moved))


def audits(
    project: ProjectConfig,
    work: Sequence[Work],
    *,
    pool: RenderPool | None = None,
    progress: Progress | None = None,
) -> list[AuditResult]:
    """Render each icon set once and audit it on each of its themes."""
    if progress is not None:
        progress[0](sum(len(w.pairs[0][1].icons) for w in work))
    out = []
    for w in work:
        # The modes differ in colours only: the icons render once.
        paints = render_paints(
            w.pairs[0][1],
            strict_svg=project.strict_svg,
            on_icon=None if progress is None else progress[1],
            pool=pool,
        )
        for (theme, iconset), kind in zip(w.pairs, w.pipelines, strict=True):
            out.append(
                audit(
                    theme,
                    iconset,
                    paints,
                    alpha=project.alpha,
                    threshold=project.threshold,
                    pipeline=kind,
                )
            )
    return out


def check_project(
    project: ProjectConfig,
    *,
    pool: RenderPool | None = None,
    progress: Progress | None = None,
    use_baseline: bool = True,
) -> CheckReport:
    """Audit every icon set on every theme (or token mode) of ``project`` and gate it.

    Every file is loaded, and every input error raised, before any icon is
    rendered; each icon set is rendered once whatever the number of themes.
    The gate applies ``project.policy`` (the CLI passes the config with its
    flags applied, :func:`~alpha_audit.load.config.resolve_config`); the
    baseline file it names is read unless ``use_baseline`` is false (when a
    new one is being written).  ``pool``: render workers started early.

    >>> from alpha_audit.bundled import bundled_iconset, bundled_theme
    >>> paper, vibrant = bundled_theme("paper16"), bundled_iconset("vibrant")
    >>> check_project(ProjectConfig(themes=(paper,), iconsets=(vibrant,))).gate.passed
    True
    """
    work, moved = plan(project)
    known = None
    if use_baseline and project.baseline is not None:
        known = read_baseline(project.baseline)
    with contextlib.ExitStack() as stack:
        if pool is None:
            pool = stack.enter_context(render_pool())
        results = audits(project, work, pool=pool, progress=progress)
    gate = evaluate(results, project.policy, baseline=known)
    return with_fixes(CheckReport(audits=tuple(results), gate=gate, gamut=moved))


def _unique(paths: Sequence[str | Path]) -> list[Path]:
    """Paths in order, each file once."""
    seen: dict[Path, Path] = {}
    for p in paths:
        seen.setdefault(Path(p).resolve(), Path(p))
    return list(seen.values())
