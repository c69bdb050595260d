"""``alpha-audit suggest``: the largest safe coefficient, and ``--apply`` to write it."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from alpha_audit.cli.console import emit, progress_bar, stderr_note, stdout_options
from alpha_audit.cli.options import (
    ConfigOption,
    ForceOption,
    GamutOption,
    IconsetArgument,
    NoCacheOption,
    PolicyFlags,
    ThemeArgument,
    flag,
    input_overrides,
    one_of,
    ranged,
    with_policy_flags,
)
from alpha_audit.cli.status import ExitStatus
from alpha_audit.ranges import ALPHA_MAX, PRECISION
from alpha_audit.render import SuggestFormat
from alpha_audit.suggest.scope import SCOPES

if TYPE_CHECKING:
    from alpha_audit.load.config import ProjectConfig

__all__ = ["suggest_command"]


def _scope(value: str | None) -> str | None:
    """--apply's scope, checked here (the enum lives with the editor, imported lazily)."""
    from alpha_audit.suggest.apply import ApplyScope

    if value is None:
        return None
    scopes = [s.value for s in ApplyScope]
    if value.strip().lower() not in scopes:
        one_of("--apply", value, scopes, "a scope")
    return value.strip().lower()


def _scopes(values: list[str] | None) -> list[str] | None:
    for value in values or []:
        one_of("--only", value, SCOPES, "a scope")
    return values


# suggest's own options (the gate's shared ones are in cli/options.py).
_AlphaMax = Annotated[
    float, ranged("--alpha-max", allowed=ALPHA_MAX, help="Largest coefficient considered.")
]
_Precision = Annotated[
    int, ranged("--precision", allowed=PRECISION, help="Decimals; the answer is rounded down.")
]
_Format = Annotated[
    SuggestFormat,
    typer.Option("--format", "-f", help="table, json or markdown.", case_sensitive=False),
]
_Output = Annotated[
    Path | None, typer.Option("--output", "-o", help="Write the report here instead of stdout.")
]
_Apply = Annotated[
    str | None,
    typer.Option(
        "--apply",
        metavar="set|colour|icon",
        help="Write the answer into the manifest: set (the set-wide alpha), colour (one "
        "alpha per group of colours) or icon (per-icon overrides); only alpha values change, "
        "and only when the gate passes with them (else nothing is written, exit 1).",
        show_default=False,
        callback=_scope,
    ),
]
_ReplaceExplicit = Annotated[
    bool,
    flag(
        "--replace-explicit", help="With --apply, also replace alphas the manifest sets per icon."
    ),
]
_Only = Annotated[
    list[str] | None,
    typer.Option(
        "--only",
        metavar="SCOPE",
        help=f"Answer only these questions (repeatable): {', '.join(SCOPES)}.",
        show_default="all",
        callback=_scopes,
    ),
]


def _the_manifest(project: ProjectConfig, iconset: Path | None, apply: str | None) -> Path:
    """The one manifest suggest answers for; refused: tokens, several themes or icon sets,
    and ``--apply`` on the bundled example (it rewrites the manifest in place)."""
    from alpha_audit.errors import UsageError

    if project.tokens is not None:
        raise UsageError(
            "suggest reads YAML themes, not the config's tokens: table (a coefficient in "
            "$extensions is never rewritten); give THEME ICONSET, or run check, which "
            "audits every token mode (docs/tokens.md)"
        )
    if len(project.themes) != 1 or len(project.iconsets) != 1:
        raise UsageError(
            "suggest needs one theme and one icon set: give THEME ICONSET, or a project "
            f"config naming exactly one of each (found {len(project.themes)} theme(s), "
            f"{len(project.iconsets)} icon set(s))"
        )
    manifest = project.iconsets[0]
    if apply is not None and iconset is not None and manifest != Path(iconset):
        raise UsageError(
            f"--apply rewrites the manifest in place and {iconset} is the bundled example; "
            f"copy {manifest.parent} into your project and give its {manifest.name}"
        )
    return manifest


@with_policy_flags
def suggest_command(
    ctx: typer.Context,
    policy_flags: PolicyFlags,  # the policy flags, handed over by with_policy_flags
    theme: ThemeArgument = None,
    iconset: IconsetArgument = None,
    config: ConfigOption = None,
    alpha_max: _AlphaMax = 2.0,
    precision: _Precision = 3,
    fmt: _Format = SuggestFormat.TABLE,
    output: _Output = None,
    force: ForceOption = False,
    gamut: GamutOption = None,
    apply: _Apply = None,
    replace_explicit: _ReplaceExplicit = False,
    only: _Only = None,
    no_cache: NoCacheOption = False,
) -> ExitStatus:
    """The largest alpha every coefficient in [1, alpha] keeps the gate policy for.

    Computed exactly from where contrast, 8-bit codes and separation change, not
    by a sweep: set-wide (one coefficient for every icon), per palette colour,
    per group of roles the gate finds confused (all moving together) and per
    icon (the others keep their configured alpha), with the canvas, rule and
    icons (for a confusion, the pair of roles) that stop each and the first
    unsafe alpha.  Losses are judged
    as check judges them (--visibility-floor, --loss-tolerance).  A big set's
    table shows the smallest answers and each colour's worst icon; --format json
    has every answer.  Nothing is written unless --apply is given.

    Example:
    [bold]alpha-audit suggest themes/paper16.yaml examples/vibrant/iconset.yaml --apply set[/]
    """
    from alpha_audit.load.config import resolve_config
    from alpha_audit.output import check_targets
    from alpha_audit.pipeline import audits, plan
    from alpha_audit.render.common import RenderOptions, check_suffix
    from alpha_audit.suggest.apply import apply_suggestion, describe_plan
    from alpha_audit.suggest.engine import suggest

    if output is not None:
        check_suffix(fmt.value, output)
        check_targets([output], overwrite=force)  # before the work, not after
    project = resolve_config(
        input_overrides(theme, iconset, config=config, **policy_flags.overrides(), gamut=gamut),
        Path.cwd(),
    )
    manifest = _the_manifest(project, iconset, apply)
    work, _, _ = plan(project)
    # The gate judges every paint of every SVG as drawn: suggest answers the same rows.
    (rows,) = audits(project, work, pool=ctx.obj)
    with progress_bar("Answering") as progress:
        result = suggest(
            rows,
            project.policy,
            alpha_max=alpha_max,
            precision=precision,
            scopes=only or SCOPES,
            progress=progress,
        )
    options = stdout_options() if output is None else RenderOptions()
    emit(fmt.renderer()(result, options), output, force)
    if apply is not None:
        applied, changed = apply_suggestion(
            manifest, result, apply, replace_explicit=replace_explicit, gamut=project.gamut
        )
        stderr_note(describe_plan(applied, manifest, changed, precision))
        if not applied.passes:
            return ExitStatus.GATE_FAILED
        stderr_note("check: the gate passes with what was written")
    return ExitStatus.OK
