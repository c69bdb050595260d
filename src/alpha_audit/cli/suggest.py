"""``alpha-audit suggest``: the largest safe coefficient, and ``--apply`` to write it."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from alpha_audit.cli.console import emit, stdout_options
from alpha_audit.cli.options import (
    ConfigOption,
    ForceOption,
    GamutOption,
    IconsetArgument,
    MaxDriftOption,
    MaxLossOption,
    MinDeltaEOption,
    MinSizeContrastOption,
    NoCacheOption,
    ThemeArgument,
    ThresholdOption,
    in_range,
    read_gamut_option,
    rules_flag,
)
from alpha_audit.cli.status import ExitStatus
from alpha_audit.ranges import ALPHA_MAX, PRECISION
from alpha_audit.render import SuggestFormat

__all__ = ["suggest_command"]


def _scope(value: str | None) -> str | None:
    """--apply's scope, checked here (the enum lives with the editor, imported lazily)."""
    from alpha_audit.errors import UsageError
    from alpha_audit.suggest.apply import ApplyScope

    if value is None:
        return None
    scopes = [s.value for s in ApplyScope]
    if value.strip().lower() not in scopes:
        raise UsageError(f"--apply {value!r} is not a scope; use one of: {', '.join(scopes)}")
    return value.strip().lower()


def suggest_command(
    ctx: typer.Context,
    theme: ThemeArgument = None,
    iconset: IconsetArgument = None,
    config: ConfigOption = None,
    alpha_max: Annotated[
        float,
        typer.Option(
            "--alpha-max",
            help="Largest coefficient considered.",
            callback=in_range("--alpha-max", ALPHA_MAX),
        ),
    ] = 2.0,
    precision: Annotated[
        int,
        typer.Option(
            "--precision",
            help="Decimals; the answer is rounded down.",
            callback=in_range("--precision", PRECISION),
        ),
    ] = 3,
    threshold: ThresholdOption = None,
    fail_on: Annotated[
        list[str] | None,
        typer.Option(
            "--fail-on",
            metavar="RULE",
            help="Rule that must hold (repeatable; replaces the policy): any rule of check "
            "(docs/ci.md). "
            "[default: the config's, else loss, newly-failing, new-collision, confusion]",
            show_default=False,
            # suggest composites colours, it never renders an SVG.
            callback=rules_flag(
                "--fail-on",
                refused=("unrenderable",),
                why="suggest never renders SVGs; use it with check",
            ),
        ),
    ] = None,
    max_loss: MaxLossOption = None,
    min_delta_e: MinDeltaEOption = None,
    max_drift: MaxDriftOption = None,
    min_size_contrast: MinSizeContrastOption = None,
    fmt: Annotated[
        SuggestFormat,
        typer.Option("--format", "-f", help="table, json or markdown.", case_sensitive=False),
    ] = SuggestFormat.TABLE,
    output: Annotated[
        Path | None, typer.Option("--output", "-o", help="Write the report here instead of stdout.")
    ] = None,
    force: ForceOption = False,
    gamut: GamutOption = None,
    apply: Annotated[
        str | None,
        typer.Option(
            "--apply",
            metavar="set|colour|icon",
            help="Write the answer into the manifest: set (the set-wide alpha), colour or icon "
            "(per-icon overrides); only alpha values change.",
            show_default=False,
            callback=_scope,
        ),
    ] = None,
    replace_explicit: Annotated[
        bool,
        typer.Option(
            "--replace-explicit",
            help="With --apply, also replace alphas the manifest sets per icon.",
        ),
    ] = False,
    no_cache: NoCacheOption = False,
) -> ExitStatus:
    """The largest alpha every coefficient in [1, alpha] keeps the gate policy for.

    Computed exactly from where contrast, 8-bit codes and separation change, not
    by a sweep: set-wide (one coefficient for every icon), per palette colour
    and per icon (the others keep their configured alpha), with the canvas,
    rule and icons that stop each and the first unsafe alpha.  Nothing is
    written unless --apply is given.

    Example:
    [bold]alpha-audit suggest themes/paper16.yaml examples/vibrant/iconset.yaml --apply set[/]
    """
    from alpha_audit.bundled import iconset_source, theme_source
    from alpha_audit.errors import UsageError
    from alpha_audit.load.config import project_config
    from alpha_audit.load.iconset import load_iconset
    from alpha_audit.load.theme import load_theme
    from alpha_audit.output import check_targets
    from alpha_audit.paint_audit import resolve_pipeline
    from alpha_audit.pipeline import render_paints
    from alpha_audit.render.common import RenderOptions, check_suffix
    from alpha_audit.suggest import suggest
    from alpha_audit.suggest.apply import apply_suggestion, describe_plan

    if output is not None:
        check_suffix(fmt.value, output)
        check_targets([output], overwrite=force)  # before the work, not after
    gamut_policy = read_gamut_option(gamut)
    if (theme is None) != (iconset is None):
        raise UsageError("give both THEME and ICONSET, or neither (to use the project config)")
    project = project_config(config, Path.cwd())
    if gamut_policy is None:
        gamut_policy = project.gamut
    if theme is None or iconset is None:
        if project.tokens is not None and not project.themes:
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
        theme, iconset = project.themes[0], project.iconsets[0]
    theme, source = theme_source(theme), iconset_source(iconset)
    if apply is not None and source != Path(iconset):
        raise UsageError(
            f"--apply rewrites the manifest in place and {iconset} is the bundled example; "
            f"copy {source.parent} into your project and give its {source.name}"
        )
    iconset = source
    policy = project.policy.with_overrides(
        rules=fail_on,
        max_loss=max_loss,
        min_delta_e=min_delta_e,
        max_drift=max_drift,
        min_size_contrast=min_size_contrast,
    )

    loaded_theme = load_theme(theme, gamut=gamut_policy)
    loaded_set = load_iconset(iconset, gamut=gamut_policy)
    policy.check_exemptions(
        (c.name for c in loaded_theme.canvases), (i.name for i in loaded_set.icons)
    )
    # The gate judges every paint of every SVG as drawn: suggest answers the same rows.
    paints = render_paints(loaded_set, strict_svg=False, on_icon=None, pool=ctx.obj)
    result = suggest(
        loaded_theme,
        loaded_set,
        policy,
        paints=paints,
        pipeline=resolve_pipeline(None, loaded_set.pipeline, loaded_theme.pipeline),
        alpha_max=alpha_max,
        precision=precision,
        threshold=threshold if threshold is not None else project.threshold,
    )
    options = stdout_options() if output is None else RenderOptions()
    emit(fmt.renderer()(result, options), output, force)
    if apply is not None:
        plan, changed = apply_suggestion(iconset, result, apply, replace_explicit=replace_explicit)
        typer.echo(describe_plan(plan, iconset, changed, precision), err=True)
    return ExitStatus.OK
