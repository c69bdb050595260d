"""Files in, report out: load, read and rasterise paints, audit the rows, gate, fix.

One way through for every command: a resolved
:class:`~alpha_audit.load.config.ProjectConfig` (:func:`~alpha_audit.load.config.resolve_config`)
-> themes and icon sets (YAML files, or one theme per design-token mode) -> each
icon set's paints, rendered once -> one :func:`~alpha_audit.rows.audit` per
theme x icon set, whose findings are taken as it is made -> the gate, against a
baseline file or the base revision's own findings (:func:`base_baseline`) -> the
fixes.  Nothing is printed.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING

from alpha_audit.baseline import read_baseline
from alpha_audit.color import Pipeline
from alpha_audit.color.metrics import preload_colour
from alpha_audit.errors import AlphaAuditError, SvgError, UsageError
from alpha_audit.findings import Finding
from alpha_audit.fixes import with_fixes
from alpha_audit.gate import Baseline, collect, judge
from alpha_audit.load.config import Overrides, ProjectConfig
from alpha_audit.load.iconset import load_iconset
from alpha_audit.load.paint_masks import measure_paints
from alpha_audit.load.svg import RenderLimits
from alpha_audit.load.theme import load_theme
from alpha_audit.model import GamutAdjustment, IconProblem, IconSet, Theme
from alpha_audit.paints import PaintSet
from alpha_audit.results import CheckReport, Progress
from alpha_audit.rows import (
    AuditResult,
    audit,
    check_combinations,
    check_pipeline,
    resolve_pipeline,
)
from alpha_audit.rules import Level

if TYPE_CHECKING:
    from alpha_audit.load.sandbox import RenderPool

__all__ = [
    "BaseAudit",
    "Work",
    "audit_pair",
    "audits",
    "base_baseline",
    "check_project",
    "plan",
    "render_paints",
    "render_pool",
]


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
    # (mode, the mode it equals): token modes audited once as another (TokenThemes.aliases).
    aliases: tuple[tuple[str, str], ...] = ()


def plan(
    project: ProjectConfig,
) -> tuple[list[Work], tuple[GamutAdjustment, ...], tuple[str, ...]]:
    """Every input loaded and checked before any icon is rendered.

    Returns the work per icon set (icon sets in order, then themes in order:
    token modes first, then YAML themes), the colours the gamut policy moved and
    what the token loader noted (one line each: the modes it found, tokens skipped).
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
        # Each icon draws a paint: refused before any icon is rendered.
        check_combinations(icons, canvases, 1, pairs[0][1].path, project.max_combinations)
        chosen = []
        for theme, iconset in pairs:
            kind = resolve_pipeline(project.pipeline, iconset.pipeline, theme.pipeline)
            check_pipeline(iconset, kind, project.alpha)
            chosen.append(kind)
        aliases = tuple(token_themes.aliases.items()) if token_themes is not None else ()
        work.append(Work(tuple(pairs), tuple(chosen), aliases))
    project.policy.check_exemptions(
        (c.name for w in work for t, _ in w.pairs for c in t.canvases),
        (i.name for w in work for i in w.pairs[0][1].icons),
    )
    moved = [a for w in work for t, s in w.pairs for a in (*t.adjusted, *s.adjusted)]
    notes: tuple[str, ...] = ()
    if token_themes is not None:
        moved += token_themes.adjusted
        notes = token_themes.notes
    return work, tuple(dict.fromkeys(moved)), notes


def _with_project_alpha(project: ProjectConfig, iconset: IconSet) -> IconSet:
    """The set with the config's (or --alpha's) coefficient, located where the config writes it."""
    if project.alpha is None:
        return iconset
    icons = tuple(
        replace(i, alpha_span=project.alpha_span, alpha_line=None)
        for i in iconset.with_alpha(project.alpha).icons
    )
    return replace(iconset, icons=icons)


