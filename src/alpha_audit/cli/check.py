"""``alpha-audit check``: audit icon sets on themes and apply the CI gate."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path
from typing import Annotated

import typer

from alpha_audit.cli.console import emit, progress_bar, stderr_note, stdout_options
from alpha_audit.cli.options import (
    OPTION_ORDER,
    ConfigOption,
    ForceOption,
    GamutOption,
    IconsetArgument,
    MaxDriftOption,
    MaxLossOption,
    MinDeltaEOption,
    MinSizeContrastOption,
    NoCacheOption,
    PipelineOption,
    StrictSvgOption,
    ThemeArgument,
    ThresholdOption,
    in_range,
    read_gamut_option,
    rules_flag,
)
from alpha_audit.cli.status import ExitStatus
from alpha_audit.load.paths import project_root
from alpha_audit.ranges import ALPHA
from alpha_audit.render import CheckFormat, RenderOptions
from alpha_audit.render.common import check_suffix

__all__ = ["check_command", "pair_outputs"]


def pair_outputs(
    formats: list[CheckFormat], outputs: list[Path], order: Sequence[str] | None = None
) -> list[tuple[CheckFormat, Path | None]]:
    """Give each ``--output`` to the ``--format`` before it (``-`` or none: stdout).

    ``order`` is ``"format"`` / ``"output"`` per option as given on the command
    line (:class:`~alpha_audit.cli_options.OrderedOptionsCommand` records it);
    without it, the n-th output goes with the n-th format.  One ``-o`` with one
    ``-f`` pair in either order.  Refused: an output whose extension belongs to
    another format (``-f junit -o a.sarif``), an output with no format before
    it, two outputs for one format, and two formats on stdout.
    """
    from alpha_audit.errors import UsageError

    formats = formats or [CheckFormat.TABLE]
    targets: list[Path | None] = [None] * len(formats)
    if (len(outputs) <= 1 and len(formats) == 1) or order is None:
        if len(outputs) > len(formats):
            raise UsageError(
                f"{len(outputs)} --output for {len(formats)} --format; give one format per output"
            )
        targets[: len(outputs)] = outputs
    else:
        f = o = 0
        for kind in order:
            if kind == "format":
                f += 1
            elif kind == "output":
                if f == 0 or targets[f - 1] is not None:
                    where = f"after --format {formats[f - 1].value}" if f else "before any --format"
                    raise UsageError(
                        f"--output {outputs[o]} has no --format of its own ({where}); "
                        "put each --output right after its --format"
                    )
                targets[f - 1] = outputs[o]
                o += 1
    pairs = [
        (fmt, None if out is None or str(out) == "-" else out)
        for fmt, out in zip(formats, targets, strict=True)
    ]
    for fmt, out in pairs:
        if out is not None:
            check_suffix(fmt.value, out)
    to_stdout = [fmt.value for fmt, out in pairs if out is None]
    if len(to_stdout) > 1:
        raise UsageError(
            f"formats {' and '.join(to_stdout)} would both go to stdout; "
            "give each but one an --output"
        )
    return pairs


def check_command(
    ctx: typer.Context,
    theme: ThemeArgument = None,
    iconset: IconsetArgument = None,
    themes: Annotated[
        list[Path] | None,
        typer.Option(
            "--theme",
            metavar="PATH",
            help="Another theme to audit (repeatable).",
            show_default=False,
        ),
    ] = None,
    iconsets: Annotated[
        list[Path] | None,
        typer.Option(
            "--iconset", metavar="PATH", help="Another icon set (repeatable).", show_default=False
        ),
    ] = None,
    config: ConfigOption = None,
    alpha: Annotated[
        float | None,
        typer.Option(
            "--alpha",
            "-a",
            help="Coefficient for every icon (overrides the manifest).",
            callback=in_range("--alpha", ALPHA),
        ),
    ] = None,
    threshold: ThresholdOption = None,
    fail_on: Annotated[
        list[str] | None,
        typer.Option(
            "--fail-on",
            metavar="RULE",
            help="Rule that fails the gate (repeatable; replaces the policy): loss, "
            "below-threshold, newly-failing, collision, new-collision, separation, unrenderable, "
            "fixed-colour, not-audited, drift, lock, confusion, thin-strokes, cvd-collision, "
            "cvd-confusion. [default: loss, newly-failing, new-collision]",
            show_default=False,
            callback=rules_flag("--fail-on"),
        ),
    ] = None,
    max_loss: MaxLossOption = None,
    min_delta_e: MinDeltaEOption = None,
    max_drift: MaxDriftOption = None,
    min_size_contrast: MinSizeContrastOption = None,
    pipeline: PipelineOption = None,
    gamut: GamutOption = None,
    exit_zero: Annotated[
        bool, typer.Option("--exit-zero", help="Report findings but exit 0 even if the gate fails.")
    ] = False,
    fmt: Annotated[
        list[CheckFormat] | None,
        typer.Option(
            "--format",
            "-f",
            metavar="FORMAT",
            help=f"Report format (repeatable): {', '.join(CheckFormat)}.",
            case_sensitive=False,
            show_default=False,
        ),
    ] = None,
    output: Annotated[
        list[Path] | None,
        typer.Option(
            "--output",
            "-o",
            metavar="PATH",
            help="File for the --format before it ('-' = stdout; repeatable).",
            show_default=False,
        ),
    ] = None,
    baseline: Annotated[
        Path | None,
        typer.Option("--baseline", help="Fail only on findings not in this baseline file."),
    ] = None,
    write_baseline: Annotated[
        Path | None,
        typer.Option("--write-baseline", help="Record today's findings as a baseline file."),
    ] = None,
    force: ForceOption = False,
    strict_svg: StrictSvgOption = False,
    no_cache: NoCacheOption = False,
) -> ExitStatus:
    """Audit icon sets on themes and fail the build on the findings the policy names.

    Per canvas: mean contrast gain against a = 1, icons at or above the threshold
    (at a = 1 -> at a), icons that newly pass, contrast losses, 8-bit collisions
    between distinct colours, and the smallest CIEDE2000 between the set's colours.
    With no THEME ICONSET, audits what the project config names.

    THEME may name a bundled theme (see [bold]alpha-audit themes[/]) and ICONSET the
    bundled example set [bold]vibrant[/].

    Exit codes: 0 the gate passed, 1 the gate failed, 2 bad input or usage, 3 a bug.

    Example:
    [bold]alpha-audit check themes/github-primer.yaml examples/vibrant/iconset.yaml -a 1.2[/]
    """
    from alpha_audit.bundled import iconset_source, theme_source
    from alpha_audit.errors import UsageError
    from alpha_audit.gate import baseline_document, read_baseline
    from alpha_audit.load.config import project_config
    from alpha_audit.output import Output, check_targets, write_files
    from alpha_audit.pipeline import check_project
    from alpha_audit.render.common import dumps

    gamut_policy = read_gamut_option(gamut)
    given = ctx.meta.get(OPTION_ORDER)
    order = None if given is None else ["format" if n == "fmt" else n for n in given]
    pairs = pair_outputs(list(fmt or []), list(output or []), order)
    # Every file target is checked before the audit runs and again as one write at the end.
    files = [out for _, out in pairs if out is not None]
    files += [write_baseline] if write_baseline is not None else []
    check_targets(files, overwrite=force)
    if (theme is None) != (iconset is None):
        raise UsageError("give both THEME and ICONSET, or neither (to use the project config)")

    project = project_config(config, Path.cwd())
    cli_themes = [theme_source(t) for t in ([theme] if theme else []) + list(themes or [])]
    cli_sets = [iconset_source(s) for s in ([iconset] if iconset else []) + list(iconsets or [])]
    policy = project.policy.with_overrides(
        rules=fail_on,
        max_loss=max_loss,
        min_delta_e=min_delta_e,
        max_drift=max_drift,
        min_size_contrast=min_size_contrast,
    )
    baseline_path = baseline if baseline is not None else project.baseline
    known = read_baseline(baseline_path) if baseline_path is not None else None

    with progress_bar("Rendering icons") as (on_start, on_icon):
        report = check_project(
            cli_themes or project.themes,
            cli_sets or project.iconsets,
            policy=policy,
            alpha=alpha if alpha is not None else project.alpha,
            threshold=threshold if threshold is not None else project.threshold,
            baseline=known,
            strict_svg=strict_svg or project.strict_svg,
            pipeline=pipeline if pipeline is not None else project.pipeline,
            on_start=on_start,
            on_icon=on_icon,
            tokens=None if cli_themes or cli_sets else project.tokens,
            gamut=gamut_policy if gamut_policy is not None else project.gamut,
            pool=ctx.obj,
        )
    # Paths in reports are relative to the repository (the folder with .git): what
    # GitHub annotations, SARIF's %SRCROOT% and GitLab expect, from any subfolder.
    base = project_root(Path.cwd())
    outputs, stdout_text = [], None
    for kind, out in pairs:
        if out is None:
            stdout_text = kind.renderer()(report, replace(stdout_options(), base=base))
        else:
            outputs.append(Output.text(out, kind.renderer()(report, RenderOptions(base=base))))
    if write_baseline is not None:
        outputs.append(Output.text(write_baseline, dumps(baseline_document(report.gate))))
    for path in write_files(outputs, overwrite=force):
        stderr_note(f"wrote {'baseline ' if path == write_baseline else ''}{path}")
    if stdout_text is not None:
        emit(stdout_text, None, force)
    if write_baseline is not None:
        return ExitStatus.OK
    gate = report.gate
    if gate.passed:
        stderr_note("gate passed")
        return ExitStatus.OK
    counts = ", ".join(f"{n} {rule}" for rule, n in gate.counts().items())
    stderr_note(f"gate failed: {counts}" + (" (--exit-zero)" if exit_zero else ""))
    return ExitStatus.OK if exit_zero else ExitStatus.GATE_FAILED
