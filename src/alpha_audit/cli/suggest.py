"""``alpha-audit suggest``: the largest safe coefficient, and ``--apply`` to write it."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from alpha_audit.cli.console import emit, stdout_options
from alpha_audit.cli.options import (
    ConfigOption,
    ForceOption,
    IconsetArgument,
    MaxDriftOption,
    MaxLossOption,
    MinDeltaEOption,
    MinSizeContrastOption,
    ThemeArgument,
    ThresholdOption,
    require_finite,
)
from alpha_audit.cli.status import ExitStatus
from alpha_audit.suggest.report import SuggestFormat

__all__ = ["suggest_command"]


def suggest_command(
    theme: ThemeArgument = None,
    iconset: IconsetArgument = None,
    config: ConfigOption = None,
    alpha_max: Annotated[
        float, typer.Option("--alpha-max", help="Largest coefficient considered.")
    ] = 2.0,
    precision: Annotated[
        int, typer.Option("--precision", help="Decimals; the answer is rounded down.")
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
    apply: Annotated[
        bool,
        typer.Option(
            "--apply",
            help="Write the set-wide alpha into the manifest (only the alpha values change).",
        ),
    ] = False,
) -> ExitStatus:
    """The largest alpha every coefficient in [1, alpha] keeps the gate policy for.

    Computed exactly from where contrast, 8-bit codes and separation change, not
    by a sweep: set-wide (one coefficient for every icon), per palette colour
    and per icon (the others keep their configured alpha), with the canvas,
    rule and icons that stop each and the first unsafe alpha.  Nothing is
    written unless --apply is given.

    Example:
    [bold]alpha-audit suggest themes/paper16.yaml examples/vibrant/iconset.yaml --apply[/]
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
    from alpha_audit.suggest.apply import apply_alpha, format_alpha

    if output is not None:
        check_suffix(fmt.value, output)
        check_targets([output], overwrite=force)  # before the work, not after
    require_finite(alpha_max, "--alpha-max")
    require_finite(threshold, "--threshold")
    if (theme is None) != (iconset is None):
        raise UsageError("give both THEME and ICONSET, or neither (to use the project config)")
    project = project_config(config, Path.cwd())
    if theme is None or iconset is None:
        if len(project.themes) != 1 or len(project.iconsets) != 1:
            raise UsageError(
                "suggest needs one theme and one icon set: give THEME ICONSET, or a project "
                f"config naming exactly one of each (found {len(project.themes)} theme(s), "
                f"{len(project.iconsets)} icon set(s))"
            )
        theme, iconset = project.themes[0], project.iconsets[0]
    theme, source = theme_source(theme), iconset_source(iconset)
    if apply and source != Path(iconset):
        raise UsageError(
            f"--apply rewrites the manifest in place and {iconset} is the bundled example; "
            f"copy {source.parent} into your project and give its {source.name}"
        )
    iconset = source
    require_finite(max_drift, "--max-drift")
    require_finite(min_size_contrast, "--min-size-contrast")
    policy = project.policy.with_overrides(
        rules=fail_on,
        max_loss=max_loss,
        min_delta_e=min_delta_e,
        max_drift=max_drift,
        min_size_contrast=min_size_contrast,
    )

    loaded_theme, loaded_set = load_theme(theme), load_iconset(iconset)
    # The gate judges every paint of every SVG as drawn: suggest answers the same rows.
    paints = render_paints(loaded_set, strict_svg=False, on_icon=None)
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
    if apply:
        if result.alpha is None:
            raise UsageError("no safe alpha to apply: the policy already fails at alpha = 1")
        changed = apply_alpha(iconset, result.alpha, precision)
        note = "wrote" if changed else "already has"
        typer.echo(f"{note} alpha {format_alpha(result.alpha, precision)} in {iconset}", err=True)
    return ExitStatus.OK