def audits(
    project: ProjectConfig,
    work: Sequence[Work],
    *,
    pool: RenderPool | None = None,
    progress: Progress | None = None,
) -> Iterator[AuditResult]:
    """Render each icon set once and audit it on each of its themes, one audit at a time.

    A generator, so a caller that keeps only what it needs of each audit (its
    findings) holds one audit's arrays at a time.
    """
    if progress is not None:
        progress[0](sum(len(w.pairs[0][1].icons) for w in work))
    for w in work:
        # The modes differ in colours only: the icons render once.
        paints = render_paints(
            w.pairs[0][1],
            strict_svg=project.strict_svg,
            on_icon=None if progress is None else progress[1],
            pool=pool,
        )
        for (theme, iconset), kind in zip(w.pairs, w.pipelines, strict=True):
            yield audit_pair(project, theme, iconset, kind, paints)
        del paints


def audit_pair(
    project: ProjectConfig,
    theme: Theme,
    iconset: IconSet,
    pipeline: Pipeline,
    paints: PaintSet | None,
) -> AuditResult:
    """One theme x icon set as ``check`` audits it: the project's alpha (located where the
    config writes it), threshold, pipeline and bound.

    ``paints`` None: every icon is its manifest colour as one ``currentColor`` paint at
    opacity 1, the rows ``export`` reads (the same rows ``check`` has for such a paint).
    """
    return audit(
        theme,
        _with_project_alpha(project, iconset),
        paints,
        threshold=project.threshold,
        pipeline=pipeline,
        max_combinations=project.max_combinations,
    )


def check_project(
    project: ProjectConfig,
    *,
    pool: RenderPool | None = None,
    progress: Progress | None = None,
    use_baseline: bool = True,
    baseline: Baseline | None = None,
    record: bool = False,
) -> CheckReport:
    """Audit every icon set on every theme (or token mode) of ``project`` and gate it.

    Every file is loaded, and every input error raised, before any icon is
    rendered; each icon set is rendered once whatever the number of themes.
    The gate applies ``project.policy`` (the CLI passes the config with its
    flags applied, :func:`~alpha_audit.load.config.resolve_config`) against
    ``baseline`` if given (the base revision's findings, :func:`base_baseline`),
    else the baseline file the project names unless ``use_baseline`` is false.
    With ``record`` (a baseline is being written from this run) the gate is
    judged against this run's own findings: they are all baselined, none stale.
    ``pool``: render workers started early.

    >>> from alpha_audit.bundled import bundled_iconset, bundled_theme
    >>> paper, vibrant = bundled_theme("paper16"), bundled_iconset("vibrant")
    >>> check_project(ProjectConfig(themes=(paper,), iconsets=(vibrant,))).gate.passed
    True
    """
    work, moved, notes = plan(project)
    known = baseline
    if known is None and use_baseline and not record and project.baseline is not None:
        known = read_baseline(project.baseline)
    results: list[AuditResult] = []
    found: list[Finding] = []
    with contextlib.ExitStack() as stack:
        if pool is None:
            pool = stack.enter_context(render_pool())
        for result in audits(project, work, pool=pool, progress=progress):
            found += collect([result], project.policy, seen=found)
            results.append(result)
    if record:
        name = str(project.baseline) if project.baseline is not None else "this run"
        keys = frozenset(f.key for f in found if f.level is Level.FAIL and f.exemption is None)
        known = Baseline(keys=keys, kind="file", name=name)
    gate = judge(results, project.policy, found, known)
    return with_fixes(CheckReport(tuple(results), gate, gamut=moved, notes=notes))


@dataclass(frozen=True)
class BaseAudit:
    """The base revision's findings as a baseline, what to say about it, and whether it
    was audited at all (when not, ``baseline`` is empty and every finding is new)."""

    baseline: Baseline
    notes: tuple[str, ...]
    audited: bool


def base_baseline(
    overrides: Overrides,
    start: Path,
    ref: str,
    *,
    pool: RenderPool | None = None,
) -> BaseAudit:
    """The findings of the project as it is at git revision ``ref``, as a baseline.

    The revision's tree is exported into a temporary folder (never into the
    checkout, :mod:`alpha_audit.load.git`), the config is resolved there from
    the same place and with the same ``overrides`` (paths given inside the
    repository point at the revision's files), and every failing-rule
    finding's key is kept.  The notes say which entries the export left out
    (links to absolute paths) and, when the revision cannot be exported or
    audited (no config, a broken file, a tree over the export's bounds), why:
    then the baseline is empty and every finding is new.  A ``ref`` that
    names no commit, or no git, is a :class:`~alpha_audit.errors.UsageError`.
    """
    import tempfile

    from alpha_audit.load.git import export_revision, git_toplevel, resolve_commit

    notes: list[str] = []
    with tempfile.TemporaryDirectory(prefix="alpha-audit-base-") as tmp:
        home = Path(tmp) / "home"
        home.mkdir()
        top = git_toplevel(start, home)
        # The repository's own folder name: a set or theme named after its folder
        # (no name: key) keeps its name, and with it its findings' keys.
        tree = Path(tmp) / "revision" / top.name
        tree.mkdir(parents=True)
        commit = resolve_commit(top, ref, home)
        try:
            skipped = export_revision(top, commit, tree, home)
            if skipped:
                notes.append(
                    f"the base revision {ref}: {len(skipped)} entr"
                    f"{'y' if len(skipped) == 1 else 'ies'} left out as unsafe to write "
                    f"(first: {skipped[0]})"
                )
            (tree / ".git").mkdir(exist_ok=True)  # the project root, as in the checkout
            found = _audit_revision(overrides, start, top, tree, pool)
        except AlphaAuditError as exc:
            # Files of the revision are named as in the repository, not in our folder.
            path = exc.path
            shown = (
                path.relative_to(tree).as_posix() if path and path.is_relative_to(tree) else None
            )
            where = exc.where(shown)
            reason = f"{where}: {exc.message}" if where else exc.message
            why = f"the base revision {ref} could not be audited ({reason}); every finding is new"
            return BaseAudit(Baseline(kind="base", name=ref), (*notes, why), audited=False)
    keys = frozenset(f.key for f in found if f.level is Level.FAIL)
    return BaseAudit(Baseline(keys=keys, kind="base", name=ref), tuple(notes), audited=True)


def _audit_revision(
    overrides: Overrides, start: Path, top: Path, tree: Path, pool: RenderPool | None
) -> list[Finding]:
    """Every finding of the revision exported to ``tree`` (the repository at ``top``),
    its config resolved from where ``start`` is in the checkout."""
    from alpha_audit.load.config import resolve_config

    def moved(path: str | Path) -> str | Path:
        """A path inside the repository, in the revision's tree; anything else as given."""
        full = (start / path).resolve()
        if not (start / path).exists() or not full.is_relative_to(top):
            return path  # a bundled name, or outside the repository
        return tree / full.relative_to(top)

    here = tree / start.resolve().relative_to(top)
    mapped = replace(
        overrides,
        config=None if overrides.config is None else Path(moved(overrides.config)),
        themes=tuple(moved(t) for t in overrides.themes),
        iconsets=tuple(moved(s) for s in overrides.iconsets),
        baseline=None,
    )
    project = replace(resolve_config(mapped, here if here.is_dir() else tree), baseline=None)
    work, _, _ = plan(project)
    with contextlib.ExitStack() as stack:
        if pool is None:
            pool = stack.enter_context(render_pool())
        found: list[Finding] = []
        for result in audits(project, work, pool=pool):
            found += collect([result], project.policy, seen=found)
    return found


def _unique(paths: Sequence[str | Path]) -> list[Path]:
    """Paths in order, each file once."""
    seen: dict[Path, Path] = {}
    for p in paths:
        seen.setdefault(Path(p).resolve(), Path(p))
    return list(seen.values())
